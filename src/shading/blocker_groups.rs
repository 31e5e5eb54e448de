//! Culling groups for the shading pass: nearby spheres gathered into groups of at most
//! [`GROUP_SIZE`] by recursive median splits (a one-level sphere hierarchy), each with a
//! bounding radius and an influence radius, so a receiver skips a whole group at once.
//!
//! The group tests are conservative: a group is skipped only when every one of its spheres
//! would be skipped by the per-sphere tests of logsh.wgsl (beyond its influence distance
//! r/min_cap_ratio, or wholly below the tangent plane), so culling never changes a pixel.
//! Far from a group its spheres are not simply dropped: one sphere of their summed
//! projected area stands in for them (`stand_in_radius_m`), taking over smoothly between
//! half the influence distance and the influence distance (no ring shows where it does),
//! for as long as it is large enough in the sky: many small blockers (a lattice's, a
//! helix's) keep the far reaches of their soft shadows, each of them alone too small to
//! count.

use glam::Vec3;

use crate::blockers::Sphere;

/// Most spheres in one group.
pub const GROUP_SIZE: usize = 8;

/// A group of consecutive spheres `first..first + count` of the reordered list.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BlockerGroup {
    pub center: Vec3,
    /// Every sphere lies within this distance of `center`: max |cᵢ − c| + rᵢ.
    pub extent_m: f32,
    /// A receiver farther than this from `center` is beyond every sphere's influence
    /// distance: max |cᵢ − c| + rᵢ / min_cap_ratio.
    pub influence_m: f32,
    /// √Σ rᵢ²: the radius of one sphere at `center` with the projected area of the
    /// group's spheres, which takes over from them between half the influence distance
    /// and `influence_m` (where each alone is too small to count). Groups hold spheres
    /// only: discs are shaded apart (`blockers::spheres_and_discs`).
    pub stand_in_radius_m: f32,
    pub first: usize,
    pub count: usize,
}

/// The spheres reordered so that groups are contiguous, and the groups.
pub fn group_blockers(spheres: &[Sphere], min_cap_ratio: f32) -> (Vec<Sphere>, Vec<BlockerGroup>) {
    let mut ordered = spheres.to_vec();
    let mut groups = Vec::new();
    split(&mut ordered, 0, min_cap_ratio, &mut groups);
    (ordered, groups)
}

fn split(spheres: &mut [Sphere], offset: usize, min_cap_ratio: f32, groups: &mut Vec<BlockerGroup>) {
    if spheres.is_empty() {
        return;
    }
    if spheres.len() <= GROUP_SIZE {
        groups.push(bound(spheres, offset, min_cap_ratio));
        return;
    }
    let (lo, hi) = spheres
        .iter()
        .fold((Vec3::INFINITY, Vec3::NEG_INFINITY), |(lo, hi), s| {
            (lo.min(s.center), hi.max(s.center))
        });
    let extent = hi - lo;
    let axis = if extent.x >= extent.y && extent.x >= extent.z {
        0
    } else if extent.y >= extent.z {
        1
    } else {
        2
    };
    let middle = spheres.len() / 2;
    spheres.select_nth_unstable_by(middle, |a, b| a.center[axis].total_cmp(&b.center[axis]));
    let (left, right) = spheres.split_at_mut(middle);
    split(left, offset, min_cap_ratio, groups);
    split(right, offset + middle, min_cap_ratio, groups);
}

fn bound(spheres: &[Sphere], first: usize, min_cap_ratio: f32) -> BlockerGroup {
    let center = spheres.iter().map(|s| s.center).sum::<Vec3>() / spheres.len() as f32;
    let reach = |s: &Sphere, radius: f32| s.center.distance(center) + radius;
    let extent_m = spheres.iter().map(|s| reach(s, s.radius_m)).fold(0.0, f32::max);
    let influence_m = if min_cap_ratio > 0.0 {
        spheres
            .iter()
            .map(|s| reach(s, s.radius_m / min_cap_ratio))
            .fold(0.0, f32::max)
    } else {
        f32::INFINITY
    };
    let stand_in_radius_m = spheres.iter().map(|s| s.radius_m * s.radius_m).sum::<f32>().sqrt();
    BlockerGroup {
        center,
        extent_m,
        influence_m,
        stand_in_radius_m,
        first,
        count: spheres.len(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn spheres(count: usize) -> Vec<Sphere> {
        (0..count)
            .map(|i| {
                let t = i as f32 * 0.37;
                Sphere {
                    center: Vec3::new(t.cos() * t, (1.3 * t).sin(), t * 0.2),
                    radius_m: 0.05 + 0.01 * (i % 7) as f32,
                    disc_normal: glam::Vec3::ZERO,
                }
            })
            .collect()
    }

    #[test]
    fn groups_cover_every_sphere_once_and_bound_them() {
        let input = spheres(203);
        let (ordered, groups) = group_blockers(&input, 0.03);
        assert_eq!(ordered.len(), input.len());
        assert_eq!(groups.iter().map(|g| g.count).sum::<usize>(), input.len());
        let mut next = 0;
        for g in &groups {
            assert_eq!(g.first, next);
            assert!(g.count <= GROUP_SIZE && g.count > 0);
            next += g.count;
            for s in &ordered[g.first..g.first + g.count] {
                assert!(s.center.distance(g.center) + s.radius_m <= g.extent_m + 1e-5);
                assert!(s.center.distance(g.center) + s.radius_m / 0.03 <= g.influence_m + 1e-3);
            }
        }
        let mut a: Vec<String> = input.iter().map(|s| format!("{s:?}")).collect();
        let mut b: Vec<String> = ordered.iter().map(|s| format!("{s:?}")).collect();
        a.sort();
        b.sort();
        assert_eq!(a, b);
    }

    #[test]
    fn no_spheres_no_groups() {
        assert!(group_blockers(&[], 0.03).1.is_empty());
    }
}
