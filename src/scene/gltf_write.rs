//! A small glTF 2.0 writer for scenes we generate ourselves: the bundled samples and the
//! test fixtures. It writes exactly what the importer reads (triangle meshes with normals
//! and UVs, metallic-roughness materials with an optional PNG base colour texture,
//! KHR_lights_punctual lights, perspective cameras, node transforms).

use glam::{Quat, Vec2, Vec3};
use serde_json::{Value, json};

use super::shapes::ShapeMesh;

/// A material to write. `specular` writes KHR_materials_specular when set.
#[derive(Debug, Clone)]
pub struct MaterialSpec {
    pub name: String,
    pub base_color: [f32; 4],
    pub metallic: f32,
    pub roughness: f32,
    pub specular: Option<f32>,
    /// PNG bytes of an sRGB base colour texture.
    pub base_color_png: Option<Vec<u8>>,
}

impl MaterialSpec {
    pub fn plain(name: &str, base_color: [f32; 3], roughness: f32) -> MaterialSpec {
        MaterialSpec {
            name: name.to_string(),
            base_color: [base_color[0], base_color[1], base_color[2], 1.0],
            metallic: 0.0,
            roughness,
            specular: None,
            base_color_png: None,
        }
    }
}

/// A KHR_lights_punctual light to write.
#[derive(Debug, Clone)]
pub enum LightSpec {
    Point {
        color: [f32; 3],
        intensity_cd: f32,
    },
    Spot {
        color: [f32; 3],
        intensity_cd: f32,
        inner_cone_rad: f32,
        outer_cone_rad: f32,
    },
    Directional {
        color: [f32; 3],
        illuminance_lux: f32,
    },
}

/// Builds a glTF document with one binary buffer.
#[derive(Debug, Default)]
pub struct GltfBuilder {
    bin: Vec<u8>,
    views: Vec<Value>,
    accessors: Vec<Value>,
    meshes: Vec<Value>,
    materials: Vec<Value>,
    images: Vec<Value>,
    textures: Vec<Value>,
    lights: Vec<Value>,
    cameras: Vec<Value>,
    nodes: Vec<Value>,
    uses_specular: bool,
}

/// The rotation that turns glTF's local −z (the way lights and cameras point) to `forward`,
/// keeping local +y as close to `up` as possible.
pub fn look_rotation(forward: Vec3, up: Vec3) -> Quat {
    let back = -forward.normalize();
    let right = up.cross(back).normalize();
    let true_up = back.cross(right);
    Quat::from_mat3(&glam::Mat3::from_cols(right, true_up, back))
}

impl GltfBuilder {
    pub fn new() -> GltfBuilder {
        GltfBuilder::default()
    }

    /// Appends raw bytes as a buffer view (4-byte aligned) and returns its index.
    pub fn push_view(&mut self, bytes: &[u8], target: Option<u32>) -> usize {
        while !self.bin.len().is_multiple_of(4) {
            self.bin.push(0);
        }
        let mut view = json!({"buffer": 0, "byteOffset": self.bin.len(), "byteLength": bytes.len()});
        if let Some(target) = target {
            view["target"] = json!(target);
        }
        self.bin.extend_from_slice(bytes);
        self.views.push(view);
        self.views.len() - 1
    }

    /// Adds an accessor as raw JSON (tests use this to write deliberately broken files).
    pub fn push_accessor(&mut self, accessor: Value) -> usize {
        self.accessors.push(accessor);
        self.accessors.len() - 1
    }

    fn float_accessor(&mut self, values: &[f32], components: usize, kind: &str, min_max: bool) -> usize {
        let view = self.push_view(bytemuck::cast_slice(values), Some(34962));
        let count = values.len() / components;
        let mut accessor = json!({"bufferView": view, "componentType": 5126, "count": count, "type": kind});
        if min_max {
            let mut min = vec![f32::INFINITY; components];
            let mut max = vec![f32::NEG_INFINITY; components];
            for element in values.chunks_exact(components) {
                for (c, &v) in element.iter().enumerate() {
                    min[c] = min[c].min(v);
                    max[c] = max[c].max(v);
                }
            }
            accessor["min"] = json!(min);
            accessor["max"] = json!(max);
        }
        self.push_accessor(accessor)
    }

