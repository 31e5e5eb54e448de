//! Plumbing of per-vertex log-SH shading (shaders/logsh_per_vertex.wgsl): a compute pass
//! writes each vertex's visibility SH into a buffer per object, which the shading pass
//! binds as a second vertex buffer. The visibility is a function of where the vertex is,
//! not of the view: each object's is computed when it first comes into view and kept
//! until what it is computed from changes ([`VisibilityInputs`]), so frames of a moving
//! camera walk no blockers for objects they saw before.

use super::vertex_light::{VertexLight, VertexLightCompute};
use crate::render::descriptors::{slot_entries, storage_buffer_entry};
use crate::render::resources::GpuScene;
use crate::shading::wgsl::sh as wgsl_sh;
use crate::shading::wgsl::slots;

/// The compute pipeline and the bind group layout of its per-object buffers (group 3).
/// It reads the frame's group (0) too: the SH lights' windows on the blockers
/// (`shading::light_windows`) depend on the lights and the environment. With it, the pass
/// that lights the vertices of fine meshes from that visibility (`vertex_light`).
pub struct PerVertexCompute {
    pub pipeline: wgpu::ComputePipeline,
    object_layout: wgpu::BindGroupLayout,
    empty_group: wgpu::BindGroup,
    /// Bytes of one vertex's visibility SH.
    pub stride: u64,
    pub light: VertexLightCompute,
}

impl PerVertexCompute {
    pub fn new(
        device: &wgpu::Device,
        module: &wgpu::ShaderModule,
        [frame_layout, material_layout, shadow_layout]: [&wgpu::BindGroupLayout; 3],
        order: usize,
        constants: &[(&str, f64)],
    ) -> PerVertexCompute {
        let storage = |slot, read_only| storage_buffer_entry(slot, wgpu::ShaderStages::COMPUTE, read_only);
        let object_layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("per-vertex object"),
            entries: &[
                storage(slots::VERTEX_DATA, true),
                storage(slots::VERTEX_VISIBILITY, false),
            ],
        });
        let empty_layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("empty"),
            entries: &[],
        });
        let empty_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("empty"),
            layout: &empty_layout,
            entries: &[],
        });
        let layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some("per-vertex visibility"),
            bind_group_layouts: &[
                Some(frame_layout),
                Some(&empty_layout),
                Some(shadow_layout),
                Some(&object_layout),
            ],
            immediate_size: 0,
        });
        // One visibility per vertex, which every light reads: the walk with windows sums
        // its caps into one log-visibility, not one per light (light_windows.wgsl).
        let constants: Vec<(&str, f64)> = constants
            .iter()
            .copied()
            .chain([("PER_LIGHT_VISIBILITY", 0.0)])
            .collect();
        let light = VertexLightCompute::new(
            device,
            module,
            [frame_layout, material_layout, shadow_layout],
            &constants,
        );
        let pipeline = device.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
            label: Some("per-vertex visibility"),
            layout: Some(&layout),
            module,
            entry_point: Some("cs_vertex_visibility"),
            compilation_options: wgpu::PipelineCompilationOptions {
                constants: &constants,
                ..Default::default()
            },
            cache: None,
        });
        PerVertexCompute {
            pipeline,
            object_layout,
            empty_group,
            stride: 16 * wgsl_sh::vec4_count(order) as u64,
            light,
        }
    }

    /// Computes the visibility of the vertices of the objects `visibility` plans
    /// ([`VertexVisibility::plan`]; all of them before the first plan) among those of
    /// `scene` drawn from the camera ([`crate::render::resources::GpuObject::drawn_in_view`]),
    /// the frame's group `frame` and the blockers' `blockers` bound (the other objects'
    /// keep what they held).
    pub fn run(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        [frame, blockers]: [&wgpu::BindGroup; 2],
        scene: &GpuScene,
        visibility: &VertexVisibility,
    ) {
        let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
            label: Some("per-vertex visibility"),
            timestamp_writes: None,
        });
        pass.set_pipeline(&self.pipeline);
        pass.set_bind_group(slots::FRAME_GROUP, frame, &[]);
        pass.set_bind_group(slots::MATERIAL_GROUP, &self.empty_group, &[]);
        pass.set_bind_group(slots::SHADOW_GROUP, blockers, &[]);
        let objects = visibility.bind_groups.iter().zip(&visibility.vertex_counts);
        for (((bind_group, vertex_count), object), planned) in objects.zip(&scene.objects).zip(&visibility.to_compute) {
            if !object.drawn_in_view() || !planned {
                continue;
            }
            pass.set_bind_group(slots::PASS_GROUP, bind_group, &[]);
            pass.dispatch_workgroups(vertex_count.div_ceil(64), 1, 1);
        }
    }

    /// The vertex buffer layout of the visibility attributes (locations 4…).
    pub fn attributes(order: usize) -> Vec<wgpu::VertexAttribute> {
        (0..wgsl_sh::vec4_count(order))
            .map(|v| wgpu::VertexAttribute {
                format: wgpu::VertexFormat::Float32x4,
                offset: 16 * v as u64,
                shader_location: 4 + v as u32,
            })
            .collect()
    }
}

