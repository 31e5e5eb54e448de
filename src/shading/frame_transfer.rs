//! The transfer strokes read once maps are baked: the light the frame then shows. The
//! frame shades each light's direct light with the real-time visibility and adds the
//! maps' bounced light as baked irradiance reflected diffusely, k_d/π·Σ_i P_i·colour_i·E_i
//! (`BakedIndirect`, interpolated across triangles by the rasteriser), so a stroke reads
//!
//!   t_i = direct_i (the direct estimate, `paint_estimate`) + lum(k_d ⊙ colour_i)/π · E_i,
//!
//! E_i the maps' indirect irradiance of light i at unit intensity, interpolated from the
//! triangle's corners at a painted point. The maps' SH of the incident light, whose band
//! limit smears a small light's direct light over the lobe, are not read for it (they
//! stay the bake's, for `BakedTransfer`).

use glam::Vec3;

use super::RenderSettings;
use super::cpu::SurfacePoint;
use super::paint_estimate::DirectEstimate;
use crate::bake::ImportanceMaps;
use crate::blockers::Sphere;
use crate::paint::{PaintedPoint, Transfer, VertexRef};
use crate::scene::{Scene, luminance};

/// [`Transfer`] of the frame drawn with baked indirect light.
pub struct FrameTransfer<'a> {
    direct: DirectEstimate<'a>,
    scene: &'a Scene,
    maps: &'a ImportanceMaps,
}

impl<'a> FrameTransfer<'a> {
    pub fn new(direct: DirectEstimate<'a>, scene: &'a Scene, maps: &'a ImportanceMaps) -> FrameTransfer<'a> {
        FrameTransfer { direct, scene, maps }
    }

    /// Adds to `transfer` the baked indirect light of `vertex`'s entries, `share` of it,
    /// reflected by a surface of diffuse reflectance `s.k_d`.
    fn add_indirect(&self, transfer: &mut Vec<(u32, f64)>, s: &SurfacePoint, vertex: VertexRef, share: f64) {
        let Some(maps) = self.maps.objects.get(vertex.object as usize) else {
            return;
        };
        if vertex.vertex as usize >= maps.vertex_count() {
            return;
        }
        for entry in maps.entries(vertex.vertex as usize) {
            let Some(light) = self.scene.lights.get(entry.light as usize) else {
                continue;
            };
            let reflected = luminance(s.k_d * light.color.as_dvec3()) / std::f64::consts::PI;
            let t = share * reflected * entry.indirect_irradiance as f64;
            if !(t.is_finite() && t > 0.0) {
                continue;
            }
            match transfer.iter_mut().find(|(l, _)| *l == entry.light) {
                Some(existing) => existing.1 += t,
                None => transfer.push((entry.light, t)),
            }
        }
    }
}

impl Transfer for FrameTransfer<'_> {
    fn light_count(&self) -> usize {
        self.direct.light_count()
    }

    fn vertex_transfer(&self, vertex: VertexRef, eye: Vec3) -> Vec<(u32, f64)> {
        self.vertex_shading(vertex, eye).1
    }

    fn fixed_luminance(&self, vertex: VertexRef, eye: Vec3) -> f64 {
        self.direct.fixed_luminance(vertex, eye)
    }

    fn vertex_shading(&self, vertex: VertexRef, eye: Vec3) -> (f64, Vec<(u32, f64)>) {
        let Some(s) = self.direct.surface(vertex) else {
            return (0.0, Vec::new());
        };
        let (fixed, mut transfer) = self.direct.shading_at(&s, eye);
        self.add_indirect(&mut transfer, &s, vertex, 1.0);
        (fixed, transfer)
    }

    fn point_shading(&self, point: &PaintedPoint, eye: Vec3) -> (f64, Vec<(u32, f64)>) {
        let Some(s) = self.direct.surface_at_point(point) else {
            return (0.0, Vec::new());
        };
        let (fixed, mut transfer) = self.direct.shading_at(&s, eye);
        for (vertex, share) in point.weighted_corners() {
            if share > 0.0 {
                self.add_indirect(&mut transfer, &s, vertex, share);
            }
        }
        (fixed, transfer)
    }
}

/// The transfer strokes read: the light the frame `settings` draw — the direct estimate
/// through `blockers` (the view's visibility), plus, when there are maps for this scene
/// and the frame adds their baked light (`settings.baked_indirect`), their bounced light
/// as the frame adds it ([`FrameTransfer`]). One choice for the editor and
/// `lightpaint paint` alike.
pub fn transfer_for<'a>(
    maps: Option<&'a crate::bake::ImportanceMaps>,
    scene: &'a Scene,
    blockers: &[Sphere],
    settings: &RenderSettings,
) -> Box<dyn Transfer + 'a> {
    let direct = DirectEstimate::new(scene, blockers.to_vec(), settings.shadows);
    match maps.filter(|_| settings.baked_indirect) {
        Some(maps) => Box::new(FrameTransfer::new(direct, scene, maps)),
        None => Box::new(direct),
    }
}

