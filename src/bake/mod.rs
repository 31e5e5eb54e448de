//! Source-importance maps (Rozon 2009, with SH instead of wavelets): for every vertex and
//! light, the SH vector of the radiance arriving at the vertex from the light at unit
//! intensity: direct light with exact visibility (obvhs rays over every triangle of the
//! scene, `direct`) plus up to eight diffuse and glossy bounces with next-event estimation
//! and Russian roulette (`indirect`), stored sparse (`maps`).

pub mod direct;
pub mod indirect;
mod maps;
pub mod scene_bvh;
mod smooth;

pub use maps::{
    CoefficientArrays, Coefficients, LightContribution, MapEntry, ObjectMaps, Precision, RawCoefficients, RawMaps,
};

use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};

use rayon::prelude::*;

use crate::scene::Scene;
use scene_bvh::SceneBvh;

/// Knobs of the bake.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct BakeSettings {
    /// SH order of the maps (n² coefficients per vertex and light).
    pub order: usize,
    /// Emitter samples per extended (sphere, rect, disk) light and vertex.
    pub light_samples: usize,
    /// Rays start this far off the surface, along the normal (self-intersection guard).
    pub ray_offset_m: f32,
    /// Bounces of indirect light, diffuse and glossy (0: direct only), Russian roulette
    /// from the third.
    pub bounces: usize,
    /// Hemisphere directions per vertex for the indirect bounce.
    pub indirect_directions: usize,
    /// A vertex's entry for a light is dropped when its DC (the light's unit-intensity
    /// incident power there) is below this share of that light's largest DC over the
    /// scene (0 keeps everything). Judged per light, so re-baking one light gives what a
    /// full bake would.
    pub relative_threshold: f32,
    /// How the coefficients are stored (f16 halves the memory).
    #[serde(default)]
    pub precision: Precision,
}

impl Default for BakeSettings {
    fn default() -> Self {
        BakeSettings {
            order: 3,
            light_samples: 16,
            ray_offset_m: 1e-3,
            bounces: 1,
            indirect_directions: 32,
            relative_threshold: 1e-4,
            precision: Precision::F16,
        }
    }
}

/// The maps of every vertex of every object (object order of the scene); each vertex lists
/// only the lights that reach it.
#[derive(Debug, Clone, PartialEq)]
pub struct ImportanceMaps {
    pub order: usize,
    pub objects: Vec<ObjectMaps>,
    /// (vertex, light) pairs that reached the vertex but fell under the threshold.
    pub dropped_entries: usize,
}

impl ImportanceMaps {
    /// Number of (vertex, light) pairs stored.
    pub fn entry_count(&self) -> usize {
        self.objects.iter().map(ObjectMaps::entry_count).sum()
    }

    /// Share of the pairs that reached a vertex which were kept (1 when none were dropped).
    pub fn kept_fraction(&self) -> f64 {
        let kept = self.entry_count();
        let all = kept + self.dropped_entries;
        if all == 0 { 1.0 } else { kept as f64 / all as f64 }
    }

    /// Whether the maps were baked for this geometry: the same objects with the same
    /// vertex counts.
    pub fn fits(&self, scene: &Scene) -> bool {
        self.objects.len() == scene.objects.len()
            && self
                .objects
                .iter()
                .zip(&scene.objects)
                .all(|(m, o)| m.vertex_count() == o.positions.len())
    }

    /// Bytes the maps take in memory.
    pub fn memory_bytes(&self) -> usize {
        self.objects.iter().map(ObjectMaps::memory_bytes).sum()
    }
}

/// Drops every entry whose DC is under `threshold` × its light's largest DC in `objects`
/// (and any entry that is not finite or not positive); returns how many were dropped.
fn sparsify(objects: &mut [ObjectMaps], light_count: usize, threshold: f32) -> usize {
    let mut peak = vec![0.0f32; light_count];
    for entry in objects.iter().flat_map(ObjectMaps::all_entries) {
        if let Some(p) = peak.get_mut(entry.light as usize)
            && entry.sh.dc().is_finite()
        {
            *p = p.max(entry.sh.dc());
        }
    }
    objects
        .par_iter_mut()
        .map(|object| {
            let (kept, dropped) = object.filtered(|e| {
                let floor = threshold * peak.get(e.light as usize).copied().unwrap_or(0.0);
                e.sh.all_finite() && e.sh.dc() > 0.0 && e.sh.dc() >= floor
            });
            *object = kept;
            dropped
        })
        .sum()
}

/// Bakes the maps of every light at every vertex, on all cores.
pub fn bake_maps(scene: &Scene, settings: &BakeSettings) -> ImportanceMaps {
    let never = AtomicBool::new(false);
    bake_maps_with(scene, settings, &|_, _| {}, &never).unwrap_or(ImportanceMaps {
        order: settings.order,
        objects: Vec::new(),
        dropped_entries: 0,
    })
}

/// [`bake_maps`] reporting `progress(vertices done, vertices in all)` as it goes and
/// stopping early, with None and nothing kept, once `cancel` is set.
pub fn bake_maps_with(
    scene: &Scene,
    settings: &BakeSettings,
    progress: &(dyn Fn(usize, usize) + Sync),
    cancel: &AtomicBool,
) -> Option<ImportanceMaps> {
    bake_maps_counting(scene, settings, progress, cancel).map(|(maps, _)| maps)
}

