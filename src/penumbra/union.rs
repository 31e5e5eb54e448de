//! How the shares of a light's disc hidden by several blockers combine: the share hidden by
//! their union. Taking the blockers as independent, 1 − Π(1 − fᵢ), is wrong both ways:
//! two caps over the same part of the disc hide it once, not 1 − (1 − f)² (too dark), and
//! two caps side by side, each over half the disc, hide all of it, not ¾ (too light).
//!
//! The union is taken blocker by blocker, each adding the part of its share that the ones
//! before it do not already hide:
//!
//!   U = Σₖ fₖ · Πₘ<ₖ (1 − Oₘₖ / fₖ),   clamped to [maxₖ fₖ, 1],
//!
//! Oₘₖ the share of the disc hidden by both m and k: within k's part of the disc, the
//! earlier blockers are taken as independent (inclusion–exclusion to the pairs, with the
//! higher orders of independence). That is exact for one blocker, for disjoint, nested or
//! identical ones, and for any two; with three or more caps over one part of the disc it
//! errs either way. Over random sets of two to four blockers across a light (the tests
//! below) its mean error is a third of the independent blockers' or less.
//!
//! Oₘₖ, the area where three caps meet (the disc and two blockers), has a closed form with
//! many cases; it is taken instead as the share of the disc hidden by one cap standing for
//! the lens where the two blockers meet: of the lens's solid angle (`cap_overlap`'s), centred
//! midway across the lens on the arc between the blockers' centres. That is exact when
//! one blocker holds the other and when the lens is far from the disc's edge, and the
//! overlap is kept within min(fₘ, fₖ). `shaders/exact_lights.wgsl` computes the same in f32.

use std::f64::consts::PI;

use glam::DVec3;

use super::cap_overlap::{cap_area, hidden_fraction};

/// A blocker's cap as one receiver sees it, with the share of a light's disc it hides.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct HidingCap {
    /// Unit direction from the receiver to the cap's centre.
    pub direction: DVec3,
    /// Angular radius of the cap.
    pub radius_rad: f64,
    /// Fade below the receiver's tangent plane (1 above it; `BlockerCap::horizon`).
    pub horizon: f64,
    /// Distance from the receiver to the blocker's centre.
    pub distance_m: f64,
    /// Share (0–1) of the light's disc the cap hides, fade included.
    pub hidden: f64,
}

/// The share of a disc (centre `disc_direction`, angular radius `disc_rad`) hidden by both
/// `a` and `b`, through the cap standing for their lens (module doc).
pub fn pair_overlap(disc_direction: DVec3, disc_rad: f64, a: &HidingCap, b: &HidingCap) -> f64 {
    let at_most = a.hidden.min(b.hidden);
    if at_most <= 0.0 {
        return 0.0;
    }
    let separation = angle_between(a.direction, b.direction);
    let lens_solid_angle = hidden_fraction(a.radius_rad, b.radius_rad, separation) * cap_area(a.radius_rad);
    if lens_solid_angle <= 0.0 {
        return 0.0;
    }
    // The lens spans, along the arc from a's centre toward b's, from the nearer of b's far
    // edge and a's back edge to the nearer of a's front edge and b's: its middle.
    let start = (separation - b.radius_rad).max(-a.radius_rad);
    let end = a.radius_rad.min(separation + b.radius_rad);
    let middle = 0.5 * (start + end);
    let across = b.direction - a.direction * a.direction.dot(b.direction);
    let lens_direction = if across.length_squared() > 0.0 {
        a.direction * middle.cos() + across.normalize() * middle.sin()
    } else {
        a.direction // concentric: the smaller cap is the lens, centred on both
    };
    // The cap of the lens's solid angle: 2π(1 − cos ρ) = Ω.
    let lens_radius = (1.0 - lens_solid_angle / (2.0 * PI)).clamp(-1.0, 1.0).acos();
    let overlap = a.horizon.min(b.horizon)
        * hidden_fraction(disc_rad, lens_radius, angle_between(lens_direction, disc_direction));
    overlap.min(at_most)
}

/// The share of the disc hidden by the union of `caps`, taken in order (module doc).
/// `disc_rad_for(m, k)` is the disc's angular radius to compare caps m and k with (the
/// exact path widens a disc by the pixel's footprint at each blocker's distance).
pub fn union_of_hidden(
    disc_direction: DVec3,
    caps: &[HidingCap],
    disc_rad_for: impl Fn(&HidingCap, &HidingCap) -> f64,
) -> f64 {
    let mut union = 0.0;
    let mut largest: f64 = 0.0;
    for (k, cap) in caps.iter().enumerate() {
        let left_open: f64 = (0..k)
            .map(|m| {
                1.0 - pair_overlap(disc_direction, disc_rad_for(&caps[m], cap), &caps[m], cap) / cap.hidden.max(1e-300)
            })
            .product();
        union += cap.hidden * left_open.clamp(0.0, 1.0);
        largest = largest.max(cap.hidden);
    }
    union.clamp(largest, 1.0)
}

