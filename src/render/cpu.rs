//! The f64 reference of the log-SH shading in `shaders/logsh.wgsl` (and, without blockers,
//! of `raster.wgsl`), term by term:
//!
//! - log-visibility F(p, n) = Σ ln ε·fade·[r/d]·rotate(cap_zh(r/d), toward the blocker),
//!   over the blockers that do not contain p and whose r/d reaches `min_cap_ratio`, where
//!   fade = smoothstep(−1, 1, (c − p)·n / r) removes blockers below the tangent plane
//!   smoothly (a hard cut leaves blotches where fitted spheres straddle their own surface);
//! - visibility G = exp*(F) by the chosen [`ExpMethod`];
//! - radiance = emissive + environment diffuse · clamp(⟨G, cos_n⟩, 0, 1) plus, summed
//!   over lights, unshadowed(light) · clamp(V̄(light), 0, 1) (with the default
//!   [`super::BrdfShading::Separate`]; the BRDF-in-SH variants are in `cpu_lobes`), where
//!   V̄ is the mean of G over the cap the light subtends: V̄ = Σ_lm w_l(s) G_lm y_lm(d)
//!   with w_0 = 1 and w_l = (1 + c)·P_l′(c)/(l(l+1)) = z_l/(z_0 √(2l+1)) of the cap
//!   (s = sin of its half-angle, c = √(1 − s²)); for a point light (s = 0) this is G(d).
//!   Lights on the exact path (`GpuLight::exact_path`, chosen per light for the frame by
//!   `render::shading_lights`) take `penumbra::light_visibility` instead (the share of
//!   their disc no blocker hides);
//! - with a terrain, F gains its log-visibility (`TerrainShadow::log_visibility`, the twin
//!   of terrain.wgsl) and exact-path lights the share of their disc above its horizon.
//!
//! Lights come in their GPU form ([`GpuLight`]) so CPU and GPU read the same parameters.

use std::f64::consts::PI;

use glam::DVec3;

use super::ShadowSettings;
use super::cpu_lobes::{direct_lobes, environment_through, light_through, lobes_from_log_visibility};
use super::gpu_types::{GpuLight, LIGHT_AREA, LIGHT_DIRECTIONAL, LIGHT_POINT, LIGHT_SPOT};
use crate::blockers::Sphere;
use crate::sh::{self, ExpMethod};
use crate::terrain::TerrainShadow;

/// A visible surface point with its material, as `Surface` in scene.wgsl.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SurfacePoint {
    pub position: DVec3,
    /// Unit shading normal facing the viewer.
    pub normal: DVec3,
    pub k_d: DVec3,
    pub k_s: DVec3,
    pub phong_exponent: f64,
    pub emissive: DVec3,
}

/// Irradiance on a plane facing the light, unit direction to it, and the sine of the
/// half-angle of the cap it subtends (`incidence` in scene.wgsl).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Incidence {
    pub irradiance: DVec3,
    pub to_light: DVec3,
    pub cap_ratio: f64,
    /// Distance to the light (infinite for directional lights).
    pub distance_m: f64,
}

fn v3(a: [f32; 4]) -> DVec3 {
    DVec3::new(a[0] as f64, a[1] as f64, a[2] as f64)
}

pub fn incidence(light: &GpuLight, p: DVec3) -> Incidence {
    let intensity = v3(light.intensity_rgb);
    let direction = v3(light.direction_range);
    if light.kind == LIGHT_DIRECTIONAL {
        return Incidence {
            irradiance: intensity,
            to_light: -direction,
            cap_ratio: 0.0,
            distance_m: f64::INFINITY,
        };
    }
    let offset = v3(light.position) - p;
    let distance2 = offset.length_squared().max(1e-8);
    let to_light = offset / distance2.sqrt();
    let mut falloff = 1.0 / distance2;
    let range = light.direction_range[3] as f64;
    if range > 0.0 {
        let ratio2 = distance2 / (range * range);
        let window = (1.0 - ratio2 * ratio2).clamp(0.0, 1.0);
        falloff *= window * window;
    }
    let size = light.source_size as f64;
    let mut cap_ratio = 0.0;
    if light.kind == LIGHT_POINT && size > 0.0 {
        cap_ratio = (size / distance2.sqrt()).min(1.0);
    }
    if light.kind == LIGHT_AREA {
        let cos_emitter = (-to_light).dot(direction).max(0.0);
        falloff *= cos_emitter;
        let u = (size * cos_emitter / distance2 / (2.0 * PI)).min(1.0);
        cap_ratio = (u * (2.0 - u)).sqrt();
    }
    if light.kind == LIGHT_SPOT {
        let cos_angle = (-to_light).dot(direction);
        let t = ((cos_angle - light.spot_cone[0] as f64) * light.spot_cone[1] as f64).clamp(0.0, 1.0);
        falloff *= t * t;
    }
    Incidence {
        irradiance: intensity * falloff,
        to_light,
        cap_ratio,
        distance_m: distance2.sqrt(),
    }
}

