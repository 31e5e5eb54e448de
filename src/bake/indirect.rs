//! Diffuse bounces of every light at every vertex: rays leave the vertex in evenly
//! spread directions ω_k of its upper hemisphere (a Fibonacci spiral, equal solid angle
//! 2π/M each, turned per vertex so neighbours do not share directions); where a ray meets
//! a surface q, that surface reflects light i diffusely with radiance ρ(q)/π·E_i(q), E_i
//! the direct irradiance at q from light i at unit intensity (exact visibility rays, next
//! event estimation), and further bounces follow the path on from q ([`indirect_sh`]).
//! The SH of the incident radiance is then (2π/M)·Σ_k L_k·y(ω_k).
//! ρ is the luminance of the hit material's diffuse colour (base colour factor × (1 −
//! metallic) × (1 − 0.04·specular), as the renderer maps it; textures are not sampled).

use std::f32::consts::{PI, TAU};

use glam::Vec3;

use super::direct::direct_irradiance;
use super::scene_bvh::SceneBvh;
use crate::random::{SplitMix64, cosine_direction};
use crate::scene::{Material, Scene};
use crate::sh;

/// Golden angle in radians.
const GOLDEN_ANGLE: f32 = 2.399_963_2;

/// Diffuse albedo of a material as one number: the Rec. 709 luminance of its k_d.
pub fn diffuse_luminance(material: &Material) -> f32 {
    (crate::scene::luminance(material.diffuse_albedo().as_dvec3()) as f32).clamp(0.0, 1.0)
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

/// Where a path meets a surface: the point, the normal facing the arriving ray, and the
/// surface's albedo.
struct PathVertex {
    point: Vec3,
    normal: Vec3,
    albedo: f32,
}

/// The first surface along `direction` from `origin`, if it reflects anything.
fn next_surface(bvh: &SceneBvh, scene: &Scene, albedo: &[f32], origin: Vec3, direction: Vec3) -> Option<PathVertex> {
    let hit = bvh.closest_hit(origin, direction, 0.0, f32::INFINITY)?;
    let object = &scene.objects[hit.object];
    let rho = albedo.get(object.material).copied().unwrap_or(0.0);
    if rho <= 0.0 {
        return None;
    }
    let mut normal = object.interpolated_normal(hit.triangle, hit.barycentric);
    if normal.dot(direction) > 0.0 {
        normal = -normal; // two-sided: the side the ray arrives on
    }
    Some(PathVertex {
        point: origin + direction * hit.distance_m,
        normal,
        albedo: rho,
    })
}

/// Per light of `lights` (index, SH at the settings' order) of the reflected radiance
/// arriving at `p` (normal `n`) after 1 to `settings.bounces` diffuse bounces; lights that
/// contribute nothing left out. `albedo` holds [`diffuse_luminance`] of each material.
///
/// From each of the evenly spread directions ω_k a path is followed: at its j-th surface
/// q_j, next-event estimation adds T_j·ρ_j/π·E_i(q_j) for every light i (E_i the exact
/// direct irradiance at unit intensity), then the path goes on in a cosine-distributed
/// direction with T_{j+1} = T_j·ρ_j (the Lambertian f·cos/pdf); from the third surface on
/// it survives with probability min(ρ_j, 0.95) and T is divided by it (Russian roulette,
/// unbiased). Paths are seeded by the vertex position, so a bake is deterministic.
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
    let solid_angle = 2.0 * PI as f64 / directions.max(1) as f64;
    let seed = p
        .to_array()
        .iter()
        .fold(0x5eed_u64, |h, c| h.rotate_left(21) ^ c.to_bits() as u64);
    let mut random = SplitMix64(seed);
    for omega in hemisphere_directions(n, directions.max(1), turn) {
        let y = sh::basis(order, omega.as_dvec3());
        let mut surface = next_surface(bvh, scene, albedo, origin, omega);
        let mut throughput = 1.0f64;
        let mut bounce = 1;
        while let Some(q) = surface {
            for &i in lights {
                let Some(light) = scene.lights.get(i) else { continue };
                let e = direct_irradiance(bvh, light, q.point, q.normal, settings.light_samples, offset);
                if e <= 0.0 {
                    continue;
                }
                let weight = solid_angle * throughput * q.albedo as f64 / PI as f64 * e as f64;
                let sum = sums[i].get_or_insert_with(|| vec![0.0; order * order]);
                for (s, yk) in sum.iter_mut().zip(&y) {
                    *s += weight * yk;
                }
            }
            if bounce >= settings.bounces {
                break;
            }
            throughput *= q.albedo as f64;
            if bounce >= 2 {
                let survival = (q.albedo as f64).min(0.95);
                if random.next_f64() >= survival {
                    break;
                }
                throughput /= survival;
            }
            let next = cosine_direction(q.normal, random.next_f64(), random.next_f64());
            surface = next_surface(bvh, scene, albedo, q.point + q.normal * offset, next);
            bounce += 1;
        }
    }
    sums.into_iter()
        .enumerate()
        .filter_map(|(i, sum)| sum.map(|s| (i as u32, s.into_iter().map(|v| v as f32).collect())))
        .collect()
}
