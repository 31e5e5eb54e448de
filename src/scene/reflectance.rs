//! The reflectance model every part shares (the shaders' `direct_radiance`, the path
//! tracer, the bake's bounces): a Lambertian lobe plus a normalised Phong lobe about the
//! mirror direction, written as what leaves toward the eye per unit irradiance arriving
//! from direction l:
//!
//!   f(l, v)·(n·l) = k_d/π·(n·l) + k_s·(r + 1)/(2π)·max(m·l, 0)^r,   m = reflect(−v, n),
//!
//! zero when n·l ≤ 0. The glossy lobe is a density over directions, so sampling it makes
//! the weight f·cos/pdf = k_s exactly. Colours are linear RGB.

use std::f64::consts::PI;

use glam::{DVec3, Vec3};

use super::{Material, luminance};
use crate::random::{SplitMix64, cosine_direction, phong_lobe_direction};

/// A surface's reflectance: diffuse and glossy colours and the Phong exponent.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Reflectance {
    pub k_d: DVec3,
    pub k_s: DVec3,
    pub phong_exponent: f64,
}

impl Reflectance {
    /// The material's reflectance from its factors (`base` multiplies the base colour: a
    /// texture sample, or 1), mapped as docs/architecture.md ("Materials") says.
    pub fn of_material(material: &Material, base: DVec3) -> Reflectance {
        Reflectance {
            k_d: material.diffuse_albedo().as_dvec3() * base,
            k_s: specular_with_base(material, base),
            phong_exponent: material.phong_exponent() as f64,
        }
    }

    /// Whether the surface reflects nothing.
    pub fn is_black(&self) -> bool {
        self.k_d == DVec3::ZERO && self.k_s == DVec3::ZERO
    }

    /// f(l, v)·(n·l) for the unit shading normal `n`, `to_eye` (v) and `to_light` (l).
    pub fn per_irradiance(&self, n: Vec3, to_eye: Vec3, to_light: Vec3) -> DVec3 {
        let n_dot_l = n.dot(to_light) as f64;
        if n_dot_l <= 0.0 {
            return DVec3::ZERO;
        }
        let cos_mirror = mirror(n, to_eye).dot(to_light) as f64;
        self.k_d / PI * n_dot_l + self.k_s * phong_lobe(self.phong_exponent, cos_mirror)
    }

    /// A direction to continue a path from a surface (shading normal `n`, face normal
    /// `geometric_normal` on the side of `to_eye`) and its weight f·cos/pdf under the
    /// mixture of the cosine and Phong densities (one-sample MIS by the balance
    /// heuristic); None when the surface reflects nothing or the sample went below the
    /// horizon.
    pub fn sample(
        &self,
        n: Vec3,
        geometric_normal: Vec3,
        to_eye: Vec3,
        random: &mut SplitMix64,
    ) -> Option<(Vec3, DVec3)> {
        let p_diffuse = self.diffuse_probability()?;
        let axis = mirror(n, to_eye);
        let (u0, u1, u2) = (random.next_f64(), random.next_f64(), random.next_f64());
        let direction = if u0 < p_diffuse {
            cosine_direction(n, u1, u2)
        } else {
            phong_lobe_direction(axis, self.phong_exponent, u1, u2)
        };
        let n_dot_l = n.dot(direction) as f64;
        if n_dot_l <= 0.0 || geometric_normal.dot(direction) <= 0.0 {
            return None;
        }
        let pdf =
            p_diffuse * n_dot_l / PI + (1.0 - p_diffuse) * phong_lobe(self.phong_exponent, axis.dot(direction) as f64);
        let weight = self.per_irradiance(n, to_eye, direction) / pdf;
        weight.is_finite().then_some((direction, weight))
    }

    /// Probability of sampling the diffuse lobe: its share of the two lobes' luminance.
    fn diffuse_probability(&self) -> Option<f64> {
        let diffuse = luminance(self.k_d).max(0.0);
        let glossy = luminance(self.k_s).max(0.0);
        (diffuse + glossy > 0.0).then(|| diffuse / (diffuse + glossy))
    }
}

