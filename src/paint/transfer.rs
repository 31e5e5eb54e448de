//! Transfer: the luminance (cd/m², linear) that a painted vertex shows the camera per unit
//! intensity of each light — t_{i,v} of Rozon's points system, t = luminance(BRDF · I_{i,v}).
//! Light transport is linear in the intensities P_i, so a vertex's luminance is
//! y_v = fixed_v + Σ_i P_i t_{i,v} (fixed: what no light changes, e.g. emission).
//!
//! Three sources implement [`Transfer`]: the renderer's direct-only estimate with the
//! view's visibility (`shading::paint_estimate`), which strokes read before a bake; after
//! a bake, that estimate plus the maps' bounced light as the frame adds it
//! (`shading::frame_transfer`); and [`BakedTransfer`], Rozon's reading of the baked
//! importance maps' SH alone (direct and indirect light, exact visibility, order-limited),
//! kept for the bake's own tests and measurements.

use glam::Vec3;

use super::pick::{PaintedPoint, VertexRef};
use crate::bake::ImportanceMaps;
use crate::scene::{Material, Scene, luminance};
use crate::sh;

/// Per-vertex, per-light transfer toward an eye.
pub trait Transfer: Sync {
    /// Number of lights the transfer knows (the scene's light count).
    fn light_count(&self) -> usize;

    /// (light, t ≥ 0) of every light that reaches `vertex` as seen from `eye`, by light.
    fn vertex_transfer(&self, vertex: VertexRef, eye: Vec3) -> Vec<(u32, f64)>;

    /// Luminance of `vertex` toward `eye` that no light intensity changes.
    fn fixed_luminance(&self, vertex: VertexRef, eye: Vec3) -> f64;

    /// Both at once ([`Transfer::fixed_luminance`], [`Transfer::vertex_transfer`]), for
    /// sources that share work between them.
    fn vertex_shading(&self, vertex: VertexRef, eye: Vec3) -> (f64, Vec<(u32, f64)>) {
        (self.fixed_luminance(vertex, eye), self.vertex_transfer(vertex, eye))
    }

    /// Fixed luminance and per-light transfer at a point of the surface under the brush,
    /// as the frame shows it there (through the base-colour texture). By default the
    /// corners' shading interpolated by the point's barycentrics (the transfer varies
    /// linearly across a triangle), times the texture's luminance; a source that can
    /// shade the point itself does so.
    fn point_shading(&self, point: &PaintedPoint, eye: Vec3) -> (f64, Vec<(u32, f64)>) {
        let texture = point.texture_rgb.map_or(1.0, luminance);
        let mut fixed = 0.0;
        let mut transfer: Vec<(u32, f64)> = Vec::new();
        for (vertex, share) in point.weighted_corners() {
            if share <= 0.0 {
                continue;
            }
            let (corner_fixed, entries) = self.vertex_shading(vertex, eye);
            fixed += share * corner_fixed;
            for (light, t) in entries {
                match transfer.iter_mut().find(|(l, _)| *l == light) {
                    Some(entry) => entry.1 += share * t * texture,
                    None => transfer.push((light, share * t * texture)),
                }
            }
        }
        (fixed, transfer)
    }
}

/// What a material reflects, reduced to what the transfer needs.
struct ProjectedReflectance {
    diffuse: f64,
    specular: f64,
    /// ZH of the normalised Phong lobe ((r + 1)/2π)·cos^r on its upper hemisphere.
    lobe_zh: Vec<f64>,
    emitted: f64,
}

impl ProjectedReflectance {
    fn new(material: &Material, order: usize) -> ProjectedReflectance {
        let exponent = material.phong_exponent() as f64;
        let lobe = |t: f64| {
            if t > 0.0 {
                (exponent + 1.0) / (2.0 * std::f64::consts::PI) * t.powf(exponent)
            } else {
                0.0
            }
        };
        ProjectedReflectance {
            diffuse: luminance(material.diffuse_albedo().as_dvec3()),
            specular: luminance(material.specular_color().as_dvec3()),
            lobe_zh: sh::zh_of_function(order, lobe, &[0.0]),
            emitted: luminance(material.emissive.as_dvec3()),
        }
    }
}

/// Transfer from baked importance maps, with the renderer's diffuse + Phong model (base
/// colour factors; textures are not sampled per vertex yet):
/// t_{i,v} = lum(colour_i)·(k_d·⟨I_{i,v}, cos⁺/π⟩ + k_s·⟨I_{i,v}, Phong lobe about the
/// mirrored view⟩).
pub struct BakedTransfer<'a> {
    scene: &'a Scene,
    maps: &'a ImportanceMaps,
    reflectance: Vec<ProjectedReflectance>,
    cosine_zh: Vec<f64>,
    light_luminance: Vec<f64>,
}

