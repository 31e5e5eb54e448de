//! Reduced-resolution log-SH shading (shaders/reduced_shading.wgsl): the costly shading
//! runs once per d × d block of pixels, and a cheap full-resolution pass rebuilds every
//! pixel from the samples on its own surface (joint bilateral upsampling guided by world
//! position and normal), multiplying its own material back in. Pixels no sample matches
//! (thin objects, silhouettes) are shaded in full on single-sampled targets, and take the
//! best sample nearby on multisampled ones (see `logsh::shades_unmatched_exactly`).
//!
//! A frame is three render passes: the depth of the low-resolution image, its shading
//! into [`LOW_RESOLUTION_FORMATS`] targets, then in the frame's [`crate::render::RenderTarget`] the
//! depth pre-pass, the upsampling and the full shading of the unmatched pixels.

use wgpu::util::DeviceExt;

use crate::render::descriptors::{DEPTH_FORMAT, frame_texture, numbered_entries};
use crate::shading::gpu_types::GpuUpsampleParams;

/// Formats of fs_shade_low's targets: one, holding view depth, lighting and the packed
/// normal (see reduced_shading.wgsl). 16 bytes a sample, read with one texel fetch.
pub const LOW_RESOLUTION_FORMATS: [wgpu::TextureFormat; 1] = [wgpu::TextureFormat::Rgba32Uint];

/// A low-resolution sample counts as lying on a pixel's surface within this many pixel
/// footprints of the pixel's tangent plane (per unit of downsampling: samples lie up to
/// about d pixels away, where a curved surface has left its tangent plane farther).
const PLANE_TOLERANCE_PX_PER_DOWNSAMPLE: f32 = 1.0;

/// A pixel whose matching samples carry less than this share of their bilinear weight is
/// shaded in full: a lone matching sample in the far corner would smear its light.
const MIN_MATCHED_WEIGHT: f32 = 0.15;

/// A pixel whose nearest samples on its surface differ in lighting by more than this
/// ratio (brightest over darkest, luminance of the exposed lighting per unit
/// reflectance, plus [`LIGHTING_FLOOR`]) lies where the light changes faster than the
/// samples' spacing — a hard shadow's edge, a rim — and is shaded in full rather than
/// interpolated; so is a pixel with fewer than two of them on its surface (a limb a few
/// pixels wide), where no disagreement can show. Measured on the studio and the sample
/// against the path tracer (docs/speed-accuracy.md).
const MAX_LIGHTING_RATIO: f32 = 1.5;

/// What [`MAX_LIGHTING_RATIO`] forgives in the dark, in exposed lighting per unit
/// reflectance: on a mid-grey surface (reflectance 0.5) 0.02 displays as about 12/255
/// after the tone curve and sRGB, so in deep shadow only differences larger than that
/// cost full shading.
const LIGHTING_FLOOR: f32 = 0.02;

/// The size of the shaded image for a `width` × `height` frame shaded once per
/// `downsample` × `downsample` pixels (rounded up, so it covers every pixel).
pub fn low_resolution_size(width: u32, height: u32, downsample: u32) -> [u32; 2] {
    let d = downsample.max(1);
    [width.div_ceil(d).max(1), height.div_ceil(d).max(1)]
}

/// The bind group layout through which fs_upsample reads the low-resolution samples.
pub fn low_resolution_layout(device: &wgpu::Device) -> wgpu::BindGroupLayout {
    let texture = |binding, sample_type| wgpu::BindGroupLayoutEntry {
        binding,
        visibility: wgpu::ShaderStages::FRAGMENT,
        ty: wgpu::BindingType::Texture {
            sample_type,
            view_dimension: wgpu::TextureViewDimension::D2,
            multisampled: false,
        },
        count: None,
    };
    device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
        label: Some("low-resolution samples"),
        entries: &[
            wgpu::BindGroupLayoutEntry {
                binding: 0,
                visibility: wgpu::ShaderStages::FRAGMENT,
                ty: wgpu::BindingType::Buffer {
                    ty: wgpu::BufferBindingType::Uniform,
                    has_dynamic_offset: false,
                    min_binding_size: None,
                },
                count: None,
            },
            texture(1, wgpu::TextureSampleType::Uint),
        ],
    })
}

