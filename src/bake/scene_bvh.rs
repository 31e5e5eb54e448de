//! An obvhs BVH over every triangle of a scene, for visibility rays. obvhs reorders
//! primitives: hits are mapped back through `primitive_indices` to our triangle list.

use glam::{Vec3, Vec3A};
use obvhs::cwbvh::CwBvh;
use obvhs::ray::Ray;
use obvhs::triangle::Triangle;

use crate::scene::Scene;

/// Where a ray first hit the scene.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Hit {
    pub distance_m: f32,
    pub object: usize,
    /// Index of the triangle in the object's index list (its indices are 3·triangle…).
    pub triangle: usize,
    /// Barycentric weights of the triangle's three vertices at the hit point.
    pub barycentric: Vec3,
    /// The ray met the triangle's front (counter-clockwise, glTF's winding) side.
    pub front_facing: bool,
}

/// The scene's triangles (degenerate ones left out) and their BVH.
pub struct SceneBvh {
    triangles: Vec<Triangle>,
    /// (object, triangle) of each entry of `triangles`.
    owners: Vec<(u32, u32)>,
    /// None when the scene has no triangle: every ray is unoccluded.
    bvh: Option<CwBvh>,
    /// Rays traced so far (for rays-per-second reports).
    rays: std::sync::atomic::AtomicU64,
}