/// k_s = mix(0.04·specular, base colour × `base`, metallic).
fn specular_with_base(material: &Material, base: DVec3) -> DVec3 {
    let dielectric = DVec3::splat((super::material::DIELECTRIC_F0 * material.specular) as f64);
    dielectric.lerp(
        material.base_color.truncate().as_dvec3() * base,
        material.metallic as f64,
    )
}

/// The mirror direction of the unit `to_eye` about the unit normal `n`.
fn mirror(n: Vec3, to_eye: Vec3) -> Vec3 {
    (2.0 * n.dot(to_eye) * n - to_eye).normalize_or(n)
}

/// (r + 1)/(2π)·max(cos, 0)^r, with exp2(r·log2 c) so that r = 0 gives the constant.
fn phong_lobe(exponent: f64, cos_mirror: f64) -> f64 {
    (exponent + 1.0) / (2.0 * PI) * (exponent * cos_mirror.max(1e-8).log2()).exp2()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn reflectance(k_d: f64, k_s: f64, exponent: f64) -> Reflectance {
        Reflectance {
            k_d: DVec3::splat(k_d),
            k_s: DVec3::splat(k_s),
            phong_exponent: exponent,
        }
    }

    /// Mean weight of many sampled directions: the directional albedo ∫ f·cos dω.
    fn albedo(s: &Reflectance, to_eye: Vec3) -> f64 {
        let mut random = SplitMix64(11);
        let n = 200_000;
        (0..n)
            .filter_map(|_| s.sample(Vec3::Y, Vec3::Y, to_eye, &mut random))
            .map(|(_, w)| w.x)
            .sum::<f64>()
            / n as f64
    }

    #[test]
    fn a_lambertian_surface_reflects_its_albedo_with_zero_variance_weights() {
        let s = reflectance(0.6, 0.0, 0.0);
        let mut random = SplitMix64(3);
        for _ in 0..1000 {
            let (_, w) = s
                .sample(Vec3::Y, Vec3::Y, Vec3::Y, &mut random)
                .expect("a direction above the horizon");
            assert!((w.x - 0.6).abs() < 1e-5, "{w}");
        }
    }

    #[test]
    fn sampled_albedo_matches_a_quadrature_of_the_model() {
        // The estimator's mean must equal ∫ f·cos dω, integrated here by a midpoint rule in
        // (cos θ, φ) over the hemisphere, for a mixed diffuse + glossy surface seen obliquely.
        let s = reflectance(0.5, 0.3, 20.0);
        let to_eye = Vec3::new(0.6, 0.8, 0.0);
        let (rows, columns) = (400, 400);
        let mut integral = 0.0;
        for i in 0..rows {
            let z = (i as f64 + 0.5) / rows as f64;
            for j in 0..columns {
                let phi = (j as f64 + 0.5) / columns as f64 * 2.0 * PI;
                let r = (1.0 - z * z).sqrt();
                let l = DVec3::new(r * phi.cos(), z, r * phi.sin()).as_vec3();
                integral += s.per_irradiance(Vec3::Y, to_eye, l).x * (2.0 * PI / (rows * columns) as f64);
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
        assert!(
            reflectance(0.0, 0.0, 5.0)
                .sample(Vec3::Y, Vec3::Y, Vec3::Y, &mut random)
                .is_none()
        );
    }

    #[test]
    fn the_material_mapping_matches_the_documented_formulas() {
        let material = Material {
            base_color: glam::Vec4::new(0.8, 0.4, 0.2, 1.0),
            metallic: 0.25,
            roughness: 0.5,
            specular: 1.0,
            ..Material::default()
        };
        let r = Reflectance::of_material(&material, DVec3::new(0.5, 1.0, 1.0));
        // k_d = base·(1 − m)·(1 − 0.04), k_s = 0.04·(1 − m) + base·m, base halved in red.
        assert!((r.k_d.x - 0.4 * 0.75 * 0.96).abs() < 1e-6, "{r:?}");
        assert!((r.k_s.x - (0.04 * 0.75 + 0.4 * 0.25)).abs() < 1e-6, "{r:?}");
        assert!((r.k_s.y - (0.04 * 0.75 + 0.4 * 0.25)).abs() < 1e-6, "{r:?}");
    }
}
