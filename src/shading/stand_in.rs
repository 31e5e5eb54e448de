//! The one sphere that stands in for a group of spheres seen from far away
//! (`blocker_groups`): at the group's centre, with the area the group's spheres cover
//! together in projection, averaged over directions.
//!
//! Far from a group its spheres' caps are too close together for the SH order to tell
//! apart (Ren et al. 2006 replace a sphere-tree node's children by the node there), so
//! what a stand-in must keep is how much of the sky they hide. Spheres fitted to one
//! caster overlap (along a ring, a tube), and √Σ rᵢ² — their areas summed — counts the
//! overlaps twice: a stand-in that large hides more of a light than its spheres do, and
//! darkens penumbrae where it takes over. So the areas are summed less each pair's
//! overlap (inclusion–exclusion to pairs, the lens of two discs), never under the largest
//! sphere's, in each of 16 directions spread over a hemisphere, and the radius is that of
//! a disc of their mean.

use glam::DVec3;

use crate::blockers::Sphere;

/// How many directions the covered area is averaged over.
const DIRECTION_COUNT: usize = 16;

/// Direction i of [`DIRECTION_COUNT`] spread evenly over a hemisphere (a projection is
/// the same from both sides): a Fibonacci spiral, z = (i + ½)/n (equal areas) and
/// azimuth (i + ½) times the golden angle. None lies along an axis or a diagonal, along
/// which the spheres of a grid or a straight row line up and hide each other: from such
/// a direction they overlap whole, which the mean over all directions hardly sees.
fn direction(i: usize) -> DVec3 {
    let z = (i as f64 + 0.5) / DIRECTION_COUNT as f64;
    let golden_angle = std::f64::consts::PI * (3.0 - 5f64.sqrt());
    let (sin, cos) = ((i as f64 + 0.5) * golden_angle).sin_cos();
    let r = (1.0 - z * z).sqrt();
    DVec3::new(r * cos, r * sin, z)
}

/// The radius of the stand-in of `spheres` (see the module): √(Ā/π), Ā the mean over the
/// directions of the area their projections cover, Σ πrᵢ² less the pairs' lenses and at
/// least the largest πrᵢ². At most √Σ rᵢ² (no overlap), at least the largest rᵢ.
pub fn stand_in_radius_m(spheres: &[Sphere]) -> f32 {
    let summed = spheres.iter().map(|s| f64::from(s.radius_m).powi(2)).sum::<f64>();
    let largest = spheres.iter().map(|s| f64::from(s.radius_m)).fold(0.0, f64::max);
    // Σ over the directions of the area covered, in units of π.
    let mut covered_sum = 0.0;
    for direction in (0..DIRECTION_COUNT).map(direction) {
        let mut overlap = 0.0;
        for (i, a) in spheres.iter().enumerate() {
            for b in &spheres[i + 1..] {
                let apart = (b.center - a.center).as_dvec3();
                let projected = apart.cross(direction).length();
                overlap += disc_overlap(f64::from(a.radius_m), f64::from(b.radius_m), projected);
            }
        }
        // In units of π, as `summed`: never under the largest sphere's area.
        covered_sum += (summed - overlap / std::f64::consts::PI).max(largest * largest);
    }
    (covered_sum / DIRECTION_COUNT as f64).sqrt() as f32
}

/// The stand-in of several groups together, from their own stand-ins' radii: √Σ Rᵢ² (the
/// overlaps between groups are not counted again).
pub fn joined_stand_in_radius_m(radii_m: impl IntoIterator<Item = f32>) -> f32 {
    radii_m.into_iter().map(|r| r * r).sum::<f32>().sqrt()
}

/// Σ rᵢ² / R², the depth at which a stand-in of radius R lies over the area `spheres`
/// cover (1 where none overlap; 1 without spheres).
pub fn stand_in_depth(spheres: &[Sphere], stand_in_radius_m: f32) -> f32 {
    let summed = spheres.iter().map(|s| s.radius_m * s.radius_m).sum::<f32>();
    if stand_in_radius_m > 0.0 {
        (summed / (stand_in_radius_m * stand_in_radius_m)).max(1.0)
    } else {
        1.0
    }
}

