//! The f64 twin of the SH lights' windows on the blockers (`shading::light_windows`, whose
//! documentation says what they are and why): each light's window at a receiver and the
//! factor each blocker cap takes from them (`open_light_windows`, `window_weight` and
//! `windowed_cap_scale` in logsh.wgsl).

use std::f64::consts::PI;

use glam::DVec3;

use super::{
    area::{bounding_radius_m, emitter},
    incidence,
};
use crate::shading::gpu_types::{GpuLight, SHADOW_PATH_SH};

/// A light's window at a receiver: the unit direction toward the light, the half-angle
/// (radians) of a cap holding its whole emitter, and the gain by which a cap's k(s)
/// grows inside it, max(1, (4π/n²)/Ω) for Ω that cap's solid angle.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LightWindow {
    pub toward: DVec3,
    pub half_angle_rad: f64,
    pub mass_gain: f64,
    /// The light's distance, the sine of its angular radius and its emitter, for the disc
    /// blockers' plane test ([`LightWindow::may_be_hidden_by_disc`]); None: every disc may
    /// hide it.
    pub light: Option<(f64, f64, crate::penumbra::Emitter)>,
}

impl LightWindow {
    /// A cap of `half_angle_rad` toward `toward` at SH order `order`.
    pub fn new(toward: DVec3, half_angle_rad: f64, order: usize) -> LightWindow {
        let solid_angle_sr = 2.0 * PI * (1.0 - half_angle_rad.cos());
        let band_sr = 4.0 * PI / (order * order).max(1) as f64;
        LightWindow {
            toward,
            half_angle_rad,
            mass_gain: (band_sr / solid_angle_sr.max(1e-12)).max(1.0),
            light: None,
        }
    }

    /// Whether a disc blocker at `center` with unit `normal` may stand between `p` and
    /// this window's light (`blockers::disc::disc_plane_between`; the shaders'
    /// `disc_window_mask`): a disc that cannot weighs nothing in the window's sum, as on
    /// the exact path.
    pub fn may_be_hidden_by_disc(&self, center: DVec3, normal: DVec3, p: DVec3) -> bool {
        let Some((distance_m, sin_light, emitter)) = self.light else {
            return true;
        };
        crate::blockers::disc::disc_plane_between(
            center,
            normal,
            p,
            self.toward,
            distance_m,
            sin_light,
            emitter.support_m(normal),
        )
    }

    /// The weight this window gives a blocker cap of half-angle `half_angle_rad` toward
    /// unit `direction`: 1 while the cap's centre lies within half its angular radius of
    /// the window's rim (θ ≤ α + β/2, θ the angle between the two centres, α the
    /// window's half-angle, β the cap's), 0 from a gap of half its angular radius between
    /// the two caps on (θ ≥ α + 3β/2), smoothstep in cos θ between (the shaders take
    /// those cosines by angle-sum formulas: no inverse trigonometry per blocker).
    pub fn weight(&self, direction: DVec3, half_angle_rad: f64) -> f64 {
        let cos_at = |angle: f64| angle.min(PI).cos();
        let whole = cos_at(self.half_angle_rad + 0.5 * half_angle_rad);
        let none = cos_at(self.half_angle_rad + 1.5 * half_angle_rad);
        let cos_between = direction.dot(self.toward).clamp(-1.0, 1.0);
        if none >= whole {
            return if cos_between >= whole { 1.0 } else { 0.0 };
        }
        smoothstep(none, whole, cos_between)
    }
}

/// The windows of a receiver's SH-path lights.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct LightWindows {
    pub windows: Vec<LightWindow>,
}

impl LightWindows {
    /// The windows at `p` of the SH-path lights among `lights`, at SH order `order`: each
    /// light's cap as seen from p, sized to hold its whole emitter (a rect's corners, a
    /// sphere's or a disk's rim), not the equal-solid-angle cap its shading uses.
    pub fn at(lights: &[GpuLight], p: DVec3, order: usize) -> LightWindows {
        let windows = lights
            .iter()
            .filter(|light| light.shadow_path == SHADOW_PATH_SH)
            .map(|light| {
                let inc = incidence(light, p);
                let bound = bounding_radius_m(light) / inc.distance_m.max(1e-300);
                LightWindow {
                    light: Some((inc.distance_m, inc.cap_ratio.clamp(0.0, 1.0), emitter(light))),
                    ..LightWindow::new(inc.to_light, inc.cap_ratio.max(bound).clamp(0.0, 1.0).asin(), order)
                }
            })
            .collect();
        LightWindows { windows }
    }

    /// The factor on the log-visibility ln ε·f_n of a blocker cap of sine `ratio` toward
    /// unit `direction`, whose cap-mass scale is `mass_scale` (k(s)): the largest
    /// weight × min(1, k(s) · gain) of any window (see the module's documentation).
    pub fn cap_scale(&self, direction: DVec3, ratio: f64, mass_scale: f64) -> f64 {
        self.disc_cap_scale(direction, ratio, mass_scale, None)
    }

