//! Direct light of every light at every vertex, as SH of the incident radiance at unit
//! intensity (the light's `intensity` and colour are applied later, so a stroke never
//! re-bakes): for a point-like source seen in direction d with irradiance E (on a plane
//! facing it), the projection of E·δ(ω − d) is E·y(d). Extended lights (sphere, rect,
//! disk) are sampled at deterministic, evenly spread points of their emitting surface,
//! each a point source of an equal share; every sample has an exact visibility ray.
//! Lights below a vertex's horizon (n·d ≤ 0 for all samples) contribute nothing, and
//! nothing is stored for them (sparse maps).

use glam::Vec3;

use super::scene_bvh::SceneBvh;
use crate::scene::{Light, LightKind, UnitIncidence};
use crate::sh;

/// Golden angle in radians, for Fibonacci spreads.
const GOLDEN_ANGLE: f32 = 2.399_963_2;

/// A point of an emitter and its share of the light (shares sum to 1 for the light).
#[derive(Debug, Clone, Copy)]
struct EmitterSample {
    position: Vec3,
    share: f32,
}

/// The emitter samples of `light` seen from `p` (empty for directional lights).
fn emitter_samples(light: &Light, p: Vec3, samples: usize) -> Vec<EmitterSample> {
    let n = samples.max(1);
    // (point, weight) pairs; weights are normalised to shares below.
    let points: Vec<(Vec3, f32)> = match light.kind {
        LightKind::Point | LightKind::Spot { .. } | LightKind::Directional => vec![(light.position, 1.0)],
        LightKind::Sphere { radius_m } => {
            // A sphere of uniform radiance L = I/(πR²): each of 2n evenly spread surface
            // points (area 4πR²/2n) adds L·cos_e·dA/r² of solid angle-weighted radiance,
            // i.e. a point source of share 2·cos_e/n where cos_e is the emitter's cosine
            // toward p (0 on the far side). No normalisation: the sum is the integral.
            let centre_to_p = p - light.position;
            let spread = 2 * n;
            return (0..spread)
                .filter_map(|k| {
                    let z = 1.0 - (k as f32 + 0.5) / n as f32;
                    let r = (1.0 - z * z).max(0.0).sqrt();
                    let phi = k as f32 * GOLDEN_ANGLE;
                    let normal = Vec3::new(r * phi.cos(), r * phi.sin(), z);
                    let position = light.position + normal * radius_m;
                    let to_p = (centre_to_p - normal * radius_m).normalize_or_zero();
                    let cos_emitter = normal.dot(to_p);
                    (cos_emitter > 0.0).then_some(EmitterSample {
                        position,
                        share: 2.0 * cos_emitter / n as f32,
                    })
                })
                .collect();
        }
        LightKind::Rect { width_m, height_m, .. } => {
            let (u, v) = light.area_axes();
            let side = (n as f32).sqrt().ceil() as usize;
            (0..side * side)
                .map(|k| {
                    let (i, j) = (k % side, k / side);
                    let a = ((i as f32 + 0.5) / side as f32 - 0.5) * width_m;
                    let b = ((j as f32 + 0.5) / side as f32 - 0.5) * height_m;
                    (light.position + u * a + v * b, 1.0)
                })
                .collect()
        }
        LightKind::Disk { radius_m } => {
            let (u, v) = light.area_axes();
            (0..n)
                .map(|k| {
                    let r = radius_m * ((k as f32 + 0.5) / n as f32).sqrt();
                    let phi = k as f32 * GOLDEN_ANGLE;
                    (light.position + (u * phi.cos() + v * phi.sin()) * r, 1.0)
                })
                .collect()
        }
    };
    let total: f32 = points.iter().map(|(_, w)| w).sum();
    points
        .into_iter()
        .map(|(position, weight)| EmitterSample {
            position,
            share: weight / total.max(f32::MIN_POSITIVE),
        })
        .collect()
}

/// The visible emitter samples of `light` from `p` (normal `n`) above its horizon: each
/// with the irradiance it gives a plane facing it per unit intensity, and its direction.
/// Rays start `offset_m` off the surface.
pub fn visible_samples(
    bvh: &SceneBvh,
    light: &Light,
    p: Vec3,
    n: Vec3,
    samples: usize,
    offset_m: f32,
) -> Vec<(f32, Vec3)> {
    let origin = p + n * offset_m;
    emitter_samples(light, p, samples)
        .into_iter()
        .filter_map(|sample| {
            let UnitIncidence {
                irradiance,
                to_light,
                distance_m: distance,
            } = light.unit_incidence(sample.position, p);
            let above = irradiance > 0.0 && n.dot(to_light) > 0.0;
            (above && !bvh.occluded(origin, to_light, 0.0, distance - offset_m * 2.0))
                .then_some((sample.share * irradiance, to_light))
        })
        .collect()
}

/// The SH (order `order`) of the radiance arriving at `p` (normal `n`) from `light` at unit
/// intensity, or None if none arrives.
pub fn direct_sh(
    bvh: &SceneBvh,
    light: &Light,
    p: Vec3,
    n: Vec3,
    order: usize,
    samples: usize,
    offset_m: f32,
) -> Option<Vec<f32>> {
    let visible = visible_samples(bvh, light, p, n, samples, offset_m);
    if visible.is_empty() {
        return None;
    }
    let mut sum = vec![0.0f64; order * order];
    for (weight, to_light) in visible {
        for (s, y) in sum.iter_mut().zip(sh::basis(order, to_light.as_dvec3())) {
            *s += weight as f64 * y;
        }
    }
    Some(sum.into_iter().map(|v| v as f32).collect())
}

/// Irradiance at `p` (normal `n`) from `light` at unit intensity: Σ E_k·(n·l_k) over its
/// visible samples.
pub fn direct_irradiance(bvh: &SceneBvh, light: &Light, p: Vec3, n: Vec3, samples: usize, offset_m: f32) -> f32 {
    visible_samples(bvh, light, p, n, samples, offset_m)
        .into_iter()
        .map(|(weight, to_light)| weight * n.dot(to_light))
        .sum()
}
