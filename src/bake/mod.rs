//! Source-importance maps (Rozon 2009, with SH instead of wavelets): for every vertex and
//! light, the SH vector of the radiance arriving at the vertex from the light at unit
//! intensity. This first part bakes direct light with exact visibility (obvhs rays over
//! every triangle of the scene); indirect bounces, progress, cancellation and the cache
//! come next (issue #7).

pub mod direct;
pub mod scene_bvh;

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
}

impl Default for BakeSettings {
    fn default() -> Self {
        BakeSettings {
            order: 3,
            light_samples: 16,
            ray_offset_m: 1e-3,
        }
    }
}

/// What one light contributes at one vertex: the light's index and the SH (order of the
/// maps) of its unit-intensity radiance there.
#[derive(Debug, Clone, PartialEq)]
pub struct LightContribution {
    pub light: u32,
    pub sh: Vec<f32>,
}

/// The maps of every vertex of every object (object order of the scene); each vertex lists
/// only the lights that reach it.
#[derive(Debug, Clone, PartialEq)]
pub struct ImportanceMaps {
    pub order: usize,
    pub objects: Vec<Vec<Vec<LightContribution>>>,
}

impl ImportanceMaps {
    /// Number of (vertex, light) pairs stored.
    pub fn entry_count(&self) -> usize {
        self.objects.iter().flatten().map(Vec::len).sum()
    }
}

/// Bakes the direct light of every light at every vertex, on all cores.
pub fn bake_direct(scene: &Scene, settings: &BakeSettings) -> ImportanceMaps {
    let never = AtomicBool::new(false);
    bake_direct_with(scene, settings, &|_, _| {}, &never).unwrap_or(ImportanceMaps {
        order: settings.order,
        objects: Vec::new(),
    })
}

/// [`bake_direct`] reporting `progress(vertices done, vertices in all)` as it goes and
/// stopping early, with None and nothing kept, once `cancel` is set.
pub fn bake_direct_with(
    scene: &Scene,
    settings: &BakeSettings,
    progress: &(dyn Fn(usize, usize) + Sync),
    cancel: &AtomicBool,
) -> Option<ImportanceMaps> {
    let bvh = SceneBvh::build(scene);
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
                let entries = scene
                    .lights
                    .iter()
                    .enumerate()
                    .filter_map(|(i, light)| {
                        direct::direct_sh(
                            &bvh,
                            light,
                            p,
                            n,
                            settings.order,
                            settings.light_samples,
                            settings.ray_offset_m,
                        )
                        .map(|sh| LightContribution { light: i as u32, sh })
                    })
                    .collect();
                let finished = done.fetch_add(1, Ordering::Relaxed) + 1;
                if finished.is_multiple_of(1024) || finished == total {
                    progress(finished, total);
                }
                Some(entries)
            })
            .collect();
        objects.push(vertices?);
    }
    Some(ImportanceMaps {
        order: settings.order,
        objects,
    })
}

#[cfg(test)]
mod tests {
    use std::f64::consts::PI;

    use glam::Vec3;

    use super::*;
    use crate::scene::shapes::{self, ShapeMesh};
    use crate::scene::{Light, LightKind, MeshObject};

    fn object(name: &str, mesh: ShapeMesh) -> MeshObject {
        MeshObject {
            name: name.into(),
            positions: mesh.positions,
            normals: mesh.normals,
            uvs: mesh.uvs,
            indices: mesh.indices,
            material: 0,
        }
    }

    fn point_light(position: Vec3) -> Light {
        Light {
            name: "bulb".into(),
            kind: LightKind::Point,
            color: Vec3::ONE,
            intensity: 5.0,
            position,
            direction: Vec3::NEG_Y,
            range: None,
        }
    }

    /// A 4 m floor of 8×8 quads, a 1 m box hovering over its −x half, a light 3 m up.
    fn floor_box_light() -> Scene {
        let floor = shapes::plane(4.0, 8, 1.0);
        let block =
            shapes::cuboid(Vec3::splat(0.5)).transformed(glam::Affine3A::from_translation(Vec3::new(-1.0, 1.5, 0.0)));
        Scene {
            objects: vec![object("floor", floor), object("box", block)],
            lights: vec![point_light(Vec3::new(-1.0, 3.0, 0.0))],
            ..Default::default()
        }
    }

