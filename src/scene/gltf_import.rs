//! glTF 2.0 import (.gltf with external or embedded buffers, and .glb) into a [`Scene`].
//!
//! The file is validated before anything is read from it: buffer views and accessors must
//! lie inside their buffers, attributes must have the types the spec requires, positions
//! must be finite and indices in range. A problem in the file is an error naming the file
//! and the element; an unsupported feature (non-triangle primitives, sparse accessors,
//! orthographic cameras, a texture that cannot be decoded) is a warning and is skipped.

use std::path::Path;

use glam::{Mat3, Mat4, Vec2, Vec3, Vec4};
use gltf::accessor::{DataType, Dimensions};
use gltf::khr_lights_punctual::Kind;

use super::{Camera, Light, LightKind, Material, MeshObject, Scene, SceneError, TextureImage};

/// Largest coordinate accepted, in metres: squared distances must stay far from f32's
/// 3.4e38 limit, and 1e7 m is already larger than the Earth.
pub const MAX_COORDINATE_M: f32 = 1.0e7;

/// Loads a `.gltf` or `.glb` file, showing its default scene.
pub fn load_gltf(path: &Path) -> Result<Scene, SceneError> {
    load_gltf_scene(path, None)
}

/// Loads a `.gltf` or `.glb` file, showing its scene number `choice` (None: the file's
/// default scene, or its first when it names none).
pub fn load_gltf_scene(path: &Path, choice: Option<usize>) -> Result<Scene, SceneError> {
    let bytes = read_file(path)?;
    parse_gltf_scene(path, &bytes, choice)
}

/// Parses the bytes of a `.gltf` or `.glb` file, showing its default scene; `path` names it
/// in messages and locates external buffers and images (relative to its directory).
pub fn parse_gltf(path: &Path, bytes: &[u8]) -> Result<Scene, SceneError> {
    parse_gltf_scene(path, bytes, None)
}

/// [`parse_gltf`] showing scene number `choice` of the file (None: its default scene).
pub fn parse_gltf_scene(path: &Path, bytes: &[u8], choice: Option<usize>) -> Result<Scene, SceneError> {
    crate::panic_guard::catch_panic(|| parse_gltf_unguarded(path, bytes, choice)).unwrap_or_else(|message| {
        Err(SceneError::Malformed {
            path: path.to_path_buf(),
            reason: format!("its structure is inconsistent (the glTF reader failed: {message})"),
        })
    })
}

fn parse_gltf_unguarded(path: &Path, bytes: &[u8], choice: Option<usize>) -> Result<Scene, SceneError> {
    if bytes.is_empty() {
        return Err(SceneError::Malformed {
            path: path.to_path_buf(),
            reason: "the file is empty".into(),
        });
    }
    let malformed = |e: gltf::Error| SceneError::Malformed {
        path: path.to_path_buf(),
        reason: describe_gltf_error(e),
    };
    let gltf = gltf::Gltf::from_slice(bytes).map_err(malformed)?;
    let base = path.parent().unwrap_or(Path::new("."));
    let buffers = gltf::import_buffers(&gltf.document, Some(base), gltf.blob.clone())
        .map_err(|e| SceneError::invalid(path, format!("cannot load buffer data: {}", describe_gltf_error(e))))?;
    let importer = Importer {
        path,
        base,
        document: &gltf.document,
        buffers: &buffers,
        scene: Scene {
            source: Some(path.to_path_buf()),
            source_hash: Some(blake3::hash(bytes).to_hex().to_string()),
            ..Scene::default()
        },
    };
    importer.run(choice)
}

fn read_file(path: &Path) -> Result<Vec<u8>, SceneError> {
    let extension = path.extension().and_then(|e| e.to_str()).map(str::to_ascii_lowercase);
    if !path.exists() {
        return Err(SceneError::NotFound {
            path: path.to_path_buf(),
        });
    }
    if !matches!(extension.as_deref(), Some("gltf" | "glb")) {
        return Err(SceneError::UnsupportedExtension {
            path: path.to_path_buf(),
        });
    }
    std::fs::read(path).map_err(|source| SceneError::Io {
        path: path.to_path_buf(),
        source,
    })
}

/// The gltf crate's messages for a truncated .glb are terse; say what happened.
fn describe_gltf_error(error: gltf::Error) -> String {
    match error {
        gltf::Error::Binary(e) => format!("broken binary glTF container (truncated or corrupt .glb?): {e:?}"),
        gltf::Error::BufferLength {
            buffer,
            expected,
            actual,
        } => format!("buffer {buffer} is truncated: {actual} of {expected} bytes present"),
        other => other.to_string(),
    }
}

