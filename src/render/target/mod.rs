//! Where a frame is drawn ([`RenderTarget`]) and how its edges are antialiased
//! ([`AntiAliasing`]).

pub mod edge_filter;

use crate::render::descriptors::{
    COLOR_FORMAT, DEPTH_FORMAT, DISPLAY_FORMAT, SAMPLE_COUNT, depth_attachment, frame_texture,
};
use edge_filter::{EdgeFilter, EdgeFilterPass};

/// How a frame's silhouettes and other edges are smoothed.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum AntiAliasing {
    /// One sample at each pixel centre, as the CPU reference shades (parity tests).
    None,
    /// One sample per pixel, then the edge filter (`render::edge_filter`): the default,
    /// a few milliseconds on lavapipe.
    #[default]
    EdgeFilter,
    /// [`SAMPLE_COUNT`] samples per pixel, resolved: exact coverage of geometric edges, at
    /// more than twice the frame time on lavapipe (docs/performance.md).
    Multisample,
}

impl AntiAliasing {
    /// Samples per pixel of the frame's colour and depth attachments.
    pub fn samples(self) -> u32 {
        match self {
            AntiAliasing::Multisample => SAMPLE_COUNT,
            AntiAliasing::None | AntiAliasing::EdgeFilter => 1,
        }
    }

    /// The antialiasing that draws with `samples` per pixel and no edge filter (1: none).
    pub fn with_samples(samples: u32) -> AntiAliasing {
        if samples > 1 {
            AntiAliasing::Multisample
        } else {
            AntiAliasing::None
        }
    }
}

/// Where a frame is drawn: a colour and depth buffer (multisampled and resolved into a
/// single-sampled texture with [`AntiAliasing::Multisample`]; drawn into an intermediate
/// image and filtered into it with [`AntiAliasing::EdgeFilter`]) whose texture holds
/// sRGB-encoded bytes. The shader writes it through an sRGB view (the hardware encodes);
/// egui and the PNG readback see the plain bytes, which is what egui expects of a user
/// texture (gamma-space `Rgba8Unorm`). Passes draw into [`Self::color_attachment`] and
/// end the frame with [`Self::finish`].
pub struct RenderTarget {
    pub width: u32,
    pub height: u32,
    pub samples: u32,
    pub color: wgpu::Texture,
    /// sRGB view: the resolve target (or the attachment itself without multisampling or
    /// edge filter).
    pub color_view: wgpu::TextureView,
    /// `Rgba8Unorm` view of the same bytes, for egui.
    pub display_view: wgpu::TextureView,
    msaa_view: Option<wgpu::TextureView>,
    edge_filter: Option<EdgeFilterPass>,
    depth: wgpu::Texture,
    depth_view: wgpu::TextureView,
}

impl RenderTarget {
    /// A target with `samples` (1 or [`SAMPLE_COUNT`]) samples per pixel and no edge
    /// filter. One sample shades exactly the pixel centres, as the CPU reference does.
    pub fn with_samples(device: &wgpu::Device, width: u32, height: u32, samples: u32) -> RenderTarget {
        RenderTarget::with_anti_aliasing(device, width, height, AntiAliasing::with_samples(samples))
    }

    /// A target antialiased the way `anti_aliasing` says (an edge filter compiles its
    /// pipelines: [`Self::with_edge_filter`] shares them between targets).
    pub fn with_anti_aliasing(
        device: &wgpu::Device,
        width: u32,
        height: u32,
        anti_aliasing: AntiAliasing,
    ) -> RenderTarget {
        match anti_aliasing {
            AntiAliasing::EdgeFilter => RenderTarget::with_edge_filter(device, width, height, &EdgeFilter::new(device)),
            _ => RenderTarget::build(device, width, height, anti_aliasing.samples(), None),
        }
    }

    /// A single-sampled target antialiased by `filter`'s pipelines.
    pub fn with_edge_filter(device: &wgpu::Device, width: u32, height: u32, filter: &EdgeFilter) -> RenderTarget {
        RenderTarget::build(device, width, height, 1, Some(filter))
    }

    fn build(
        device: &wgpu::Device,
        width: u32,
        height: u32,
        samples: u32,
        edge_filter: Option<&EdgeFilter>,
    ) -> RenderTarget {
        let size = wgpu::Extent3d {
            width: width.max(1),
            height: height.max(1),
            depth_or_array_layers: 1,
        };
        let texture = |label, format, samples, usage, view_formats: &[wgpu::TextureFormat]| {
            frame_texture(device, label, size, format, samples, usage, view_formats)
        };
        let attachment = wgpu::TextureUsages::RENDER_ATTACHMENT;
        let color = texture(
            "colour",
            DISPLAY_FORMAT,
            1,
            attachment
                | wgpu::TextureUsages::COPY_SRC
                | wgpu::TextureUsages::COPY_DST
                | wgpu::TextureUsages::TEXTURE_BINDING,
            &[COLOR_FORMAT],
        );
        let view = |t: &wgpu::Texture| t.create_view(&wgpu::TextureViewDescriptor::default());
        let msaa_view = (samples > 1).then(|| view(&texture("colour msaa", COLOR_FORMAT, samples, attachment, &[])));
        // With an edge filter the depth is read too (where the surfaces break: see
        // edge_filter.wgsl), and copied in when a frame is not rasterised into it.
        let depth_usage = match edge_filter {
            Some(_) => attachment | wgpu::TextureUsages::TEXTURE_BINDING | wgpu::TextureUsages::COPY_DST,
            None => attachment,
        };
        let depth = texture("depth", DEPTH_FORMAT, samples, depth_usage, &[]);
        let edge_filter = edge_filter.map(|filter| EdgeFilterPass::new(device, size, filter, &view(&depth)));
        RenderTarget {
            width: size.width,
            height: size.height,
            samples,
            color_view: color.create_view(&wgpu::TextureViewDescriptor {
                format: Some(COLOR_FORMAT),
                ..Default::default()
            }),
            display_view: view(&color),
            msaa_view,
            edge_filter,
            depth_view: view(&depth),
            depth,
            color,
        }
    }

