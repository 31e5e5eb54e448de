//! The direct-only transfer estimate painting uses before (or instead of) a bake: the
//! real-time renderer's own shading (`cpu.rs`, the f64 twin of logsh.wgsl), evaluated at
//! the painted vertices, one light at a time at unit intensity. Visibility is what the
//! view shows: the sphere blockers and the terrain (the log-SH, or the exact share for the
//! lights the settings send that way), and for the lights the view shadows by shadow maps
//! the scene's triangles themselves, by a ray cast per painted vertex on a BVH built at
//! the first such light; indirect light is left out (the bake adds it).

use glam::{DVec3, Vec3};

use super::ShadowSettings;
use super::cpu::mapped_visibility;
use super::cpu::{self, SurfacePoint};
use super::gpu_types::{GpuLight, SHADOW_PATH_MAP, environment_irradiance};
use crate::bake::scene_bvh::SceneBvh;
use crate::blockers::Sphere;
use crate::paint::{PaintedPoint, Transfer, VertexRef};
use crate::scene::{Light, Material, Scene, luminance};
use crate::sh;
use crate::terrain::TerrainShadow;

/// [`Transfer`] from the log-SH shading of the scene's lights, each at unit intensity.
pub struct DirectEstimate<'a> {
    scene: &'a Scene,
    blockers: Vec<Sphere>,
    terrain: Option<TerrainShadow>,
    settings: ShadowSettings,
    unit_lights: Vec<GpuLight>,
    environment: [[f32; 4]; 9],
    /// The scene's triangles for the lights the view shadows by shadow maps, built when
    /// first needed.
    occluders: std::sync::OnceLock<SceneBvh>,
}

impl<'a> DirectEstimate<'a> {
    pub fn new(scene: &'a Scene, blockers: Vec<Sphere>, settings: ShadowSettings) -> DirectEstimate<'a> {
        // Unit intensities, each light on the shadow path the frame gives it.
        let context = super::LightPathContext::of_scene(scene, &blockers);
        let shading = super::shading_lights(&scene.lights, &settings, &context);
        let unit_lights = scene
            .lights
            .iter()
            .zip(shading)
            .map(|(light, shaded)| GpuLight {
                shadow_path: shaded.shadow_path,
                first_shadow_view: shaded.first_shadow_view,
                shadow_view_count: shaded.shadow_view_count,
                ..GpuLight::new(&Light {
                    intensity: 1.0,
                    ..light.clone()
                })
            })
            .collect();
        DirectEstimate {
            scene,
            blockers,
            terrain: scene
                .terrain
                .as_ref()
                .map(|t| super::terrain::terrain_march(&t.field, &settings)),
            settings,
            unit_lights,
            environment: environment_irradiance(scene.environment.as_ref()),
            occluders: std::sync::OnceLock::new(),
        }
    }

    pub(crate) fn surface(&self, vertex: VertexRef) -> Option<SurfacePoint> {
        let object = self.scene.objects.get(vertex.object as usize)?;
        let v = vertex.vertex as usize;
        let default = Material::default();
        let material = self.scene.materials.get(object.material).unwrap_or(&default);
        Some(SurfacePoint {
            position: object.positions.get(v)?.as_dvec3(),
            normal: object.normals.get(v)?.as_dvec3(),
            k_d: material.diffuse_albedo().as_dvec3(),
            k_s: material.specular_color().as_dvec3(),
            phong_exponent: material.phong_exponent() as f64,
            emissive: material.emissive.as_dvec3(),
        })
    }

    /// The surface at a point under the brush: position and shading normal interpolated
    /// from the triangle's corners (as the rasteriser interpolates them), the material's
    /// colour times the base-colour texture there (as the frame's shading takes it).
    pub(crate) fn surface_at_point(&self, point: &PaintedPoint) -> Option<SurfacePoint> {
        let object = self.scene.objects.get(point.object as usize)?;
        let mut position = DVec3::ZERO;
        let mut normal = DVec3::ZERO;
        for (vertex, share) in point.weighted_corners() {
            let v = vertex.vertex as usize;
            position += share * object.positions.get(v)?.as_dvec3();
            normal += share * object.normals.get(v)?.as_dvec3();
        }
        let normal = normal.try_normalize()?;
        let mut material = self.scene.materials.get(object.material).cloned().unwrap_or_default();
        if let Some(rgb) = point.texture_rgb {
            let colour = material.base_color.truncate() * rgb.as_vec3();
            material.base_color = colour.extend(material.base_color.w);
        }
        (position.is_finite() && normal.is_finite()).then(|| SurfacePoint {
            position,
            normal,
            k_d: material.diffuse_albedo().as_dvec3(),
            k_s: material.specular_color().as_dvec3(),
            phong_exponent: material.phong_exponent() as f64,
            emissive: material.emissive.as_dvec3(),
        })
    }

    /// Exponentiated visibility SH at the surface point: one shared by the environment and
    /// every SH light, or, where the view's light windows apply (same lights, same
    /// environment), one per windowed light (`cpu::harmonic_log_visibility`).
    fn visibility(&self, s: &SurfacePoint) -> cpu::HarmonicVisibility<Vec<f64>> {
        cpu::harmonic_log_visibility(
            &self.settings,
            &self.blockers,
            self.terrain.as_ref(),
            &self.environment,
            &self.unit_lights,
            s.position,
            s.normal,
        )
        .map(|f| sh::exp(self.settings.exp, f))
    }
}

/// The exponentiated visibility at a surface point, evaluated on first use and shared by
/// the transfer and the fixed light of the same vertex.
struct LazyVisibility<'e, 'a> {
    estimate: &'e DirectEstimate<'a>,
    g: Option<cpu::HarmonicVisibility<Vec<f64>>>,
}

impl LazyVisibility<'_, '_> {
    fn at(&mut self, s: &SurfacePoint) -> &cpu::HarmonicVisibility<Vec<f64>> {
        let estimate = self.estimate;
        self.g.get_or_insert_with(|| estimate.visibility(s))
    }
}

impl<'a> DirectEstimate<'a> {
    fn lazy(&self) -> LazyVisibility<'_, 'a> {
        LazyVisibility {
            estimate: self,
            g: None,
        }
    }