    pub fn add_material(&mut self, spec: &MaterialSpec) -> usize {
        let mut pbr = json!({
            "baseColorFactor": spec.base_color,
            "metallicFactor": spec.metallic,
            "roughnessFactor": spec.roughness,
        });
        if let Some(png) = &spec.base_color_png {
            let view = self.push_view(png, None);
            self.images.push(
                json!({"bufferView": view, "mimeType": "image/png", "name": format!("{}_base_color", spec.name)}),
            );
            self.textures.push(json!({"source": self.images.len() - 1}));
            pbr["baseColorTexture"] = json!({"index": self.textures.len() - 1});
        }
        let mut material = json!({"name": spec.name, "pbrMetallicRoughness": pbr});
        if let Some(specular) = spec.specular {
            material["extensions"] = json!({"KHR_materials_specular": {"specularFactor": specular}});
            self.uses_specular = true;
        }
        self.materials.push(material);
        self.materials.len() - 1
    }

    /// Adds a one-primitive triangle mesh and returns its index.
    pub fn add_mesh(
        &mut self,
        name: &str,
        positions: &[Vec3],
        normals: Option<&[Vec3]>,
        uvs: Option<&[Vec2]>,
        indices: &[u32],
        material: Option<usize>,
    ) -> usize {
        let flat = |v: &[Vec3]| v.iter().flat_map(|p| p.to_array()).collect::<Vec<f32>>();
        let mut attributes = json!({"POSITION": self.float_accessor(&flat(positions), 3, "VEC3", true)});
        if let Some(normals) = normals {
            attributes["NORMAL"] = json!(self.float_accessor(&flat(normals), 3, "VEC3", false));
        }
        if let Some(uvs) = uvs {
            let flat_uvs: Vec<f32> = uvs.iter().flat_map(|p| p.to_array()).collect();
            attributes["TEXCOORD_0"] = json!(self.float_accessor(&flat_uvs, 2, "VEC2", false));
        }
        let index_view = self.push_view(bytemuck::cast_slice(indices), Some(34963));
        let index_accessor = self.push_accessor(
            json!({"bufferView": index_view, "componentType": 5125, "count": indices.len(), "type": "SCALAR"}),
        );
        let mut primitive = json!({"attributes": attributes, "indices": index_accessor, "mode": 4});
        if let Some(material) = material {
            primitive["material"] = json!(material);
        }
        self.meshes.push(json!({"name": name, "primitives": [primitive]}));
        self.meshes.len() - 1
    }

    /// Adds `shape` as a mesh in `material` and a node placing it (unit scale); returns the
    /// node's index.
    pub fn add_shape(
        &mut self,
        name: &str,
        shape: &ShapeMesh,
        material: usize,
        translation: Vec3,
        rotation: Quat,
    ) -> usize {
        let mesh = self.add_mesh(
            name,
            &shape.positions,
            Some(&shape.normals),
            Some(&shape.uvs),
            &shape.indices,
            Some(material),
        );
        self.add_mesh_node(name, mesh, translation, rotation, Vec3::ONE)
    }

    /// Adds a mesh primitive as raw JSON attributes (for deliberately broken test files).
    pub fn add_raw_mesh(&mut self, name: &str, primitive: Value) -> usize {
        self.meshes.push(json!({"name": name, "primitives": [primitive]}));
        self.meshes.len() - 1
    }

    pub fn add_node(&mut self, node: Value) -> usize {
        self.nodes.push(node);
        self.nodes.len() - 1
    }

    pub fn add_mesh_node(&mut self, name: &str, mesh: usize, translation: Vec3, rotation: Quat, scale: Vec3) -> usize {
        self.add_node(json!({
            "name": name, "mesh": mesh,
            "translation": translation.to_array(), "rotation": rotation.to_array(), "scale": scale.to_array(),
        }))
    }

    pub fn add_light_node(&mut self, name: &str, light: &LightSpec, position: Vec3, forward: Vec3) -> usize {
        let value = match light {
            LightSpec::Point { color, intensity_cd } => {
                json!({"type": "point", "color": color, "intensity": intensity_cd})
            }
            LightSpec::Spot {
                color,
                intensity_cd,
                inner_cone_rad,
                outer_cone_rad,
            } => json!({
                "type": "spot", "color": color, "intensity": intensity_cd,
                "spot": {"innerConeAngle": inner_cone_rad, "outerConeAngle": outer_cone_rad},
            }),
            LightSpec::Directional { color, illuminance_lux } => {
                json!({"type": "directional", "color": color, "intensity": illuminance_lux})
            }
        };
        let mut value = value;
        value["name"] = json!(name);
        self.lights.push(value);
        let rotation = look_rotation(
            forward,
            if forward.normalize().y.abs() > 0.99 {
                Vec3::Z
            } else {
                Vec3::Y
            },
        );
        self.add_node(json!({
            "name": name,
            "translation": position.to_array(), "rotation": rotation.to_array(),
            "extensions": {"KHR_lights_punctual": {"light": self.lights.len() - 1}},
        }))
    }

