//! Bounces of every light at every vertex: rays leave the vertex in evenly spread
//! directions ω_k of its upper hemisphere (a Fibonacci spiral, equal solid angle 2π/M each,
//! turned per vertex so neighbours do not share directions); where a ray meets a surface q,
//! that surface reflects light i toward the vertex with radiance Σ_s E_s·f(l_s, v)·(n·l_s)
//! over the light's visible emitter samples s (exact visibility rays, next event
//! estimation), f the shared diffuse + Phong model ([`Reflectance`]), so glossy surfaces
//! bounce light in their mirror direction; further bounces follow the path on from q
//! ([`indirect_sh`]). The SH of the incident radiance is then (2π/M)·Σ_k L_k·y(ω_k).
//! Colours are reduced to their Rec. 709 luminance, and a surface's reflectance comes from
//! its material's factors (base colour, metallic, roughness, specular) and its base-colour
//! texture at the hit, sampled as the path tracer samples it (bilinear, no mip chain): a
//! checkered floor bounces its texture's light, not its factor's.

use std::f32::consts::{PI, TAU};

use glam::{DVec3, Vec3};

use super::LightContribution;
use super::direct::visible_samples;
use super::scene_bvh::SceneBvh;
use crate::random::SplitMix64;
use crate::scene::{Material, Reflectance, Scene, luminance};
use crate::sh;

/// Golden angle in radians.
const GOLDEN_ANGLE: f32 = 2.399_963_2;

