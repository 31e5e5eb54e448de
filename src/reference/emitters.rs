//! Next-event estimation: one sample of each light's emitter as seen from a receiver, as
//! an estimate of the irradiance it gives a plane facing the sampled direction.
//!
//! - point, spot and directional lights are exact (one direction);
//! - a sphere light of intensity I and radius R is a uniform emitter of radiance
//!   L = I/(πR²); directions are drawn uniformly in the cone it subtends (solid angle
//!   Ω = 2π(1 − cos α), sin α = R/d), each worth L·Ω;
//! - rect and disk lights (luminance L, one-sided) are sampled uniformly by area, each
//!   point worth L·A·cos θ_e/d² ([`Light::unit_incidence`] of the sampled point).
//!
//! Every estimate carries the light's colour, the glTF range window (at the sphere's
//! centre for sphere lights) and the spot cone.

use std::f32::consts::TAU;

use glam::{DVec3, Vec3};

use crate::random::SplitMix64;
use crate::scene::{Light, LightKind};

/// One sample of a light seen from a receiver.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct EmitterSample {
    /// Unit direction from the receiver toward the sampled point.
    pub to_light: Vec3,
    /// Distance to the sampled point in metres (∞ for directional lights).
    pub distance_m: f32,
    /// Irradiance estimate on a plane facing `to_light` (linear RGB).
    pub irradiance: DVec3,
}

/// One sample of `light` from `p`; None when it delivers nothing there (off, out of
/// range, outside its cone, behind its emitting side, or `p` inside a sphere light).
pub fn sample_light(light: &Light, p: Vec3, random: &mut SplitMix64) -> Option<EmitterSample> {
    let power = light.color.as_dvec3() * light.intensity as f64;
    if power == DVec3::ZERO {
        return None;
    }
    let (to_light, distance_m, unit) = match light.kind {
        LightKind::Point | LightKind::Spot { .. } | LightKind::Directional => {
            let incidence = light.unit_incidence(light.position, p);
            (incidence.to_light, incidence.distance_m, incidence.irradiance as f64)
        }
        LightKind::Sphere { radius_m } => sample_sphere(light, radius_m, p, random)?,
        LightKind::Rect { width_m, height_m, .. } => {
            let (u, v) = light.area_axes();
            let a = (random.next_f64() as f32 - 0.5) * width_m;
            let b = (random.next_f64() as f32 - 0.5) * height_m;
            let incidence = light.unit_incidence(light.position + u * a + v * b, p);
            (incidence.to_light, incidence.distance_m, incidence.irradiance as f64)
        }
        LightKind::Disk { radius_m } => {
            let (u, v) = light.area_axes();
            let r = radius_m * (random.next_f64() as f32).sqrt();
            let phi = random.next_f64() as f32 * TAU;
            let incidence = light.unit_incidence(light.position + (u * phi.cos() + v * phi.sin()) * r, p);
            (incidence.to_light, incidence.distance_m, incidence.irradiance as f64)
        }
    };
    (unit > 0.0).then(|| EmitterSample {
        to_light,
        distance_m,
        irradiance: power * unit,
    })
}

