//! An obvhs BVH over every triangle of a scene, for visibility rays. obvhs reorders
//! primitives: hits are mapped back through `primitive_indices` to our triangle list.

use glam::{Vec3, Vec3A};
use obvhs::cwbvh::CwBvh;
use obvhs::ray::Ray;
use obvhs::triangle::Triangle;

use crate::scene::Scene;

/// The scene's triangles (degenerate ones left out) and their BVH.
pub struct SceneBvh {
    triangles: Vec<Triangle>,
    /// None when the scene has no triangle: every ray is unoccluded.
    bvh: Option<CwBvh>,
}

impl SceneBvh {
    pub fn build(scene: &Scene) -> SceneBvh {
        let mut triangles = Vec::with_capacity(scene.triangle_count());
        for object in &scene.objects {
            for tri in object.indices.chunks_exact(3) {
                let [a, b, c] = [tri[0], tri[1], tri[2]].map(|i| object.positions.get(i as usize).copied());
                let (Some(a), Some(b), Some(c)) = (a, b, c) else {
                    continue;
                };
                if (b - a).cross(c - a).length_squared() > 0.0 {
                    triangles.push(Triangle {
                        v0: a.into(),
                        v1: b.into(),
                        v2: c.into(),
                    });
                }
            }
        }
        let bvh = (!triangles.is_empty()).then(|| {
            obvhs::cwbvh::builder::build_cwbvh_from_tris(
                &triangles,
                obvhs::BvhBuildParams::medium_build(),
                &mut std::time::Duration::default(),
            )
        });
        SceneBvh { triangles, bvh }
    }

    pub fn triangle_count(&self) -> usize {
        self.triangles.len()
    }

    /// Whether anything lies on the segment from `origin` along the unit `direction`
    /// between `t_min` and `t_max` metres.
    pub fn occluded(&self, origin: Vec3, direction: Vec3, t_min: f32, t_max: f32) -> bool {
        let Some(bvh) = &self.bvh else { return false };
        let ray = Ray::new(Vec3A::from(origin), Vec3A::from(direction), t_min, t_max);
        !bvh.ray_traverse_miss(ray, |ray, id| {
            self.triangles[bvh.primitive_indices[id] as usize].intersect(ray)
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::MeshObject;

    fn quad_at_height(y: f32) -> MeshObject {
        let positions = vec![
            Vec3::new(-1.0, y, -1.0),
            Vec3::new(-1.0, y, 1.0),
            Vec3::new(1.0, y, 1.0),
            Vec3::new(1.0, y, -1.0),
        ];
        MeshObject {
            name: "quad".into(),
            normals: vec![Vec3::Y; 4],
            uvs: vec![glam::Vec2::ZERO; 4],
            positions,
            indices: vec![0, 1, 2, 0, 2, 3],
            material: 0,
        }
    }

    #[test]
    fn a_quad_blocks_rays_through_it_and_only_those() {
        let scene = Scene {
            objects: vec![quad_at_height(1.0)],
            ..Default::default()
        };
        let bvh = SceneBvh::build(&scene);
        assert_eq!(bvh.triangle_count(), 2);
        // Off the quad's diagonal: a ray along a shared edge may slip between the triangles.
        let below = Vec3::new(0.3, 0.0, -0.2);
        assert!(bvh.occluded(below, Vec3::Y, 0.0, 10.0));
        assert!(
            !bvh.occluded(below, Vec3::Y, 0.0, 0.5),
            "the quad is beyond the segment"
        );
        assert!(!bvh.occluded(Vec3::new(3.0, 0.0, 0.0), Vec3::Y, 0.0, 10.0));
        assert!(!bvh.occluded(below, -Vec3::Y, 0.0, 10.0));
    }

    #[test]
    fn an_empty_scene_occludes_nothing() {
        let bvh = SceneBvh::build(&Scene::default());
        assert!(!bvh.occluded(Vec3::ZERO, Vec3::Y, 0.0, f32::INFINITY));
    }
}