/// What a path bounces off, per material: its reflectance from the material's factors
/// (a black one reflects nothing, whatever its texture).
pub fn bounce_reflectance(material: &Material) -> Reflectance {
    Reflectance::of_material(material, DVec3::ONE)
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

/// Where a path meets a surface: the point, the normals facing the arriving ray, the way
/// back along it, and the surface's reflectance.
struct PathVertex {
    point: Vec3,
    normal: Vec3,
    geometric_normal: Vec3,
    to_eye: Vec3,
    reflectance: Reflectance,
}

/// The first surface along `direction` from `origin`, if it reflects anything.
fn next_surface(
    bvh: &SceneBvh,
    scene: &Scene,
    reflectances: &[Reflectance],
    origin: Vec3,
    direction: Vec3,
) -> Option<PathVertex> {
    let hit = bvh.closest_hit(origin, direction, 0.0, f32::INFINITY)?;
    let object = &scene.objects[hit.object];
    let mut reflectance = *reflectances.get(object.material)?;
    if reflectance.is_black() {
        return None;
    }
    let material = scene.materials.get(object.material);
    if let Some(texture) = material
        .and_then(|m| m.base_color_texture)
        .and_then(|t| scene.textures.get(t))
    {
        let colour = texture.sample_bilinear(object.interpolated_uv(hit.triangle, hit.barycentric));
        reflectance = Reflectance::of_material(material?, colour);
    }
    let mut geometric_normal = object.face_normal(hit.triangle);
    let mut normal = object.interpolated_normal(hit.triangle, hit.barycentric);
    if normal == Vec3::ZERO {
        normal = geometric_normal;
    }
    if geometric_normal.dot(direction) > 0.0 {
        // Two-sided: the side the ray arrives on.
        geometric_normal = -geometric_normal;
        normal = -normal;
    }
    Some(PathVertex {
        point: origin + direction * hit.distance_m,
        normal,
        geometric_normal,
        to_eye: -direction,
        reflectance,
    })
}

impl PathVertex {
    /// Luminance of the radiance `light` (unit intensity) sends back along the path from
    /// here: Σ_s E_s·f(l_s, v)·(n·l_s) over its visible emitter samples.
    fn reflected(&self, bvh: &SceneBvh, light: &crate::scene::Light, samples: usize, offset_m: f32) -> f64 {
        visible_samples(bvh, light, self.point, self.geometric_normal, samples, offset_m)
            .into_iter()
            .map(|(irradiance, to_light)| {
                irradiance as f64 * luminance(self.reflectance.per_irradiance(self.normal, self.to_eye, to_light))
            })
            .sum()
    }
}

/// Per light of `lights`, the SH (the settings' order) of the reflected radiance arriving
/// at `p` (normal `n`) after 1 to `settings.bounces` bounces, and the irradiance it gives
/// the surface, (2π/M)·Σ_k L_k·(n·ω_k); lights that contribute nothing left out.
/// `reflectances` holds [`bounce_reflectance`] of each material.
///
/// From each of the evenly spread directions ω_k a path is followed: at its j-th surface
/// q_j, next-event estimation adds T_j·L_i(q_j → q_{j−1}) for every light i (the exact
/// direct light reflected back along the path, at unit intensity), then the path goes on
/// in a direction drawn from the reflectance model (cosine or Phong lobe) with
/// T_{j+1} = T_j·f·cos/pdf; from the third surface on it survives with probability
/// min(f·cos/pdf, 0.95) and T is divided by it (Russian roulette, unbiased). Paths are
/// seeded by the vertex position, so a bake is deterministic.
pub fn indirect_sh(
    bvh: &SceneBvh,
    scene: &Scene,
    reflectances: &[Reflectance],
    lights: &[usize],
    p: Vec3,
    n: Vec3,
    settings: &super::BakeSettings,
) -> Vec<LightContribution> {
    let (order, directions) = (settings.order, settings.indirect_directions);
    let offset = settings.ray_offset_m;
    let origin = p + n * offset;
    // A per-vertex turn from its position, so the spiral differs between neighbours.
    let turn = (p.dot(Vec3::new(12.9898, 78.233, 37.719)).sin() * 43_758.547).fract() * TAU;
    // Per light: the SH sum, then the irradiance in the last slot.
    let mut sums: Vec<Option<Vec<f64>>> = vec![None; scene.lights.len()];
    let solid_angle = 2.0 * PI as f64 / directions.max(1) as f64;
    let seed = p
        .to_array()
        .iter()
        .fold(0x5eed_u64, |h, c| h.rotate_left(21) ^ c.to_bits() as u64);
    let mut random = SplitMix64(seed);
    for omega in hemisphere_directions(n, directions.max(1), turn) {
        let mut y = sh::basis(order, omega.as_dvec3());
        y.push(n.dot(omega) as f64);
        let mut surface = next_surface(bvh, scene, reflectances, origin, omega);
        let mut throughput = 1.0f64;
        let mut bounce = 1;
        while let Some(q) = surface {
            for &i in lights {
                let Some(light) = scene.lights.get(i) else { continue };
                let radiance = q.reflected(bvh, light, settings.light_samples, offset);
                if radiance <= 0.0 {
                    continue;
                }
                let weight = solid_angle * throughput * radiance;
                let sum = sums[i].get_or_insert_with(|| vec![0.0; order * order + 1]);
                for (s, yk) in sum.iter_mut().zip(&y) {
                    *s += weight * yk;
                }
            }
            if bounce >= settings.bounces {
                break;
            }
            let Some((next, weight)) = q
                .reflectance
                .sample(q.normal, q.geometric_normal, q.to_eye, &mut random)
            else {
                break;
            };
            let weight = luminance(weight);
            throughput *= weight;
            if bounce >= 2 {
                let survival = weight.min(0.95);
                if random.next_f64() >= survival {
                    break;
                }
                throughput /= survival;
            }
            surface = next_surface(bvh, scene, reflectances, q.point + q.geometric_normal * offset, next);
            bounce += 1;
        }
    }
    sums.into_iter()
        .enumerate()
        .filter_map(|(i, sum)| {
            let mut sh: Vec<f32> = sum?.into_iter().map(|v| v as f32).collect();
            let indirect_irradiance = sh.pop().unwrap_or(0.0);
            Some(LightContribution {
                light: i as u32,
                sh,
                indirect_irradiance,
            })
        })
        .collect()
}
