//! The path estimator: radiance along one ray, with next-event estimation of every light
//! at every surface, continuation by sampling the reflectance model, and Russian roulette
//! from the third reflection.
//!
//! Bounce counting matches the bake: with `bounces` = B, light reaches the eye after at
//! most B + 1 reflections, so B = 0 is direct light only. Lights are not geometry: they
//! are reached only by next-event estimation, which keeps the estimator unbiased without
//! multiple importance sampling. Emissive surfaces and the environment are reached only by
//! continuation rays.

use glam::{DVec3, Vec3};

use super::emitters::sample_light;
use super::surface::{SurfaceHit, surface_at};
use crate::bake::scene_bvh::SceneBvh;
use crate::random::SplitMix64;
use crate::scene::Scene;

/// Russian roulette starts at this reflection (the bake's choice).
const ROULETTE_FROM_REFLECTION: u32 = 3;

/// Everything a path needs to know about the scene.
pub struct PathTracer<'a> {
    scene: &'a Scene,
    bvh: SceneBvh,
    /// World radiance SH (order 3, RGB) of the environment, with its intensity.
    environment_sh: Option<Vec<[f64; 3]>>,
    /// How far rays start off a surface, from the scene's size (f32 positions).
    offset_m: f32,
    bounces: u32,
}

impl<'a> PathTracer<'a> {
    pub fn new(scene: &'a Scene, bounces: u32) -> PathTracer<'a> {
        let bounds = scene.bounds();
        let extent = if bounds.is_empty() {
            1.0
        } else {
            (bounds.max - bounds.min)
                .length()
                .max(bounds.max.abs().max(bounds.min.abs()).max_element())
        };
        PathTracer {
            scene,
            bvh: SceneBvh::build(scene),
            environment_sh: scene.environment.as_ref().map(|e| e.world_radiance_sh()),
            offset_m: (extent * 1e-5).max(f32::MIN_POSITIVE),
            bounces,
        }
    }

    /// Rays traced so far (camera, continuation and shadow rays).
    pub fn rays_cast(&self) -> u64 {
        self.bvh.rays_cast()
    }

    /// Radiance arriving at `origin` from unit `direction` (a camera ray valid between
    /// `t_min` and `t_max`), or None when the ray meets no surface.
    pub fn radiance(
        &self,
        origin: Vec3,
        direction: Vec3,
        t_min: f32,
        t_max: f32,
        random: &mut SplitMix64,
    ) -> Option<DVec3> {
        let surface = self.next_surface(origin, direction, t_min, t_max)?;
        Some(self.radiance_leaving(surface, -direction, random))
    }

    /// `captured`, a rasterised pixel's surface point, as a ray from `eye` toward it
    /// meets the scene: where that ray meets a surface well before the point (it lies
    /// inside other geometry, as where meshes interpenetrate or at a crack the depth test
    /// resolved the other way), that surface, which the eye sees; otherwise the point,
    /// with the face normal of the triangle the ray meets there for rays to leave by (the
    /// capture keeps only the shading normal).
    pub fn as_seen_from(&self, eye: Vec3, captured: SurfaceHit) -> SurfaceHit {
        let offset = captured.position - eye;
        let distance = offset.length();
        if !(distance.is_finite() && distance > 0.0) {
            return captured;
        }
        let direction = offset / distance;
        let slack = (distance * 2e-5).max(4.0 * self.offset_m);
        let Some(hit) = self.next_surface(eye, direction, 0.0, distance + slack) else {
            return captured;
        };
        if (hit.position - eye).length() < distance - slack {
            return hit;
        }
        SurfaceHit {
            geometric_normal: hit.geometric_normal,
            ..captured
        }
    }

    /// Radiance leaving `surface` toward unit `to_eye` (emission plus reflected light).
    pub fn radiance_leaving(&self, mut surface: SurfaceHit, mut to_eye: Vec3, random: &mut SplitMix64) -> DVec3 {
        let mut radiance = surface.emissive;
        let mut throughput = DVec3::ONE;
        for reflection in 1..=self.bounces + 1 {
            radiance += throughput * self.next_event(&surface, to_eye, random);
            let sampled = surface
                .reflectance
                .sample(surface.normal, surface.geometric_normal, to_eye, random);
            let Some((next, weight)) = sampled else {
                break;
            };
            throughput *= weight;
            if reflection >= ROULETTE_FROM_REFLECTION {
                let survival = weight.max_element().min(0.95);
                if random.next_f64() >= survival {
                    break;
                }
                throughput /= survival;
            }
            match self.next_surface(self.leave(&surface, next), next, 0.0, f32::INFINITY) {
                Some(hit) => {
                    radiance += throughput * hit.emissive;
                    surface = hit;
                    to_eye = -next;
                }
                None => {
                    radiance += throughput * self.environment_radiance(next);
                    break;
                }
            }
        }
        radiance
    }

    fn next_surface(&self, origin: Vec3, direction: Vec3, t_min: f32, t_max: f32) -> Option<SurfaceHit> {
        let hit = self.bvh.closest_hit(origin, direction, t_min, t_max)?;
        Some(surface_at(self.scene, &hit, origin, direction))
    }

    /// Where a ray toward unit `direction` starts: off the surface on the side it leaves.
    fn leave(&self, surface: &SurfaceHit, direction: Vec3) -> Vec3 {
        let side = if surface.geometric_normal.dot(direction) >= 0.0 {
            1.0
        } else {
            -1.0
        };
        surface.position + surface.geometric_normal * (side * self.offset_m)
    }

    /// Light reflected toward `to_eye` from one sample of every light, each with an exact
    /// visibility ray.
    fn next_event(&self, surface: &SurfaceHit, to_eye: Vec3, random: &mut SplitMix64) -> DVec3 {
        if surface.reflectance.is_black() {
            return DVec3::ZERO;
        }
        let mut sum = DVec3::ZERO;
        for light in &self.scene.lights {
            let Some(sample) = sample_light(light, surface.position, random) else {
                continue;
            };
            if surface.geometric_normal.dot(sample.to_light) <= 0.0 {
                continue; // behind the surface itself
            }
            let reflected = surface
                .reflectance
                .per_irradiance(surface.normal, to_eye, sample.to_light);
            if reflected == DVec3::ZERO {
                continue;
            }
            let origin = self.leave(surface, sample.to_light);
            let free = sample.distance_m - 2.0 * self.offset_m;
            if !self.bvh.occluded(origin, sample.to_light, 0.0, free) {
                sum += sample.irradiance * reflected;
            }
        }
        sum
    }

    /// Radiance of the environment from unit `direction` (its order-3 SH, clamped at 0
    /// against ringing), or black.
    fn environment_radiance(&self, direction: Vec3) -> DVec3 {
        let Some(sh) = &self.environment_sh else {
            return DVec3::ZERO;
        };
        let y = crate::sh::basis16(direction.as_dvec3());
        let radiance = sh
            .iter()
            .zip(y)
            .fold(DVec3::ZERO, |acc, (c, yi)| acc + DVec3::from_array(*c) * yi);
        radiance.max(DVec3::ZERO)
    }
}
