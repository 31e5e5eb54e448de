//! The log-visibility each SH-path light and the environment read at a point
//! (`harmonic_radiance` and `add_cap` in logsh.wgsl, `PER_LIGHT_VISIBILITY`).
//!
//! Where a point opens light windows (`shading::light_windows`: at most eight SH lights,
//! four under an environment, or past that many the few that reach it) each of those
//! lights reads the visibility over its own cap alone. Weighing every blocker by the largest weight any window gives it, and
//! summing those caps into one log-visibility that all the lights read, made each light
//! read the log-visibility its neighbours' blockers spread over the band limit's width:
//! with a few lights spread over the sky each dimmed the others' lit ground and blurred
//! their penumbrae. So each windowed light reads a log-visibility of its own, the
//! blockers weighed by its window alone (one exponentiation per light). An environment
//! lights the point from the whole sky and reads the visibility of every blocker at k(s)
//! (no window); before the lights had their own, its presence took the windows away from
//! the lights too, and their lit ground was dragged down by every blocker's ringing.
//!
//! Measured against exact visibility of the same spheres (`tests/sh_against_exact.rs`;
//! docs/performance.md, "Each windowed SH light reads its own visibility").

use glam::DVec3;

use super::LightWindows;
use super::visibility::scene_log_visibilities;
use crate::blockers::Sphere;
use crate::shading::ShadowSettings;
use crate::shading::gpu_types::{GpuLight, irradiance_lights};
use crate::shading::light_windows::light_window_indices;
use crate::terrain::TerrainShadow;

/// What the SH-path lights and the environment read at a point.
#[derive(Debug, Clone, PartialEq)]
pub struct HarmonicVisibility<T> {
    /// The visibility of every blocker at k(s), which the environment reads, and every SH
    /// light where no window opens; None where windows open and no environment lights
    /// the frame (nothing reads it).
    pub shared: Option<T>,
    /// Where windows open, each windowed light's own (its index among the frame's
    /// lights): the SH lights not listed add nothing at the point (out of range or cone).
    pub per_light: Option<Vec<(usize, T)>>,
}

impl<T> HarmonicVisibility<T> {
    /// What light `index` reads: its own where windows open (None: it is not one of the
    /// point's windowed lights), else the shared visibility.
    pub fn of_light(&self, index: usize) -> Option<&T> {
        match &self.per_light {
            Some(own) => own.iter().find(|(i, _)| *i == index).map(|(_, v)| v),
            None => self.shared.as_ref(),
        }
    }

    /// Each visibility mapped by `f`.
    pub fn map<U>(&self, mut f: impl FnMut(&T) -> U) -> HarmonicVisibility<U> {
        HarmonicVisibility {
            shared: self.shared.as_ref().map(&mut f),
            per_light: self
                .per_light
                .as_ref()
                .map(|own| own.iter().map(|(i, v)| (*i, f(v))).collect()),
        }
    }
}

