//! The log-SH soft-shadow pipeline (shaders/logsh.wgsl): a depth pre-pass, then one
//! shading pass in which every visible pixel sums its blockers' log-visibility,
//! exponentiates it and shades each light through it. The SH order and exponentiation
//! method are baked into the module at creation (generated WGSL, `wgsl_sh`).

pub use super::gpu_blockers::{GpuBlockers, shadow_layout};
use super::gpu_scene::{GpuObject, GpuScene};
use super::gpu_types::GpuVertex;
use super::per_vertex::{PerVertexCompute, VertexVisibility};
use super::pipeline::{DEPTH_FORMAT, RenderTarget, SceneLayouts};
use super::{ShadowSettings, shaders, wgsl_sh};
use crate::sh::ExpMethod;

/// Pipelines drawing a scene with log-SH shadows at one order and method.
pub struct LogShPipeline {
    pub order: usize,
    pub exp: ExpMethod,
    pub samples: u32,
    pub shadow_layout: wgpu::BindGroupLayout,
    depth_prepass: wgpu::RenderPipeline,
    shade: wgpu::RenderPipeline,
    /// Per-vertex shading, where the order allows it.
    pub per_vertex: Option<(PerVertexCompute, wgpu::RenderPipeline)>,
}

/// What a pipeline's fragment stage is for.
#[derive(Clone, Copy)]
enum Stage<'a> {
    DepthOnly,
    Shade,
    /// Shading through per-vertex visibility attributes of this order.
    ShadePerVertex(usize),
    /// One surface channel (fs_surface) as raw f32.
    Surface(u32, &'a str),
}

impl LogShPipeline {
    /// Pipelines for `settings.order` and `settings.exp` drawing into targets of `samples`
    /// samples (the settings must be valid: see [`ShadowSettings::gpu_problems`]).
    pub fn new(
        device: &wgpu::Device,
        layouts: &SceneLayouts,
        settings: &ShadowSettings,
        samples: u32,
    ) -> LogShPipeline {
        let shadow_layout = shadow_layout(device);
        let source = shaders::logsh_source(settings.order, settings.exp);
        let module = shaders::create_module(device, "log-SH shadows", &source);
        let make = |stage| scene_pipeline(device, layouts, &shadow_layout, &module, stage, samples);
        let per_vertex = wgsl_sh::supports_per_vertex(settings.order).then(|| {
            (
                PerVertexCompute::new(device, &module, &shadow_layout, settings.order),
                make(Stage::ShadePerVertex(settings.order)),
            )
        });
        LogShPipeline {
            order: settings.order,
            exp: settings.exp,
            samples,
            depth_prepass: make(Stage::DepthOnly),
            shade: make(Stage::Shade),
            per_vertex,
            shadow_layout,
        }
    }

    /// Whether this pipeline was built for `settings`' order and method.
    pub fn matches(&self, settings: &ShadowSettings) -> bool {
        self.order == settings.order && self.exp == settings.exp
    }

    /// The per-vertex visibility buffers for `scene`, if this order supports them.
    pub fn vertex_visibility(&self, device: &wgpu::Device, scene: &GpuScene) -> Option<VertexVisibility> {
        self.per_vertex
            .as_ref()
            .map(|(compute, _)| VertexVisibility::new(device, compute, scene))
    }

    /// Clears `target` to `background` (linear RGB) and draws every object with shadows:
    /// per pixel, or with `per_vertex` visibility (from [`Self::vertex_visibility`] for
    /// the same scene) computed at the vertices first.
    pub fn draw(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        target: &RenderTarget,
        scene: &GpuScene,
        blockers: &GpuBlockers,
        background_linear: [f64; 3],
        per_vertex: Option<&VertexVisibility>,
    ) {
        let per_vertex = per_vertex.zip(self.per_vertex.as_ref());
        if let Some((visibility, (compute, _))) = per_vertex {
            compute.run(encoder, &blockers.bind_group, visibility);
        }
        let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
            label: Some("log-SH scene"),
            color_attachments: &[Some(target.color_attachment(background_linear))],
            depth_stencil_attachment: Some(target.depth_attachment()),
            timestamp_writes: None,
            occlusion_query_set: None,
            multiview_mask: None,
        });
        pass.set_bind_group(0, &scene.frame_bind_group, &[]);
        pass.set_bind_group(2, &blockers.bind_group, &[]);
        // The pre-pass settles depth, so the costly shading runs once per visible pixel.
        pass.set_pipeline(&self.depth_prepass);
        draw_objects(&mut pass, scene);
        match per_vertex {
            Some((visibility, (_, shade))) => {
                pass.set_pipeline(shade);
                for (object, buffer) in scene.objects.iter().zip(&visibility.buffers) {
                    if object.hidden {
                        continue;
                    }
                    pass.set_vertex_buffer(1, buffer.slice(..));
                    draw_object(&mut pass, scene, object);
                }
            }
            None => {
                pass.set_pipeline(&self.shade);
                draw_objects(&mut pass, scene);
            }
        }
    }
}

pub(crate) fn draw_objects(pass: &mut wgpu::RenderPass<'_>, scene: &GpuScene) {
    for object in scene.objects.iter().filter(|o| !o.hidden) {
        draw_object(pass, scene, object);
    }
}

