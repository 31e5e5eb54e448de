//! What the path tracer knows about a surface it hit: position, normals turned toward the
//! arriving ray, and the material mapped as the renderer maps it (`surface` in
//! shaders/scene.wgsl): k_d = base·(1 − metallic)·(1 − 0.04·specular),
//! k_s = mix(0.04·specular, base, metallic), base = factor × sRGB-decoded texture.

use glam::{DVec3, Vec2, Vec3};

use crate::bake::scene_bvh::Hit;
use crate::scene::{Material, Reflectance, Scene, TextureImage};
use crate::shading::srgb_to_linear;

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
            sample_bilinear(texture, object.interpolated_uv(hit.triangle, hit.barycentric))
        });
    SurfaceHit {
        position: origin + direction * hit.distance_m,
        geometric_normal,
        normal,
        reflectance: Reflectance::of_material(material, texture),
        emissive: material.emissive.as_dvec3(),
    }
}

/// Linear RGB of `texture` at `uv`, bilinear between texel centres, repeating (the
/// renderer's sampler without its mip chain: the path tracer filters by supersampling).
pub fn sample_bilinear(texture: &TextureImage, uv: Vec2) -> DVec3 {
    let (w, h) = (texture.width.max(1) as usize, texture.height.max(1) as usize);
    if texture.rgba8.len() < w * h * 4 {
        return DVec3::ONE;
    }
    let x = uv.x as f64 * w as f64 - 0.5;
    let y = uv.y as f64 * h as f64 - 0.5;
    let (x0, y0) = (x.floor(), y.floor());
    let (fx, fy) = (x - x0, y - y0);
    let texel = |i: f64, j: f64| {
        let column = (i as i64).rem_euclid(w as i64) as usize;
        let row = (j as i64).rem_euclid(h as i64) as usize;
        let at = (row * w + column) * 4;
        let c = &texture.rgba8[at..at + 3];
        DVec3::new(c[0] as f64, c[1] as f64, c[2] as f64).map(|v| srgb_to_linear(v / 255.0))
    };
    let top = texel(x0, y0).lerp(texel(x0 + 1.0, y0), fx);
    let bottom = texel(x0, y0 + 1.0).lerp(texel(x0 + 1.0, y0 + 1.0), fx);
    top.lerp(bottom, fy)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bilinear_sampling_returns_texels_at_their_centres_and_blends_between() {
        // 2×1: black, white (sRGB 255 → linear 1).
        let texture = TextureImage {
            name: "ramp".into(),
            width: 2,
            height: 1,
            rgba8: vec![0, 0, 0, 255, 255, 255, 255, 255],
        };
        assert!(sample_bilinear(&texture, Vec2::new(0.25, 0.5)).length() < 1e-12);
        assert!((sample_bilinear(&texture, Vec2::new(0.75, 0.5)) - DVec3::ONE).length() < 1e-12);
        let middle = sample_bilinear(&texture, Vec2::new(0.5, 0.5));
        assert!((middle - DVec3::splat(0.5)).length() < 1e-12, "{middle}");
        // Repeats: u = 1.25 is u = 0.25.
        assert!(sample_bilinear(&texture, Vec2::new(1.25, 0.5)).length() < 1e-12);
    }
}