/// The log-visibility (blockers and terrain, `scene_log_visibility`) the SH lights among
/// `lights` and the environment of irradiance `environment_irradiance` (order-3 SH,
/// `Frame::environment_irradiance`) read at `p` with normal `n`: where the point opens
/// windows, one per windowed light, its blockers weighed by its own window, and with an
/// environment the unweighed one (k(s) on every cap) for it; elsewhere the unweighed one
/// for all.
pub fn harmonic_log_visibility(
    settings: &ShadowSettings,
    blockers: &[Sphere],
    terrain: Option<&TerrainShadow>,
    environment_irradiance: &[[f32; 4]; 9],
    lights: &[GpuLight],
    p: DVec3,
    n: DVec3,
) -> HarmonicVisibility<Vec<f64>> {
    let environment = irradiance_lights(environment_irradiance);
    let indices = light_window_indices(lights, environment, p);
    let windows: Vec<(usize, LightWindows)> = indices
        .iter()
        .flatten()
        .map(|&i| (i, LightWindows::at(&lights[i..=i], p, settings.order)))
        .collect();
    let read_by_all = indices.is_none() || environment;
    // One walk for every reader, as the shaders' (each light's window, then the walk's
    // own for the environment or every light).
    let mut readers: Vec<Option<&LightWindows>> = windows.iter().map(|(_, w)| Some(w)).collect();
    if read_by_all {
        readers.push(None);
    }
    let mut sums = scene_log_visibilities(settings, blockers, terrain, p, n, &readers);
    let shared = read_by_all.then(|| sums.pop().expect("the walk's own sum"));
    HarmonicVisibility {
        shared,
        per_light: indices.map(|_| windows.iter().map(|(i, _)| *i).zip(sums).collect()),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::shading::cpu::scene_log_visibility;
    use crate::shading::gpu_types::SHADOW_PATH_SH;

    fn lamp(x: f32) -> GpuLight {
        GpuLight::new(&crate::scene::Light {
            name: "lamp".into(),
            kind: crate::scene::LightKind::Point,
            color: glam::Vec3::ONE,
            intensity: 1.0,
            position: glam::Vec3::new(x, 2.0, 0.0),
            direction: glam::Vec3::NEG_Y,
            range: None,
            locked: false,
        })
    }

    fn sphere(x: f32) -> Sphere {
        Sphere::ball(glam::Vec3::new(x, 1.0, 0.0), 0.2)
    }

    /// Under two lamps, a sphere under the first shadows the first's visibility and leaves
    /// the second's as if it were not there (outside its window), and with one lamp the
    /// per-light visibility is the windowed one the whole frame read before.
    #[test]
    fn each_light_reads_the_blockers_in_its_own_window() {
        let settings = ShadowSettings::default();
        let dark = [[0.0; 4]; 9];
        let lamps = [lamp(0.0), lamp(3.0)];
        assert!(lamps.iter().all(|l| l.shadow_path == SHADOW_PATH_SH));
        let p = DVec3::ZERO;
        let visibility = harmonic_log_visibility(&settings, &[sphere(0.0)], None, &dark, &lamps, p, DVec3::Y);
        assert!(visibility.shared.is_none(), "no environment: nothing reads it");
        let under = visibility.of_light(0).expect("the first lamp's");
        let beside = visibility.of_light(1).expect("the second lamp's");
        assert!(under[0] < 0.0, "the sphere hides the first lamp: {}", under[0]);
        assert!(beside.iter().all(|c| *c == 0.0), "{beside:?}");
        let alone = harmonic_log_visibility(&settings, &[sphere(0.0)], None, &dark, &lamps[..1], p, DVec3::Y);
        let windows = LightWindows::at(&lamps[..1], p, settings.order);
        let windowed = scene_log_visibility(&settings, &[sphere(0.0)], None, p, DVec3::Y, Some(&windows));
        assert_eq!(alone.of_light(0), Some(&windowed));
    }

    /// Under a sky the environment reads every blocker at k(s), and each lamp still its
    /// own windowed visibility.
    #[test]
    fn with_an_environment_it_reads_the_unweighed_visibility_and_each_light_its_own() {
        let settings = ShadowSettings::default();
        let mut sky = [[0.0; 4]; 9];
        sky[0] = [0.2, 0.3, 0.4, 0.0];
        let lamps = [lamp(0.0), lamp(3.0)];
        let p = DVec3::ZERO;
        let visibility = harmonic_log_visibility(&settings, &[sphere(3.0)], None, &sky, &lamps, p, DVec3::Y);
        let unweighed = scene_log_visibility(&settings, &[sphere(3.0)], None, p, DVec3::Y, None);
        assert_eq!(visibility.shared.as_ref(), Some(&unweighed));
        let windows = LightWindows::at(&lamps[1..], p, settings.order);
        let own = scene_log_visibility(&settings, &[sphere(3.0)], None, p, DVec3::Y, Some(&windows));
        assert_eq!(visibility.of_light(1), Some(&own));
        assert!(
            visibility
                .of_light(0)
                .expect("the first lamp's")
                .iter()
                .all(|c| *c == 0.0),
            "the sphere lies outside the first lamp's window"
        );
        assert!(unweighed[0] < 0.0, "the sky sees it");
    }

    /// Five SH lights each read their own visibility; past eight that all reach a point
    /// no window opens and every reader shares the unweighed visibility.
    #[test]
    fn up_to_eight_lights_read_their_own_past_eight_every_reader_shares_one() {
        use crate::shading::light_windows::MAX_WINDOW_LIGHTS;
        let settings = ShadowSettings::default();
        let dark = [[0.0; 4]; 9];
        let p = DVec3::ZERO;
        let five: Vec<GpuLight> = (0..5).map(|k| lamp(k as f32)).collect();
        let visibility = harmonic_log_visibility(&settings, &[sphere(0.0)], None, &dark, &five, p, DVec3::Y);
        assert!(visibility.shared.is_none());
        for i in 0..5 {
            let windows = LightWindows::at(&five[i..=i], p, settings.order);
            let own = scene_log_visibility(&settings, &[sphere(0.0)], None, p, DVec3::Y, Some(&windows));
            assert_eq!(visibility.of_light(i), Some(&own), "lamp {i}");
        }
        let many: Vec<GpuLight> = (0..=MAX_WINDOW_LIGHTS).map(|k| lamp(k as f32)).collect();
        let visibility = harmonic_log_visibility(&settings, &[sphere(3.0)], None, &dark, &many, p, DVec3::Y);
        let unweighed = scene_log_visibility(&settings, &[sphere(3.0)], None, p, DVec3::Y, None);
        assert!(visibility.per_light.is_none());
        for i in 0..many.len() {
            assert_eq!(visibility.of_light(i), Some(&unweighed));
        }
    }
}
