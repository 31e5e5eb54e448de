use glam::Vec3;

/// Axis-aligned bounding box. [`Aabb::EMPTY`] is the identity of [`Aabb::union`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Aabb {
    pub min: Vec3,
    pub max: Vec3,
}

impl Aabb {
    pub const EMPTY: Aabb = Aabb {
        min: Vec3::splat(f32::INFINITY),
        max: Vec3::splat(f32::NEG_INFINITY),
    };

    pub fn from_points(points: &[Vec3]) -> Aabb {
        points.iter().fold(Aabb::EMPTY, |acc, &p| acc.including(p))
    }

    pub fn including(&self, p: Vec3) -> Aabb {
        Aabb {
            min: self.min.min(p),
            max: self.max.max(p),
        }
    }

    pub fn union(&self, other: &Aabb) -> Aabb {
        Aabb {
            min: self.min.min(other.min),
            max: self.max.max(other.max),
        }
    }

    pub fn is_empty(&self) -> bool {
        self.min.cmpgt(self.max).any()
    }

    pub fn center(&self) -> Vec3 {
        if self.is_empty() {
            Vec3::ZERO
        } else {
            0.5 * (self.min + self.max)
        }
    }

    /// Radius of the sphere around [`Aabb::center`] that holds the box (0 when empty).
    pub fn radius(&self) -> f32 {
        if self.is_empty() {
            0.0
        } else {
            0.5 * (self.max - self.min).length()
        }
    }

    /// The distance from `p` to the box's nearest point: 0 inside it; infinite for an
    /// empty box.
    pub fn distance_to(&self, p: Vec3) -> f32 {
        if self.is_empty() {
            return f32::INFINITY;
        }
        (p.clamp(self.min, self.max) - p).length()
    }

    /// The eight corners, corner k taking max along x, y, z where bits 0, 1, 2 of k are set.
    pub fn corners(&self) -> [Vec3; 8] {
        std::array::from_fn(|k| {
            let pick = |bit: usize, lo: f32, hi: f32| if k & bit == 0 { lo } else { hi };
            Vec3::new(
                pick(1, self.min.x, self.max.x),
                pick(2, self.min.y, self.max.y),
                pick(4, self.min.z, self.max.z),
            )
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn distance_to_a_box_is_to_its_nearest_point() {
        let unit = Aabb {
            min: Vec3::ZERO,
            max: Vec3::ONE,
        };
        assert_eq!(unit.distance_to(Vec3::splat(0.5)), 0.0);
        assert_eq!(unit.distance_to(Vec3::new(3.0, 0.5, 0.5)), 2.0);
        assert_eq!(unit.distance_to(Vec3::new(4.0, 5.0, 1.0)), 5.0);
        assert_eq!(Aabb::EMPTY.distance_to(Vec3::ZERO), f32::INFINITY);
    }

    #[test]
    fn empty_box_is_union_identity() {
        let b = Aabb::from_points(&[Vec3::new(1.0, 2.0, 3.0), Vec3::new(-1.0, 0.0, 5.0)]);
        assert_eq!(Aabb::EMPTY.union(&b), b);
        assert!(Aabb::EMPTY.is_empty());
        assert_eq!(b.center(), Vec3::new(0.0, 1.0, 4.0));
        assert!((b.radius() - (4.0f32 + 4.0 + 4.0).sqrt() / 2.0).abs() < 1e-6);
        let corners = b.corners();
        assert_eq!(corners[0], b.min);
        assert_eq!(corners[7], b.max);
        assert_eq!(corners[5], Vec3::new(1.0, 0.0, 5.0));
        assert_eq!(Aabb::from_points(&corners), b);
    }
}
