//! Shadows beyond the SH band limit (design.md §4b): for a light that subtends a small
//! angle, its visibility from a receiver is computed per light, exactly for each sphere
//! blocker — the share of the light's disc the blocker's cap hides ([`hidden_fraction`]) —
//! and combined over blockers in log space, ln V = Σ_b ln(1 − f_b) (blockers are taken as
//! independent: where two hide the same part of the light, the product over-darkens).
//! The SH path cannot resolve such lights at any real-time order (§4b: 30–39 % penumbra
//! error for a 5° light at order 4); this path is exact for sphere blockers, at a cost per
//! light and blocker instead of per blocker.
//!
//! The blockers skipped are the SH path's ([`Sphere::cap_from`]): those that contain the
//! receiver, those with r/d under `min_cap_ratio`, and those below the tangent plane,
//! faded by the same smoothstep; and, as depth now matters, those wholly beyond the
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
        let Some(cap) = b.cap_from(p, n, min_cap_ratio) else {
            continue;
        };
        if cap.distance_m - b.radius_m as f64 >= light_distance_m {
            continue; // wholly beyond the light
        }
        let separation = cap
            .direction
            .cross(to_light)
            .length()
            .atan2(cap.direction.dot(to_light));
        let hidden = cap.horizon * hidden_fraction(light_rad, cap.ratio.asin(), separation);
        if hidden >= 1.0 {
            return 0.0;
        }
        log_visibility += (1.0 - hidden).ln();
    }
    log_visibility.exp()
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::Vec3;

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
