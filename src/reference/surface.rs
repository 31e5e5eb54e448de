//! What the path tracer knows about a surface it hit: position, normals turned toward the
//! arriving ray, and the material mapped as the renderer maps it (`surface` in
//! shaders/scene.wgsl): k_d = base·(1 − metallic)·(1 − 0.04·specular),
//! k_s = mix(0.04·specular, base, metallic), base = factor × sRGB-decoded texture.

use glam::{DVec3, Vec3};

use crate::bake::scene_bvh::Hit;
use crate::scene::{Material, Reflectance, Scene};

/// A point where a ray met a surface.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SurfaceHit {
    pub position: Vec3,
    /// Unit face normal on the side the ray came from (rays leave from this side).
    pub geometric_normal: Vec3,
    /// Unit interpolated normal, turned with the face toward the ray (as the rasteriser
    /// turns back faces); the face normal where the vertex normals cancel.
    pub normal: Vec3,
    pub reflectance: Reflectance,
    /// Emitted radiance (both sides, as the renderer draws it).
    pub emissive: DVec3,
}

/// The surface the ray (`origin`, unit `direction`) met at `hit`.
pub fn surface_at(scene: &Scene, hit: &Hit, origin: Vec3, direction: Vec3) -> SurfaceHit {
    let object = &scene.objects[hit.object];
    let mut geometric_normal = object.face_normal(hit.triangle);
    let mut normal = object.interpolated_normal(hit.triangle, hit.barycentric);
    if normal == Vec3::ZERO {
        normal = geometric_normal;
    }
    if geometric_normal.dot(direction) > 0.0 {
        geometric_normal = -geometric_normal;
        normal = -normal;
    }
    // A missing material shades as glTF's default (validated scenes always have one).
    static DEFAULT: std::sync::OnceLock<Material> = std::sync::OnceLock::new();
    let material = scene
        .materials
        .get(object.material)
        .unwrap_or_else(|| DEFAULT.get_or_init(Material::default));
    let texture = material
        .base_color_texture
        .and_then(|t| scene.textures.get(t))
        .map_or(DVec3::ONE, |texture| {
            texture.sample_bilinear(object.interpolated_uv(hit.triangle, hit.barycentric))
        });
    SurfaceHit {
        position: origin + direction * hit.distance_m,
        geometric_normal,
        normal,
        reflectance: Reflectance::of_material(material, texture),
        emissive: material.emissive.as_dvec3(),
    }
}