/// The low-resolution images of one frame size: where fs_shade_low writes and
/// fs_upsample reads.
pub struct LowResolutionTargets {
    /// The full-resolution frame size these serve.
    pub full_size: [u32; 2],
    pub downsample: u32,
    pub size: [u32; 2],
    views: [wgpu::TextureView; 1],
    depth: wgpu::TextureView,
    pub(crate) bind_group: wgpu::BindGroup,
}

impl LowResolutionTargets {
    /// Targets for frames of `full_size` shaded once per `downsample` × `downsample`
    /// pixels, read through `layout` ([`low_resolution_layout`]).
    pub fn new(
        device: &wgpu::Device,
        layout: &wgpu::BindGroupLayout,
        full_size: [u32; 2],
        downsample: u32,
    ) -> LowResolutionTargets {
        let size = low_resolution_size(full_size[0], full_size[1], downsample);
        let extent = wgpu::Extent3d {
            width: size[0],
            height: size[1],
            depth_or_array_layers: 1,
        };
        let texture = |label, format, usage| {
            frame_texture(device, label, extent, format, 1, usage, &[]).create_view(&Default::default())
        };
        let sampled = wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::TEXTURE_BINDING;
        let views = LOW_RESOLUTION_FORMATS.map(|format| texture("low-resolution samples", format, sampled));
        let depth = texture(
            "low-resolution depth",
            DEPTH_FORMAT,
            wgpu::TextureUsages::RENDER_ATTACHMENT,
        );
        let params = GpuUpsampleParams {
            full_to_low: [
                size[0] as f32 / full_size[0].max(1) as f32,
                size[1] as f32 / full_size[1].max(1) as f32,
            ],
            plane_tolerance_px: PLANE_TOLERANCE_PX_PER_DOWNSAMPLE * downsample as f32,
            min_matched_weight: MIN_MATCHED_WEIGHT,
            max_lighting_ratio: MAX_LIGHTING_RATIO,
            lighting_floor: LIGHTING_FLOOR,
            _pad: [0.0; 2],
        };
        let params = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some("upsample parameters"),
            contents: bytemuck::bytes_of(&params),
            usage: wgpu::BufferUsages::UNIFORM,
        });
        let bind_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("low-resolution samples"),
            layout,
            entries: &numbered_entries([
                params.as_entire_binding(),
                wgpu::BindingResource::TextureView(&views[0]),
            ]),
        });
        LowResolutionTargets {
            full_size,
            downsample,
            size,
            views,
            depth,
            bind_group,
        }
    }

    /// Whether these serve frames of `full_size` at `downsample`.
    pub fn fits(&self, full_size: [u32; 2], downsample: u32) -> bool {
        self.full_size == full_size && self.downsample == downsample
    }

    /// The depth attachment, cleared by the depth pass (`clear`) and kept for the shading.
    pub(crate) fn depth_attachment(&self, clear: bool) -> wgpu::RenderPassDepthStencilAttachment<'_> {
        wgpu::RenderPassDepthStencilAttachment {
            view: &self.depth,
            depth_ops: Some(wgpu::Operations {
                load: if clear {
                    wgpu::LoadOp::Clear(1.0)
                } else {
                    wgpu::LoadOp::Load
                },
                store: if clear {
                    wgpu::StoreOp::Store
                } else {
                    wgpu::StoreOp::Discard
                },
            }),
            stencil_ops: None,
        }
    }

    /// The sample attachments, cleared (view depth 0 marks "no surface").
    pub(crate) fn color_attachments(&self) -> Vec<Option<wgpu::RenderPassColorAttachment<'_>>> {
        self.views
            .iter()
            .map(|view| {
                Some(wgpu::RenderPassColorAttachment {
                    view,
                    depth_slice: None,
                    resolve_target: None,
                    ops: wgpu::Operations {
                        load: wgpu::LoadOp::Clear(wgpu::Color::TRANSPARENT),
                        store: wgpu::StoreOp::Store,
                    },
                })
            })
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_low_resolution_image_covers_every_pixel() {
        assert_eq!(low_resolution_size(960, 540, 2), [480, 270]);
        assert_eq!(low_resolution_size(961, 541, 2), [481, 271]);
        assert_eq!(low_resolution_size(5, 3, 4), [2, 1]);
        assert_eq!(low_resolution_size(1, 1, 4), [1, 1]);
        assert_eq!(low_resolution_size(7, 7, 1), [7, 7]);
    }
}
