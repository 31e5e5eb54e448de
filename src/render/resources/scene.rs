//! A [`Scene`] uploaded to the GPU: vertex and index buffers per object, one bind group
//! per material (uniform, mipmapped base colour texture, sampler), and the frame uniform,
//! light storage buffer and baked indirect light shared by every draw.

use std::ops::Range;

use rayon::prelude::*;
use wgpu::util::DeviceExt;

use super::layouts::SceneLayouts;
use super::light_buffers::LightBuffers;
use super::texture::upload_texture;
use crate::render::descriptors::slot_entries;
use crate::scene::detail_levels::{DetailLevels, MAX_SHADOW_TEXEL_SHARE, VertexValues};
use crate::scene::{Aabb, Camera, Environment, Frustum, Scene, TextureImage, encloses_outward};
use crate::shading::BakedIndirect;
use crate::shading::gpu_types::{GpuFrame, GpuLight, GpuMaterial, GpuVertex, environment_irradiance, srgb8_word};
use crate::shading::light_grid::{LightGrid, grid_worth_it};
use crate::shading::shadow_maps::ShadowViews;
use crate::shading::vertex_lighting::MeshFineness;
use crate::shading::wgsl::slots;

pub struct GpuObject {
    /// [`GpuVertex`]es, also readable as storage (the per-vertex shadow pass reads them).
    pub vertex_buffer: wgpu::Buffer,
    pub vertex_count: u32,
    /// Every level of detail's triangle list, one after another (`detail_levels`); the
    /// mesh itself, which the shadow maps draw, first.
    pub index_buffer: wgpu::Buffer,
    /// The mesh's own indices: `0..index_count` of `index_buffer`.
    pub index_count: u32,
    /// The levels of detail (`scene::detail_levels`): their ranges of `index_buffer`,
    /// errors and longest edges.
    pub detail_levels: DetailLevels,
    /// The indices the camera's passes draw: the level [`GpuScene::write_frame`] chose.
    pub drawn_indices: Range<u32>,
    pub material: usize,
    /// Whether its material samples a base colour texture.
    pub textured: bool,
    /// Whether the baked indirect light gives some vertex of it light (otherwise the
    /// surface buffer draws it, where it is untextured, without that varying:
    /// vs_plain_surface in low_resolution.wgsl).
    pub baked_light: bool,
    /// Where this object's vertices start in the baked indirect light buffer.
    pub first_vertex: u32,
    /// Index of the object in [`Scene::objects`] (objects without triangles are not uploaded).
    pub source: usize,
    /// Hidden in the viewport: not drawn (see [`GpuScene::set_hidden`]).
    pub hidden: bool,
    /// World-space bounds of its vertices.
    pub bounds: Aabb,
    /// Whether the last camera written ([`GpuScene::write_frame`]) may see it: the
    /// camera's passes draw only such objects (the shadow maps draw every one shown).
    pub in_view: bool,
    /// How finely the mesh is tessellated, and its material's glossy exponent: whether
    /// per-vertex shading may light it at its vertices (`shading::vertex_lighting`).
    pub fineness: MeshFineness,
    pub phong_exponent: f32,
    /// Whether its mesh encloses volume with its faces turned outward
    /// ([`crate::scene::encloses_outward`]), and so whether the last camera written
    /// (outside its bounds and their reach of the near plane) cannot see a back face of
    /// it: the passes seen from the camera may cull them.
    pub encloses_outward: bool,
    pub back_faces_hidden: bool,
}

impl GpuObject {
    /// Drawn by the passes seen from the camera: shown and within its frustum.
    pub fn drawn_in_view(&self) -> bool {
        !self.hidden && self.in_view
    }
}

