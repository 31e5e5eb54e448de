//! The scene model: what the renderer, the bake and the painting engine all read.
//!
//! Conventions (shading-model.md §3): world space is glTF's (right-handed, +y up, metres);
//! colours are linear RGB; light units follow KHR_lights_punctual (point and spot lights in
//! candela, directional lights in lux).

mod bounds;
mod camera;
pub mod color_temperature;
pub mod detail_levels;
mod enclosure;
pub mod environment;
mod error;
mod frustum;
mod gltf_import;
pub mod gltf_write;
mod level_deviation;
mod light;
mod light_edit;
mod material;
mod mesh;
mod reflectance;
pub mod shapes;
pub mod terrain;
pub mod texture_mips;

pub use bounds::Aabb;
pub use camera::{Camera, OrbitCamera};
pub use enclosure::encloses_outward;
pub use environment::{Environment, equirect_direction, project_equirect};
pub use error::SceneError;
pub use frustum::Frustum;
pub use gltf_import::{load_gltf, load_gltf_scene, parse_gltf, parse_gltf_scene};
pub use light::{Light, LightKind, UnitIncidence};
pub use light_edit::{LIGHT_KINDS, direction_angles_deg, direction_from_angles_deg};
pub use material::{Material, TextureImage, linear_to_srgb, luminance, srgb_to_linear};
pub use mesh::MeshObject;
pub use reflectance::Reflectance;
pub use terrain::{Terrain, TerrainSource, TerrainSpec};

use std::path::{Path, PathBuf};

/// A loaded scene, flattened to world space: every mesh primitive instanced by a node
/// becomes one [`MeshObject`] with the node's transform applied.
#[derive(Debug, Clone, Default)]
pub struct Scene {
    pub objects: Vec<MeshObject>,
    pub materials: Vec<Material>,
    pub textures: Vec<TextureImage>,
    pub lights: Vec<Light>,
    /// Light from all around (an HDR image as SH), if any.
    pub environment: Option<Environment>,
    /// The first camera of the glTF scene, if it has one.
    pub camera: Option<Camera>,
    /// The file the scene was loaded from.
    pub source: Option<PathBuf>,
    /// BLAKE3 hash (hex) of that file's bytes, so a project can tell when it changed.
    pub source_hash: Option<String>,
    /// Non-fatal problems found while loading (unsupported features, missing textures).
    pub warnings: Vec<String>,
    /// The names of every scene in the glTF file, in the file's order ("" when unnamed).
    pub gltf_scenes: Vec<String>,
    /// Which of [`Self::gltf_scenes`] this scene shows (None: the file has none).
    pub gltf_scene: Option<usize>,
    /// The height-field terrain, if the project has one (its mesh is in `objects`).
    pub terrain: Option<Terrain>,
}

impl Scene {
    /// Loads a scene from a `.gltf` or `.glb` file (the file's default scene).
    pub fn load(path: &Path) -> Result<Scene, SceneError> {
        load_gltf(path)
    }

    /// Loads scene number `choice` of a `.gltf` or `.glb` file (None: its default scene).
    pub fn load_choosing(path: &Path, choice: Option<usize>) -> Result<Scene, SceneError> {
        load_gltf_scene(path, choice)
    }

    /// How to name glTF scene `index` to a user: "1 'Night'", or "1" when unnamed.
    pub fn gltf_scene_label(&self, index: usize) -> String {
        match self.gltf_scenes.get(index).map(String::as_str) {
            Some(name) if !name.is_empty() => format!("{index} '{name}'"),
            _ => index.to_string(),
        }
    }

    /// World-space bounds of all geometry (empty if the scene has no geometry).
    pub fn bounds(&self) -> Aabb {
        self.objects
            .iter()
            .fold(Aabb::EMPTY, |acc, object| acc.union(&object.bounds()))
    }

    pub fn vertex_count(&self) -> usize {
        self.objects.iter().map(|o| o.positions.len()).sum()
    }

    pub fn triangle_count(&self) -> usize {
        self.objects.iter().map(|o| o.indices.len() / 3).sum()
    }