/// The angle between two unit vectors, accurate when tiny.
pub fn angle_between(a: DVec3, b: DVec3) -> f64 {
    a.cross(b).length().atan2(a.dot(b))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::random::SplitMix64;

    /// A unit direction `angle_rad` from +z toward azimuth `azimuth_rad`.
    fn toward(angle_rad: f64, azimuth_rad: f64) -> DVec3 {
        DVec3::new(
            angle_rad.sin() * azimuth_rad.cos(),
            angle_rad.sin() * azimuth_rad.sin(),
            angle_rad.cos(),
        )
    }

    fn cap(direction: DVec3, radius_rad: f64, disc_rad: f64) -> HidingCap {
        HidingCap {
            direction,
            radius_rad,
            horizon: 1.0,
            distance_m: 1.0,
            hidden: hidden_fraction(disc_rad, radius_rad, angle_between(direction, DVec3::Z)),
        }
    }

    /// The share of the disc about +z hidden by any of the caps, by counting a fine grid
    /// of equal-area cells over the disc.
    fn union_by_counting(disc_rad: f64, caps: &[HidingCap]) -> f64 {
        let (rings, sectors) = (400, 400);
        let mut hidden = 0usize;
        for i in 0..rings {
            let cos_t = 1.0 - (i as f64 + 0.5) / rings as f64 * (1.0 - disc_rad.cos());
            let t = cos_t.clamp(-1.0, 1.0).acos();
            for j in 0..sectors {
                let d = toward(t, (j as f64 + 0.5) / sectors as f64 * 2.0 * PI);
                let inside = caps.iter().any(|c| d.dot(c.direction) > c.radius_rad.cos());
                hidden += usize::from(inside);
            }
        }
        hidden as f64 / (rings * sectors) as f64
    }

    #[test]
    fn one_disjoint_nested_and_identical_blockers_are_exact() {
        let disc = 5f64.to_radians();
        let deg = |x: f64| x.to_radians();
        let union = |caps: &[HidingCap]| union_of_hidden(DVec3::Z, caps, |_, _| disc);
        // One blocker: its own share.
        let one = cap(toward(deg(4.0), 0.0), deg(3.0), disc);
        assert_eq!(union(&[one]), one.hidden);
        // Two side by side, each over one half of the disc: the whole disc, where taking
        // them as independent leaves a quarter lit.
        let left = cap(toward(deg(90.0), 0.0), deg(90.0), disc);
        let right = cap(toward(deg(90.0), PI), deg(90.0), disc);
        assert!((left.hidden - 0.5).abs() < 1e-9, "{}", left.hidden);
        assert!((union(&[left, right]) - 1.0).abs() < 2e-3, "{}", union(&[left, right]));
        // The same cap twice, and a small cap inside a larger one (either order): the
        // larger share alone.
        let small = cap(toward(deg(3.0), 1.0), deg(1.0), disc);
        let large = cap(toward(deg(3.0), 1.0), deg(2.5), disc);
        assert!((union(&[one, one]) - one.hidden).abs() < 1e-12);
        assert!((union(&[small, large]) - large.hidden).abs() < 1e-9);
        assert!((union(&[large, small]) - large.hidden).abs() < 1e-9);
    }

    /// Against the counted union over random sets of two to four blockers across the light:
    /// far closer than taking the blockers as independent, and within a stated error.
    #[test]
    fn the_union_matches_counting_far_better_than_independent_shares() {
        let mut rng = SplitMix64(7);
        let (mut error_union, mut error_independent, mut worst_union) = (0.0f64, 0.0f64, 0.0f64);
        let trials = 150;
        for trial in 0..trials {
            let disc = (1.0 + 29.0 * rng.next_f64()).to_radians();
            let count = 2 + trial % 3;
            let caps: Vec<HidingCap> = (0..count)
                .map(|_| {
                    let radius = disc * (0.3 + 1.5 * rng.next_f64());
                    let from_centre = (disc + radius) * rng.next_f64();
                    cap(toward(from_centre, 2.0 * PI * rng.next_f64()), radius, disc)
                })
                .collect();
            let truth = union_by_counting(disc, &caps);
            let union = union_of_hidden(DVec3::Z, &caps, |_, _| disc);
            let independent = 1.0 - caps.iter().map(|c| 1.0 - c.hidden).product::<f64>();
            error_union += (union - truth).abs();
            error_independent += (independent - truth).abs();
            worst_union = worst_union.max((union - truth).abs());
        }
        let (mean_union, mean_independent) = (error_union / trials as f64, error_independent / trials as f64);
        eprintln!("mean error: union {mean_union:.4}, independent {mean_independent:.4}; worst union {worst_union:.4}");
        assert!(
            mean_union < 0.4 * mean_independent,
            "{mean_union} vs {mean_independent}"
        );
        assert!(mean_union < 0.01, "{mean_union}");
        assert!(worst_union < 0.1, "{worst_union}");
    }

    /// Laws for any caps: the union hides at least the largest share and at most the sum
    /// (and all of the disc), and another blocker never gives back light.
    #[test]
    fn the_union_lies_between_the_largest_share_and_the_sum_and_grows_with_each_blocker() {
        let mut rng = SplitMix64(11);
        for _ in 0..2000 {
            let disc = (0.01 + 60.0 * rng.next_f64()).to_radians();
            let caps: Vec<HidingCap> = (0..1 + rng.below(6))
                .map(|_| {
                    let radius = disc * (0.05 + 3.0 * rng.next_f64());
                    let from_centre = (disc + radius) * 1.2 * rng.next_f64();
                    let mut c = cap(toward(from_centre, 2.0 * PI * rng.next_f64()), radius, disc);
                    c.horizon = if rng.next_f64() < 0.3 { rng.next_f64() } else { 1.0 };
                    c.hidden *= c.horizon;
                    c
                })
                .collect();
            let mut last = 0.0;
            for n in 1..=caps.len() {
                let union = union_of_hidden(DVec3::Z, &caps[..n], |_, _| disc);
                let largest = caps[..n].iter().map(|c| c.hidden).fold(0.0, f64::max);
                let sum: f64 = caps[..n].iter().map(|c| c.hidden).sum();
                assert!(union.is_finite() && union >= largest - 1e-12, "{union} < {largest}");
                assert!(union <= sum.min(1.0) + 1e-12, "{union} > {sum}");
                assert!(
                    union >= last - 1e-12,
                    "a blocker more gave back light: {last} → {union}"
                );
                last = union;
            }
        }
    }
}