/// [`bake_maps_with`], also returning the number of rays traced.
pub fn bake_maps_counting(
    scene: &Scene,
    settings: &BakeSettings,
    progress: &(dyn Fn(usize, usize) + Sync),
    cancel: &AtomicBool,
) -> Option<(ImportanceMaps, u64)> {
    let all: Vec<usize> = (0..scene.lights.len()).collect();
    bake_lights(scene, settings, &all, progress, cancel)
}

/// Re-bakes only `lights` (say, the one the artist moved) and keeps every other light's
/// maps from `previous`: light transport is linear and lights are independent, so the
/// result equals a full bake. Falls back to a full bake when `previous` does not match
/// the scene's geometry or order. None if cancelled (then `previous` is still whole).
pub fn rebake_lights(
    scene: &Scene,
    settings: &BakeSettings,
    previous: &ImportanceMaps,
    lights: &[usize],
    progress: &(dyn Fn(usize, usize) + Sync),
    cancel: &AtomicBool,
) -> Option<ImportanceMaps> {
    if previous.order != settings.order || !previous.fits(scene) {
        return bake_maps_with(scene, settings, progress, cancel);
    }
    let (fresh, _) = bake_lights(scene, settings, lights, progress, cancel)?;
    let order = settings.order;
    let objects = previous
        .objects
        .iter()
        .zip(&fresh.objects)
        .map(|(old, new)| {
            let vertices: Vec<Vec<LightContribution>> = (0..old.vertex_count())
                .map(|v| {
                    let mut kept: Vec<LightContribution> = old
                        .contributions(v)
                        .into_iter()
                        .filter(|e| !lights.contains(&(e.light as usize)))
                        .collect();
                    kept.extend(new.contributions(v));
                    kept.sort_by_key(|e| e.light);
                    kept
                })
                .collect();
            ObjectMaps::from_vertices(order, &vertices, settings.precision)
        })
        .collect();
    // The re-baked lights' dropped count replaces theirs in the old total only
    // approximately (the old maps do not say which light each drop was); it is a report.
    Some(ImportanceMaps {
        order: settings.order,
        objects,
        dropped_entries: previous.dropped_entries.max(fresh.dropped_entries),
    })
}

/// The maps of `lights` only (indices into `scene.lights`), and the rays traced.
fn bake_lights(
    scene: &Scene,
    settings: &BakeSettings,
    lights: &[usize],
    progress: &(dyn Fn(usize, usize) + Sync),
    cancel: &AtomicBool,
) -> Option<(ImportanceMaps, u64)> {
    let bvh = SceneBvh::build(scene);
    let reflectances: Vec<_> = scene.materials.iter().map(indirect::bounce_reflectance).collect();
    let total = scene.vertex_count();
    let done = AtomicUsize::new(0);
    let mut objects = Vec::with_capacity(scene.objects.len());
    for object in &scene.objects {
        let vertices: Option<Vec<Vec<LightContribution>>> = (0..object.positions.len())
            .into_par_iter()
            .map(|v| {
                if cancel.load(Ordering::Relaxed) {
                    return None;
                }
                let (p, n) = (object.positions[v], object.normals[v]);
                let mut entries: Vec<LightContribution> = lights
                    .iter()
                    .filter_map(|&i| {
                        let light = scene.lights.get(i)?;
                        direct::direct_sh(
                            &bvh,
                            light,
                            p,
                            n,
                            settings.order,
                            settings.light_samples,
                            settings.ray_offset_m,
                        )
                        .map(|sh| LightContribution {
                            light: i as u32,
                            sh,
                            indirect_irradiance: 0.0,
                        })
                    })
                    .collect();
                if settings.bounces > 0 {
                    let bounced = indirect::indirect_sh(&bvh, scene, &reflectances, lights, p, n, settings);
                    merge(&mut entries, bounced);
                }
                let finished = done.fetch_add(1, Ordering::Relaxed) + 1;
                if finished.is_multiple_of(1024) || finished == total {
                    progress(finished, total);
                }
                Some(entries)
            })
            .collect();
        let mut vertices = vertices?;
        if settings.bounces > 0 {
            smooth::smooth_indirect_irradiance(object, &mut vertices);
        }
        objects.push(ObjectMaps::from_vertices(settings.order, &vertices, settings.precision));
    }
    let dropped_entries = sparsify(&mut objects, scene.lights.len(), settings.relative_threshold);
    let maps = ImportanceMaps {
        order: settings.order,
        objects,
        dropped_entries,
    };
    Some((maps, bvh.rays_cast()))
}

/// Adds each indirect contribution of `more` into `entries` (which stay sorted by light).
fn merge(entries: &mut Vec<LightContribution>, more: Vec<LightContribution>) {
    for indirect in more {
        match entries.iter_mut().find(|e| e.light == indirect.light) {
            Some(entry) => {
                entry.sh.iter_mut().zip(&indirect.sh).for_each(|(a, b)| *a += b);
                entry.indirect_irradiance += indirect.indirect_irradiance;
            }
            None => entries.push(indirect),
        }
    }
    entries.sort_by_key(|e| e.light);
}

#[cfg(test)]
mod tests;
