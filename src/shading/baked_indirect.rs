//! Baked indirect light for the real-time renderer: the bake stores, per vertex and light,
//! the irradiance the light's bounced light gives the vertex at unit intensity
//! ([`crate::bake::MapEntry::indirect_irradiance`]). Light transport is linear in the
//! intensities, so the vertex's indirect irradiance now is
//!
//!   E_v = Σ_i P_i · colour_i · E_{i,v},
//!
//! recomputed on the CPU when intensities or colours change (no re-bake), interpolated
//! across triangles by the rasteriser and reflected diffusely, k_d/π·E_v, unshadowed by
//! the sphere blockers (the bake traced the real geometry). The bake reduces the bounce
//! surfaces' colours to their luminance, so indirect light carries the light's colour but
//! no colour bleeding; it is baked for the side the vertex normal faces.

use rayon::prelude::*;

use crate::bake::ImportanceMaps;
use crate::scene::Scene;

/// Per object of a [`Scene`], each vertex's indirect irradiance (linear RGB, lux).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct BakedIndirect {
    pub objects: Vec<Vec<[f32; 3]>>,
}

impl BakedIndirect {
    /// The indirect irradiance of every vertex of `scene` under its current lights, from
    /// `maps` (baked for this geometry; objects the maps do not cover get none).
    pub fn from_maps(scene: &Scene, maps: &ImportanceMaps) -> BakedIndirect {
        let light_rgb: Vec<glam::Vec3> = scene.lights.iter().map(|l| l.color * l.intensity).collect();
        let objects = scene
            .objects
            .iter()
            .enumerate()
            .map(|(o, object)| {
                let Some(object_maps) = maps.objects.get(o) else {
                    return vec![[0.0; 3]; object.positions.len()];
                };
                (0..object.positions.len())
                    .into_par_iter()
                    .map(|v| {
                        let sum = object_maps
                            .entries(v)
                            .filter_map(|e| Some(*light_rgb.get(e.light as usize)? * e.indirect_irradiance))
                            .fold(glam::Vec3::ZERO, |acc, e| acc + e);
                        if sum.is_finite() {
                            sum.max(glam::Vec3::ZERO).to_array()
                        } else {
                            [0.0; 3]
                        }
                    })
                    .collect()
            })
            .collect();
        BakedIndirect { objects }
    }

    /// The irradiance of vertex `v` of object `o` (0 where there is none).
    pub fn at(&self, o: usize, v: usize) -> glam::Vec3 {
        self.objects
            .get(o)
            .and_then(|vertices| vertices.get(v))
            .map_or(glam::Vec3::ZERO, |&rgb| glam::Vec3::from_array(rgb))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::bake::{ImportanceMaps, LightContribution, ObjectMaps, Precision};

    /// Two lights at one vertex: E = Σ P_i·colour_i·E_i, and doubling a light's intensity
    /// doubles its share (linearity), with no re-bake.
    #[test]
    fn indirect_irradiance_is_the_intensity_weighted_sum_of_the_lights() {
        let mut scene = Scene::lambert_floor_under_point_light(1, glam::Vec3::Y, 2.0);
        let mut second = scene.lights[0].clone();
        second.color = glam::Vec3::new(0.0, 0.5, 1.0);
        second.intensity = 3.0;
        scene.lights.push(second);
        let vertex = vec![
            LightContribution {
                light: 0,
                sh: vec![1.0; 4],
                indirect_irradiance: 0.25,
            },
            LightContribution {
                light: 1,
                sh: vec![1.0; 4],
                indirect_irradiance: 0.5,
            },
        ];
        let vertices = vec![vertex; scene.objects[0].positions.len()];
        let maps = ImportanceMaps {
            order: 2,
            objects: vec![ObjectMaps::from_vertices(2, &vertices, Precision::F32)],
            dropped_entries: 0,
        };
        let e = BakedIndirect::from_maps(&scene, &maps).at(0, 0);
        // Light 0: white × 2 × 0.25; light 1: (0, 0.5, 1) × 3 × 0.5.
        assert_eq!(e, glam::Vec3::new(0.5, 0.5 + 0.75, 0.5 + 1.5));
        scene.lights[1].intensity = 6.0;
        let doubled = BakedIndirect::from_maps(&scene, &maps).at(0, 0);
        assert_eq!(doubled - glam::Vec3::splat(0.5), 2.0 * (e - glam::Vec3::splat(0.5)));
    }
}