/// What the per-vertex visibility is computed from besides the vertices: the SH path's
/// lights' geometry (not their intensities) where their windows on the blockers apply
/// (`shading::light_windows`: without them the walk reads no light), the environment,
/// the shadow settings, the blockers and the scene's upload (new geometry, objects
/// hidden or shown).
#[derive(Debug, Clone, PartialEq)]
pub struct VisibilityInputs {
    windowed_lights: Option<Vec<crate::shading::gpu_types::GpuLight>>,
    environment_irradiance: [[f32; 4]; 9],
    settings: crate::shading::ShadowSettings,
    blockers_generation: u64,
    scene_generation: u64,
}

impl VisibilityInputs {
    pub fn new(
        lighting: crate::render::resources::HarmonicLighting,
        settings: crate::shading::ShadowSettings,
        blockers_generation: u64,
        scene_generation: u64,
    ) -> VisibilityInputs {
        let windows = crate::shading::light_windows::windows_apply(&lighting.environment_irradiance, &lighting.lights);
        // The windows read where the lights are, not how bright: a stroke keeps them.
        VisibilityInputs {
            windowed_lights: windows.then(|| lighting.lights.iter().map(|light| light.geometry()).collect()),
            environment_irradiance: lighting.environment_irradiance,
            settings,
            blockers_generation,
            scene_generation,
        }
    }
}

/// The visibility SH of every vertex of a [`GpuScene`], one buffer per object, and which
/// objects' buffers hold it for the inputs of the last plan.
pub struct VertexVisibility {
    pub buffers: Vec<wgpu::Buffer>,
    bind_groups: Vec<wgpu::BindGroup>,
    vertex_counts: Vec<u32>,
    computed_from: Option<VisibilityInputs>,
    computed: Vec<bool>,
    /// The objects the next [`PerVertexCompute::run`] computes.
    to_compute: Vec<bool>,
    /// The light of the vertices of the meshes fine enough to be lit there.
    pub light: VertexLight,
}

impl VertexVisibility {
    pub fn new(device: &wgpu::Device, compute: &PerVertexCompute, scene: &GpuScene) -> VertexVisibility {
        let mut buffers = Vec::new();
        let mut bind_groups = Vec::new();
        let mut vertex_counts = Vec::new();
        for object in &scene.objects {
            let buffer = device.create_buffer(&wgpu::BufferDescriptor {
                label: Some("vertex visibility"),
                size: compute.stride * object.vertex_count.max(1) as u64,
                usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::VERTEX | wgpu::BufferUsages::COPY_SRC,
                mapped_at_creation: false,
            });
            bind_groups.push(device.create_bind_group(&wgpu::BindGroupDescriptor {
                label: Some("per-vertex object"),
                layout: &compute.object_layout,
                entries: &slot_entries([
                    (slots::VERTEX_DATA, object.vertex_buffer.as_entire_binding()),
                    (slots::VERTEX_VISIBILITY, buffer.as_entire_binding()),
                ]),
            }));
            buffers.push(buffer);
            vertex_counts.push(object.vertex_count);
        }
        let objects = vertex_counts.len();
        let light = VertexLight::new(device, &compute.light, scene, &buffers);
        VertexVisibility {
            light,
            buffers,
            bind_groups,
            vertex_counts,
            computed_from: None,
            computed: vec![false; objects],
            to_compute: vec![true; objects],
        }
    }

    /// Plans a frame of `scene` seen from `eye` with shadow `settings` and the blockers of
    /// `blockers_generation`: the vertices whose visibility it computes ([`Self::plan`])
    /// and the objects it lights at their vertices ([`VertexLight::plan`]; with the
    /// separate BRDF only, the one whose light splits into what k_d and k_s multiply).
    /// Returns how many of each.
    pub fn plan_frame(
        &mut self,
        scene: &GpuScene,
        settings: crate::shading::ShadowSettings,
        blockers_generation: u64,
        eye: glam::Vec3,
    ) -> (u64, usize) {
        let lighting = scene.harmonic_lighting();
        let separate = settings.brdf == crate::shading::BrdfShading::Separate;
        let lit = self.light.plan(scene, &lighting.lights, eye, separate);
        let inputs = VisibilityInputs::new(lighting, settings, blockers_generation, scene.surfaces_generation());
        (self.plan(inputs, scene), lit)
    }

    /// Plans the next run for a frame whose visibility is computed from `inputs`: the
    /// objects drawn from its camera whose buffers do not hold it yet (every one of them
    /// when the inputs changed). Returns how many vertices it will compute.
    pub fn plan(&mut self, inputs: VisibilityInputs, scene: &GpuScene) -> u64 {
        if self.computed_from.as_ref() != Some(&inputs) {
            self.computed.fill(false);
            self.computed_from = Some(inputs);
        }
        let mut vertices = 0;
        for (k, object) in scene.objects.iter().enumerate().take(self.computed.len()) {
            self.to_compute[k] = object.drawn_in_view() && !self.computed[k];
            self.computed[k] |= self.to_compute[k];
            vertices += u64::from(self.to_compute[k]) * u64::from(self.vertex_counts[k]);
        }
        vertices
    }
}