    /// [`Self::add_light_node`] with a glTF `range`: the distance in metres past which the
    /// light has no effect.
    pub fn add_ranged_light_node(
        &mut self,
        name: &str,
        light: &LightSpec,
        position: Vec3,
        forward: Vec3,
        range_m: f32,
    ) -> usize {
        let node = self.add_light_node(name, light, position, forward);
        if let Some(written) = self.lights.last_mut() {
            written["range"] = json!(range_m);
        }
        node
    }

    pub fn add_camera_node(
        &mut self,
        name: &str,
        yfov_rad: f32,
        znear: f32,
        position: Vec3,
        forward: Vec3,
        up: Vec3,
    ) -> usize {
        self.cameras
            .push(json!({"type": "perspective", "perspective": {"yfov": yfov_rad, "znear": znear}}));
        self.add_node(json!({
            "name": name, "camera": self.cameras.len() - 1,
            "translation": position.to_array(), "rotation": look_rotation(forward, up).to_array(),
        }))
    }

    /// The JSON document; `buffer_uri` names an external .bin (None for .glb).
    pub fn document(&self, buffer_uri: Option<&str>) -> Value {
        let mut buffer = json!({"byteLength": self.padded_bin().len()});
        if let Some(uri) = buffer_uri {
            buffer["uri"] = json!(uri);
        }
        let mut extensions_used = vec![];
        let mut root = json!({
            "asset": {"version": "2.0", "generator": "lightpaint"},
            "scene": 0,
            "scenes": [{"nodes": (0..self.nodes.len()).collect::<Vec<_>>()}],
            "nodes": self.nodes,
            "buffers": [buffer],
            "bufferViews": self.views,
            "accessors": self.accessors,
        });
        for (key, values) in [
            ("meshes", &self.meshes),
            ("materials", &self.materials),
            ("images", &self.images),
            ("textures", &self.textures),
            ("cameras", &self.cameras),
        ] {
            if !values.is_empty() {
                root[key] = json!(values);
            }
        }
        if !self.lights.is_empty() {
            root["extensions"] = json!({"KHR_lights_punctual": {"lights": self.lights}});
            extensions_used.push("KHR_lights_punctual");
        }
        if self.uses_specular {
            extensions_used.push("KHR_materials_specular");
        }
        if !extensions_used.is_empty() {
            root["extensionsUsed"] = json!(extensions_used);
        }
        root
    }

    fn padded_bin(&self) -> Vec<u8> {
        let mut bin = self.bin.clone();
        while !bin.len().is_multiple_of(4) {
            bin.push(0);
        }
        bin
    }

    /// The binary buffer, for a `.gltf` whose buffer is an external `.bin`.
    pub fn bin(&self) -> Vec<u8> {
        self.padded_bin()
    }

    /// A complete `.glb` file.
    pub fn to_glb(&self) -> Vec<u8> {
        glb_bytes(&self.document(None), &self.padded_bin())
    }
}

/// The `.glb` container around a JSON document and its binary chunk (padded as the
/// format requires).
pub fn glb_bytes(document: &Value, bin: &[u8]) -> Vec<u8> {
    let mut json = serde_json::to_vec(document).expect("a serde_json::Value always serialises");
    while !json.len().is_multiple_of(4) {
        json.push(b' ');
    }
    let mut bin = bin.to_vec();
    while !bin.len().is_multiple_of(4) {
        bin.push(0);
    }
    let total = 12 + 8 + json.len() + 8 + bin.len();
    let mut out = Vec::with_capacity(total);
    out.extend_from_slice(b"glTF");
    out.extend_from_slice(&2u32.to_le_bytes());
    out.extend_from_slice(&(total as u32).to_le_bytes());
    out.extend_from_slice(&(json.len() as u32).to_le_bytes());
    out.extend_from_slice(b"JSON");
    out.extend_from_slice(&json);
    out.extend_from_slice(&(bin.len() as u32).to_le_bytes());
    out.extend_from_slice(b"BIN\0");
    out.extend_from_slice(&bin);
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn look_rotation_points_minus_z_forward() {
        let forward = Vec3::new(1.0, -2.0, 0.5).normalize();
        let q = look_rotation(forward, Vec3::Y);
        assert!((q * -Vec3::Z - forward).length() < 1e-5);
        assert!((q * Vec3::Y).y > 0.0);
    }
}
