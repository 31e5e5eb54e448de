//! Shadows beyond the SH band limit (design.md §4b): for a light that subtends a small
//! angle, its visibility from a receiver is computed per light, exactly for each sphere
//! blocker — the share of the light's disc the blocker's cap hides ([`hidden_fraction`]) —
//! and combined over blockers in log space, ln V = Σ_b ln(1 − f_b) (blockers are taken as
//! independent: where two hide the same part of the light, the product over-darkens).
//! The SH path cannot resolve such lights at any real-time order (§4b: 30–39 % penumbra
//! error for a 5° light at order 4); this path is exact for sphere blockers, at a cost per
//! light and blocker instead of per blocker.
//!
//! The blockers skipped are the SH path's (`render::cpu::log_visibility`): those that
//! contain the receiver, those with r/d under `min_cap_ratio`, and those below the tangent
//! plane, faded by the same smoothstep; and, as depth now matters, those wholly beyond the
//! light. `shaders/logsh.wgsl` (`exact_light_visibility`) is the f32 twin.

pub mod cap_overlap;

pub use cap_overlap::hidden_fraction;

use glam::DVec3;

use crate::blockers::Sphere;

/// Visibility (0–1) from `p` (unit normal `n`) of a light in unit direction `to_light`,
/// `light_distance_m` away (infinite for directional lights), whose disc has
/// sin(angular radius) `cap_ratio`, through `blockers`.
pub fn light_visibility(
    p: DVec3,
    n: DVec3,
    to_light: DVec3,
    light_distance_m: f64,
    cap_ratio: f64,
    blockers: &[Sphere],
    min_cap_ratio: f64,
) -> f64 {
    let light_rad = cap_ratio.clamp(0.0, 1.0).asin();
    let mut log_visibility = 0.0;
    for b in blockers {
        let offset = b.center.as_dvec3() - p;
        let radius = b.radius_m as f64;
        let distance2 = offset.length_squared();
        if distance2 <= radius * radius {
            continue;
        }
        let distance = distance2.sqrt();
        let ratio = radius / distance;
        let horizon = smoothstep(-1.0, 1.0, offset.dot(n) / radius);
        if ratio < min_cap_ratio || horizon <= 0.0 || distance - radius >= light_distance_m {
            continue;
        }
        let direction = offset / distance;
        let separation = direction.cross(to_light).length().atan2(direction.dot(to_light));
        let hidden = horizon * hidden_fraction(light_rad, ratio.asin(), separation);
        if hidden >= 1.0 {
            return 0.0;
        }
        log_visibility += (1.0 - hidden).ln();
    }
    log_visibility.exp()
}

fn smoothstep(edge0: f64, edge1: f64, x: f64) -> f64 {
    let t = ((x - edge0) / (edge1 - edge0)).clamp(0.0, 1.0);
    t * t * (3.0 - 2.0 * t)
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::Vec3;

    /// A ball of radius r at height h over the origin under a sphere light straight above:
    /// along a line through the penumbra, the visibility is 1 − the exact hidden share,
    /// which a fine Monte Carlo-free integration over the light's disc confirms.
    #[test]
    fn a_ball_over_a_plane_casts_the_exact_penumbra() {
        let ball = [Sphere {
            center: Vec3::new(0.0, 1.0, 0.0),
            radius_m: 0.3,
        }];
        let light = DVec3::new(0.0, 3.0, 0.0);
        let light_radius = 0.5;
        let mut last = 0.0;
        for k in 0..=40 {
            let p = DVec3::new(k as f64 * 0.05, 0.0, 0.0);
            let offset = light - p;
            let d = offset.length();
            let v = light_visibility(p, DVec3::Y, offset / d, d, light_radius / d, &ball, 0.0);
            // Independent: the share of the light's disc (sampled on a fine polar grid of
            // its solid angle) whose direction meets the ball.
            let expected = 1.0 - disc_share_hidden(p, light, light_radius, DVec3::new(0.0, 1.0, 0.0), 0.3);
            assert!((v - expected).abs() < 3e-3, "x = {:.2}: {v} vs {expected}", p.x);
            assert!(v >= last - 1e-9, "visibility rises away from the ball");
            last = v;
        }
        assert!(last > 0.999, "far points see the whole light");
    }

    /// Share of the light's cap (as seen from p) whose rays toward it meet the ball.
    fn disc_share_hidden(p: DVec3, light: DVec3, light_radius: f64, centre: DVec3, radius: f64) -> f64 {
        let axis = (light - p).normalize();
        let half_angle = (light_radius / (light - p).length()).asin();
        let (t, b) = axis.any_orthonormal_pair();
        let (rings, sectors) = (600, 600);
        let mut hidden = 0usize;
        for i in 0..rings {
            let cos_t = 1.0 - (i as f64 + 0.5) / rings as f64 * (1.0 - half_angle.cos());
            let sin_t = (1.0 - cos_t * cos_t).sqrt();
            for j in 0..sectors {
                let phi = (j as f64 + 0.5) / sectors as f64 * std::f64::consts::TAU;
                let d = axis * cos_t + (t * phi.cos() + b * phi.sin()) * sin_t;
                // Does the ray p + s·d meet the ball?
                let oc = p - centre;
                let half_b = oc.dot(d);
                let c = oc.length_squared() - radius * radius;
                hidden += usize::from(half_b * half_b - c >= 0.0 && half_b < 0.0);
            }
        }
        hidden as f64 / (rings * sectors) as f64
    }

    #[test]
    fn a_blocker_behind_the_light_or_below_the_horizon_hides_nothing() {
        let ball = [Sphere {
            center: Vec3::new(0.0, 5.0, 0.0),
            radius_m: 0.5,
        }];
        // The light at 3 m, the ball beyond it at 5 m.
        assert_eq!(
            light_visibility(DVec3::ZERO, DVec3::Y, DVec3::Y, 3.0, 0.1, &ball, 0.0),
            1.0
        );
        // A ball under the floor.
        let under = [Sphere {
            center: Vec3::new(0.0, -2.0, 0.0),
            radius_m: 0.5,
        }];
        assert_eq!(
            light_visibility(DVec3::ZERO, DVec3::Y, DVec3::Y, 3.0, 0.1, &under, 0.0),
            1.0
        );
        // A ball between covering the whole light: nothing arrives, no light leaks.
        let cover = [Sphere {
            center: Vec3::new(0.0, 1.0, 0.0),
            radius_m: 0.5,
        }];
        assert_eq!(
            light_visibility(DVec3::ZERO, DVec3::Y, DVec3::Y, 3.0, 0.05, &cover, 0.0),
            0.0
        );
    }
}
