//! The unshadowed side of the f64 shading twin: a visible surface point, one light's
//! incidence on it, the BRDF's lobes (`scene.wgsl`: `incidence`, `direct_lobes`,
//! `direct_radiance`) and the environment's diffuse light.

use std::f64::consts::PI;

use glam::DVec3;

use crate::sh;
use crate::shading::gpu_types::{GpuLight, LIGHT_AREA, LIGHT_DIRECTIONAL, LIGHT_POINT, LIGHT_SPOT};

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
    /// On the plane facing `diffuse_to_light`.
    pub irradiance: DVec3,
    /// Toward the light's centre (its shadows are looked up that way).
    pub to_light: DVec3,
    /// The direction whose cosine with a receiver's normal scales `irradiance` to the
    /// receiver's: `to_light`, except for area lights, whose vector irradiance points
    /// elsewhere near them (`area::area_vector_irradiance`).
    pub diffuse_to_light: DVec3,
    pub cap_ratio: f64,
    /// Distance to the light (infinite for directional lights).
    pub distance_m: f64,
}

pub(super) fn v3(a: [f32; 4]) -> DVec3 {
    DVec3::new(a[0] as f64, a[1] as f64, a[2] as f64)
}

pub fn incidence(light: &GpuLight, p: DVec3) -> Incidence {
    let intensity = v3(light.intensity_rgb);
    let direction = v3(light.direction_range);
    if light.kind == LIGHT_DIRECTIONAL {
        return Incidence {
            irradiance: intensity,
            to_light: -direction,
            diffuse_to_light: -direction,
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
    let mut diffuse_to_light = to_light;
    if light.kind == LIGHT_POINT && size > 0.0 {
        cap_ratio = (size / distance2.sqrt()).min(1.0);
    }
    if light.kind == LIGHT_AREA {
        let cos_emitter = (-to_light).dot(direction).max(0.0);
        let u = (size * cos_emitter / distance2 / (2.0 * PI)).min(1.0);
        cap_ratio = (u * (2.0 - u)).sqrt();
        // intensity = L·A; on the plane facing Φ the irradiance is L·|Φ|.
        let phi = super::area::area_vector_irradiance(light, p);
        let length = phi.length();
        falloff *= distance2 * length / size.max(f64::MIN_POSITIVE);
        if length > 0.0 {
            diffuse_to_light = phi / length;
        }
    }
    if light.kind == LIGHT_SPOT {
        let cos_angle = (-to_light).dot(direction);
        let t = ((cos_angle - light.spot_cone[0] as f64) * light.spot_cone[1] as f64).clamp(0.0, 1.0);
        falloff *= t * t;
    }
    Incidence {
        irradiance: intensity * falloff,
        to_light,
        diffuse_to_light,
        cap_ratio,
        distance_m: distance2.sqrt(),
    }
}

/// Unshadowed radiance toward `eye` from one light (`direct_radiance` in scene.wgsl).
pub fn direct_radiance(s: &SurfacePoint, inc: &Incidence, eye: DVec3) -> DVec3 {
    let (diffuse, glossy) = direct_lobes(s, inc, eye);
    inc.irradiance * (s.k_d * diffuse + s.k_s * glossy)
}

/// The view direction mirrored about the normal, the Phong lobe's axis.
pub fn mirrored_view(s: &SurfacePoint, eye: DVec3) -> DVec3 {
    let to_eye = (eye - s.position).normalize_or_zero();
    -to_eye - 2.0 * s.normal.dot(-to_eye) * s.normal
}

/// The unshadowed diffuse and glossy factors of a light, n·l_d/π and (r+1)/(2π)·(ρ·l)^r
/// with l_d = `diffuse_to_light` and l = `to_light` (0, 0 below the horizon of l_d):
/// `direct_lobes` in scene.wgsl.
pub fn direct_lobes(s: &SurfacePoint, inc: &Incidence, eye: DVec3) -> (f64, f64) {
    let n_dot_l = s.normal.dot(inc.diffuse_to_light);
    if n_dot_l <= 0.0 {
        return (0.0, 0.0);
    }
    let cos_mirror = mirrored_view(s, eye).dot(inc.to_light).max(1e-8);
    let r = s.phong_exponent;
    (n_dot_l / PI, (r + 1.0) / (2.0 * PI) * (r * cos_mirror.log2()).exp2())
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