impl<'a> BakedTransfer<'a> {
    pub fn new(scene: &'a Scene, maps: &'a ImportanceMaps) -> BakedTransfer<'a> {
        let order = maps.order;
        let mut reflectance: Vec<ProjectedReflectance> = scene
            .materials
            .iter()
            .map(|m| ProjectedReflectance::new(m, order))
            .collect();
        reflectance.push(ProjectedReflectance::new(&Material::default(), order));
        BakedTransfer {
            scene,
            maps,
            reflectance,
            cosine_zh: sh::clamped_cosine_zh(order),
            light_luminance: scene.lights.iter().map(|l| luminance(l.color.as_dvec3())).collect(),
        }
    }

    fn reflectance_of(&self, object: usize) -> &ProjectedReflectance {
        let material = self.scene.objects[object].material;
        self.reflectance
            .get(material)
            .unwrap_or_else(|| &self.reflectance[self.reflectance.len() - 1])
    }
}

impl Transfer for BakedTransfer<'_> {
    fn light_count(&self) -> usize {
        self.scene.lights.len()
    }

    fn vertex_transfer(&self, vertex: VertexRef, eye: Vec3) -> Vec<(u32, f64)> {
        let (o, v) = (vertex.object as usize, vertex.vertex as usize);
        let Some(maps) = self.maps.objects.get(o) else {
            return Vec::new();
        };
        let entries = maps.entries(v);
        let object = &self.scene.objects[o];
        let (p, n) = (object.positions[v].as_dvec3(), object.normals[v].as_dvec3());
        let reflectance = self.reflectance_of(o);
        let diffuse = sh::rotate_zh(&self.cosine_zh, n);
        let glossy = (reflectance.specular > 0.0).then(|| {
            let to_eye = (eye.as_dvec3() - p).normalize_or(n);
            let mirrored = 2.0 * n.dot(to_eye) * n - to_eye;
            sh::rotate_zh(&reflectance.lobe_zh, mirrored.normalize_or(n))
        });
        entries
            .filter_map(|entry| {
                let dot = |basis: &[f64]| -> f64 { entry.sh.dot(basis) };
                let mut t = reflectance.diffuse * dot(&diffuse);
                if let Some(glossy) = &glossy {
                    t += reflectance.specular * dot(glossy);
                }
                let t = self.light_luminance.get(entry.light as usize)? * t;
                (t.is_finite() && t > 0.0).then_some((entry.light, t))
            })
            .collect()
    }

    fn fixed_luminance(&self, vertex: VertexRef, _eye: Vec3) -> f64 {
        self.reflectance_of(vertex.object as usize).emitted
    }
}

#[cfg(test)]
mod tests {
    use std::f64::consts::PI;

    use glam::DVec3;

    use super::*;
    use crate::bake::{BakeSettings, bake_maps};

    /// A white Lambertian floor 2 m under a point light. The map holds E·y(d) (E = cos θ/d²
    /// is not applied: E_facing = 1/d²), so ⟨I, cos⁺/π⟩ is, by Funk–Hecke, the order-4
    /// truncation of cos⁺/π at d: Σ_l z_l·√((2l+1)/4π)·P_l(cos θ)/d², with the clamped
    /// cosine ZH [0.282095, 0.325735, 0.157696, 0] of shading-model.md §4.
    #[test]
    fn a_lambertian_floor_under_a_point_light_has_the_closed_form_transfer() {
        let scene = Scene::lambert_floor_under_point_light(4, Vec3::new(0.0, 2.0, 0.0), 1.0);
        // Single precision: the bake's math to 1e-5; the default half precision to its
        // three significant digits.
        let single = BakeSettings {
            order: 4,
            bounces: 0,
            precision: crate::bake::Precision::F32,
            ..BakeSettings::default()
        };
        let half = BakeSettings {
            precision: crate::bake::Precision::F16,
            ..single
        };
        for (settings, tolerance) in [(single, 1e-5), (half, 1e-3)] {
            floor_transfer_matches(&scene, &settings, tolerance);
        }
    }

    fn floor_transfer_matches(scene: &Scene, settings: &BakeSettings, tolerance: f64) {
        let maps = bake_maps(scene, settings);
        let transfer = BakedTransfer::new(scene, &maps);
        for v in 0..scene.objects[0].positions.len() {
            let p = scene.objects[0].positions[v].as_dvec3();
            let offset = DVec3::new(0.0, 2.0, 0.0) - p;
            let cos = offset.normalize().y;
            let zh = [0.282_095, 0.325_735, 0.157_696];
            let legendre = [1.0, cos, 0.5 * (3.0 * cos * cos - 1.0)];
            let truncated: f64 = (0..3)
                .map(|l| zh[l] * ((2 * l + 1) as f64 / (4.0 * PI)).sqrt() * legendre[l])
                .sum();
            let expected = truncated / offset.length_squared();
            let vertex = VertexRef {
                object: 0,
                vertex: v as u32,
            };
            let t = transfer.vertex_transfer(vertex, Vec3::new(0.0, 5.0, 5.0));
            assert_eq!(t.len(), 1);
            assert!(
                (t[0].1 / expected - 1.0).abs() < tolerance,
                "{:?} vertex {v}: {} vs {expected}",
                settings.precision,
                t[0].1
            );
        }
    }
}
