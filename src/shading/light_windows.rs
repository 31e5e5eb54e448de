//! Windows on the blockers for the SH path's lights (`light_window_weight` in logsh.wgsl).
//!
//! A light reads the visibility SH only over its own cap (`visibility_toward`). Outside
//! its cap the exact visibility does not matter, yet each blocker's log-visibility,
//! truncated to order n, reaches ~180°/n around the blocker: hundreds of small blockers
//! around a light, none of them in front of it, summed darken the lights they do not hide
//! (the thin-caster bench's floor, 600 spheres, order 4: −23 % where nothing hides the
//! light). When no environment lights the frame, every SH reader is a light, so each
//! blocker cap is weighed by how near it comes to the nearest of those lights' caps: 1
//! where its centre lies within half its angular radius of the light's cap, falling
//! smoothly to 0 where the gap between the two caps reaches half its angular radius
//! (a smooth ramp across the caps' touching, so no shadow edge appears where a blocker
//! enters a light's window; `cpu::LightWindow::weight`; the twin in `cpu::windows`).
//!
//! Inside a window a cap's log-visibility is scaled for the light's mean rather than for
//! the whole sphere's: the cap-mass scale k(s) of `sh::cap_mass_scales` makes a small
//! cap block its true solid angle once its log-visibility has spread over the band
//! limit's width, about 4π/n², which a light smaller than that reads only a share of
//! (before the windows, the neighbouring caps a light does not see made up for it). A
//! lone small cap in the middle of a light of solid angle Ω blocks its true share of it,
//! to first order, at k(s)·(4π/n²)/Ω; the scale is that, at least k(s), and at most 1 —
//! the cap's own log-visibility, ln ε. With several lights each reads a log-visibility
//! of its own, every cap weighed by that light's window alone
//! (`cpu::harmonic_log_visibility`; one sum weighed by the largest window's weight, read
//! by every light, made each read its neighbours' blockers). Measured on the thin-caster bench (f64
//! twin, HYB, against the exact path over the same 600 spheres; `cargo nextest run
//! --test sh_against_exact --run-ignored only --no-capture`, docs/performance.md): at
//! order 4 the lit floor −23.1 % → −2.5 %, penumbra RMS 0.397 → 0.329, umbra RMS 0.079 →
//! 0.062; at order 8 the lit floor −4.6 % → −5.0 %, umbra 0.139 → 0.019, penumbra 0.291
//! → 0.484 (too dark: blockers at the light's rim spread their mass over its middle;
//! a light this small, 10–13°, is what the exact path and the shadow maps are for, and
//! Auto gives it them). Without the larger scale (k(s) in the windows) the umbrae at
//! order 4 came out 36 % too light.
//!
//! With an environment its light comes from the whole sky, so its visibility is the one
//! with every blocker at k(s) (no window); the SH lights still read each their own
//! windowed one ([`light_window_indices`]), and per vertex, where one visibility serves
//! every reader, no window applies. With more
//! than [`MAX_WINDOW_LIGHTS`] SH lights (the shaders keep each window in registers) a
//! point opens windows for those of them that reach it ([`light_reaches`]: within its
//! range, inside a spot's cone), when at most [`MAX_WINDOW_LIGHTS`] do: the others add
//! exactly nothing there, so nothing else reads its visibility (a street of lamps with
//! ranges; a point no SH light reaches opens none, and no blocker weighs anything there).
//! Past that many at a point, its blockers all weigh, as with an environment.
//!
//! Where one visibility serves every light (per vertex), the limit is
//! [`MAX_SHARED_WINDOW_LIGHTS`]: with more, one sum weighed by the largest window's
//! weight made each light read its neighbours' blockers, and five panels' penumbrae came
//! out darker than with no window at all (docs/performance.md, "Windows for several
//! lights spread over the sky"). Under an environment it is [`MAX_SKY_WINDOW_LIGHTS`]
//! ([`most_windows`]).

use super::gpu_types::{GpuLight, SHADOW_PATH_SH, irradiance_lights};

/// The most windows a point opens, each SH light reading a visibility of its own
/// (`MAX_WINDOW_LIGHTS` in light_windows.wgsl).
pub const MAX_WINDOW_LIGHTS: usize = 8;

/// The most windows a point opens where one visibility serves every reader (the
/// per-vertex pass; `MAX_SHARED_WINDOW_LIGHTS` in light_windows.wgsl).
pub const MAX_SHARED_WINDOW_LIGHTS: usize = 4;

/// The most windows a point opens under an environment (`MAX_SKY_WINDOW_LIGHTS` in
/// light_windows.wgsl): the environment reads the walk without windows, which visits
/// every cap in reach and adds it to each window's sum besides its own, so every window
/// costs every cap there, where the walk with windows leaves out the groups outside all
/// of them. The large sample (an environment and eight SH lights without a range) took
/// 360 → 569 ms a frame with its eight lights' windows (docs/performance.md).
pub const MAX_SKY_WINDOW_LIGHTS: usize = 4;