    /// The colour attachment, cleared to `background` (linear RGB).
    pub fn color_attachment(&self, background_linear: [f64; 3]) -> wgpu::RenderPassColorAttachment<'_> {
        let [r, g, b] = background_linear;
        let (view, resolve_target, store) = match (&self.msaa_view, &self.edge_filter) {
            (Some(msaa), _) => (msaa, Some(&self.color_view), wgpu::StoreOp::Discard),
            (None, Some(filter)) => (&filter.attachment_view, None, wgpu::StoreOp::Store),
            (None, None) => (&self.color_view, None, wgpu::StoreOp::Store),
        };
        wgpu::RenderPassColorAttachment {
            view,
            depth_slice: None,
            resolve_target,
            ops: wgpu::Operations {
                load: wgpu::LoadOp::Clear(wgpu::Color { r, g, b, a: 1.0 }),
                store,
            },
        }
    }

    /// The single-sampled image behind [`Self::color_attachment`] (`Rgba8Unorm` bytes,
    /// sRGB-encoded): the edge filter's input, or the colour texture itself; None when
    /// multisampled. A frame may be copied into it in place of passes drawing it.
    pub fn single_sampled_image(&self) -> Option<&wgpu::Texture> {
        match (&self.msaa_view, &self.edge_filter) {
            (Some(_), _) => None,
            (None, Some(filter)) => Some(&filter.image),
            (None, None) => Some(&self.color),
        }
    }

    /// The depth attachment, cleared to the far plane, for one pass (kept for the edge
    /// filter, which reads it).
    pub fn depth_attachment(&self) -> wgpu::RenderPassDepthStencilAttachment<'_> {
        depth_attachment(&self.depth_view, Some(1.0), self.edge_filter.is_some())
    }

    /// Writes `rgba8` (sRGB-encoded bytes, row by row) as the frame drawn so far, in place
    /// of the passes that draw into [`Self::color_attachment`]: what the edge filter makes
    /// of a given image (without an edge filter, nothing is written).
    pub(super) fn write_unfiltered(&self, queue: &wgpu::Queue, rgba8: &[u8]) {
        if let Some(filter) = &self.edge_filter {
            queue.write_texture(
                filter.image.as_image_copy(),
                rgba8,
                wgpu::TexelCopyBufferLayout {
                    offset: 0,
                    bytes_per_row: Some(4 * self.width),
                    rows_per_image: Some(self.height),
                },
                filter.image.size(),
            );
        }
    }

    /// Makes `surfaces_depth` (a depth image of the frame's size and format) the frame's
    /// depth where an edge filter reads it: for frames whose colours are copied in
    /// rather than rasterised (the deferred full-resolution frame).
    pub(crate) fn copy_depth_from(&self, encoder: &mut wgpu::CommandEncoder, surfaces_depth: &wgpu::Texture) {
        if self.edge_filter.is_some() && surfaces_depth.size() == self.depth.size() {
            encoder.copy_texture_to_texture(
                surfaces_depth.as_image_copy(),
                self.depth.as_image_copy(),
                self.depth.size(),
            );
        }
    }

    /// Clears the depth to the far plane with nothing drawn: an image written with
    /// [`Self::write_unfiltered`] has no surfaces, and the edge filter then judges it by
    /// its colours alone.
    pub(super) fn clear_depth(&self, encoder: &mut wgpu::CommandEncoder) {
        drop(encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
            label: Some("depth cleared"),
            color_attachments: &[],
            depth_stencil_attachment: Some(self.depth_attachment()),
            timestamp_writes: None,
            occlusion_query_set: None,
            multiview_mask: None,
        }));
    }

    /// Whether [`RenderTarget::finish`] runs the edge filter.
    pub fn has_edge_filter(&self) -> bool {
        self.edge_filter.is_some()
    }

    /// Ends a frame drawn into [`Self::color_attachment`]: runs the edge filter into the
    /// colour texture where there is one.
    pub fn finish(&self, encoder: &mut wgpu::CommandEncoder) {
        if let Some(filter) = &self.edge_filter {
            filter.run(encoder, &self.display_view);
        }
    }
}
