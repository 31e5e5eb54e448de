//! The viewport's frame drawn into egui's frame by a paint callback with its own small
//! pipeline (shaders/viewport_image.wgsl) instead of egui's image shader: on lavapipe
//! egui's shader cost about 14 ms for a 959 × 543 image, since it carries a second,
//! bilinear path (four texel loads, wrap arithmetic) that a software GPU runs beside the
//! first; one texel fetch costs a fraction of that (docs/performance.md, the editor's
//! interface).

use std::sync::Arc;

use crate::render::descriptors::{bilinear_sampler, create_module, image_and_sampler_layout, slot_entries};
use crate::shading::wgsl::{self, slots};

/// The pipelines, kept in egui's callback resources (one per render state).
struct ViewportImagePipelines {
    layout: wgpu::BindGroupLayout,
    sampler: wgpu::Sampler,
    /// The image as large as the viewport: one texel per pixel.
    texel: wgpu::RenderPipeline,
    /// The image of another size: filtered.
    filtered: wgpu::RenderPipeline,
}

impl ViewportImagePipelines {
    fn new(device: &wgpu::Device, target_format: wgpu::TextureFormat) -> ViewportImagePipelines {
        let layout = image_and_sampler_layout(device, "viewport image");
        let pipeline_layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some("viewport image"),
            bind_group_layouts: &[Some(&layout)],
            immediate_size: 0,
        });
        let module = create_module(device, "viewport image", &wgsl::viewport_image_source());
        let constants = [("SRGB_TARGET", f64::from(u8::from(target_format.is_srgb())))];
        let pipeline = |entry_point| {
            device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
                label: Some(entry_point),
                layout: Some(&pipeline_layout),
                vertex: wgpu::VertexState {
                    module: &module,
                    entry_point: Some("vs_viewport"),
                    compilation_options: Default::default(),
                    buffers: &[],
                },
                primitive: wgpu::PrimitiveState::default(),
                depth_stencil: None,
                multisample: Default::default(),
                fragment: Some(wgpu::FragmentState {
                    module: &module,
                    entry_point: Some(entry_point),
                    compilation_options: wgpu::PipelineCompilationOptions {
                        constants: &constants,
                        ..Default::default()
                    },
                    targets: &[Some(wgpu::ColorTargetState {
                        format: target_format,
                        blend: None,
                        write_mask: wgpu::ColorWrites::ALL,
                    })],
                }),
                multiview_mask: None,
                cache: None,
            })
        };
        ViewportImagePipelines {
            sampler: bilinear_sampler(device, "viewport image"),
            texel: pipeline("fs_texel"),
            filtered: pipeline("fs_filtered"),
            layout,
        }
    }
}

/// The viewport's frame as egui draws it: its texture bound for the callback.
#[derive(Clone)]
pub struct ViewportImage {
    bind_group: Arc<wgpu::BindGroup>,
    size_px: [u32; 2],
}

impl ViewportImage {
    /// The image of `view` (`size_px`, an `Rgba8Unorm` view of sRGB-encoded bytes), with
    /// the pipelines made in `render_state`'s callback resources the first time.
    pub fn new(render_state: &egui_wgpu::RenderState, view: &wgpu::TextureView, size_px: [u32; 2]) -> ViewportImage {
        let device = &render_state.device;
        let mut renderer = render_state.renderer.write();
        let pipelines = renderer
            .callback_resources
            .entry::<ViewportImagePipelines>()
            .or_insert_with(|| ViewportImagePipelines::new(device, render_state.target_format));
        let bind_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("viewport image"),
            layout: &pipelines.layout,
            entries: &slot_entries([
                (slots::FRAME_IMAGE, wgpu::BindingResource::TextureView(view)),
                (slots::FRAME_SAMPLER, wgpu::BindingResource::Sampler(&pipelines.sampler)),
            ]),
        });
        ViewportImage {
            bind_group: Arc::new(bind_group),
            size_px,
        }
    }

    /// Paints the image over `rect` (points).
    pub fn paint(&self, painter: &egui::Painter, rect: egui::Rect) {
        painter.add(egui_wgpu::Callback::new_paint_callback(rect, self.clone()));
    }
}

impl egui_wgpu::CallbackTrait for ViewportImage {
    fn paint(
        &self,
        info: egui::PaintCallbackInfo,
        render_pass: &mut wgpu::RenderPass<'static>,
        callback_resources: &egui_wgpu::CallbackResources,
    ) {
        let Some(pipelines) = callback_resources.get::<ViewportImagePipelines>() else {
            return;
        };
        let viewport = info.viewport_in_pixels();
        let one_to_one = [viewport.width_px, viewport.height_px] == self.size_px.map(|v| v as i32);
        render_pass.set_pipeline(if one_to_one {
            &pipelines.texel
        } else {
            &pipelines.filtered
        });
        render_pass.set_bind_group(slots::IMAGE_GROUP, Some(self.bind_group.as_ref()), &[]);
        render_pass.draw(0..3, 0..1);
    }
}
