//! The light of the SH path kept at the full-resolution pixels shaded in full
//! (full_resolution.wgsl's kept_harmonic_light, in cs_shade_listed_full): the exposed
//! light as pack_lighting's two words and the generation of the inputs it was shaded
//! with; a frame of the same generation reads it instead of walking the blockers. The
//! generation (never 0, which the images hold at first) changes whenever the surfaces or
//! the soft light's inputs do (`LowResolutionTargets::expect_inputs`), as the soft layer
//! is kept.
//!
//! Not at the low-resolution samples fs_shade_low shades in full: a fragment shader that
//! writes storage runs before its depth test unless it is marked for early tests (a
//! capability wgpu has only as a native feature), so every sample, not only those left,
//! paid for the walk (docs/performance.md).

use super::surface_buffer::image_extent;
use crate::render::descriptors::{buffer_type, frame_texture, layout_entry};
use crate::shading::wgsl::slots::{self, Slot};

/// The images' format: one that every device reads and writes in place.
const FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::R32Uint;

/// The layout entries of the kept light, for a pass run in `stage`: its three images
/// read and written, the generation read.
pub(super) fn layout_entries(stage: wgpu::ShaderStages) -> [wgpu::BindGroupLayoutEntry; 4] {
    let image = |slot| {
        layout_entry(
            slot,
            stage,
            wgpu::BindingType::StorageTexture {
                access: wgpu::StorageTextureAccess::ReadWrite,
                format: FORMAT,
                view_dimension: wgpu::TextureViewDimension::D2,
            },
        )
    };
    [
        image(slots::KEPT_HARMONIC_X),
        image(slots::KEPT_HARMONIC_Y),
        image(slots::KEPT_HARMONIC_STAMP),
        layout_entry(
            slots::KEPT_HARMONIC_GENERATION,
            stage,
            buffer_type(wgpu::BufferBindingType::Uniform),
        ),
    ]
}

/// The uniform holding the generation the next frames shade with (`set_generation`).
pub(super) fn generation_buffer(device: &wgpu::Device) -> wgpu::Buffer {
    device.create_buffer(&wgpu::BufferDescriptor {
        label: Some("SH path's light kept: generation"),
        size: 16,
        usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
        mapped_at_creation: false,
    })
}

/// Sets `buffer` (from [`generation_buffer`]) to `generation`.
pub(super) fn set_generation(queue: &wgpu::Queue, buffer: &wgpu::Buffer, generation: u32) {
    queue.write_buffer(buffer, 0, bytemuck::bytes_of(&[generation, 0, 0, 0]));
}

/// The kept light of an image of one size (zeros at first: no pixel kept).
pub(super) struct KeptHarmonicImages {
    x: wgpu::TextureView,
    y: wgpu::TextureView,
    stamp: wgpu::TextureView,
}

impl KeptHarmonicImages {
    pub(super) fn new(device: &wgpu::Device, size: [u32; 2]) -> KeptHarmonicImages {
        let image = |label| {
            frame_texture(
                device,
                label,
                image_extent(size),
                FORMAT,
                1,
                wgpu::TextureUsages::STORAGE_BINDING,
                &[],
            )
            .create_view(&Default::default())
        };
        KeptHarmonicImages {
            x: image("SH path's light kept: first word"),
            y: image("SH path's light kept: second word"),
            stamp: image("SH path's light kept: generation"),
        }
    }

    /// The bind group entries of these images and `generation` (layout_entries' slots).
    pub(super) fn entries<'a>(&'a self, generation: &'a wgpu::Buffer) -> [(Slot, wgpu::BindingResource<'a>); 4] {
        [
            (slots::KEPT_HARMONIC_X, wgpu::BindingResource::TextureView(&self.x)),
            (slots::KEPT_HARMONIC_Y, wgpu::BindingResource::TextureView(&self.y)),
            (
                slots::KEPT_HARMONIC_STAMP,
                wgpu::BindingResource::TextureView(&self.stamp),
            ),
            (slots::KEPT_HARMONIC_GENERATION, generation.as_entire_binding()),
        ]
    }
}
