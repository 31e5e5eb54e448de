//! The f64 twin of the BRDF-in-SH shading of `shaders/logsh.wgsl` ([`BrdfShading`]): the
//! visibility SH each BRDF lobe is shaded through, and one light's or the environment's
//! shadowed radiance through them.
//!
//! - Separate: both lobes read the visibility G = exp*(F); a light contributes its exact
//!   unshadowed radiance times clamp(V̄, 0, 1), V̄ the mean of G over its cap.
//! - Log (Ren et al. 2006): G_d = exp*(F + log diffuse lobe about n) and
//!   G_s = exp*(F + log Phong lobe about the mirrored view), `sh::log_phong_lobe_zh`.
//! - Product: G_d = G ∗ diffuse lobe, G_s = G ∗ Phong lobe (truncated SH product).
//!
//! In Log and Product a light contributes E·(k_d·clamp(V̄_d, 0, n·l/π) + k_s·clamp(V̄_s, 0,
//! glossy)), V̄ the means of G_d and G_s over its cap, clamped to [0, unshadowed] per lobe
//! (shading-model.md §4b: the band-limited lobes ring). Phong lobes sharper than the order
//! carries (`sh::max_carried_phong_exponent`) stay out of the SH: G_s is then G and the
//! specular is shaded as in Separate. The environment's diffuse light becomes
//! k_d·clamp(⟨G_d, L_env⟩, 0, E(n)/π), L_env its radiance SH (bands 0–2).

use std::f64::consts::PI;

use glam::DVec3;

use super::surface::{Incidence, SurfacePoint, direct_lobes, environment_irradiance_at, mirrored_view};
use super::visibility::visibility_toward;
use crate::sh;
use crate::shading::{BrdfShading, ShadowSettings};

/// The visibility SH the diffuse and the specular lobe are shaded through
/// (`LobeVisibility` in logsh.wgsl).
#[derive(Debug, Clone, PartialEq)]
pub struct LobeVisibility {
    pub diffuse: Vec<f64>,
    pub specular: Vec<f64>,
    /// Whether `specular` carries the Phong lobe (false: it is the plain visibility).
    pub specular_in_sh: bool,
}

/// Whether the order's SH carry the surface's Phong lobe.
fn specular_in_sh(settings: &ShadowSettings, s: &SurfacePoint) -> bool {
    settings.brdf != BrdfShading::Separate && s.phong_exponent <= sh::max_carried_phong_exponent(settings.order)
}

/// The lobes' visibility from the log-visibility `f`, exponentiated by `exp`.
pub fn lobes_from_log_visibility(
    settings: &ShadowSettings,
    s: &SurfacePoint,
    eye: DVec3,
    f: &[f64],
    exp: impl Fn(&[f64]) -> Vec<f64>,
) -> LobeVisibility {
    if settings.brdf != BrdfShading::Log {
        return lobes_through(settings, s, eye, exp(f));
    }
    let (order, epsilon) = (settings.order, settings.epsilon as f64);
    let plus = |lobe: Vec<f64>| f.iter().zip(lobe).map(|(a, b)| a + b).collect::<Vec<f64>>();
    let diffuse = exp(&plus(sh::rotate_zh(
        &sh::log_phong_lobe_zh(order, 1.0, epsilon),
        s.normal,
    )));
    let carried = specular_in_sh(settings, s);
    let specular = if carried {
        let lobe = sh::log_phong_lobe_zh(order, s.phong_exponent, epsilon);
        exp(&plus(sh::rotate_zh(&lobe, mirrored_view(s, eye))))
    } else {
        exp(f)
    };
    LobeVisibility {
        diffuse,
        specular,
        specular_in_sh: carried,
    }
}