    /// Whether every object with triangles has a single-sided material (glTF
    /// `doubleSided` false), so that the renderer may cull back faces: it culls for all
    /// objects or none, as the cull mode is fixed per pipeline. False for a scene without
    /// triangles; an object whose material index is out of range counts as double-sided.
    pub fn every_material_single_sided(&self) -> bool {
        let mut drawn = self.objects.iter().filter(|o| !o.indices.is_empty()).peekable();
        drawn.peek().is_some() && drawn.all(|o| self.materials.get(o.material).is_some_and(|m| !m.double_sided))
    }

    /// Every light's intensity, in light order: the state painting changes.
    pub fn light_intensities(&self) -> Vec<f32> {
        self.lights.iter().map(|l| l.intensity).collect()
    }

    /// The indices of the lights the artist locked (`Light::locked`), which painting
    /// leaves as they are: what a stroke records (`StrokeRecord::locked_lights`).
    pub fn locked_lights(&self) -> Vec<u32> {
        (0..self.lights.len() as u32)
            .filter(|&i| self.lights[i as usize].locked)
            .collect()
    }

    /// Sets the lights' intensities from `intensities` (in light order).
    pub fn set_light_intensities(&mut self, intensities: &[f32]) {
        for (light, &p) in self.lights.iter_mut().zip(intensities) {
            light.intensity = p;
        }
    }

    /// A test scene with a closed-form answer: a 2 m white Lambertian floor of
    /// `segments`² quads facing +y under one white point light of `intensity_cd`.
    #[cfg(test)]
    pub(crate) fn lambert_floor_under_point_light(segments: u32, position: glam::Vec3, intensity_cd: f32) -> Scene {
        Scene {
            objects: vec![shapes::plane(2.0, segments, 1.0).into_object("floor")],
            materials: vec![Material {
                metallic: 0.0,
                specular: 0.0,
                ..Material::default()
            }],
            lights: vec![Light {
                name: "bulb".into(),
                kind: LightKind::Point,
                color: glam::Vec3::ONE,
                intensity: intensity_cd,
                position,
                direction: glam::Vec3::NEG_Y,
                range: None,
                locked: false,
            }],
            ..Default::default()
        }
    }

    /// The camera to open the scene with: the glTF camera, or one framing the bounds.
    pub fn initial_camera(&self) -> Camera {
        self.camera.clone().unwrap_or_else(|| Camera::framing(&self.bounds()))
    }

    /// The orbit camera matching [`Self::initial_camera`], pivoting at the distance of
    /// the scene's centre: what the editor and the CLI view a project without a saved
    /// camera from.
    pub fn initial_orbit(&self) -> OrbitCamera {
        let camera = self.initial_camera();
        let pivot = (self.bounds().center() - camera.position).length().max(0.1);
        OrbitCamera::from_camera(&camera, pivot)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn one_side() -> Material {
        Material {
            double_sided: false,
            ..Material::default()
        }
    }

    #[test]
    fn back_faces_are_culled_only_when_every_drawn_object_is_single_sided() {
        let floor = || shapes::plane(1.0, 1, 1.0).into_object("floor");
        let scene = |objects: Vec<MeshObject>, materials: Vec<Material>| Scene {
            objects,
            materials,
            ..Scene::default()
        };
        assert!(
            !scene(vec![], vec![one_side()]).every_material_single_sided(),
            "nothing drawn"
        );
        assert!(scene(vec![floor()], vec![one_side()]).every_material_single_sided());
        let mut second = floor();
        second.material = 1;
        assert!(
            !scene(vec![floor(), second.clone()], vec![one_side(), Material::default()]).every_material_single_sided()
        );
        assert!(
            !scene(vec![floor(), second.clone()], vec![one_side()]).every_material_single_sided(),
            "material out of range"
        );
        // An object without triangles is not drawn, whatever its material.
        second.indices.clear();
        assert!(scene(vec![floor(), second], vec![one_side(), Material::default()]).every_material_single_sided());
    }
}