impl SceneBvh {
    pub fn build(scene: &Scene) -> SceneBvh {
        let mut triangles = Vec::with_capacity(scene.triangle_count());
        let mut owners = Vec::with_capacity(scene.triangle_count());
        for (o, object) in scene.objects.iter().enumerate() {
            for (t, tri) in object.indices.chunks_exact(3).enumerate() {
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
                    owners.push((o as u32, t as u32));
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
        SceneBvh {
            triangles,
            owners,
            bvh,
            rays: std::sync::atomic::AtomicU64::new(0),
        }
    }

    /// Rays traced through this BVH so far.
    pub fn rays_cast(&self) -> u64 {
        self.rays.load(std::sync::atomic::Ordering::Relaxed)
    }

    fn count_ray(&self) {
        self.rays.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
    }

    /// The first surface the ray from `origin` along the unit `direction` meets between
    /// `t_min` and `t_max` metres, if any.
    pub fn closest_hit(&self, origin: Vec3, direction: Vec3, t_min: f32, t_max: f32) -> Option<Hit> {
        self.count_ray();
        let bvh = self.bvh.as_ref()?;
        let ray = Ray::new(Vec3A::from(origin), positive_zeros(direction), t_min, t_max);
        let mut hit = obvhs::ray::RayHit::none();
        if !bvh.ray_traverse(ray, &mut hit, |ray, id| {
            intersect(&self.triangles[bvh.primitive_indices[id] as usize], ray)
        }) {
            return None;
        }
        let index = bvh.primitive_indices[hit.primitive_id as usize] as usize;
        let tri = &self.triangles[index];
        let point = Vec3A::from(origin) + Vec3A::from(direction) * hit.t;
        let (object, triangle) = self.owners[index];
        Some(Hit {
            distance_m: hit.t,
            object: object as usize,
            triangle: triangle as usize,
            barycentric: barycentric(tri, point),
            front_facing: (tri.v1 - tri.v0).cross(tri.v2 - tri.v0).dot(Vec3A::from(direction)) < 0.0,
        })
    }

    /// The nearest hit along the ray that is not on one of the objects `ignored` lists.
    pub fn closest_hit_ignoring(&self, origin: Vec3, direction: Vec3, t_max: f32, ignored: &[u32]) -> Option<Hit> {
        self.closest_hit_where(origin, direction, t_max, |hit| !ignored.contains(&(hit.object as u32)))
    }

    /// The nearest hit along the ray that `keep` accepts (surfaces it rejects are seen
    /// through).
    pub fn closest_hit_where(
        &self,
        origin: Vec3,
        direction: Vec3,
        t_max: f32,
        keep: impl Fn(&Hit) -> bool,
    ) -> Option<Hit> {
        let mut t_min = 0.0;
        // Each round steps past one rejected surface; a bounded number keeps a ray grazing
        // many coplanar rejected triangles from looping for long.
        for _ in 0..64 {
            let hit = self.closest_hit(origin, direction, t_min, t_max)?;
            if keep(&hit) {
                return Some(hit);
            }
            t_min = hit.distance_m + 1e-4 * hit.distance_m.max(1.0);
        }
        None
    }

    pub fn triangle_count(&self) -> usize {
        self.triangles.len()
    }

    /// Like [`Self::occluded`], but triangles of the objects `ignored` lists do not block
    /// (objects hidden in the viewport, which the brush sees through).
    pub fn occluded_ignoring(&self, origin: Vec3, direction: Vec3, t_min: f32, t_max: f32, ignored: &[u32]) -> bool {
        if ignored.is_empty() {
            return self.occluded(origin, direction, t_min, t_max);
        }
        self.count_ray();
        let Some(bvh) = &self.bvh else { return false };
        let ray = Ray::new(Vec3A::from(origin), positive_zeros(direction), t_min, t_max);
        !bvh.ray_traverse_miss(ray, |ray, id| {
            let primitive = bvh.primitive_indices[id] as usize;
            if ignored.contains(&self.owners[primitive].0) {
                f32::INFINITY
            } else {
                intersect(&self.triangles[primitive], ray)
            }
        })
    }

    /// Whether anything lies on the segment from `origin` along the unit `direction`
    /// between `t_min` and `t_max` metres.
    pub fn occluded(&self, origin: Vec3, direction: Vec3, t_min: f32, t_max: f32) -> bool {
        self.count_ray();
        let Some(bvh) = &self.bvh else { return false };
        let ray = Ray::new(Vec3A::from(origin), positive_zeros(direction), t_min, t_max);
        !bvh.ray_traverse_miss(ray, |ray, id| {
            intersect(&self.triangles[bvh.primitive_indices[id] as usize], ray)
        })
    }
}

/// `direction` with −0.0 components made +0.0: obvhs's traversal misses boxes for a ray
/// whose direction has a −0.0 component (it reads the sign two ways), and vertex-to-eye
/// directions of axis-aligned meshes often have one.
fn positive_zeros(direction: Vec3) -> Vec3A {
    Vec3A::from(direction) + Vec3A::ZERO
}

/// Möller–Trumbore ray/triangle intersection with a tolerance of 1e-6 in barycentric
/// units, so a ray through a vertex or along an edge shared by two triangles hits
/// (obvhs's bitwise sign test rejects u or v = −0.0, and such rays slipped through
/// meshes). Returns the distance, or +∞ for a miss.
fn intersect(tri: &Triangle, ray: &Ray) -> f32 {
    const SLACK: f32 = 1e-6;
    let e1 = tri.v1 - tri.v0;
    let e2 = tri.v2 - tri.v0;
    let p = ray.direction.cross(e2);
    let determinant = e1.dot(p);
    if determinant.abs() < f32::MIN_POSITIVE {
        return f32::INFINITY;
    }
    let inverse = 1.0 / determinant;
    let s = ray.origin - tri.v0;
    let u = s.dot(p) * inverse;
    let q = s.cross(e1);
    let v = ray.direction.dot(q) * inverse;
    if u < -SLACK || v < -SLACK || u + v > 1.0 + SLACK {
        return f32::INFINITY;
    }
    let t = e2.dot(q) * inverse;
    if t >= ray.tmin && t <= ray.tmax {
        t
    } else {
        f32::INFINITY
    }
}

/// Barycentric weights of `p` (on the triangle's plane) for its three vertices.
fn barycentric(tri: &Triangle, p: Vec3A) -> Vec3 {
    let (e1, e2, ep) = (tri.v1 - tri.v0, tri.v2 - tri.v0, p - tri.v0);
    let (d11, d12, d22) = (e1.dot(e1), e1.dot(e2), e2.dot(e2));
    let (dp1, dp2) = (ep.dot(e1), ep.dot(e2));
    let denominator = d11 * d22 - d12 * d12;
    if denominator.abs() < f32::MIN_POSITIVE {
        return Vec3::new(1.0, 0.0, 0.0);
    }
    let v = (d22 * dp1 - d12 * dp2) / denominator;
    let w = (d11 * dp2 - d12 * dp1) / denominator;
    Vec3::new(1.0 - v - w, v, w)
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

    /// The BVH of a scene made of `objects` alone.
    fn bvh_of(objects: Vec<MeshObject>) -> SceneBvh {
        SceneBvh::build(&Scene {
            objects,
            ..Default::default()
        })
    }

    #[test]
    fn a_quad_blocks_rays_through_it_and_only_those() {
        let bvh = bvh_of(vec![quad_at_height(1.0)]);
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
    fn closest_hits_name_the_triangle_and_where_on_it() {
        let bvh = bvh_of(vec![quad_at_height(1.0), quad_at_height(2.0)]);
        let hit = bvh
            .closest_hit(Vec3::new(0.5, 0.0, -0.5), Vec3::Y, 0.0, 10.0)
            .expect("hit");
        assert_eq!(hit.object, 0);
        assert!((hit.distance_m - 1.0).abs() < 1e-5);
        let object = quad_at_height(1.0);
        let corners = [0, 1, 2].map(|k| object.positions[object.indices[3 * hit.triangle + k] as usize]);
        let p = corners[0] * hit.barycentric.x + corners[1] * hit.barycentric.y + corners[2] * hit.barycentric.z;
        assert!((p - Vec3::new(0.5, 1.0, -0.5)).length() < 1e-5, "{p}");
        assert!(
            bvh.closest_hit(Vec3::new(0.5, 1.5, -0.5), Vec3::Y, 0.0, 10.0)
                .expect("hit")
                .object
                == 1
        );
    }

    #[test]
    fn a_ray_along_an_edge_between_two_triangles_is_blocked_whatever_the_zero_sign() {
        // A 2×2-quad plate: the ray crosses it on the shared edge x = 0, on the faces of
        // the BVH boxes of both halves.
        let plate = crate::scene::shapes::plane(1.0, 2, 1.0)
            .transformed(glam::Affine3A::from_translation(Vec3::Y))
            .into_object("plate");
        let bvh = bvh_of(vec![plate]);
        for x in [0.0f32, -0.0] {
            let direction = Vec3::new(x, -0.995_037_2, -0.099_503_72);
            assert!(bvh.occluded(Vec3::new(0.0, 5.0, 0.0), direction, 0.0, 6.0), "x = {x:?}");
        }
    }

    #[test]
    fn an_empty_scene_occludes_nothing() {
        let bvh = SceneBvh::build(&Scene::default());
        assert!(!bvh.occluded(Vec3::ZERO, Vec3::Y, 0.0, f32::INFINITY));
    }

    #[test]
    fn hits_know_which_side_they_met_and_rejected_surfaces_are_seen_through() {
        // Both quads face up (+y: counter-clockwise seen from above).
        let bvh = bvh_of(vec![quad_at_height(1.0), quad_at_height(0.0)]);
        let (above, below) = (Vec3::new(0.3, 3.0, -0.2), Vec3::new(0.3, -1.0, -0.2));
        let from_above = bvh.closest_hit(above, Vec3::NEG_Y, 0.0, 10.0).expect("hit");
        assert!(from_above.front_facing && from_above.object == 0);
        let from_below = bvh.closest_hit(below, Vec3::Y, 0.0, 10.0).expect("hit");
        assert!(!from_below.front_facing && from_below.object == 1);
        // Front faces only: from below every surface is a back face.
        assert!(
            bvh.closest_hit_where(below, Vec3::Y, 10.0, |hit| hit.front_facing)
                .is_none()
        );
        // Seeing through the upper quad reaches the lower one.
        let through = bvh.closest_hit_where(above, Vec3::NEG_Y, 10.0, |hit| hit.object != 0);
        assert_eq!(through.map(|hit| hit.object), Some(1));
    }
}