/// The lobes' visibility from the visibility SH `g` (Separate and Product; per-vertex
/// shading interpolates `g`).
pub fn lobes_through(settings: &ShadowSettings, s: &SurfacePoint, eye: DVec3, g: Vec<f64>) -> LobeVisibility {
    if settings.brdf == BrdfShading::Separate {
        return LobeVisibility {
            diffuse: g.clone(),
            specular: g,
            specular_in_sh: false,
        };
    }
    let order = settings.order;
    let times_lobe =
        |exponent: f64, axis: DVec3| sh::product(order, &g, &sh::rotate_zh(&sh::phong_lobe_zh(order, exponent), axis));
    let diffuse = times_lobe(1.0, s.normal);
    let carried = specular_in_sh(settings, s);
    let specular = if carried {
        times_lobe(s.phong_exponent, mirrored_view(s, eye))
    } else {
        g
    };
    LobeVisibility {
        diffuse,
        specular,
        specular_in_sh: carried,
    }
}

/// One light's shadowed radiance through the lobes' visibility (SH path).
pub fn light_through(
    settings: &ShadowSettings,
    s: &SurfacePoint,
    inc: &Incidence,
    eye: DVec3,
    lobes: &LobeVisibility,
) -> DVec3 {
    let (diffuse, glossy) = direct_lobes(s, inc, eye);
    let mean = |g: &[f64]| visibility_toward(g, inc.to_light, inc.cap_ratio);
    if settings.brdf == BrdfShading::Separate {
        let unshadowed = inc.irradiance * (s.k_d * diffuse + s.k_s * glossy);
        return unshadowed * mean(&lobes.diffuse).clamp(0.0, 1.0);
    }
    let specular = if lobes.specular_in_sh {
        mean(&lobes.specular).clamp(0.0, glossy)
    } else {
        glossy * mean(&lobes.specular).clamp(0.0, 1.0)
    };
    inc.irradiance * (s.k_d * mean(&lobes.diffuse).clamp(0.0, diffuse) + s.k_s * specular)
}

/// The environment's diffuse light through the lobes' visibility; `irradiance_sh` as
/// `Frame::environment_irradiance` (E_lm = Â_l L_lm).
pub fn environment_through(
    settings: &ShadowSettings,
    s: &SurfacePoint,
    irradiance_sh: &[[f32; 4]; 9],
    lobes: &LobeVisibility,
) -> DVec3 {
    if settings.brdf == BrdfShading::Separate {
        return environment_through_visibility(s, irradiance_sh, &lobes.diffuse);
    }
    let diffuse_unshadowed = environment_irradiance_at(s.normal, irradiance_sh) / PI;
    let through = dot_environment_radiance(&lobes.diffuse, irradiance_sh);
    s.k_d * through.clamp(DVec3::ZERO, diffuse_unshadowed)
}

/// The environment's diffuse light through the visibility SH `g`, ⟨g ∗ cos⁺/π, L_env⟩:
/// the visibility weighted by where the environment is bright, clamped to the unshadowed
/// light (logsh.wgsl's `environment_through` with the separate BRDF). A wall standing on
/// a floor under a sky brighter above than below loses the dim half the floor hides, not
/// the floor's share of the cosine-weighted hemisphere.
pub fn environment_through_visibility(s: &SurfacePoint, irradiance_sh: &[[f32; 4]; 9], g: &[f64]) -> DVec3 {
    let order = sh::order_of(g.len()).unwrap_or(0);
    let cosine = sh::rotate_zh(&sh::phong_lobe_zh(order, 1.0), s.normal);
    let through = dot_environment_radiance(&sh::product(order, g, &cosine), irradiance_sh);
    let diffuse_unshadowed = environment_irradiance_at(s.normal, irradiance_sh) / PI;
    s.k_d * through.clamp(DVec3::ZERO, diffuse_unshadowed)
}

/// ⟨g, L_env⟩ per channel with L_lm = E_lm / Â_l over the bands both carry.
pub fn dot_environment_radiance(g: &[f64], irradiance_sh: &[[f32; 4]; 9]) -> DVec3 {
    g.iter()
        .zip(irradiance_sh)
        .enumerate()
        .fold(DVec3::ZERO, |sum, (i, (gi, e))| {
            let a_hat = sh::irradiance_band_scale((i as f64).sqrt() as usize);
            sum + DVec3::new(e[0] as f64, e[1] as f64, e[2] as f64) * (*gi / a_hat)
        })
}