    #[test]
    fn lit_vertices_get_the_projected_point_source_and_shadowed_ones_nothing() {
        let scene = floor_box_light();
        let maps = bake_direct(&scene, &BakeSettings::default());
        let floor = &scene.objects[0];
        let mut lit = 0;
        for (v, entries) in maps.objects[0].iter().enumerate() {
            let p = floor.positions[v];
            // Under the box (|x + 1| < 0.5·(3/1.5 − …)): the box's shadow on the floor from
            // a light 1.5 m above its top face covers |x + 1|, |z| < 0.5 · 3/2 = 0.75.
            let in_umbra = (p.x + 1.0).abs() < 0.7 && p.z.abs() < 0.7;
            if in_umbra {
                assert!(entries.is_empty(), "vertex {p} is under the box: {entries:?}");
                continue;
            }
            let Some(entry) = entries.first() else { continue };
            lit += 1;
            let offset = (scene.lights[0].position - p).as_dvec3();
            let d = offset.normalize();
            let e = 1.0 / offset.length_squared();
            // SH of E·δ(ω − d): coefficient i is E·y_i(d); y_0 = 1/(2√π).
            assert!(
                (entry.sh[0] as f64 - e / (2.0 * PI.sqrt())).abs() < 1e-5 * e.max(1.0),
                "{entry:?}"
            );
            let y1 = -0.488_602_511_902_919_9 * d.y;
            assert!((entry.sh[1] as f64 - e * y1).abs() < 1e-5, "{entry:?}");
        }
        assert!(lit > 40, "most of the floor is lit: {lit}");
        // The box's bottom face looks down, away from the light: nothing stored there.
        assert!(maps.entry_count() < scene.vertex_count());
    }

    #[test]
    fn an_unoccluded_sphere_light_lights_like_a_point_at_its_centre() {
        // A uniformly emitting sphere wholly above a receiver's horizon gives E = I/d² at
        // its centre's distance; the sample sum converges to that integral.
        let mut scene = floor_box_light();
        scene.objects.truncate(1);
        scene.lights[0].kind = LightKind::Sphere { radius_m: 0.2 };
        let settings = BakeSettings {
            light_samples: 256,
            ..BakeSettings::default()
        };
        let maps = bake_direct(&scene, &settings);
        let floor = &scene.objects[0];
        for (v, entries) in maps.objects[0].iter().enumerate() {
            let offset = (scene.lights[0].position - floor.positions[v]).as_dvec3();
            let e = 1.0 / offset.length_squared();
            let dc = entries[0].sh[0] as f64 * 2.0 * PI.sqrt();
            assert!((dc / e - 1.0).abs() < 0.005, "vertex {v}: {dc} vs {e}");
        }
    }

    #[test]
    fn a_cancelled_bake_keeps_nothing_and_progress_reaches_the_end() {
        let scene = floor_box_light();
        let cancelled = AtomicBool::new(true);
        assert!(bake_direct_with(&scene, &BakeSettings::default(), &|_, _| {}, &cancelled).is_none());
        let last = std::sync::Mutex::new((0, 0));
        let go = AtomicBool::new(false);
        let maps = bake_direct_with(
            &scene,
            &BakeSettings::default(),
            &|done, total| {
                let mut last = last.lock().unwrap();
                *last = (last.0.max(done), total);
            },
            &go,
        );
        assert!(maps.is_some());
        let (done, total) = *last.lock().unwrap();
        assert_eq!((done, total), (scene.vertex_count(), scene.vertex_count()));
    }

    #[test]
    fn no_lights_or_no_geometry_bake_to_empty_maps() {
        let mut scene = floor_box_light();
        scene.lights.clear();
        assert_eq!(bake_direct(&scene, &BakeSettings::default()).entry_count(), 0);
        let empty = Scene {
            lights: vec![point_light(Vec3::Y)],
            ..Default::default()
        };
        assert!(bake_direct(&empty, &BakeSettings::default()).objects.is_empty());
    }
}