/// A direction uniform in the cone a sphere light subtends from `p`: (direction, distance
/// to the sphere's near surface, L·Ω per unit intensity with the range window).
fn sample_sphere(light: &Light, radius_m: f32, p: Vec3, random: &mut SplitMix64) -> Option<(Vec3, f32, f64)> {
    let offset = (light.position - p).as_dvec3();
    let distance = offset.length();
    let radius = radius_m as f64;
    if distance <= radius {
        return None;
    }
    let axis = offset / distance;
    let sin_alpha = radius / distance;
    let cos_alpha_max = (1.0 - sin_alpha * sin_alpha).max(0.0).sqrt();
    // 1 − cos α_max without cancellation for small spheres: sin²α/(1 + cos α_max).
    let one_minus_cos = sin_alpha * sin_alpha / (1.0 + cos_alpha_max);
    let cos_alpha = 1.0 - random.next_f64() * one_minus_cos;
    let sin = (1.0 - cos_alpha * cos_alpha).max(0.0).sqrt();
    let phi = random.next_f64() * std::f64::consts::TAU;
    let t = axis.any_orthonormal_vector();
    let b = axis.cross(t);
    let direction = (t * (sin * phi.cos()) + b * (sin * phi.sin()) + axis * cos_alpha).normalize();
    // Nearest root of |p + s·ω − c| = R.
    let along = direction.dot(offset);
    let to_surface = along
        - (along * along - (distance * distance - radius * radius))
            .max(0.0)
            .sqrt();
    let radiance_per_cd = 1.0 / (std::f64::consts::PI * radius * radius);
    let solid_angle = std::f64::consts::TAU * one_minus_cos;
    let window = light.range_window(distance as f32) as f64;
    Some((
        direction.as_vec3(),
        to_surface as f32,
        radiance_per_cd * solid_angle * window,
    ))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn light(kind: LightKind, position: Vec3) -> Light {
        Light {
            name: "l".into(),
            kind,
            color: Vec3::ONE,
            intensity: 2.0,
            position,
            direction: Vec3::NEG_Y,
            range: None,
            locked: false,
        }
    }

    /// Mean over `n` samples of the irradiance on a plane of normal +y at the origin.
    fn mean_irradiance(light: &Light, n: usize) -> f64 {
        let mut random = SplitMix64(5);
        (0..n)
            .filter_map(|_| sample_light(light, Vec3::ZERO, &mut random))
            .map(|s| s.irradiance.x * s.to_light.y.max(0.0) as f64)
            .sum::<f64>()
            / n as f64
    }

    #[test]
    fn a_sphere_above_the_horizon_gives_the_irradiance_of_a_point_at_its_centre() {
        // Any sphere of uniform radiance wholly above the plane gives E = I·cos θ/d².
        let position = Vec3::new(1.0, 2.0, 0.5);
        let sphere = light(LightKind::Sphere { radius_m: 0.8 }, position);
        let expected = 2.0 * (position.y / position.length()) as f64 / position.length_squared() as f64;
        let e = mean_irradiance(&sphere, 400_000);
        assert!((e - expected).abs() < 3e-3 * expected, "{e} vs {expected}");
    }

    #[test]
    fn a_disk_overhead_gives_its_closed_form() {
        // On the axis of a Lambertian disk of radius R at height h: E = πL·R²/(h² + R²).
        let (radius, height) = (0.7f32, 1.5f32);
        let disk = light(LightKind::Disk { radius_m: radius }, Vec3::new(0.0, height, 0.0));
        let expected = std::f64::consts::PI * 2.0 * (radius * radius / (height * height + radius * radius)) as f64;
        let e = mean_irradiance(&disk, 400_000);
        assert!((e - expected).abs() < 3e-3 * expected, "{e} vs {expected}");
    }

    #[test]
    fn a_square_overhead_gives_its_closed_form() {
        // Below the centre of a square of side 2a at height h (Lambertian, luminance L):
        // E = 4L·a/√(a² + h²)·atan(a/√(a² + h²)) (the polygon formula for a square).
        let (a, h) = (0.5f64, 1.0f64);
        let rect = light(
            LightKind::Rect {
                width_m: 2.0 * a as f32,
                height_m: 2.0 * a as f32,
                turn_rad: 0.0,
            },
            Vec3::new(0.0, h as f32, 0.0),
        );
        let k = a / (a * a + h * h).sqrt();
        let expected = 4.0 * 2.0 * k * k.atan();
        let e = mean_irradiance(&rect, 400_000);
        assert!((e - expected).abs() < 3e-3 * expected, "{e} vs {expected}");
    }

    #[test]
    fn a_one_sided_emitter_gives_nothing_behind_it_and_a_dark_light_nothing_at_all() {
        let mut random = SplitMix64(1);
        let facing_up = Light {
            direction: Vec3::Y,
            ..light(LightKind::Disk { radius_m: 0.5 }, Vec3::new(0.0, 1.0, 0.0))
        };
        assert!(sample_light(&facing_up, Vec3::ZERO, &mut random).is_none());
        let off = Light {
            intensity: 0.0,
            ..light(LightKind::Point, Vec3::Y)
        };
        assert!(sample_light(&off, Vec3::ZERO, &mut random).is_none());
    }
}