    /// Per-light transfer at `s` toward `eye`.
    fn transfer_at(&self, s: &SurfacePoint, eye: Vec3, g: &mut LazyVisibility) -> Vec<(u32, f64)> {
        let eye = eye.as_dvec3();
        self.unit_lights
            .iter()
            .enumerate()
            .filter_map(|(i, light)| {
                let incidence = cpu::incidence(light, s.position);
                let unshadowed = cpu::direct_radiance(s, &incidence, eye);
                if unshadowed == DVec3::ZERO {
                    return None;
                }
                if light.shadow_path == SHADOW_PATH_MAP {
                    // What the view's shadow map shows: the scene's triangles, by rays.
                    let occluders = self.occluders.get_or_init(|| SceneBvh::build(self.scene));
                    let visible = mapped_visibility(occluders, s.position, s.normal, &incidence);
                    let t = luminance(unshadowed) * visible;
                    return (t.is_finite() && t > 0.0).then_some((i as u32, t));
                }
                let visible = cpu::exact_visibility(
                    s,
                    light,
                    &incidence,
                    &self.settings,
                    &self.blockers,
                    self.terrain.as_ref(),
                    0.0,
                )
                .unwrap_or_else(|| {
                    // None: a windowed frame's light that does not reach s (it adds nothing).
                    g.at(s).of_light(i).map_or(0.0, |g| {
                        cpu::visibility_toward(g, incidence.to_light, incidence.cap_ratio).clamp(0.0, 1.0)
                    })
                });
                let t = luminance(unshadowed) * visible;
                (t.is_finite() && t > 0.0).then_some((i as u32, t))
            })
            .collect()
    }

    /// Fixed luminance and per-light transfer at `s` toward `eye`.
    pub(crate) fn shading_at(&self, s: &SurfacePoint, eye: Vec3) -> (f64, Vec<(u32, f64)>) {
        let mut g = self.lazy();
        let transfer = self.transfer_at(s, eye, &mut g);
        (self.fixed_at(s, &mut g), transfer)
    }

    /// Luminance at `s` that no light changes: emission and the shadowed environment.
    fn fixed_at(&self, s: &SurfacePoint, g: &mut LazyVisibility) -> f64 {
        let mut radiance = s.emissive;
        if self.scene.environment.is_some()
            && let Some(g) = &g.at(s).shared
        {
            radiance += cpu::environment_through_visibility(s, &self.environment, g);
        }
        luminance(radiance)
    }
}

impl Transfer for DirectEstimate<'_> {
    fn light_count(&self) -> usize {
        self.unit_lights.len()
    }

