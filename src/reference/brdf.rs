//! The renderer's reflectance model as the path tracer evaluates and samples it: a
//! Lambertian lobe plus a normalised Phong lobe about the mirror direction, written as
//! what reaches the eye per unit irradiance from direction l (`direct_radiance` in
//! shaders/scene.wgsl):
//!
//!   f(l, v)·(n·l) = k_d/π·(n·l) + k_s·(r + 1)/(2π)·max(m·l, 0)^r,   m = reflect(−v, n),
//!
//! zero when n·l ≤ 0. The glossy lobe is a density over directions, so sampling it makes
//! the weight f·cos/pdf = k_s exactly.

use std::f64::consts::PI;

use glam::{DVec3, Vec3};

use super::surface::SurfaceHit;
use crate::random::{SplitMix64, cosine_direction, phong_lobe_direction};
use crate::scene::luminance;

/// The mirror direction of the unit `to_eye` about the surface normal.
fn mirror(surface: &SurfaceHit, to_eye: Vec3) -> Vec3 {
    let n = surface.normal;
    (2.0 * n.dot(to_eye) * n - to_eye).normalize_or(n)
}

/// (r + 1)/(2π)·max(cos, 0)^r, with exp2(r·log2 c) so that r = 0 gives the constant.
fn phong_lobe(exponent: f64, cos_mirror: f64) -> f64 {
    (exponent + 1.0) / (2.0 * PI) * (exponent * cos_mirror.max(1e-8).log2()).exp2()
}

/// f(l, v)·(n·l) for unit `to_eye` (v) and `to_light` (l).
pub fn reflected_per_irradiance(surface: &SurfaceHit, to_eye: Vec3, to_light: Vec3) -> DVec3 {
    let n_dot_l = surface.normal.dot(to_light) as f64;
    if n_dot_l <= 0.0 {
        return DVec3::ZERO;
    }
    let cos_mirror = mirror(surface, to_eye).dot(to_light) as f64;
    surface.k_d / PI * n_dot_l + surface.k_s * phong_lobe(surface.phong_exponent, cos_mirror)
}

/// Probability of sampling the diffuse lobe: its share of the two lobes' luminance.
fn diffuse_probability(surface: &SurfaceHit) -> Option<f64> {
    let diffuse = luminance(surface.k_d).max(0.0);
    let glossy = luminance(surface.k_s).max(0.0);
    (diffuse + glossy > 0.0).then(|| diffuse / (diffuse + glossy))
}

/// A direction to continue a path from `surface` seen along `to_eye`, and its weight
/// f·cos/pdf under the mixture of the cosine and Phong densities (one-sample MIS by the
/// balance heuristic); None when the surface reflects nothing or the sample went below the
/// horizon.
pub fn sample_direction(surface: &SurfaceHit, to_eye: Vec3, random: &mut SplitMix64) -> Option<(Vec3, DVec3)> {
    let p_diffuse = diffuse_probability(surface)?;
    let axis = mirror(surface, to_eye);
    let (u0, u1, u2) = (random.next_f64(), random.next_f64(), random.next_f64());
    let direction = if u0 < p_diffuse {
        cosine_direction(surface.normal, u1, u2)
    } else {
        phong_lobe_direction(axis, surface.phong_exponent, u1, u2)
    };
    let n_dot_l = surface.normal.dot(direction) as f64;
    if n_dot_l <= 0.0 || surface.geometric_normal.dot(direction) <= 0.0 {
        return None;
    }
    let pdf =
        p_diffuse * n_dot_l / PI + (1.0 - p_diffuse) * phong_lobe(surface.phong_exponent, axis.dot(direction) as f64);
    let weight = reflected_per_irradiance(surface, to_eye, direction) / pdf;
    weight.is_finite().then_some((direction, weight))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn surface(k_d: f64, k_s: f64, exponent: f64) -> SurfaceHit {
        SurfaceHit {
            position: Vec3::ZERO,
            geometric_normal: Vec3::Y,
            normal: Vec3::Y,
            k_d: DVec3::splat(k_d),
            k_s: DVec3::splat(k_s),
            phong_exponent: exponent,
            emissive: DVec3::ZERO,
        }
    }

    /// Mean weight of many sampled directions: the directional albedo ∫ f·cos dω.
    fn albedo(s: &SurfaceHit, to_eye: Vec3) -> f64 {
        let mut random = SplitMix64(11);
        let n = 200_000;
        (0..n)
            .filter_map(|_| sample_direction(s, to_eye, &mut random))
            .map(|(_, w)| w.x)
            .sum::<f64>()
            / n as f64
    }

    #[test]
    fn a_lambertian_surface_reflects_its_albedo_with_zero_variance_weights() {
        let s = surface(0.6, 0.0, 0.0);
        let mut random = SplitMix64(3);
        for _ in 0..1000 {
            let (_, w) = sample_direction(&s, Vec3::Y, &mut random).expect("a direction above the horizon");
            assert!((w.x - 0.6).abs() < 1e-5, "{w}");
        }
    }

    #[test]
    fn sampled_albedo_matches_a_quadrature_of_the_model() {
        // The estimator's mean must equal ∫ f·cos dω, integrated here by a midpoint rule in
        // (cos θ, φ) over the hemisphere, for a mixed diffuse + glossy surface seen obliquely.
        let s = surface(0.5, 0.3, 20.0);
        let to_eye = Vec3::new(0.6, 0.8, 0.0);
        let (rows, columns) = (400, 400);
        let mut integral = 0.0;
        for i in 0..rows {
            let z = (i as f64 + 0.5) / rows as f64;
            for j in 0..columns {
                let phi = (j as f64 + 0.5) / columns as f64 * 2.0 * PI;
                let r = (1.0 - z * z).sqrt();
                let l = DVec3::new(r * phi.cos(), z, r * phi.sin()).as_vec3();
                integral += reflected_per_irradiance(&s, to_eye, l).x * (2.0 * PI / (rows * columns) as f64);
            }
        }
        let sampled = albedo(&s, to_eye);
        assert!(
            (sampled - integral).abs() < 0.01 * integral,
            "sampled {sampled} vs quadrature {integral}"
        );
    }

    #[test]
    fn a_black_surface_continues_no_path() {
        let mut random = SplitMix64(1);
        assert!(sample_direction(&surface(0.0, 0.0, 5.0), Vec3::Y, &mut random).is_none());
    }
}