/// Draws one object; its one instance's index is the object's first vertex in the baked
/// indirect light (scene.wgsl reads it as `instance_index`).
fn draw_object(pass: &mut wgpu::RenderPass<'_>, scene: &GpuScene, object: &GpuObject) {
    pass.set_bind_group(1, &scene.material_bind_groups[object.material], &[]);
    pass.set_vertex_buffer(0, object.vertex_buffer.slice(..));
    pass.set_index_buffer(object.index_buffer.slice(..), wgpu::IndexFormat::Uint32);
    pass.draw_indexed(0..object.index_count, 0, object.first_vertex..object.first_vertex + 1);
}

/// Format of the surface channels read back for the CPU reference.
pub const SURFACE_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba32Float;

/// Number of surface channels fs_surface writes (position, normal, k_d, k_s, emissive).
pub const SURFACE_CHANNELS: u32 = 5;

/// One pipeline per surface channel (see fs_surface), each writing that property of every
/// visible pixel into an [`SURFACE_FORMAT`] target with one sample, all from one module.
pub fn surface_pipelines(
    device: &wgpu::Device,
    layouts: &SceneLayouts,
    shadow_layout: &wgpu::BindGroupLayout,
) -> Vec<wgpu::RenderPipeline> {
    // Any order and method: fs_surface uses no SH.
    let source = shaders::logsh_source(2, ExpMethod::Dc);
    let module = shaders::create_module(device, "surface channels", &source);
    (0..SURFACE_CHANNELS)
        .map(|channel| {
            scene_pipeline(
                device,
                layouts,
                shadow_layout,
                &module,
                Stage::Surface(channel, "SURFACE_CHANNEL"),
                1,
            )
        })
        .collect()
}

fn scene_pipeline(
    device: &wgpu::Device,
    layouts: &SceneLayouts,
    shadow_layout: &wgpu::BindGroupLayout,
    module: &wgpu::ShaderModule,
    stage: Stage,
    samples: u32,
) -> wgpu::RenderPipeline {
    let layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
        label: Some("log-SH"),
        bind_group_layouts: &[Some(&layouts.frame), Some(&layouts.material), Some(shadow_layout)],
        immediate_size: 0,
    });
    let visibility_attributes = match stage {
        Stage::ShadePerVertex(order) => PerVertexCompute::attributes(order),
        _ => Vec::new(),
    };
    let visibility_layout = wgpu::VertexBufferLayout {
        array_stride: 16 * visibility_attributes.len() as u64,
        step_mode: wgpu::VertexStepMode::Vertex,
        attributes: &visibility_attributes,
    };
    let (vertex_entry, buffers) = match stage {
        Stage::ShadePerVertex(_) => (
            "vs_per_vertex",
            vec![Some(GpuVertex::layout()), Some(visibility_layout)],
        ),
        _ => ("vs_main", vec![Some(GpuVertex::layout())]),
    };
    let (entry_point, format, write_mask, depth_write, compare) = match stage {
        Stage::DepthOnly => (
            "fs_surface",
            super::pipeline::COLOR_FORMAT,
            wgpu::ColorWrites::empty(),
            true,
            wgpu::CompareFunction::Less,
        ),
        Stage::ShadePerVertex(_) => (
            "fs_per_vertex",
            super::pipeline::COLOR_FORMAT,
            wgpu::ColorWrites::ALL,
            false,
            wgpu::CompareFunction::LessEqual,
        ),
        Stage::Shade => (
            "fs_logsh",
            super::pipeline::COLOR_FORMAT,
            wgpu::ColorWrites::ALL,
            false,
            wgpu::CompareFunction::LessEqual,
        ),
        Stage::Surface(..) => (
            "fs_surface",
            SURFACE_FORMAT,
            wgpu::ColorWrites::ALL,
            true,
            wgpu::CompareFunction::Less,
        ),
    };
    let constants: Vec<(&str, f64)> = match stage {
        Stage::Surface(channel, name) => vec![(name, channel as f64)],
        _ => Vec::new(),
    };
    device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
        label: Some(entry_point),
        layout: Some(&layout),
        vertex: wgpu::VertexState {
            module,
            entry_point: Some(vertex_entry),
            compilation_options: Default::default(),
            buffers: &buffers,
        },
        primitive: wgpu::PrimitiveState {
            topology: wgpu::PrimitiveTopology::TriangleList,
            front_face: wgpu::FrontFace::Ccw,
            cull_mode: None,
            ..Default::default()
        },
        depth_stencil: Some(wgpu::DepthStencilState {
            format: DEPTH_FORMAT,
            depth_write_enabled: Some(depth_write),
            depth_compare: Some(compare),
            stencil: Default::default(),
            bias: Default::default(),
        }),
        multisample: wgpu::MultisampleState {
            count: samples,
            ..Default::default()
        },
        fragment: Some(wgpu::FragmentState {
            module,
            entry_point: Some(entry_point),
            compilation_options: wgpu::PipelineCompilationOptions {
                constants: &constants,
                ..Default::default()
            },
            targets: &[Some(wgpu::ColorTargetState {
                format,
                blend: None,
                write_mask,
            })],
        }),
        multiview_mask: None,
        cache: None,
    })
}
