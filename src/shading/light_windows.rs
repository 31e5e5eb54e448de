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
//! the cap's own log-visibility, ln ε. With several lights a cap takes the largest
//! weight × scale any light's window gives it. Measured on the thin-caster bench (f64
//! twin, HYB, against the exact path over the same 600 spheres; `cargo nextest run
//! --test sh_against_exact --run-ignored only --no-capture`, docs/performance.md): at
//! order 4 the lit floor −23.1 % → −2.5 %, penumbra RMS 0.397 → 0.329, umbra RMS 0.079 →
//! 0.062; at order 8 the lit floor −4.6 % → −5.0 %, umbra 0.139 → 0.019, penumbra 0.291
//! → 0.484 (too dark: blockers at the light's rim spread their mass over its middle;
//! a light this small, 10–13°, is what the exact path and the shadow maps are for, and
//! Auto gives it them). Without the larger scale (k(s) in the windows) the umbrae at
//! order 4 came out 36 % too light.
//!
//! With an environment the windows are off: its light comes from the whole sky. So are
//! they past [`MAX_WINDOW_LIGHTS`] SH lights (the shaders keep each window in registers).

use super::gpu_types::{GpuLight, SHADOW_PATH_SH, irradiance_lights};

/// The most SH-path lights a frame may have for the windows to apply
/// (`MAX_WINDOW_LIGHTS` in logsh.wgsl).
pub const MAX_WINDOW_LIGHTS: usize = 4;

/// Whether the windows apply to a frame with this environment irradiance (order-3 SH,
/// `Frame::environment_irradiance`) and these lights on their paths: no environment
/// light, and 1 to [`MAX_WINDOW_LIGHTS`] lights on the SH path (`light_windows_apply` in
/// logsh.wgsl decides alike from the same numbers).
pub fn windows_apply(environment_irradiance: &[[f32; 4]; 9], lights: &[GpuLight]) -> bool {
    compiled_windows(irradiance_lights(environment_irradiance), lights) > 0
}

/// The windows the shaders compile in for a frame with (`environment_lights`) or without
/// an environment's light and these lights: the SH lights' count where
/// [`windows_apply`] would hold, else 0 (`CompiledPaths::light_windows`).
pub fn compiled_windows(environment_lights: bool, lights: &[GpuLight]) -> u32 {
    let sh_lights = lights.iter().filter(|l| l.shadow_path == SHADOW_PATH_SH).count();
    if !environment_lights && (1..=MAX_WINDOW_LIGHTS).contains(&sh_lights) {
        sh_lights as u32
    } else {
        0
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_windows_apply_without_an_environment_to_one_to_four_sh_lights() {
        let light = GpuLight {
            shadow_path: SHADOW_PATH_SH,
            ..bytemuck::Zeroable::zeroed()
        };
        let dark = [[0.0; 4]; 9];
        let mut sky = dark;
        sky[0] = [0.2, 0.3, 0.4, 0.0];
        assert!(windows_apply(&dark, &[light]));
        assert!(windows_apply(&dark, &[light; MAX_WINDOW_LIGHTS]));
        assert!(!windows_apply(&dark, &[light; MAX_WINDOW_LIGHTS + 1]));
        assert!(!windows_apply(&dark, &[]));
        assert!(!windows_apply(&sky, &[light]));
        assert_eq!(compiled_windows(false, &[light; 3]), 3);
        assert_eq!(compiled_windows(true, &[light; 3]), 0);
        assert_eq!(compiled_windows(false, &[light; MAX_WINDOW_LIGHTS + 1]), 0);
    }
}