pub struct GpuScene {
    pub objects: Vec<GpuObject>,
    pub material_bind_groups: Vec<wgpu::BindGroup>,
    frame_buffer: wgpu::Buffer,
    lights: LightBuffers,
    /// Baked indirect irradiance, linear RGB per vertex of every object (zeros: none).
    indirect_buffer: wgpu::Buffer,
    pub frame_bind_group: wgpu::BindGroup,
    pub light_count: usize,
    /// Lights from this index on (in the buffer's order) take the exact shadow path.
    /// The first light with a shadow map and the first on the exact path, in the order
    /// uploaded.
    first_light_on: [usize; 2],
    environment_irradiance: [[f32; 4]; 9],
    /// The lights on the SH path as uploaded (the first of the ordered lights), which the
    /// soft layer of reduced shading reads.
    harmonic_lights: Vec<GpuLight>,
    /// The lights on the shadow-map path as uploaded, with their intensities zeroed: what
    /// their visibility depends on (`mapped_light_geometry`).
    mapped_light_geometry: Vec<GpuLight>,
    /// The scene's bounds, which the lights' grid covers.
    bounds: Aabb,
    /// The lights' grid of the uploaded lights (`shading::light_grid`), and those lights
    /// without their intensities, what it was built from (a stroke leaves it as it is;
    /// None before the first upload).
    light_grid: LightGrid,
    light_grid_key: Option<Vec<GpuLight>>,
    /// Whether objects outside the camera's frustum are left out of its passes (on unless
    /// a test compares frames without it: [`GpuScene::set_view_culling`]).
    view_culling: bool,
    /// Whether the camera's passes may cull the back faces of closed meshes (on unless a
    /// test compares frames without it: [`GpuScene::set_back_face_culling`]).
    back_face_culling: bool,
    /// Whether the camera's passes draw each object's level of detail for its distance
    /// (on unless a frame is compared with the meshes drawn as they are:
    /// [`GpuScene::set_detail_levels`]).
    detail_levels: bool,
    /// Changes whenever what the surfaces pass draws may change (a new upload, objects
    /// hidden or shown, new baked indirect light); unique among every scene uploaded.
    surfaces_generation: u64,
    /// Changes whenever a frame draws some object at another level of detail than the
    /// frame before (unique likewise): with the camera still, a light brought near an
    /// object shrinks its maps' texels and asks for a finer level.
    levels_generation: u64,
}

/// The lighting of the SH path: see [`GpuScene::harmonic_lighting`].
#[derive(Debug, Clone, PartialEq)]
pub struct HarmonicLighting {
    pub lights: Vec<GpuLight>,
    pub environment_irradiance: [[f32; 4]; 9],
}

/// How the objects drawn from the camera are chosen among their levels of detail
/// ([`GpuScene::write_frame`]).
#[derive(Clone, Copy)]
pub enum Detail<'a> {
    /// The meshes as they are: per-vertex shading and the heat map, whose values live at
    /// the vertices, and the surfaces the reference starts its paths from (its rays meet
    /// the meshes themselves).
    Whole,
    /// Each the coarsest level within a fifth of a pixel and within the finest texel
    /// these shadow-map views lay on it (`scene::detail_levels`).
    Levels(&'a ShadowViews),
}

/// A number no earlier call returned: the generations of every [`GpuScene`] differ.
fn next_surfaces_generation() -> u64 {
    static NEXT: std::sync::atomic::AtomicU64 = std::sync::atomic::AtomicU64::new(0);
    NEXT.fetch_add(1, std::sync::atomic::Ordering::Relaxed)
}