    fn vertex_transfer(&self, vertex: VertexRef, eye: Vec3) -> Vec<(u32, f64)> {
        let Some(s) = self.surface(vertex) else {
            return Vec::new();
        };
        self.transfer_at(&s, eye, &mut self.lazy())
    }

    fn fixed_luminance(&self, vertex: VertexRef, _eye: Vec3) -> f64 {
        let Some(s) = self.surface(vertex) else { return 0.0 };
        self.fixed_at(&s, &mut self.lazy())
    }

    fn vertex_shading(&self, vertex: VertexRef, eye: Vec3) -> (f64, Vec<(u32, f64)>) {
        let Some(s) = self.surface(vertex) else {
            return (0.0, Vec::new());
        };
        self.shading_at(&s, eye)
    }

    /// The frame's shading at the point itself, not its corners': a highlight or a shadow
    /// edge between vertices shows in the stroke's reading as in the frame.
    fn point_shading(&self, point: &PaintedPoint, eye: Vec3) -> (f64, Vec<(u32, f64)>) {
        let Some(s) = self.surface_at_point(point) else {
            return (0.0, Vec::new());
        };
        self.shading_at(&s, eye)
    }
}

#[cfg(test)]
pub(crate) mod tests {
    use std::f64::consts::PI;

    use super::*;

    /// Without blockers, a white Lambertian floor under a unit point light shows
    /// L = (1/π)·cos θ/d² (closed form).
    #[test]
    fn an_unoccluded_lambertian_floor_matches_the_closed_form() {
        let scene = Scene::lambert_floor_under_point_light(2, Vec3::new(0.5, 2.0, 0.0), 30.0);
        let estimate = DirectEstimate::new(&scene, Vec::new(), ShadowSettings::default());
        for v in 0..scene.objects[0].positions.len() {
            let p = scene.objects[0].positions[v].as_dvec3();
            let offset = DVec3::new(0.5, 2.0, 0.0) - p;
            let expected = offset.normalize().y / offset.length_squared() / PI;
            let vertex = VertexRef {
                object: 0,
                vertex: v as u32,
            };
            let t = estimate.vertex_transfer(vertex, Vec3::new(0.0, 3.0, 3.0));
            assert_eq!(t.len(), 1);
            assert!((t[0].1 / expected - 1.0).abs() < 1e-6, "{} vs {expected}", t[0].1);
        }
    }

    /// A painted point inside the first triangle of the scene's first object, off its
    /// centre (barycentrics 0.2, 0.5, 0.3), and where it lies.
    pub(crate) fn point_inside_the_first_triangle(scene: &Scene) -> (PaintedPoint, DVec3) {
        let object = &scene.objects[0];
        let corners = [object.indices[0], object.indices[1], object.indices[2]];
        let barycentric = glam::Vec3::new(0.2, 0.5, 0.3);
        let at = corners
            .iter()
            .zip(barycentric.to_array())
            .map(|(&v, b)| object.positions[v as usize].as_dvec3() * b as f64)
            .sum();
        let point = PaintedPoint {
            object: 0,
            corners,
            barycentric,
            weight: 1.0,
            texture_rgb: None,
        };
        (point, at)
    }

    /// At a point inside a triangle the estimate is the closed form at that point, not
    /// the corners' values interpolated (which differ: cos θ/d² is not linear).
    #[test]
    fn a_painted_point_reads_the_light_at_the_point_itself() {
        let light = Vec3::new(0.3, 1.0, 0.2);
        let scene = Scene::lambert_floor_under_point_light(2, light, 30.0);
        let estimate = DirectEstimate::new(&scene, Vec::new(), ShadowSettings::default());
        let (point, at) = point_inside_the_first_triangle(&scene);
        let offset = light.as_dvec3() - at;
        let expected = offset.normalize().y / offset.length_squared() / PI;
        let (_, t) = estimate.point_shading(&point, Vec3::new(0.0, 3.0, 3.0));
        assert_eq!(t.len(), 1);
        assert!((t[0].1 / expected - 1.0).abs() < 1e-5, "{} vs {expected}", t[0].1);
        let interpolated: f64 = point
            .weighted_corners()
            .iter()
            .map(|&(v, b)| b * estimate.vertex_transfer(v, Vec3::new(0.0, 3.0, 3.0))[0].1)
            .sum();
        assert!(
            (interpolated / expected - 1.0).abs() > 1e-2,
            "the corners alone would not tell"
        );
    }
}
