//! Shadows beyond the SH band limit (shading-model.md §4b): for a light that subtends a small
//! angle, its visibility from a receiver is computed per light, exactly for each sphere
//! blocker — the share of the light's disc the blocker's cap hides ([`hidden_fraction`]) —
//! and combined over blockers as the share their union hides ([`union`]: blockers taken as
//! independent, Π_b(1 − f_b), would darken twice where two hide the same part of the
//! light, and too little where two hide its two halves).
//! The SH path cannot resolve such lights at any real-time order (§4b: 30–39 % penumbra
//! error for a 5° light at order 4); this path is exact for sphere blockers, at a cost per
//! light and blocker instead of per blocker.
//!
//! The blockers skipped are the SH path's ([`Sphere::cap_from`]): those that contain the
//! receiver, those with r/d under `min_cap_ratio`, and those below the tangent plane,
//! faded by the same smoothstep; and, as depth now matters, those wholly beyond the
//! light. `shaders/exact_lights.wgsl` (`exact_batch_visibility`) is the f32 twin. Given the width
//! of a pixel at the receiver, hard edges (point lights, and lights narrower than a pixel's
//! worth of angle) are anti-aliased by widening the light's disc to it, per blocker.

pub mod cap_overlap;
pub mod union;

pub use cap_overlap::hidden_fraction;
use union::{HidingCap, union_of_hidden};

use glam::DVec3;

use crate::blockers::Sphere;

/// A light as one receiver sees it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LightDisc {
    /// Unit direction from the receiver toward the light.
    pub to_light: DVec3,
    /// Distance to the light (infinite for directional lights).
    pub distance_m: f64,
    /// sin of the angular radius of the light's disc (0 for point-like lights).
    pub cap_ratio: f64,
    /// The emitter's shape about its centre, for the disc blockers' plane test.
    pub emitter: Emitter,
}

/// A light's emitter about its centre: how far it reaches along an axis is what decides
/// whether it lies wholly on one side of a disc blocker's plane
/// ([`crate::blockers::disc::disc_plane_between`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Emitter {
    /// A point, or a sphere of this radius.
    Sphere { radius_m: f64 },
    /// A rect of these half extents (vectors in its plane).
    Rect { half_width_m: DVec3, half_height_m: DVec3 },
    /// A disk of this radius facing unit `normal`.
    Disk { radius_m: f64, normal: DVec3 },
    /// A directional light: at infinity, no extent in metres.
    AtInfinity,
}

impl Emitter {
    /// How far the emitter reaches from its centre along unit `axis` (its support), None
    /// at infinity: a sphere's radius, a rect's |w·a| + |h·a|, a disk's r·√(1 − (n·a)²).
    /// The same in scene.wgsl (`emitter_support_m`).
    pub fn support_m(&self, axis: DVec3) -> Option<f64> {
        match *self {
            Emitter::Sphere { radius_m } => Some(radius_m),
            Emitter::Rect {
                half_width_m,
                half_height_m,
            } => Some(half_width_m.dot(axis).abs() + half_height_m.dot(axis).abs()),
            Emitter::Disk { radius_m, normal } => Some(radius_m * (1.0 - normal.dot(axis).powi(2)).max(0.0).sqrt()),
            Emitter::AtInfinity => None,
        }
    }
}