/// The area of the intersection of two discs of radii `a` and `b` whose centres are
/// `distance` apart (the lens: the two circular segments).
pub fn disc_overlap(a: f64, b: f64, distance: f64) -> f64 {
    use std::f64::consts::PI;
    if distance >= a + b {
        return 0.0;
    }
    if distance <= (a - b).abs() {
        return PI * a.min(b).powi(2);
    }
    let d2 = distance * distance;
    let angle_a = ((d2 + a * a - b * b) / (2.0 * distance * a)).clamp(-1.0, 1.0).acos();
    let angle_b = ((d2 + b * b - a * a) / (2.0 * distance * b)).clamp(-1.0, 1.0).acos();
    let kite = (-distance + a + b) * (distance + a - b) * (distance - a + b) * (distance + a + b);
    a * a * angle_a + b * b * angle_b - 0.5 * kite.max(0.0).sqrt()
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::Vec3;
    use std::f64::consts::PI;

    fn sphere(x: f32, y: f32, z: f32, radius_m: f32) -> Sphere {
        Sphere {
            center: Vec3::new(x, y, z),
            radius_m,
            disc_normal: Vec3::ZERO,
        }
    }

    #[test]
    fn the_lens_of_two_unit_discs_a_radius_apart() {
        // Two unit circles through each other's centres: 2π/3 − √3/2.
        let lens = disc_overlap(1.0, 1.0, 1.0);
        assert!((lens - (2.0 * PI / 3.0 - 3f64.sqrt() / 2.0)).abs() < 1e-12, "{lens}");
        assert_eq!(disc_overlap(1.0, 0.5, 1.5), 0.0);
        assert!((disc_overlap(1.0, 0.5, 0.2) - PI * 0.25).abs() < 1e-12);
        // Continuous where one disc enters the other, and where they part.
        assert!((disc_overlap(1.0, 0.5, 0.5 + 1e-9) - PI * 0.25).abs() < 1e-6);
        assert!(disc_overlap(1.0, 0.5, 1.5 - 1e-9) < 1e-6);
    }

    #[test]
    fn the_lens_agrees_with_counting_points() {
        // Independent of the formula: the share of a fine grid over disc a inside b.
        for (a, b, distance) in [(1.0, 0.7, 0.9), (0.4, 1.1, 1.2), (1.0, 1.0, 0.3)] {
            let steps = 1200;
            let cell = 2.0 * a / steps as f64;
            let mut inside = 0usize;
            for i in 0..steps {
                for j in 0..steps {
                    let x = -a + (i as f64 + 0.5) * cell;
                    let y = -a + (j as f64 + 0.5) * cell;
                    if x * x + y * y <= a * a && (x - distance).powi(2) + y * y <= b * b {
                        inside += 1;
                    }
                }
            }
            let counted = inside as f64 * cell * cell;
            let lens = disc_overlap(a, b, distance);
            assert!(
                (counted - lens).abs() < 2e-3 * (1.0 + lens),
                "{a} {b} {distance}: {counted} against {lens}"
            );
        }
    }

    #[test]
    fn apart_spheres_keep_their_summed_area_and_one_sphere_is_itself() {
        // Small for their distances: no direction of the set sees two of them overlap.
        let apart = [
            sphere(0.0, 0.0, 0.0, 0.03),
            sphere(5.0, 1.0, -2.0, 0.04),
            sphere(-4.0, 3.0, 6.0, 0.02),
        ];
        let expected = (0.0009f32 + 0.0016 + 0.0004).sqrt();
        assert!((stand_in_radius_m(&apart) - expected).abs() < 1e-7);
        assert!((stand_in_radius_m(&apart[1..2]) - 0.04).abs() < 1e-8);
        assert_eq!(stand_in_radius_m(&[]), 0.0);
    }

    #[test]
    fn coincident_spheres_stand_in_as_one_four_deep() {
        let same = [sphere(1.0, 2.0, 3.0, 0.5); 4];
        let radius = stand_in_radius_m(&same);
        assert!((radius - 0.5).abs() < 1e-6, "{radius}");
        assert!((stand_in_depth(&same, radius) - 4.0).abs() < 1e-5);
        // Apart from every direction of the set.
        let apart = [sphere(0.0, 0.0, 0.0, 0.05), sphere(9.0, 0.0, 0.0, 0.05)];
        assert!((stand_in_depth(&apart, stand_in_radius_m(&apart)) - 1.0).abs() < 1e-6);
        assert_eq!(stand_in_depth(&[], 0.0), 1.0);
    }

    #[test]
    fn a_row_of_spheres_apart_is_not_taken_for_one() {
        // Eight spheres of radius 0.1 a metre apart along x (a grid's row): they hide each
        // other only within about 6° of the axis, so nearly their whole summed area counts.
        let row: Vec<Sphere> = (0..8).map(|i| sphere(i as f32, 0.0, 0.0, 0.1)).collect();
        let summed = (8f32 * 0.01).sqrt();
        let radius = stand_in_radius_m(&row);
        assert!(radius >= 0.99 * summed, "{radius} against {summed}");
    }

    #[test]
    fn overlapping_spheres_along_a_tube_cover_what_their_projections_cover() {
        // Eight spheres of radius 0.1 every 0.1 m along x: independent of the pairs'
        // formula, the area their projections cover counted on a grid in each direction.
        let tube: Vec<Sphere> = (0..8).map(|i| sphere(0.1 * i as f32, 0.0, 0.0, 0.1)).collect();
        let mut covered = 0.0;
        for d in (0..DIRECTION_COUNT).map(direction) {
            let u = d.any_orthonormal_vector();
            let v = d.cross(u);
            let projected: Vec<(f64, f64)> = tube
                .iter()
                .map(|s| (s.center.as_dvec3().dot(u), s.center.as_dvec3().dot(v)))
                .collect();
            let (steps, lo, hi) = (800, -1.0, 1.0);
            let cell = (hi - lo) / steps as f64;
            let mut inside = 0usize;
            for i in 0..steps {
                for j in 0..steps {
                    let (x, y) = (lo + (i as f64 + 0.5) * cell, lo + (j as f64 + 0.5) * cell);
                    if projected
                        .iter()
                        .any(|(px, py)| (x - px).powi(2) + (y - py).powi(2) <= 0.01)
                    {
                        inside += 1;
                    }
                }
            }
            covered += inside as f64 * cell * cell;
        }
        let radius_covering = (covered / DIRECTION_COUNT as f64 / PI).sqrt();
        let radius = f64::from(stand_in_radius_m(&tube));
        // Pairs only: where three discs meet, the lenses are taken once too often, so
        // the stand-in may come out a little under what the spheres cover.
        assert!(
            (radius - radius_covering).abs() < 0.1 * radius_covering,
            "{radius} against {radius_covering}"
        );
        assert!(
            radius < 0.9 * (8f64 * 0.01).sqrt(),
            "overlaps must shrink the stand-in: {radius}"
        );
    }

    #[test]
    fn the_radius_lies_between_the_largest_sphere_and_the_summed_area() {
        let mut state = 12345u64;
        let mut next = || {
            state = state
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            (state >> 40) as f32 / (1u64 << 24) as f32
        };
        for _ in 0..200 {
            let count = 1 + (next() * 12.0) as usize;
            let spheres: Vec<Sphere> = (0..count)
                .map(|_| sphere(next(), next(), next(), 0.01 + 0.5 * next()))
                .collect();
            let radius = stand_in_radius_m(&spheres);
            let largest = spheres.iter().map(|s| s.radius_m).fold(0.0, f32::max);
            let summed = joined_stand_in_radius_m(spheres.iter().map(|s| s.radius_m));
            assert!(radius >= largest * (1.0 - 1e-6) && radius <= summed * (1.0 + 1e-6));
        }
    }
}
