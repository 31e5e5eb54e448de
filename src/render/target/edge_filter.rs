//! Edge antialiasing of single-sample frames (shaders/edge_filter.wgsl): the frame is drawn
//! into an intermediate image, then one full-screen pass writes the target's colour,
//! blending each pixel on a contrast edge with its neighbour across the edge by how far
//! along the edge's staircase step it lies. The pass draws twice: the pixels without
//! contrast are copied and marked in a depth buffer, so that the costly edge search runs
//! only at the others. On lavapipe it costs a few milliseconds where 4× multisampling
//! costs the reduced-resolution shading most of its gain: lavapipe runs a multisampled
//! pass's fragment shader even where the depth test has rejected every sample, and the
//! upsampling must search wider for the pixels it cannot match.

use crate::render::descriptors::{
    COLOR_FORMAT, DEPTH_FORMAT, DISPLAY_FORMAT, bilinear_sampler, create_module, depth_attachment, depth_test,
    frame_texture, image_and_sampler_entries, slot_entries, texture_entry,
};
use crate::shading::wgsl::{self, slots};

/// The edge filter's pipelines, compiled once and shared by the targets that use them
/// (the viewport makes a new target whenever its size changes).
#[derive(Clone)]
pub struct EdgeFilter {
    layout: wgpu::BindGroupLayout,
    sampler: wgpu::Sampler,
    keep_flat: wgpu::RenderPipeline,
    filter_edges: wgpu::RenderPipeline,
}

impl EdgeFilter {
    pub fn new(device: &wgpu::Device) -> EdgeFilter {
        let sampler = bilinear_sampler(device, "edge filter");
        // The frame's image and sampler, and its depth (where the surfaces break).
        let [image_entry, sampler_entry] = image_and_sampler_entries();
        let depth_entry = texture_entry(
            slots::FRAME_DEPTH,
            wgpu::ShaderStages::FRAGMENT,
            wgpu::TextureSampleType::Depth,
        );
        let layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("edge filter"),
            entries: &[image_entry, sampler_entry, depth_entry],
        });
        let module = create_module(device, "edge filter", &wgsl::edge_filter_source());
        let pipeline_layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some("edge filter"),
            bind_group_layouts: &[Some(&layout)],
            immediate_size: 0,
        });
        // Both draw at depth 0: the first writes it wherever it keeps a pixel (and
        // discards the others), the second passes only where the clear value 1 is left.
        let pipeline = |fragment, depth_write, compare| {
            device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
                label: Some(fragment),
                layout: Some(&pipeline_layout),
                vertex: wgpu::VertexState {
                    module: &module,
                    entry_point: Some("vs_full_screen"),
                    compilation_options: Default::default(),
                    buffers: &[],
                },
                primitive: wgpu::PrimitiveState::default(),
                depth_stencil: Some(depth_test(depth_write, compare)),
                multisample: wgpu::MultisampleState::default(),
                fragment: Some(wgpu::FragmentState {
                    module: &module,
                    entry_point: Some(fragment),
                    compilation_options: Default::default(),
                    targets: &[Some(wgpu::ColorTargetState {
                        format: DISPLAY_FORMAT,
                        blend: None,
                        write_mask: wgpu::ColorWrites::ALL,
                    })],
                }),
                multiview_mask: None,
                cache: None,
            })
        };
        EdgeFilter {
            keep_flat: pipeline("fs_keep_flat", true, wgpu::CompareFunction::Always),
            filter_edges: pipeline("fs_edge_filter", false, wgpu::CompareFunction::Less),
            layout,
            sampler,
        }
    }
}

/// The intermediate image a frame is drawn into and the pass that filters it into the
/// target's colour.
pub struct EdgeFilterPass {
    /// The intermediate image (sRGB-encoded bytes).
    pub(super) image: wgpu::Texture,
    /// sRGB view of it: the frame's colour attachment.
    pub(super) attachment_view: wgpu::TextureView,
    /// Marks the pixels fs_keep_flat copied (depth 0).
    depth_view: wgpu::TextureView,
    bind_group: wgpu::BindGroup,
    filter: EdgeFilter,
}

impl EdgeFilterPass {
    /// An intermediate image of `size` (width, height) and `filter` reading it and the
    /// frame's depth `frame_depth`.
    pub fn new(
        device: &wgpu::Device,
        size: wgpu::Extent3d,
        filter: &EdgeFilter,
        frame_depth: &wgpu::TextureView,
    ) -> EdgeFilterPass {
        let texture = |label, format, usage, view_formats: &[wgpu::TextureFormat]| {
            frame_texture(device, label, size, format, 1, usage, view_formats)
        };
        let image = texture(
            "unfiltered frame",
            DISPLAY_FORMAT,
            wgpu::TextureUsages::RENDER_ATTACHMENT
                | wgpu::TextureUsages::TEXTURE_BINDING
                | wgpu::TextureUsages::COPY_DST,
            &[COLOR_FORMAT],
        );
        let attachment_view = image.create_view(&wgpu::TextureViewDescriptor {
            format: Some(COLOR_FORMAT),
            ..Default::default()
        });
        // The filter reads and writes the stored (sRGB-encoded) values as they are.
        let raw_view = image.create_view(&Default::default());
        let bind_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("edge filter"),
            layout: &filter.layout,
            entries: &slot_entries([
                (slots::FRAME_IMAGE, wgpu::BindingResource::TextureView(&raw_view)),
                (slots::FRAME_SAMPLER, wgpu::BindingResource::Sampler(&filter.sampler)),
                (slots::FRAME_DEPTH, wgpu::BindingResource::TextureView(frame_depth)),
            ]),
        });
        let depth = texture(
            "edge filter marks",
            DEPTH_FORMAT,
            wgpu::TextureUsages::RENDER_ATTACHMENT,
            &[],
        );
        EdgeFilterPass {
            image,
            attachment_view,
            depth_view: depth.create_view(&Default::default()),
            bind_group,
            filter: filter.clone(),
        }
    }

    /// Filters the intermediate image into `output` (a raw, non-sRGB view).
    pub fn run(&self, encoder: &mut wgpu::CommandEncoder, output: &wgpu::TextureView) {
        let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
            label: Some("edge filter"),
            color_attachments: &[Some(wgpu::RenderPassColorAttachment {
                view: output,
                depth_slice: None,
                resolve_target: None,
                ops: wgpu::Operations {
                    load: wgpu::LoadOp::Clear(wgpu::Color::BLACK),
                    store: wgpu::StoreOp::Store,
                },
            })],
            depth_stencil_attachment: Some(depth_attachment(&self.depth_view, Some(1.0), false)),
            timestamp_writes: None,
            occlusion_query_set: None,
            multiview_mask: None,
        });
        pass.set_bind_group(slots::IMAGE_GROUP, &self.bind_group, &[]);
        for pipeline in [&self.filter.keep_flat, &self.filter.filter_edges] {
            pass.set_pipeline(pipeline);
            pass.draw(0..3, 0..1);
        }
    }
}