    /// [`Self::cap_scale`] for a cap that may be a disc blocker's: `disc` its centre and
    /// unit normal and the receiver, and then windows whose light it cannot hide
    /// ([`LightWindow::may_be_hidden_by_disc`]) give it no weight.
    pub fn disc_cap_scale(
        &self,
        direction: DVec3,
        ratio: f64,
        mass_scale: f64,
        disc: Option<(DVec3, DVec3, DVec3)>,
    ) -> f64 {
        let half_angle = ratio.clamp(0.0, 1.0).asin();
        self.windows
            .iter()
            .filter(|w| disc.is_none_or(|(center, normal, p)| w.may_be_hidden_by_disc(center, normal, p)))
            .map(|w| w.weight(direction, half_angle) * (mass_scale * w.mass_gain).min(1.0))
            .fold(0.0, f64::max)
    }
}

/// WGSL's smoothstep.
fn smoothstep(low: f64, high: f64, x: f64) -> f64 {
    let t = ((x - low) / (high - low)).clamp(0.0, 1.0);
    t * t * (3.0 - 2.0 * t)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn window(half_angle_deg: f64) -> LightWindow {
        LightWindow::new(DVec3::Y, half_angle_deg.to_radians(), 4)
    }

    fn toward(angle_deg: f64) -> DVec3 {
        let a = angle_deg.to_radians();
        DVec3::new(a.sin(), a.cos(), 0.0)
    }

    #[test]
    fn a_cap_whose_centre_is_in_the_light_counts_whole_and_a_far_one_not_at_all() {
        let w = window(10.0);
        let half_angle = 5f64.to_radians();
        assert_eq!(w.weight(toward(0.0), half_angle), 1.0);
        // Centre within half its radius (2.5°) of the light's rim: whole.
        assert_eq!(w.weight(toward(12.4), half_angle), 1.0);
        // A gap of half its radius between the caps: nothing.
        assert_eq!(w.weight(toward(17.6), half_angle), 0.0);
        assert_eq!(w.weight(toward(90.0), half_angle), 0.0);
        assert_eq!(w.weight(toward(180.0), half_angle), 0.0);
    }

    #[test]
    fn the_weight_falls_smoothly_and_steadily_across_the_caps_touching() {
        let w = window(10.0);
        let half_angle = 5f64.to_radians();
        let weights: Vec<f64> = (0..=200)
            .map(|k| w.weight(toward(12.0 + 0.03 * k as f64), half_angle))
            .collect();
        for pair in weights.windows(2) {
            assert!(
                pair[1] <= pair[0],
                "the weight never rises as the cap moves away: {pair:?}"
            );
            assert!(pair[0] - pair[1] < 0.03, "no step: {pair:?}");
        }
        // Where the caps just touch (15°), part way down the ramp.
        let touching = w.weight(toward(15.0), half_angle);
        assert!(touching > 0.3 && touching < 0.7, "{touching}");
    }

    #[test]
    fn the_gain_is_the_band_over_the_window_and_never_below_one() {
        // Order 4: the band's width 4π/16 sr; a 10° cap holds 2π(1 − cos 10°) sr.
        let w = window(10.0);
        let expected = (4.0 * PI / 16.0) / (2.0 * PI * (1.0 - 10f64.to_radians().cos()));
        assert!((w.mass_gain - expected).abs() < 1e-9 * expected);
        assert_eq!(LightWindow::new(DVec3::Y, 80f64.to_radians(), 4).mass_gain, 1.0);
        // The scale never passes the cap's own log-visibility, nor falls below k(s).
        let windows = LightWindows { windows: vec![w] };
        assert_eq!(windows.cap_scale(DVec3::Y, 0.05, 0.39), 1.0);
        let wide = LightWindows {
            windows: vec![LightWindow::new(DVec3::Y, 80f64.to_radians(), 4)],
        };
        assert_eq!(wide.cap_scale(DVec3::Y, 0.05, 0.39), 0.39);
    }

    #[test]
    fn each_light_opens_its_own_window() {
        let windows = LightWindows {
            windows: vec![LightWindow::new(DVec3::Y, 0.1, 4), LightWindow::new(DVec3::X, 0.1, 4)],
        };
        assert_eq!(windows.cap_scale(DVec3::Y, 0.05, 1.0), 1.0);
        assert_eq!(windows.cap_scale(DVec3::X, 0.05, 1.0), 1.0);
        assert_eq!(windows.cap_scale(DVec3::Z, 0.05, 1.0), 0.0);
    }

    #[test]
    fn a_rect_lights_window_holds_its_corners() {
        // The bench's 1.2 m × 0.8 m panel, 3.2 m above the floor, facing down.
        let panel = &crate::samples::blocker_bench::thin_casters_scene().lights[0];
        let below = DVec3::new(0.3, 0.0, 0.6);
        assert!((panel.position.as_dvec3() - below - 3.2 * DVec3::Y).length() < 1e-6);
        let windows = LightWindows::at(&[GpuLight::new(panel)], below, 4);
        let w = windows.windows[0];
        assert!((w.toward - DVec3::Y).length() < 1e-6);
        // Half diagonal √(0.6² + 0.4²) at 3.2 m.
        let expected = (0.52f64.sqrt() / 3.2).asin();
        assert!(
            (w.half_angle_rad - expected).abs() < 1e-6,
            "{} vs {expected}",
            w.half_angle_rad
        );
    }
}
