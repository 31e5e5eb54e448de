//! One diffuse bounce of every light at every vertex: rays leave the vertex in evenly
//! spread directions ω_k of its upper hemisphere (a Fibonacci spiral, equal solid angle
//! 2π/M each, turned per vertex so neighbours do not share directions); where a ray meets
//! a surface q, that surface reflects light i diffusely with radiance ρ(q)/π·E_i(q), E_i
//! the direct irradiance at q from light i at unit intensity (exact visibility rays, next
//! event estimation). The SH of the incident radiance is then (2π/M)·Σ_k L_k·y(ω_k).
//! ρ is the luminance of the hit material's diffuse colour (base colour factor × (1 −
//! metallic) × (1 − 0.04·specular), as the renderer maps it; textures are not sampled).

use std::f32::consts::{PI, TAU};

use glam::Vec3;

use super::direct::direct_irradiance;
use super::scene_bvh::SceneBvh;
use crate::scene::{Material, Scene};
use crate::sh;

/// Golden angle in radians.
const GOLDEN_ANGLE: f32 = 2.399_963_2;

/// Diffuse albedo of a material as one number: the Rec. 709 luminance of its k_d.
pub fn diffuse_luminance(material: &Material) -> f32 {
    let k_d = material.diffuse_albedo();
    (0.2126 * k_d.x + 0.7152 * k_d.y + 0.0722 * k_d.z).clamp(0.0, 1.0)
}

/// `count` directions evenly spread over the hemisphere around unit `n`, turned by `turn_rad`.
fn hemisphere_directions(n: Vec3, count: usize, turn_rad: f32) -> impl Iterator<Item = Vec3> {
    let t = n.any_orthonormal_vector();
    let b = n.cross(t);
    (0..count).map(move |k| {
        // Uniform in cos θ over [0, 1]: equal solid angle per direction.
        let z = 1.0 - (k as f32 + 0.5) / count as f32;
        let r = (1.0 - z * z).max(0.0).sqrt();
        let phi = k as f32 * GOLDEN_ANGLE + turn_rad;
        t * (r * phi.cos()) + b * (r * phi.sin()) + n * z
    })
}

/// Per light of `lights` (index, SH at the settings' order) of the once-reflected radiance
/// arriving at `p` (normal `n`), lights that contribute nothing left out.
/// `albedo` holds [`diffuse_luminance`] of each of the scene's materials.
pub fn indirect_sh(
    bvh: &SceneBvh,
    scene: &Scene,
    albedo: &[f32],
    lights: &[usize],
    p: Vec3,
    n: Vec3,
    settings: &super::BakeSettings,
) -> Vec<(u32, Vec<f32>)> {
    let (order, directions) = (settings.order, settings.indirect_directions);
    let offset = settings.ray_offset_m;
    let origin = p + n * offset;
    // A per-vertex turn from its position, so the spiral differs between neighbours.
    let turn = (p.dot(Vec3::new(12.9898, 78.233, 37.719)).sin() * 43_758.547).fract() * TAU;
    let mut sums: Vec<Option<Vec<f64>>> = vec![None; scene.lights.len()];
    let solid_angle = 2.0 * PI / directions.max(1) as f32;
    for omega in hemisphere_directions(n, directions.max(1), turn) {
        let Some(hit) = bvh.closest_hit(origin, omega, 0.0, f32::INFINITY) else {
            continue;
        };
        let object = &scene.objects[hit.object];
        let rho = albedo.get(object.material).copied().unwrap_or(0.0);
        if rho <= 0.0 {
            continue;
        }
        let corners = [0, 1, 2].map(|k| object.indices[3 * hit.triangle + k] as usize);
        let mut normal = (object.normals[corners[0]] * hit.barycentric.x
            + object.normals[corners[1]] * hit.barycentric.y
            + object.normals[corners[2]] * hit.barycentric.z)
            .normalize_or_zero();
        if normal.dot(omega) > 0.0 {
            normal = -normal; // two-sided: the side the ray arrives on
        }
        let q = origin + omega * hit.distance_m;
        let y = sh::basis(order, omega.as_dvec3());
        for &i in lights {
            let Some(light) = scene.lights.get(i) else { continue };
            let e = direct_irradiance(bvh, light, q, normal, settings.light_samples, offset);
            if e <= 0.0 {
                continue;
            }
            let weight = (solid_angle * rho / PI * e) as f64;
            let sum = sums[i].get_or_insert_with(|| vec![0.0; order * order]);
            for (s, yk) in sum.iter_mut().zip(&y) {
                *s += weight * yk;
            }
        }
    }
    sums.into_iter()
        .enumerate()
        .filter_map(|(i, sum)| sum.map(|s| (i as u32, s.into_iter().map(|v| v as f32).collect())))
        .collect()
}