/// The most windows a point opens, each SH light reading its own visibility, with or
/// without an environment lighting the frame.
pub fn most_windows(environment: bool) -> usize {
    if environment {
        MAX_SKY_WINDOW_LIGHTS
    } else {
        MAX_WINDOW_LIGHTS
    }
}

/// Whether one visibility weighed by the windows may serve every reader in a frame with
/// this environment irradiance (order-3 SH, `Frame::environment_irradiance`) and these
/// lights on their paths (the per-vertex pass; per pixel each light reads its own): no
/// environment light, and some light on the SH path — at every point when there are 1 to
/// [`MAX_SHARED_WINDOW_LIGHTS`], else at the points where at most that many reach
/// (`open_light_windows` in light_windows.wgsl decides alike from the same numbers).
pub fn windows_apply(environment_irradiance: &[[f32; 4]; 9], lights: &[GpuLight]) -> bool {
    !irradiance_lights(environment_irradiance) && windows_up_to(lights, MAX_SHARED_WINDOW_LIGHTS) > 0
}

/// The windows the shaders compile in for a frame with these lights on their paths, under
/// an environment or not (`environment`), for m = [`most_windows`]: the SH lights' count
/// when there are 1 to m, m when there are more (each point opens those of the lights
/// that reach it), 0 without SH lights or with more than m SH lights that reach every
/// point (no range, not a spot: no point would open a window)
/// (`CompiledPaths::light_windows`).
pub fn compiled_windows(lights: &[GpuLight], environment: bool) -> u32 {
    windows_up_to(lights, most_windows(environment))
}

/// [`compiled_windows`] where a point opens at most `most` windows.
fn windows_up_to(lights: &[GpuLight], most: usize) -> u32 {
    let sh_lights = lights.iter().filter(|l| l.shadow_path == SHADOW_PATH_SH);
    let count = sh_lights.clone().count();
    // Past `most` lights that reach every point, none ever opens a window.
    let everywhere = sh_lights.filter(|light| reaches_everywhere(light)).count();
    if count == 0 || everywhere > most {
        0
    } else {
        count.min(most) as u32
    }
}

/// Whether [`light_reaches`] holds at every point: a light neither a spot nor bounded by
/// a range (the lights' grid's `bounded`: a sun, whatever range it carries, or a point
/// or area light without one).
fn reaches_everywhere(light: &GpuLight) -> bool {
    light.kind != super::gpu_types::LIGHT_SPOT && !super::light_grid::bounded(light)
}

/// Whether each point decides for itself whether windows apply (past
/// [`most_windows`] SH lights), so that the shaders compile the walk without windows
/// beside the one with them (`CompiledPaths::per_point_windows`).
pub fn windows_per_point(lights: &[GpuLight], environment: bool) -> bool {
    let sh_lights = lights.iter().filter(|l| l.shadow_path == SHADOW_PATH_SH).count();
    compiled_windows(lights, environment) > 0 && sh_lights > most_windows(environment)
}

/// The SH-path lights (indices into `lights`, in order: the slots of `window_lights` in
/// light_windows.wgsl) whose windows a point at `p` opens, each to read a visibility of
/// its own, under an environment or not (`environment`), for m = [`most_windows`]: every
/// SH light when there are at most m, else those that reach p when at most m do; None
/// where no window opens (no SH light, or more than m reach p). Where [`compiled_windows`]
/// is 0 with SH lights, more than m of them reach every point, and so p: None too.
pub fn light_window_indices(lights: &[GpuLight], environment: bool, p: glam::DVec3) -> Option<Vec<usize>> {
    let most = most_windows(environment);
    let harmonic: Vec<usize> = (0..lights.len())
        .filter(|&i| lights[i].shadow_path == SHADOW_PATH_SH)
        .collect();
    if harmonic.is_empty() {
        return None;
    }
    if harmonic.len() <= most {
        return Some(harmonic);
    }
    let reaching: Vec<usize> = harmonic.into_iter().filter(|&i| light_reaches(&lights[i], p)).collect();
    (reaching.len() <= most).then_some(reaching)
}