/// Unshadowed radiance toward `eye` from one light (`direct_radiance` in scene.wgsl).
pub fn direct_radiance(s: &SurfacePoint, inc: &Incidence, eye: DVec3) -> DVec3 {
    let (diffuse, glossy) = direct_lobes(s, inc, eye);
    inc.irradiance * (s.k_d * diffuse + s.k_s * glossy)
}

/// Log-visibility of `blockers` at `p` with normal `n` (`log_visibility` in logsh.wgsl).
pub fn log_visibility(settings: &ShadowSettings, blockers: &[Sphere], p: DVec3, n: DVec3) -> Vec<f64> {
    let order = settings.order;
    let ln_epsilon = (settings.epsilon as f64).ln();
    let mut f = vec![0.0; order * order];
    for cap in blockers
        .iter()
        .filter_map(|b| b.cap_from(p, n, settings.min_cap_ratio as f64))
    {
        let (ratio, horizon) = (cap.ratio, cap.horizon);
        let scale = if settings.ratio_attenuation {
            ln_epsilon * horizon * ratio
        } else {
            ln_epsilon * horizon
        };
        // Funk–Hecke: f_lm += scale·√(4π/(2l+1))·z_l·y_lm(d), without building the
        // rotated vector.
        with_basis(order, cap.direction, |y| {
            sh::cap_zh_ratio_each(order, ratio, |l, z| {
                let weight = scale * (4.0 * PI / (2 * l + 1) as f64).sqrt() * z;
                for i in l * l..(l + 1) * (l + 1) {
                    f[i] += weight * y[i];
                }
            });
        });
    }
    f
}

/// The blockers' log-visibility plus, with a terrain, the terrain's (`log_visibility` in
/// logsh.wgsl, which adds `terrain_log_visibility`).
pub fn scene_log_visibility(
    settings: &ShadowSettings,
    blockers: &[Sphere],
    terrain: Option<&TerrainShadow>,
    p: DVec3,
    n: DVec3,
) -> Vec<f64> {
    let mut f = log_visibility(settings, blockers, p, n);
    if let Some(terrain) = terrain {
        let ln_epsilon = (settings.epsilon as f64).ln();
        for (a, b) in f.iter_mut().zip(terrain.log_visibility(p, ln_epsilon)) {
            *a += b;
        }
    }
    f
}

/// The SH basis at unit `d`: the unrolled polynomials up to order 4 (as the shaders
/// evaluate it), the general recurrence above.
fn basis(order: usize, d: DVec3) -> Vec<f64> {
    with_basis(order, d, <[f64]>::to_vec)
}

/// Calls `f` with the n² basis values at unit `d`, on the stack up to order 4 (the shading
/// loops call this per blocker and per light).
fn with_basis<R>(order: usize, d: DVec3, f: impl FnOnce(&[f64]) -> R) -> R {
    if order <= 4 {
        f(&sh::basis16(d.normalize_or(DVec3::Z))[..order * order])
    } else {
        f(&sh::basis(order, d))
    }
}

/// Mean of the visibility SH `g` over a cap of sin(half-angle) `cap_ratio` around `d`.
pub fn visibility_toward(g: &[f64], d: DVec3, cap_ratio: f64) -> f64 {
    let order = sh::order_of(g.len()).unwrap_or(0);
    let s = cap_ratio.clamp(0.0, 1.0);
    if s == 0.0 {
        // A point: every band's weight is 1, V̄ = G(d).
        return with_basis(order, d, |y| g.iter().zip(y).map(|(a, b)| a * b).sum());
    }
    let y = basis(order, d);
    let c = (1.0 - s * s).max(0.0).sqrt();
    let dp = sh::legendre_derivative(order, c);
    (0..order)
        .map(|l| {
            let w = if l == 0 {
                1.0
            } else {
                (1.0 + c) * dp[l] / (l * (l + 1)) as f64
            };
            w * (l * l..(l + 1) * (l + 1)).map(|i| g[i] * y[i]).sum::<f64>()
        })
        .sum()
}

/// Clamped-cosine average of `g` about `n`: ⟨G, max(n·ω, 0)/π⟩ (1 when unoccluded).
pub fn visibility_cosine(g: &[f64], n: DVec3) -> f64 {
    let order = sh::order_of(g.len()).unwrap_or(0);
    let cosine = sh::rotate_zh(&sh::phong_lobe_zh(order, 1.0), n);
    g.iter().zip(cosine).map(|(a, b)| a * b).sum()
}