/// Visibility (0–1) from `p` (unit normal `n`) of `light` through `spheres` and `discs`.
///
/// The spheres' shares of the light's disc combine as their union ([`union`], in the
/// order given: the GPU's, `blocker_groups`); the discs' multiply in after, as
/// independent (the shader takes them in a loop of their own), each only where the light
/// is not wholly on the receiver's side of its plane
/// ([`crate::blockers::disc::disc_plane_between`]).
///
/// `pixel_footprint_m`, the width of one pixel at `p` (0: none), anti-aliases hard edges:
/// against a blocker at distance d the disc's sine is taken at least footprint/(2d),
/// about the angle over which one pixel's step across the receiver turns the blocker's
/// direction, so a point light's shadow edge ramps over about one pixel instead of
/// stepping. Two spheres' overlap is measured on the wider of their two discs.
pub fn light_visibility(
    p: DVec3,
    n: DVec3,
    light: &LightDisc,
    spheres: &[Sphere],
    discs: &[Sphere],
    min_cap_ratio: f64,
    pixel_footprint_m: f64,
) -> f64 {
    let sin_light = light.cap_ratio.clamp(0.0, 1.0);
    let disc_sine_at = |distance_m: f64| sin_light.max(0.5 * pixel_footprint_m / distance_m).min(1.0);
    let hides = |b: &Sphere| -> Hides {
        let Some(cap) = b.cap_from(p, n, min_cap_ratio) else {
            return Hides::Nothing;
        };
        if cap.distance_m - b.radius_m as f64 >= light.distance_m {
            return Hides::Nothing; // wholly beyond the light
        }
        let radius_rad = cap.ratio.asin();
        let separation = union::angle_between(cap.direction, light.to_light);
        let disc_rad = disc_sine_at(cap.distance_m).asin();
        let hidden = cap.horizon * hidden_fraction(disc_rad, radius_rad, separation);
        if hidden >= 1.0 {
            Hides::All
        } else if hidden > 0.0 {
            Hides::Part(HidingCap {
                direction: cap.direction,
                radius_rad,
                horizon: cap.horizon,
                distance_m: cap.distance_m,
                hidden,
            })
        } else {
            Hides::Nothing
        }
    };
    let mut caps = Vec::new();
    for b in spheres {
        match hides(b) {
            Hides::All => return 0.0,
            Hides::Part(cap) => caps.push(cap),
            Hides::Nothing => {}
        }
    }
    let hidden_by_spheres = union_of_hidden(light.to_light, &caps, |a, b| {
        disc_sine_at(a.distance_m.min(b.distance_m)).asin()
    });
    let mut visibility = 1.0 - hidden_by_spheres;
    for b in discs {
        let (center, normal) = (b.center.as_dvec3(), b.disc_normal.as_dvec3());
        let support_m = light.emitter.support_m(normal);
        if !crate::blockers::disc::disc_plane_between(
            center,
            normal,
            p,
            light.to_light,
            light.distance_m,
            sin_light,
            support_m,
        ) {
            continue; // the light is on the receiver's side of the disc's plane
        }
        match hides(b) {
            Hides::All => return 0.0,
            Hides::Part(cap) => visibility *= 1.0 - cap.hidden,
            Hides::Nothing => {}
        }
    }
    visibility
}

/// What one blocker does to the light's disc as the receiver sees it.
enum Hides {
    Nothing,
    Part(HidingCap),
    All,
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::Vec3;

    /// A light straight up (+y) at 3 m with the disc of sin(angular radius) `cap_ratio`.
    fn overhead(cap_ratio: f64) -> LightDisc {
        LightDisc {
            to_light: DVec3::Y,
            distance_m: 3.0,
            cap_ratio,
            emitter: Emitter::Sphere {
                radius_m: 3.0 * cap_ratio,
            },
        }
    }

    #[test]
    fn a_blocker_behind_the_light_or_below_the_horizon_hides_nothing() {
        let ball = [Sphere {
            center: Vec3::new(0.0, 5.0, 0.0),
            radius_m: 0.5,
            disc_normal: glam::Vec3::ZERO,
        }];
        // The light at 3 m, the ball beyond it at 5 m.
        assert_eq!(
            light_visibility(DVec3::ZERO, DVec3::Y, &overhead(0.1), &ball, &[], 0.0, 0.0),
            1.0
        );
        // A ball under the floor.
        let under = [Sphere {
            center: Vec3::new(0.0, -2.0, 0.0),
            radius_m: 0.5,
            disc_normal: glam::Vec3::ZERO,
        }];
        assert_eq!(
            light_visibility(DVec3::ZERO, DVec3::Y, &overhead(0.1), &under, &[], 0.0, 0.0),
            1.0
        );
        // A ball between covering the whole light: nothing arrives, no light leaks.
        let cover = [Sphere {
            center: Vec3::new(0.0, 1.0, 0.0),
            radius_m: 0.5,
            disc_normal: glam::Vec3::ZERO,
        }];
        assert_eq!(
            light_visibility(DVec3::ZERO, DVec3::Y, &overhead(0.05), &cover, &[], 0.0, 0.0),
            0.0
        );
    }
}