/// Whether `light` adds anything at `p` as far as its range and cone say (scene.wgsl
/// `light_reaches`, in f32 there): within its range (KHR_lights_punctual's window is 0
/// from the range on), and for a spot inside its outer cone.
pub fn light_reaches(light: &GpuLight, p: glam::DVec3) -> bool {
    let position = glam::Vec3::from_slice(&light.position[..3]).as_dvec3();
    let offset = position - p;
    let range = f64::from(light.direction_range[3]);
    if light.kind == super::gpu_types::LIGHT_DIRECTIONAL {
        return true;
    }
    if range > 0.0 && offset.length_squared() >= range * range {
        return false;
    }
    if light.kind == super::gpu_types::LIGHT_SPOT {
        let direction = glam::Vec3::from_slice(&light.direction_range[..3]).as_dvec3();
        let cos_angle = (-offset).normalize_or_zero().dot(direction);
        let t = (cos_angle - f64::from(light.spot_cone[0])) * f64::from(light.spot_cone[1]);
        return t > 0.0;
    }
    true
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_windows_apply_to_one_to_eight_sh_lights_and_to_four_sharing_one_visibility() {
        let light = GpuLight {
            shadow_path: SHADOW_PATH_SH,
            ..bytemuck::Zeroable::zeroed()
        };
        // A light with a range of 1 m, which some points lie beyond.
        let mut bounded = light;
        bounded.direction_range[3] = 1.0;
        let dark = [[0.0; 4]; 9];
        let mut sky = dark;
        sky[0] = [0.2, 0.3, 0.4, 0.0];
        // Each light reading its own visibility: up to eight windows at every point.
        assert_eq!(compiled_windows(&[light; 3], false), 3, "each light's own, sky or not");
        assert_eq!(compiled_windows(&[light; 6], false), 6);
        assert_eq!(
            compiled_windows(&[light; MAX_WINDOW_LIGHTS], false),
            MAX_WINDOW_LIGHTS as u32
        );
        assert_eq!(
            compiled_windows(&[bounded; MAX_WINDOW_LIGHTS + 1], false),
            MAX_WINDOW_LIGHTS as u32
        );
        assert_eq!(
            compiled_windows(&[light; MAX_WINDOW_LIGHTS + 1], false),
            0,
            "nine lights without a range reach every point: no window ever opens"
        );
        let eight_everywhere = [[light; MAX_WINDOW_LIGHTS].as_slice(), &[bounded]].concat();
        assert_eq!(
            compiled_windows(&eight_everywhere, false),
            MAX_WINDOW_LIGHTS as u32,
            "beyond the ninth's range only eight reach"
        );
        assert!(!windows_per_point(&[light; MAX_WINDOW_LIGHTS], false));
        assert!(windows_per_point(&[bounded; MAX_WINDOW_LIGHTS + 1], false));
        assert!(windows_per_point(&eight_everywhere, false));
        assert!(!windows_per_point(&[light; MAX_WINDOW_LIGHTS + 1], false));
        let six = light_window_indices(&[light; 6], false, glam::DVec3::ZERO);
        assert_eq!(six, Some((0..6).collect()));
        // Under an environment up to four.
        assert_eq!(compiled_windows(&[light; 3], true), 3);
        assert_eq!(compiled_windows(&[light; 6], true), 0, "six reach every point");
        assert_eq!(compiled_windows(&[bounded; 6], true), MAX_SKY_WINDOW_LIGHTS as u32);
        assert!(windows_per_point(&[bounded; 6], true));
        assert_eq!(light_window_indices(&[light; 6], true, glam::DVec3::ZERO), None);
        // One visibility for every reader (per vertex): up to MAX_SHARED_WINDOW_LIGHTS.
        assert!(windows_apply(&dark, &[light]));
        assert!(windows_apply(&dark, &[light; MAX_SHARED_WINDOW_LIGHTS]));
        assert!(
            windows_apply(&dark, &[bounded; MAX_SHARED_WINDOW_LIGHTS + 1]),
            "at the points few of them reach"
        );
        assert!(
            !windows_apply(&dark, &[light; MAX_SHARED_WINDOW_LIGHTS + 1]),
            "five lights without a range reach every point: no shared window ever opens"
        );
        assert!(!windows_apply(&dark, &[]));
        assert!(!windows_apply(&sky, &[light]), "the sky reads the visibility unweighed");
    }

    /// Past eight SH lights a point opens the windows of those within their range, when
    /// at most eight are; the rest of the scene has none.
    #[test]
    fn past_eight_sh_lights_a_point_opens_the_windows_of_the_lights_that_reach_it() {
        let lamp = |x: f32| {
            GpuLight::new(&crate::scene::Light {
                name: "lamp".into(),
                kind: crate::scene::LightKind::Point,
                color: glam::Vec3::ONE,
                intensity: 1.0,
                position: glam::Vec3::new(x, 1.0, 0.0),
                direction: glam::Vec3::NEG_Y,
                range: Some(1.5),
                locked: false,
            })
        };
        let lamps: Vec<GpuLight> = (0..10).map(|k| lamp(2.0 * k as f32)).collect();
        let under_the_third = light_window_indices(&lamps, false, glam::DVec3::new(4.0, 0.0, 0.0));
        assert_eq!(under_the_third, Some(vec![2]), "the lamp at x = 4 m");
        let between = light_window_indices(&lamps, false, glam::DVec3::new(5.0, 0.5, 0.0)).expect("windows");
        assert_eq!(between, vec![2, 3]);
        let far = light_window_indices(&lamps, false, glam::DVec3::new(5.0, 0.0, 30.0)).expect("windows");
        assert!(far.is_empty(), "no lamp reaches it: no window, nothing weighs");
        let mut bright = lamps.clone();
        for light in &mut bright {
            light.direction_range[3] = 0.0;
        }
        assert!(
            light_window_indices(&bright, false, glam::DVec3::ZERO).is_none(),
            "ten unbounded lamps reach it"
        );
        let mut sky = [[0.0; 4]; 9];
        sky[0] = [0.2, 0.3, 0.4, 0.0];
        assert!(windows_apply(&[[0.0; 4]; 9], &lamps));
        assert!(
            !windows_apply(&sky, &lamps),
            "under the sky no window weighs the one visibility every reader shares"
        );
    }
}