/// What shades a frame besides the surface: lights, environment, blockers, settings.
#[derive(Debug, Clone, Copy)]
pub struct ShadingInputs<'a> {
    pub lights: &'a [GpuLight],
    /// Order-3 SH of the environment's irradiance, as `Frame::environment_irradiance`.
    pub environment_irradiance: &'a [[f32; 4]; 9],
    pub blockers: &'a [Sphere],
    /// The terrain's shadow model, if the scene has a terrain.
    pub terrain: Option<&'a TerrainShadow>,
    pub settings: &'a ShadowSettings,
    pub eye: DVec3,
    /// The angle one pixel subtends (`gpu_types::pixel_angle_rad`): exact-path shadow edges
    /// ramp over one pixel's width; 0 leaves them hard.
    pub pixel_angle_rad: f64,
}

/// Diffuse environment light at `s` (`environment_radiance` in scene.wgsl).
pub fn environment_radiance(s: &SurfacePoint, irradiance_sh: &[[f32; 4]; 9]) -> DVec3 {
    s.k_d / PI * environment_irradiance_at(s.normal, irradiance_sh)
}

/// The environment's irradiance on a plane of normal `n`, clamped at 0 against ringing.
pub fn environment_irradiance_at(n: DVec3, irradiance_sh: &[[f32; 4]; 9]) -> DVec3 {
    let y = sh::basis(3, n);
    let e = irradiance_sh
        .iter()
        .zip(&y)
        .fold(DVec3::ZERO, |acc, (c, yi)| acc + v3(*c) * *yi);
    e.max(DVec3::ZERO)
}

/// Linear radiance toward the eye with log-SH shadows (`shadowed_radiance` in logsh.wgsl).
pub fn shadowed_radiance(s: &SurfacePoint, inputs: &ShadingInputs) -> DVec3 {
    let settings = inputs.settings;
    let f = scene_log_visibility(settings, inputs.blockers, inputs.terrain, s.position, s.normal);
    let lobes = lobes_from_log_visibility(settings, s, inputs.eye, &f, |f| exp_for_shading(settings.exp, f));
    let mut radiance = s.emissive + environment_through(settings, s, inputs.environment_irradiance, &lobes);
    let footprint = (inputs.eye - s.position).length() * inputs.pixel_angle_rad;
    for light in inputs.lights {
        let inc = incidence(light, s.position);
        let unshadowed = direct_radiance(s, &inc, inputs.eye);
        if unshadowed == DVec3::ZERO {
            continue;
        }
        radiance += match exact_visibility(s, light, &inc, settings, inputs.blockers, inputs.terrain, footprint) {
            Some(visibility) => unshadowed * visibility,
            None => light_through(settings, s, &inc, inputs.eye, &lobes),
        };
    }
    radiance
}

/// The visibility of `light`, seen as `inc` from `s`, when it is on the exact path
/// (`GpuLight::exact_path`, which `render::shading_lights` sets): `crate::penumbra` times
/// the share of its disc above the terrain's horizon. None when it takes the SH path.
/// `pixel_footprint_m` anti-aliases hard blocker edges (`penumbra::light_visibility`; 0:
/// none).
pub fn exact_visibility(
    s: &SurfacePoint,
    light: &GpuLight,
    inc: &Incidence,
    settings: &ShadowSettings,
    blockers: &[Sphere],
    terrain: Option<&TerrainShadow>,
    pixel_footprint_m: f64,
) -> Option<f64> {
    (light.exact_path != 0).then(|| {
        let above_terrain = terrain.map_or(1.0, |t| t.light_visibility(s.position, inc.to_light, inc.cap_ratio));
        let light = crate::penumbra::LightDisc {
            to_light: inc.to_light,
            distance_m: inc.distance_m,
            cap_ratio: inc.cap_ratio,
        };
        let min_cap_ratio = settings.min_cap_ratio as f64;
        above_terrain
            * crate::penumbra::light_visibility(
                s.position,
                s.normal,
                &light,
                blockers,
                min_cap_ratio,
                pixel_footprint_m,
            )
    })
}

/// exp* as the GPU evaluates it: HYB's carried magnitude capped where f32 stops (see
/// `wgsl_sh::F32_MAX_EXPONENT`); every other method as in `sh::exp`.
fn exp_for_shading(method: ExpMethod, f: &[f64]) -> Vec<f64> {
    let g = sh::exp(method, f);
    if method != ExpMethod::Hyb {
        return g;
    }
    let cap = super::wgsl_sh::F32_MAX_EXPONENT.exp();
    let norm = g.iter().map(|v| v * v).sum::<f64>().sqrt();
    if norm > cap {
        g.into_iter().map(|v| v * cap / norm).collect()
    } else {
        g
    }
}
