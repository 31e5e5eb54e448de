//! The log-visibility each SH-path light reads at a point (`harmonic_radiance` and
//! `add_cap` in logsh.wgsl, `PER_LIGHT_VISIBILITY`).
//!
//! Where the light windows apply (`shading::light_windows`: no environment, and a point
//! that opens the windows of at most four SH lights) every reader of the visibility is
//! one of those lights, and each reads it over its own cap alone. Weighing every blocker
//! by the largest weight any window gives it, and summing those caps into one
//! log-visibility that all the lights read, makes a light read the log-visibility its
//! neighbours' blockers spread over the band limit's width: with a few lights spread
//! over the sky each dims the others' lit ground and blurs their penumbrae. So each
//! windowed light reads a log-visibility of its own, the blockers weighed by its window
//! alone (one exponentiation per light). With one window the two are the same.
//!
//! Measured against exact visibility of the same spheres under several panels
//! (`tests/sh_against_exact.rs`, the ignored
//! `measure_the_sh_path_against_exact_visibility_under_several_panels`;
//! docs/performance.md): see the table there.

use glam::DVec3;

use super::LightWindows;
use super::visibility::scene_log_visibility;
use crate::blockers::Sphere;
use crate::shading::ShadowSettings;
use crate::shading::gpu_types::GpuLight;
use crate::shading::light_windows::windowed_light_indices;
use crate::terrain::TerrainShadow;

/// What the SH-path lights and the environment read at a point: one visibility for all,
/// or one per windowed light.
#[derive(Debug, Clone, PartialEq)]
pub enum HarmonicVisibility<T> {
    /// No window applies: the environment and every SH light read this one.
    Shared(T),
    /// Windows apply: each light (its index among the frame's lights) reads its own; the
    /// SH lights not listed add nothing at the point (out of range or cone), and no
    /// environment lights the frame.
    PerLight(Vec<(usize, T)>),
}

impl<T> HarmonicVisibility<T> {
    /// What light `index` reads: the shared visibility, or its own (None: it is not one of
    /// the point's windowed lights).
    pub fn of_light(&self, index: usize) -> Option<&T> {
        match self {
            HarmonicVisibility::Shared(shared) => Some(shared),
            HarmonicVisibility::PerLight(own) => own.iter().find(|(i, _)| *i == index).map(|(_, v)| v),
        }
    }

    /// The visibility the environment reads (None: per light, where no environment lights
    /// the frame).
    pub fn shared(&self) -> Option<&T> {
        match self {
            HarmonicVisibility::Shared(shared) => Some(shared),
            HarmonicVisibility::PerLight(_) => None,
        }
    }

    /// Each visibility mapped by `f`.
    pub fn map<U>(&self, mut f: impl FnMut(&T) -> U) -> HarmonicVisibility<U> {
        match self {
            HarmonicVisibility::Shared(shared) => HarmonicVisibility::Shared(f(shared)),
            HarmonicVisibility::PerLight(own) => {
                HarmonicVisibility::PerLight(own.iter().map(|(i, v)| (*i, f(v))).collect())
            }
        }
    }
}

/// The log-visibility (blockers and terrain, `scene_log_visibility`) the SH lights among
/// `lights` read at `p` with normal `n`, with the environment's irradiance
/// `environment_irradiance` (order-3 SH, `Frame::environment_irradiance`): without windows
/// one, unweighed (k(s) on every cap); with them one per windowed light, its blockers
/// weighed by its own window.
pub fn harmonic_log_visibility(
    settings: &ShadowSettings,
    blockers: &[Sphere],
    terrain: Option<&TerrainShadow>,
    environment_irradiance: &[[f32; 4]; 9],
    lights: &[GpuLight],
    p: DVec3,
    n: DVec3,
) -> HarmonicVisibility<Vec<f64>> {
    let log_visibility =
        |windows: Option<&LightWindows>| scene_log_visibility(settings, blockers, terrain, p, n, windows);
    match windowed_light_indices(environment_irradiance, lights, p) {
        None => HarmonicVisibility::Shared(log_visibility(None)),
        Some(indices) => HarmonicVisibility::PerLight(
            indices
                .into_iter()
                .map(|i| {
                    let windows = LightWindows::at(&lights[i..=i], p, settings.order);
                    (i, log_visibility(Some(&windows)))
                })
                .collect(),
        ),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
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
        assert!(visibility.shared().is_none());
        let under = visibility.of_light(0).expect("the first lamp's");
        let beside = visibility.of_light(1).expect("the second lamp's");
        assert!(under[0] < 0.0, "the sphere hides the first lamp: {}", under[0]);
        assert!(beside.iter().all(|c| *c == 0.0), "{beside:?}");
        let alone = harmonic_log_visibility(&settings, &[sphere(0.0)], None, &dark, &lamps[..1], p, DVec3::Y);
        let windows = LightWindows::at(&lamps[..1], p, settings.order);
        let windowed = scene_log_visibility(&settings, &[sphere(0.0)], None, p, DVec3::Y, Some(&windows));
        assert_eq!(alone.of_light(0), Some(&windowed));
    }

    #[test]
    fn with_an_environment_every_reader_shares_one_unweighed_visibility() {
        let settings = ShadowSettings::default();
        let mut sky = [[0.0; 4]; 9];
        sky[0] = [0.2, 0.3, 0.4, 0.0];
        let lamps = [lamp(0.0), lamp(3.0)];
        let p = DVec3::ZERO;
        let visibility = harmonic_log_visibility(&settings, &[sphere(3.0)], None, &sky, &lamps, p, DVec3::Y);
        let unweighed = scene_log_visibility(&settings, &[sphere(3.0)], None, p, DVec3::Y, None);
        assert_eq!(visibility.shared(), Some(&unweighed));
        assert_eq!(visibility.of_light(0), Some(&unweighed));
        assert_eq!(visibility.of_light(1), Some(&unweighed));
    }
}