impl GpuScene {
    pub fn upload(device: &wgpu::Device, queue: &wgpu::Queue, layouts: &SceneLayouts, scene: &Scene) -> GpuScene {
        let mut first_vertex = 0u32;
        // The simplifications of large meshes take a while: one object per thread.
        let detail_levels: Vec<DetailLevels> = scene
            .objects
            .par_iter()
            .filter(|o| !o.indices.is_empty())
            .map(|o| DetailLevels::of_mesh(&o.positions, &o.indices))
            .collect();
        let objects: Vec<GpuObject> = scene
            .objects
            .iter()
            .enumerate()
            .filter(|(_, o)| !o.indices.is_empty())
            .zip(detail_levels)
            .map(|((source, object), detail_levels)| {
                let vertices: Vec<GpuVertex> = (0..object.positions.len())
                    .map(|i| GpuVertex {
                        position: object.positions[i].to_array(),
                        normal: object.normals[i].to_array(),
                        uv: object.uvs[i].to_array(),
                    })
                    .collect();
                let material = object.material.min(scene.materials.len().saturating_sub(1));
                let object_first_vertex = first_vertex;
                first_vertex += vertices.len() as u32;
                GpuObject {
                    vertex_buffer: device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
                        label: Some(&object.name),
                        contents: bytemuck::cast_slice(&vertices),
                        usage: wgpu::BufferUsages::VERTEX | wgpu::BufferUsages::STORAGE,
                    }),
                    index_buffer: device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
                        label: Some(&object.name),
                        contents: bytemuck::cast_slice(&detail_levels.indices),
                        usage: wgpu::BufferUsages::INDEX,
                    }),
                    vertex_count: vertices.len() as u32,
                    index_count: object.indices.len() as u32,
                    drawn_indices: 0..object.indices.len() as u32,
                    detail_levels,
                    material,
                    textured: scene
                        .materials
                        .get(material)
                        .and_then(|m| m.base_color_texture)
                        .is_some_and(|t| t < scene.textures.len()),
                    first_vertex: object_first_vertex,
                    baked_light: false,
                    source,
                    hidden: false,
                    bounds: object.bounds(),
                    in_view: true,
                    fineness: MeshFineness::of(&object.positions, &object.normals, &object.indices),
                    phong_exponent: scene.materials.get(material).map_or(0.0, |m| m.phong_exponent()),
                    encloses_outward: encloses_outward(&object.positions, &object.indices),
                    back_faces_hidden: false,
                }
            })
            .collect();
        let indirect_buffer = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("baked indirect light"),
            // Never empty: a binding needs a buffer of some size.
            size: 12 * first_vertex.max(1) as u64,
            usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });

        let textures: Vec<wgpu::TextureView> = scene
            .textures
            .iter()
            .map(|t| upload_texture(device, queue, t))
            .collect();
        let white = upload_texture(
            device,
            queue,
            &TextureImage {
                name: "white".into(),
                width: 1,
                height: 1,
                rgba8: vec![255; 4],
            },
        );
        let material_bind_groups = scene
            .materials
            .iter()
            .map(|material| {
                let texture = material.base_color_texture.and_then(|i| textures.get(i));
                let uniform = GpuMaterial::new(material, texture.is_some());
                let buffer = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
                    label: Some(&material.name),
                    contents: bytemuck::bytes_of(&uniform),
                    usage: wgpu::BufferUsages::UNIFORM,
                });
                device.create_bind_group(&wgpu::BindGroupDescriptor {
                    label: Some(&material.name),
                    layout: &layouts.material,
                    entries: &slot_entries([
                        (slots::MATERIAL, buffer.as_entire_binding()),
                        (
                            slots::BASE_COLOR_TEXTURE,
                            wgpu::BindingResource::TextureView(texture.unwrap_or(&white)),
                        ),
                        (
                            slots::BASE_COLOR_SAMPLER,
                            wgpu::BindingResource::Sampler(&layouts.sampler),
                        ),
                    ]),
                })
            })
            .collect();

        let frame_buffer = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("frame"),
            size: std::mem::size_of::<GpuFrame>() as u64,
            usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        let lights = LightBuffers::new(device, scene.lights.len());
        let frame_bind_group = frame_bind_group(device, layouts, &frame_buffer, &lights, &indirect_buffer);
        let mut gpu_scene = GpuScene {
            objects,
            material_bind_groups,
            frame_buffer,
            lights,
            indirect_buffer,
            frame_bind_group,
            light_count: 0,
            first_light_on: [0, 0],
            environment_irradiance: environment_irradiance(scene.environment.as_ref()),
            view_culling: true,
            back_face_culling: true,
            detail_levels: true,
            surfaces_generation: next_surfaces_generation(),
            levels_generation: next_surfaces_generation(),
            harmonic_lights: Vec::new(),
            mapped_light_geometry: Vec::new(),
            bounds: scene.bounds(),
            light_grid: LightGrid::every_light(&[], [0, 0]),
            light_grid_key: None,
        };
        let lights: Vec<GpuLight> = scene.lights.iter().map(GpuLight::new).collect();
        gpu_scene.update_lights(device, queue, layouts, &lights);
        gpu_scene
    }

    /// A frame bind group like [`Self::frame_bind_group`] whose per-vertex binding (2)
    /// reads `per_vertex` instead of the baked indirect light: 3 floats per vertex of
    /// every uploaded object, in [`Self::objects`]' order.
    pub fn frame_bind_group_with(
        &self,
        device: &wgpu::Device,
        layouts: &SceneLayouts,
        per_vertex: &wgpu::Buffer,
    ) -> wgpu::BindGroup {
        frame_bind_group(device, layouts, &self.frame_buffer, &self.lights, per_vertex)
    }

    /// Vertices of every uploaded object together.
    pub fn vertex_total(&self) -> u32 {
        self.objects.iter().map(|o| o.vertex_count).sum()
    }

    /// Hides the objects whose [`Scene::objects`] index `hidden` holds (and shows the rest).
    pub fn set_hidden(&mut self, hidden: &std::collections::BTreeSet<usize>) {
        for object in &mut self.objects {
            object.hidden = hidden.contains(&object.source);
        }
        self.surfaces_generation = next_surfaces_generation();
    }

    /// What the surfaces pass draws, as a number: equal numbers from one scene mean the
    /// same objects, materials and per-vertex emission (the camera aside).
    pub fn surfaces_generation(&self) -> u64 {
        self.surfaces_generation
    }

    /// Rewrites the light buffer, growing it when there are more lights than it holds;
    /// lights come ordered by shadow path
    /// ([`crate::shading::gpu_types::order_by_shadow_path`]).
    pub fn update_lights(
        &mut self,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        layouts: &SceneLayouts,
        lights: &[GpuLight],
    ) {
        if lights.len() > self.lights.every_capacity {
            self.lights = LightBuffers::new(device, lights.len().next_power_of_two());
            self.frame_bind_group =
                frame_bind_group(device, layouts, &self.frame_buffer, &self.lights, &self.indirect_buffer);
        }
        let (ordered, first_light_on) = crate::shading::gpu_types::order_by_shadow_path(lights);
        self.lights.write(queue, &ordered);
        // The lights without their intensities: what the grid and the mapped lights'
        // visibility depend on.
        let geometry: Vec<GpuLight> = ordered.iter().map(GpuLight::geometry).collect();
        let mapped = first_light_on[0].min(ordered.len())..first_light_on[1].min(ordered.len());
        self.mapped_light_geometry = geometry[mapped].to_vec();
        if self.light_grid_key.as_ref() != Some(&geometry) {
            // Written whether or not this frame's pipelines walk it: a pipeline compiled
            // for earlier lights may draw a frame or two while the next one compiles (a
            // grid of no box, listing every light, for lights not worth one).
            self.light_grid = if grid_worth_it(&ordered) {
                LightGrid::build(&ordered, first_light_on, self.bounds)
            } else {
                LightGrid::every_light(&ordered, first_light_on)
            };
            if self.lights.write_grid(device, queue, &self.light_grid.words) {
                self.frame_bind_group =
                    frame_bind_group(device, layouts, &self.frame_buffer, &self.lights, &self.indirect_buffer);
            }
            self.light_grid_key = Some(geometry);
        }
        self.light_count = ordered.len();
        self.first_light_on = first_light_on;
        self.harmonic_lights = ordered[..first_light_on[0].min(ordered.len())].to_vec();
    }

    /// The lights on the shadow-map path as uploaded, in order, without their intensity
    /// and colour: two frames with equal geometry (and equal maps and surfaces) see the
    /// same visibility of those lights at every pixel, whatever their intensities.
    pub fn mapped_light_geometry(&self) -> &[GpuLight] {
        &self.mapped_light_geometry
    }

    /// What the light of soft shadows reads of the lighting besides the blockers and the
    /// settings: the lights on the SH path and the environment's irradiance.
    pub fn harmonic_lighting(&self) -> HarmonicLighting {
        HarmonicLighting {
            lights: self.harmonic_lights.clone(),
            environment_irradiance: self.environment_irradiance,
        }
    }

    /// Writes the per-frame constants for `camera` drawn into `size_px` (width, height),
    /// marks the objects its frustum may see (the rest are not drawn from it) and chooses
    /// the level of detail each is drawn at from it (`detail`).
    pub fn write_frame(
        &mut self,
        queue: &wgpu::Queue,
        camera: &Camera,
        size_px: [u32; 2],
        (exposure_ev, background_linear): (f32, [f64; 3]),
        detail: Detail<'_>,
    ) {
        let mut frame = GpuFrame::new(
            camera,
            size_px,
            exposure_ev,
            self.light_count,
            self.first_light_on,
            self.environment_irradiance,
        );
        frame.background_srgb8 = srgb8_word(background_linear);
        let grid = &self.light_grid;
        frame.light_grid_origin = grid.origin.extend(1.0 / grid.box_side_m).to_array();
        frame.light_grid_boxes = grid.boxes.extend(grid.box_count() as u32).to_array();
        queue.write_buffer(&self.frame_buffer, 0, bytemuck::bytes_of(&frame));
        let aspect = size_px[0].max(1) as f32 / size_px[1].max(1) as f32;
        let frustum = Frustum::of_camera(camera, aspect);
        let near_reach_m = camera.near_plane_reach_m(aspect);
        // Metres a pixel spans per metre of distance, at the image's centre.
        let pixel_m_per_m = 2.0 * (0.5 * camera.yfov_rad).tan() / size_px[1].max(1) as f32;
        let mut level_changed = false;
        for object in &mut self.objects {
            object.in_view = !self.view_culling || frustum.may_see(&object.bounds);
            // Per-vertex frames, which cull them, draw the meshes as they are (level 0).
            object.back_faces_hidden = self.back_face_culling
                && object.encloses_outward
                && object.bounds.distance_to(camera.position) > near_reach_m;
            let level = match detail {
                Detail::Levels(shadow_views) if self.detail_levels => {
                    let max_error_m = MAX_SHADOW_TEXEL_SHARE * shadow_views.finest_texel_m(&object.bounds);
                    let values = VertexValues::of(
                        object.fineness.widest_normal_turn_rad,
                        object.textured,
                        object.baked_light,
                    );
                    object.detail_levels.level_for(
                        object.bounds.distance_to(camera.position),
                        pixel_m_per_m,
                        max_error_m,
                        values,
                    )
                }
                _ => 0,
            };
            let indices = object.detail_levels.levels[level].indices.clone();
            level_changed |= indices != object.drawn_indices;
            object.drawn_indices = indices;
        }
        if level_changed {
            self.levels_generation = next_surfaces_generation();
        }
    }

    /// Which levels of detail the last [`Self::write_frame`] chose, as a number: equal
    /// numbers mean every object drawn at the same level as then.
    pub fn levels_generation(&self) -> u64 {
        self.levels_generation
    }

    /// Draws each object's level of detail for its distance from the camera (the
    /// default) or every mesh as it is, from the next [`Self::write_frame`] on.
    pub fn set_detail_levels(&mut self, enabled: bool) {
        // The levels the next frame draws then change its levels' generation.
        self.detail_levels = enabled;
    }

    /// The lights' grid of the uploaded lights (`shading::light_grid`).
    pub fn light_grid(&self) -> &LightGrid {
        &self.light_grid
    }

    /// Leaves objects outside the camera's frustum out of its passes (the default) or
    /// draws every one shown, from the next [`Self::write_frame`] on: the frames must be
    /// the same either way (tests/view_culling.rs).
    pub fn set_view_culling(&mut self, enabled: bool) {
        self.view_culling = enabled;
    }

    /// Culls the back faces of closed meshes the camera sees from outside (the default)
    /// or draws them, from the next [`Self::write_frame`] on: the frames must be the same
    /// either way but for ties at silhouettes (tests/back_faces.rs).
    pub fn set_back_face_culling(&mut self, enabled: bool) {
        self.back_face_culling = enabled;
    }

    /// How many objects the last camera written draws whose back faces it cannot see.
    pub fn objects_seen_from_outside(&self) -> usize {
        self.objects
            .iter()
            .filter(|o| o.drawn_in_view() && o.back_faces_hidden)
            .count()
    }

    /// Whether views leave out the objects outside their frustum: the camera's from the
    /// next [`Self::write_frame`] on, the shadow maps' from their next draw.
    pub fn view_culling(&self) -> bool {
        self.view_culling
    }

    /// The triangles of the objects the last camera written may see, and of every
    /// object shown (for `render`'s summary).
    pub fn triangles_in_view(&self) -> (u64, u64) {
        let shown = self.objects.iter().filter(|o| !o.hidden);
        (
            shown
                .clone()
                .filter(|o| o.in_view)
                .map(|o| o.drawn_indices.len() as u64 / 3)
                .sum(),
            shown.map(|o| o.index_count as u64 / 3).sum(),
        )
    }

    /// Replaces the baked indirect light (None: none): per object of the [`Scene`] it was
    /// uploaded from, the irradiance of each vertex.
    pub fn set_baked_indirect(&mut self, queue: &wgpu::Queue, indirect: Option<&BakedIndirect>) {
        self.surfaces_generation = next_surfaces_generation();
        let vertex_count: u32 = self.objects.iter().map(|o| o.vertex_count).sum();
        let mut values = vec![0.0f32; 3 * vertex_count as usize];
        for object in &mut self.objects {
            object.baked_light = false;
            let Some(irradiance) = indirect.and_then(|indirect| indirect.objects.get(object.source)) else {
                continue;
            };
            let start = 3 * object.first_vertex as usize;
            let count = irradiance.len().min(object.vertex_count as usize);
            values[start..start + 3 * count].copy_from_slice(bytemuck::cast_slice(&irradiance[..count]));
            // What the shaders add is max(E, 0) (scene.wgsl `surface`).
            object.baked_light = irradiance[..count].iter().flatten().any(|&e| e > 0.0);
        }
        if !values.is_empty() {
            queue.write_buffer(&self.indirect_buffer, 0, bytemuck::cast_slice(&values));
        }
    }

    /// Replaces the environment light (None: no environment).
    pub fn set_environment(&mut self, environment: Option<&Environment>) {
        self.environment_irradiance = environment_irradiance(environment);
    }
}