#[cfg(test)]
mod tests {
    use std::f64::consts::PI;

    use glam::DVec3;

    use super::*;
    use crate::bake::{LightContribution, ObjectMaps, Precision};
    use crate::shading::ShadowSettings;

    /// Indirect irradiance (per unit intensity) the test maps give a vertex at p: linear in x.
    fn indirect_at(p: Vec3) -> f32 {
        0.1 + 0.05 * (p.x + 1.0)
    }

    /// Maps of `scene`'s one object and one light whose indirect irradiance is
    /// [`indirect_at`].
    fn linear_maps(scene: &Scene) -> ImportanceMaps {
        let vertices: Vec<Vec<LightContribution>> = scene.objects[0]
            .positions
            .iter()
            .map(|&p| {
                vec![LightContribution {
                    light: 0,
                    sh: vec![1.0; 9],
                    indirect_irradiance: indirect_at(p),
                }]
            })
            .collect();
        ImportanceMaps {
            order: 3,
            objects: vec![ObjectMaps::from_vertices(3, &vertices, Precision::F32)],
            dropped_entries: 0,
        }
    }

    /// A white Lambertian floor under a unit point light whose maps give every vertex an
    /// indirect irradiance that grows along x: at a point inside a triangle a stroke reads
    /// the closed-form direct light there, cos θ/(π d²), plus the corners' indirect
    /// irradiance interpolated to the point over π — the frame's own sum.
    #[test]
    fn a_point_reads_the_direct_light_there_and_the_interpolated_bounced_light() {
        let light = Vec3::new(0.3, 1.0, 0.2);
        let scene = Scene::lambert_floor_under_point_light(2, light, 30.0);
        let object = &scene.objects[0];
        let maps = linear_maps(&scene);
        let direct = DirectEstimate::new(&scene, Vec::new(), ShadowSettings::default());
        let transfer = FrameTransfer::new(direct, &scene, &maps);
        let (point, at) = crate::shading::paint_estimate::tests::point_inside_the_first_triangle(&scene);
        let offset = light.as_dvec3() - at;
        let direct = offset.normalize().y / offset.length_squared() / PI;
        // The indirect irradiance is linear in x, so interpolating it is exact.
        let bounced = indirect_at(at.as_vec3()) as f64 / PI;
        let (_, t) = transfer.point_shading(&point, Vec3::new(0.0, 3.0, 3.0));
        assert_eq!(t.len(), 1);
        let expected = direct + bounced;
        assert!((t[0].1 / expected - 1.0).abs() < 1e-5, "{} vs {expected}", t[0].1);
        // At a vertex, the same sum there.
        let vertex = VertexRef { object: 0, vertex: 0 };
        let p = object.positions[0];
        let offset: DVec3 = (light - p).as_dvec3();
        let expected = offset.normalize().y / offset.length_squared() / PI + indirect_at(p) as f64 / PI;
        let t = transfer.vertex_transfer(vertex, Vec3::new(0.0, 3.0, 3.0));
        assert!((t[0].1 / expected - 1.0).abs() < 1e-5, "{} vs {expected}", t[0].1);
    }

    /// Where the frame adds no baked light (`baked_indirect` off), strokes read the direct
    /// light alone, maps or not: cos θ/(π d²) at the point.
    #[test]
    fn without_baked_light_in_the_frame_the_maps_add_nothing() {
        let light = Vec3::new(0.3, 1.0, 0.2);
        let scene = Scene::lambert_floor_under_point_light(2, light, 30.0);
        let maps = linear_maps(&scene);
        let (point, at) = crate::shading::paint_estimate::tests::point_inside_the_first_triangle(&scene);
        let offset = light.as_dvec3() - at;
        let direct = offset.normalize().y / offset.length_squared() / PI;
        let read = |baked_indirect: bool| {
            let settings = RenderSettings {
                baked_indirect,
                ..RenderSettings::default()
            };
            let transfer = transfer_for(Some(&maps), &scene, &[], &settings);
            transfer.point_shading(&point, Vec3::new(0.0, 3.0, 3.0)).1[0].1
        };
        assert!((read(false) / direct - 1.0).abs() < 1e-5, "{} vs {direct}", read(false));
        let bounced = indirect_at(at.as_vec3()) as f64 / PI;
        assert!((read(true) / (direct + bounced) - 1.0).abs() < 1e-5);
    }
}