struct Importer<'a> {
    path: &'a Path,
    base: &'a Path,
    document: &'a gltf::Document,
    buffers: &'a [gltf::buffer::Data],
    scene: Scene,
}

impl Importer<'_> {
    fn run(mut self, choice: Option<usize>) -> Result<Scene, SceneError> {
        self.check_buffer_views()?;
        let document = self.document;
        let count = document.scenes().len();
        let gltf_scene = match choice {
            Some(index) => Some(document.scenes().nth(index).ok_or_else(|| {
                self.invalid(format!(
                    "scene {index} was asked for, but the file has {count} scene(s) (numbered from 0)"
                ))
            })?),
            None => document.default_scene().or_else(|| document.scenes().next()),
        };
        self.scene.gltf_scenes = document.scenes().map(|s| s.name().unwrap_or("").to_string()).collect();
        self.scene.gltf_scene = gltf_scene.as_ref().map(gltf::Scene::index);
        self.import_materials();
        let default_material = self.scene.materials.len();
        self.scene.materials.push(Material::default());

        match gltf_scene {
            Some(gltf_scene) => {
                if count > 1 && choice.is_none() {
                    let name = gltf_scene.name().unwrap_or("unnamed");
                    self.warn(format!(
                        "the file has {count} scenes; showing scene {} ('{name}'; another can be chosen)",
                        gltf_scene.index()
                    ));
                }
                for node in gltf_scene.nodes() {
                    self.visit(node, Mat4::IDENTITY, default_material, 0)?;
                }
            }
            None => self.warn("the file has no scene; nothing to show".to_string()),
        }
        Ok(self.scene)
    }

    fn warn(&mut self, message: String) {
        self.scene.warnings.push(message);
    }

    fn invalid(&self, what: String) -> SceneError {
        SceneError::invalid(self.path, what)
    }

    fn check_buffer_views(&self) -> Result<(), SceneError> {
        for view in self.document.views() {
            let buffer_len = self.buffers[view.buffer().index()].len();
            let end = view.offset().checked_add(view.length());
            if end.is_none_or(|end| end > buffer_len) {
                return Err(self.invalid(format!(
                    "bufferView {} (bytes {}..{}) lies outside buffer {} ({buffer_len} bytes)",
                    view.index(),
                    view.offset(),
                    view.offset().saturating_add(view.length()),
                    view.buffer().index()
                )));
            }
        }
        Ok(())
    }

    /// Checks an accessor's type and that every element lies inside its buffer view.
    fn check_accessor(
        &self,
        accessor: &gltf::Accessor,
        role: &str,
        dimensions: &[Dimensions],
        data_types: &[DataType],
    ) -> Result<(), SceneError> {
        let index = accessor.index();
        if !dimensions.contains(&accessor.dimensions()) || !data_types.contains(&accessor.data_type()) {
            return Err(self.invalid(format!(
                "accessor {index} ({role}) has type {:?} {:?}, which glTF does not allow there",
                accessor.dimensions(),
                accessor.data_type()
            )));
        }
        if accessor.sparse().is_some() {
            return Err(self.invalid(format!(
                "accessor {index} ({role}) is sparse, which lightpaint does not support"
            )));
        }
        let Some(view) = accessor.view() else {
            return Err(self.invalid(format!("accessor {index} ({role}) has no bufferView")));
        };
        if accessor.count() == 0 {
            return Ok(());
        }
        let element = accessor.size();
        let stride = view.stride().unwrap_or(element);
        let needed = (accessor.count() - 1)
            .checked_mul(stride)
            .and_then(|n| n.checked_add(element))
            .and_then(|n| n.checked_add(accessor.offset()));
        match needed {
            Some(needed) if needed <= view.length() && stride >= element => Ok(()),
            _ => Err(self.invalid(format!(
                "accessor {index} ({role}) is out of range: {} elements of {element} bytes \
                 from offset {} do not fit bufferView {} ({} bytes)",
                accessor.count(),
                accessor.offset(),
                view.index(),
                view.length()
            ))),
        }
    }

    fn import_materials(&mut self) {
        let document = self.document;
        for material in document.materials() {
            let pbr = material.pbr_metallic_roughness();
            let base_color_texture = pbr
                .base_color_texture()
                .and_then(|info| self.import_texture(info.texture()));
            let emissive_strength = material.emissive_strength().unwrap_or(1.0);
            let converted = Material {
                name: material.name().unwrap_or("unnamed").to_string(),
                base_color: Vec4::from(pbr.base_color_factor()),
                base_color_texture,
                metallic: pbr.metallic_factor().clamp(0.0, 1.0),
                roughness: pbr.roughness_factor().clamp(0.0, 1.0),
                specular: material.specular().map_or(1.0, |s| s.specular_factor().clamp(0.0, 1.0)),
                emissive: Vec3::from(material.emissive_factor()) * emissive_strength,
                double_sided: material.double_sided(),
            };
            if !converted.base_color.is_finite() || !converted.emissive.is_finite() {
                let name = converted.name.clone();
                self.warn(format!("material '{name}' has non-finite colours; using the default"));
                self.scene.materials.push(Material {
                    name,
                    double_sided: material.double_sided(),
                    ..Material::default()
                });
            } else {
                self.scene.materials.push(converted);
            }
        }
    }

    /// Decodes a texture's image into sRGB RGBA8; a missing or undecodable image is a
    /// warning and the material falls back to its colour factor.
    fn import_texture(&mut self, texture: gltf::Texture) -> Option<usize> {
        let image = texture.source();
        let name = image
            .name()
            .map(str::to_string)
            .unwrap_or_else(|| match image.source() {
                gltf::image::Source::Uri { uri, .. } if !uri.starts_with("data:") => uri.to_string(),
                _ => format!("image {}", image.index()),
            });
        match gltf::image::Data::from_source(image.source(), Some(self.base), self.buffers) {
            Ok(data) => match to_rgba8(&data) {
                Some(rgba8) => {
                    self.scene.textures.push(TextureImage {
                        name,
                        width: data.width,
                        height: data.height,
                        rgba8,
                    });
                    Some(self.scene.textures.len() - 1)
                }
                None => {
                    self.warn(format!(
                        "texture '{name}': pixel format {:?} is not supported; ignored",
                        data.format
                    ));
                    None
                }
            },
            Err(e) => {
                self.warn(format!(
                    "texture '{name}' cannot be loaded ({e}); using the colour factor"
                ));
                None
            }
        }
    }

    fn visit(
        &mut self,
        node: gltf::Node,
        parent: Mat4,
        default_material: usize,
        depth: usize,
    ) -> Result<(), SceneError> {
        // glTF forbids cycles; the bound turns a malicious file into an error, not a stack overflow.
        if depth > 256 {
            return Err(self.invalid(format!("node {} is nested more than 256 levels deep", node.index())));
        }
        let world = parent * Mat4::from_cols_array_2d(&node.transform().matrix());
        if !world.is_finite() {
            return Err(self.invalid(format!("node {} has a non-finite transform", node.index())));
        }
        if let Some(mesh) = node.mesh() {
            for primitive in mesh.primitives() {
                self.import_primitive(&node, &mesh, &primitive, world, default_material)?;
            }
        }
        if let Some(light) = node.light() {
            self.import_light(&node, &light, world)?;
        }
        if let Some(camera) = node.camera()
            && self.scene.camera.is_none()
        {
            self.import_camera(&camera, world);
        }
        for child in node.children() {
            self.visit(child, world, default_material, depth + 1)?;
        }
        Ok(())
    }

    fn import_primitive(
        &mut self,
        node: &gltf::Node,
        mesh: &gltf::Mesh,
        primitive: &gltf::Primitive,
        world: Mat4,
        default_material: usize,
    ) -> Result<(), SceneError> {
        let mesh_name = mesh
            .name()
            .map(str::to_string)
            .unwrap_or_else(|| format!("mesh {}", mesh.index()));
        let label = format!("mesh '{mesh_name}' primitive {}", primitive.index());
        if primitive.mode() != gltf::mesh::Mode::Triangles {
            self.warn(format!(
                "{label}: mode {:?} is not supported (triangles only); skipped",
                primitive.mode()
            ));
            return Ok(());
        }
        let Some(position_accessor) = primitive.get(&gltf::Semantic::Positions) else {
            self.warn(format!("{label}: has no POSITION attribute; skipped"));
            return Ok(());
        };
        self.check_accessor(
            &position_accessor,
            &format!("{label} POSITION"),
            &[Dimensions::Vec3],
            &[DataType::F32],
        )?;
        let normal_accessor = primitive.get(&gltf::Semantic::Normals);
        if let Some(accessor) = &normal_accessor {
            self.check_accessor(
                accessor,
                &format!("{label} NORMAL"),
                &[Dimensions::Vec3],
                &[DataType::F32],
            )?;
        }
        let uv_accessor = primitive.get(&gltf::Semantic::TexCoords(0));
        if let Some(accessor) = &uv_accessor {
            self.check_accessor(
                accessor,
                &format!("{label} TEXCOORD_0"),
                &[Dimensions::Vec2],
                &[DataType::F32, DataType::U8, DataType::U16],
            )?;
        }
        if let Some(accessor) = primitive.indices() {
            self.check_accessor(
                &accessor,
                &format!("{label} indices"),
                &[Dimensions::Scalar],
                &[DataType::U8, DataType::U16, DataType::U32],
            )?;
        }
        for accessor in [Some(&position_accessor), normal_accessor.as_ref(), uv_accessor.as_ref()]
            .into_iter()
            .flatten()
        {
            if accessor.count() != position_accessor.count() {
                return Err(self.invalid(format!(
                    "{label}: attribute accessor {} has {} elements but POSITION has {}",
                    accessor.index(),
                    accessor.count(),
                    position_accessor.count()
                )));
            }
        }

        let buffers = self.buffers;
        let reader = primitive.reader(|buffer| buffers.get(buffer.index()).map(|data| &data.0[..]));
        let local_positions: Vec<Vec3> = reader
            .read_positions()
            .map(|iter| iter.map(Vec3::from).collect())
            .unwrap_or_default();
        if let Some(bad) = local_positions.iter().position(|p| !p.is_finite()) {
            return Err(self.invalid(format!(
                "{label}: position {bad} is not finite ({})",
                local_positions[bad]
            )));
        }
        let vertex_count = local_positions.len();
        let indices: Vec<u32> = match reader.read_indices() {
            Some(indices) => indices.into_u32().collect(),
            None => (0..vertex_count as u32).collect(),
        };
        if let Some(&bad) = indices.iter().find(|&&i| i as usize >= vertex_count) {
            return Err(self.invalid(format!(
                "{label}: index {bad} is out of range ({vertex_count} vertices)"
            )));
        }
        let uvs: Vec<Vec2> = reader
            .read_tex_coords(0)
            .map(|uvs| uvs.into_f32().map(Vec2::from).collect())
            .unwrap_or_else(|| vec![Vec2::ZERO; vertex_count]);

        let positions: Vec<Vec3> = local_positions.iter().map(|&p| world.transform_point3(p)).collect();
        if let Some(bad) = positions.iter().position(|p| !p.is_finite()) {
            return Err(self.invalid(format!(
                "{label}: position {bad} overflows once transformed by node {}",
                node.index()
            )));
        }
        if let Some(bad) = positions.iter().position(|p| p.abs().max_element() > MAX_COORDINATE_M) {
            return Err(self.invalid(format!(
                "{label}: position {bad} ({}) lies beyond ±{MAX_COORDINATE_M:e} m, which lightpaint cannot shade in f32",
                positions[bad]
            )));
        }
        let mut triangles: Vec<u32> = Vec::with_capacity(indices.len());
        let mirrored = world.determinant() < 0.0;
        let mut degenerate = 0usize;
        for tri in indices.chunks_exact(3) {
            let [a, b, c] = [tri[0], tri[1], tri[2]];
            let area2 = (positions[b as usize] - positions[a as usize])
                .cross(positions[c as usize] - positions[a as usize])
                .length();
            let has_area = area2 > 0.0; // false for NaN too
            if !has_area {
                degenerate += 1;
                continue;
            }
            // A mirroring transform turns counter-clockwise faces clockwise: restore them.
            triangles.extend(if mirrored { [a, c, b] } else { [a, b, c] });
        }
        if degenerate > 0 {
            self.warn(format!("{label}: {degenerate} degenerate triangle(s) dropped"));
        }

        let normal_matrix = Mat3::from_mat4(world).inverse().transpose();
        let file_normals: Option<Vec<Vec3>> = reader.read_normals().map(|normals| {
            normals
                .map(|n| (normal_matrix * Vec3::from(n)).normalize_or_zero())
                .collect()
        });
        let normals = match file_normals {
            Some(normals) if normals.iter().all(|n| n.is_finite() && *n != Vec3::ZERO) => normals,
            Some(_) => {
                self.warn(format!(
                    "{label}: some normals are zero or not finite; normals regenerated"
                ));
                MeshObject::generate_normals(&positions, &triangles)
            }
            None => MeshObject::generate_normals(&positions, &triangles),
        };

        let name = match (node.name(), mesh.primitives().len()) {
            (Some(node_name), 1) => node_name.to_string(),
            (Some(node_name), _) => format!("{node_name}.{}", primitive.index()),
            (None, 1) => mesh_name,
            (None, _) => format!("{mesh_name}.{}", primitive.index()),
        };
        self.scene.objects.push(MeshObject {
            name,
            positions,
            normals,
            uvs,
            indices: triangles,
            material: primitive.material().index().unwrap_or(default_material),
        });
        Ok(())
    }

    fn import_light(
        &mut self,
        node: &gltf::Node,
        light: &gltf::khr_lights_punctual::Light,
        world: Mat4,
    ) -> Result<(), SceneError> {
        let name = light
            .name()
            .or(node.name())
            .map(str::to_string)
            .unwrap_or_else(|| format!("light {}", light.index()));
        let kind = match light.kind() {
            Kind::Point => LightKind::Point,
            Kind::Directional => LightKind::Directional,
            Kind::Spot {
                inner_cone_angle,
                outer_cone_angle,
            } => LightKind::Spot {
                inner_cone_rad: inner_cone_angle,
                outer_cone_rad: outer_cone_angle,
            },
        };
        let mut direction = world.transform_vector3(-Vec3::Z).normalize_or_zero();
        if kind == LightKind::Point && direction == Vec3::ZERO {
            // A point light has no direction; a collapsed node transform does not matter.
            direction = Vec3::NEG_Z;
        }
        let imported = Light {
            name,
            kind,
            color: Vec3::from(light.color()),
            intensity: light.intensity(),
            position: world.transform_point3(Vec3::ZERO),
            direction,
            range: light.range(),
            locked: false,
        };
        if let Some((field, message)) = imported.problems().into_iter().next() {
            return Err(self.invalid(format!("light '{}': {field} {message}", imported.name)));
        }
        self.scene.lights.push(imported);
        Ok(())
    }

    fn import_camera(&mut self, camera: &gltf::Camera, world: Mat4) {
        match camera.projection() {
            gltf::camera::Projection::Perspective(p) => {
                let forward = world.transform_vector3(-Vec3::Z).normalize_or_zero();
                let up = world.transform_vector3(Vec3::Y).normalize_or_zero();
                let yfov_ok = p.yfov() > 0.0 && p.yfov() < std::f32::consts::PI;
                let znear_ok = p.znear() > 0.0;
                if forward == Vec3::ZERO || up == Vec3::ZERO || !yfov_ok || !znear_ok {
                    self.warn("the camera is degenerate; framing the scene instead".to_string());
                    return;
                }
                self.scene.camera = Some(Camera {
                    position: world.transform_point3(Vec3::ZERO),
                    forward,
                    up,
                    yfov_rad: p.yfov(),
                    znear: p.znear(),
                    zfar: p.zfar().filter(|&f| f > p.znear()),
                });
            }
            gltf::camera::Projection::Orthographic(_) => {
                self.warn("orthographic cameras are not supported; framing the scene instead".to_string());
            }
        }
    }
}

fn to_rgba8(data: &gltf::image::Data) -> Option<Vec<u8>> {
    use gltf::image::Format;
    let pixels = &data.pixels;
    let rgba = match data.format {
        Format::R8G8B8A8 => pixels.clone(),
        Format::R8G8B8 => pixels.chunks_exact(3).flat_map(|p| [p[0], p[1], p[2], 255]).collect(),
        Format::R8 => pixels.iter().flat_map(|&v| [v, v, v, 255]).collect(),
        Format::R8G8 => pixels.chunks_exact(2).flat_map(|p| [p[0], p[0], p[0], p[1]]).collect(),
        // 16-bit images keep their high byte.
        Format::R16G16B16A16 => pixels.chunks_exact(8).flat_map(|p| [p[1], p[3], p[5], p[7]]).collect(),
        Format::R16G16B16 => pixels.chunks_exact(6).flat_map(|p| [p[1], p[3], p[5], 255]).collect(),
        _ => return None,
    };
    (rgba.len() == (data.width as usize) * (data.height as usize) * 4).then_some(rgba)
}
