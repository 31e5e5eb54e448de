//! How much of one light reaches each vertex, for the editor's heat map: the luminance
//! the light adds at the vertex toward the eye, P_i · t_{i,v} (cd/m²), from the same
//! transfer strokes read (baked maps, or the direct estimate before a bake).

use glam::Vec3;
use rayon::prelude::*;

use super::{Transfer, VertexRef};
use crate::scene::Scene;

/// P_light · t_{light,v} for every vertex of every object of `scene`, seen from `eye`
/// (one list per object, in vertex order); 0 where the light does not reach.
pub fn light_reach_per_vertex(scene: &Scene, transfer: &dyn Transfer, light: usize, eye: Vec3) -> Vec<Vec<f32>> {
    let intensity = scene.lights.get(light).map_or(0.0, |l| l.intensity as f64);
    scene
        .objects
        .iter()
        .enumerate()
        .map(|(o, object)| {
            (0..object.positions.len())
                .into_par_iter()
                .map(|v| {
                    let vertex = VertexRef {
                        object: o as u32,
                        vertex: v as u32,
                    };
                    let t = transfer
                        .vertex_transfer(vertex, eye)
                        .into_iter()
                        .find(|&(l, _)| l as usize == light)
                        .map_or(0.0, |(_, t)| t);
                    (intensity * t) as f32
                })
                .collect()
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::{Light, LightKind, shapes};

    /// A transfer that is known in closed form: t_{i,v} = (i + 1)·(v + 1) for lights 0 and 2.
    struct Known;

    impl Transfer for Known {
        fn light_count(&self) -> usize {
            3
        }

        fn vertex_transfer(&self, vertex: VertexRef, _eye: Vec3) -> Vec<(u32, f64)> {
            [0u32, 2]
                .iter()
                .map(|&i| (i, ((i + 1) * (vertex.vertex + 1)) as f64))
                .collect()
        }

        fn fixed_luminance(&self, _vertex: VertexRef, _eye: Vec3) -> f64 {
            0.0
        }
    }

    #[test]
    fn the_reach_is_intensity_times_transfer_and_zero_for_unreached_lights() {
        let mut scene = Scene::default();
        scene.objects.push(shapes::plane(2.0, 2, 1.0).into_object("floor"));
        scene.lights = (0..3)
            .map(|i| Light {
                name: format!("light {i}"),
                kind: LightKind::Point,
                color: Vec3::ONE,
                intensity: 10.0 * (i + 1) as f32,
                position: Vec3::Y,
                direction: Vec3::NEG_Y,
                range: None,
                locked: false,
            })
            .collect();
        let reach = light_reach_per_vertex(&scene, &Known, 2, Vec3::ONE);
        let expected: Vec<f32> = (0..scene.objects[0].positions.len())
            .map(|v| 30.0 * 3.0 * (v + 1) as f32)
            .collect();
        assert_eq!(reach, vec![expected]);
        let none = light_reach_per_vertex(&scene, &Known, 1, Vec3::ONE);
        assert!(none[0].iter().all(|&r| r == 0.0));
    }
}
