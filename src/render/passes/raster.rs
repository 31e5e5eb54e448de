//! The raster pipeline that draws a [`GpuScene`] into a [`RenderTarget`].

use crate::render::descriptors::{COLOR_FORMAT, SAMPLE_COUNT, create_module, depth_test, scene_triangles};
use crate::render::resources::{GpuScene, SceneLayouts, draw_objects, vertex_layout};
use crate::render::target::RenderTarget;
use crate::shading::wgsl;
use crate::shading::wgsl::slots;

pub struct ScenePipeline {
    pub layouts: SceneLayouts,
    pipeline: wgpu::RenderPipeline,
}

impl ScenePipeline {
    /// The raster pipeline with [`SAMPLE_COUNT`] samples per pixel.
    pub fn new(device: &wgpu::Device) -> ScenePipeline {
        ScenePipeline::with_samples(device, SAMPLE_COUNT)
    }

    /// The raster pipeline with `samples` (1 or [`SAMPLE_COUNT`]) samples per pixel.
    pub fn with_samples(device: &wgpu::Device, samples: u32) -> ScenePipeline {
        let layouts = SceneLayouts::new(device);
        let module = create_module(device, "raster", &wgsl::raster_source());
        let pipeline = mesh_pipeline(device, &layouts, &module, "fs_main", samples);
        ScenePipeline { layouts, pipeline }
    }

    /// Clears `target` to `background` (linear RGB) and draws every object.
    pub fn draw(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        target: &RenderTarget,
        scene: &GpuScene,
        background_linear: [f64; 3],
    ) {
        draw_meshes(
            encoder,
            target,
            &self.pipeline,
            &scene.frame_bind_group,
            scene,
            background_linear,
        );
    }
}

/// Clears `target` to `background` (linear RGB) and draws every shown object of `scene`
/// with `pipeline` (a [`mesh_pipeline`]) and `frame_group` as bind group 0.
pub fn draw_meshes(
    encoder: &mut wgpu::CommandEncoder,
    target: &RenderTarget,
    pipeline: &wgpu::RenderPipeline,
    frame_group: &wgpu::BindGroup,
    scene: &GpuScene,
    background_linear: [f64; 3],
) {
    let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
        label: Some("scene"),
        color_attachments: &[Some(target.color_attachment(background_linear))],
        depth_stencil_attachment: Some(target.depth_attachment()),
        timestamp_writes: None,
        occlusion_query_set: None,
        multiview_mask: None,
    });
    pass.set_pipeline(pipeline);
    pass.set_bind_group(slots::FRAME_GROUP, frame_group, &[]);
    draw_objects(&mut pass, scene);
    drop(pass);
    target.finish(encoder);
}

/// A pipeline drawing the scene's meshes with scene.wgsl's vertex stage and `fragment`
/// of `module` (which has the scene's bind groups 0 and 1), depth-tested, both faces,
/// into a [`COLOR_FORMAT`] target of `samples` samples.
pub fn mesh_pipeline(
    device: &wgpu::Device,
    layouts: &SceneLayouts,
    module: &wgpu::ShaderModule,
    fragment: &str,
    samples: u32,
) -> wgpu::RenderPipeline {
    let layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
        label: Some(fragment),
        bind_group_layouts: &[Some(&layouts.frame), Some(&layouts.material)],
        immediate_size: 0,
    });
    device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
        label: Some(fragment),
        layout: Some(&layout),
        vertex: wgpu::VertexState {
            module,
            entry_point: Some("vs_main"),
            compilation_options: Default::default(),
            buffers: &[Some(vertex_layout())],
        },
        // The preview without shadows draws both faces of every mesh.
        primitive: scene_triangles(false),
        depth_stencil: Some(depth_test(true, wgpu::CompareFunction::Less)),
        multisample: wgpu::MultisampleState {
            count: samples,
            ..Default::default()
        },
        fragment: Some(wgpu::FragmentState {
            module,
            entry_point: Some(fragment),
            compilation_options: Default::default(),
            targets: &[Some(wgpu::ColorTargetState {
                format: COLOR_FORMAT,
                blend: None,
                write_mask: wgpu::ColorWrites::ALL,
            })],
        }),
        multiview_mask: None,
        cache: None,
    })
}