fn frame_bind_group(
    device: &wgpu::Device,
    layouts: &SceneLayouts,
    frame: &wgpu::Buffer,
    lights: &LightBuffers,
    indirect: &wgpu::Buffer,
) -> wgpu::BindGroup {
    device.create_bind_group(&wgpu::BindGroupDescriptor {
        label: Some("frame"),
        layout: &layouts.frame,
        entries: &slot_entries([
            (slots::FRAME, frame.as_entire_binding()),
            (slots::LIGHTS, lights.uniform.as_entire_binding()),
            (slots::BAKED_INDIRECT, indirect.as_entire_binding()),
            (slots::EVERY_LIGHT, lights.every.as_entire_binding()),
            (slots::LIGHT_GRID, lights.grid.as_entire_binding()),
        ]),
    })
}

/// Draws every shown object of `scene` into `pass` (pipeline and group 0 set).
pub fn draw_objects(pass: &mut wgpu::RenderPass<'_>, scene: &GpuScene) {
    for object in scene.objects.iter().filter(|o| o.drawn_in_view()) {
        draw_object(pass, scene, object);
    }
}

/// Draws one object; its one instance's index is the object's first vertex in the baked
/// indirect light (scene.wgsl reads it as `instance_index`).
pub fn draw_object(pass: &mut wgpu::RenderPass<'_>, scene: &GpuScene, object: &GpuObject) {
    pass.set_bind_group(slots::MATERIAL_GROUP, &scene.material_bind_groups[object.material], &[]);
    pass.set_vertex_buffer(0, object.vertex_buffer.slice(..));
    pass.set_index_buffer(object.index_buffer.slice(..), wgpu::IndexFormat::Uint32);
    pass.draw_indexed(
        object.drawn_indices.clone(),
        0,
        object.first_vertex..object.first_vertex + 1,
    );
}
