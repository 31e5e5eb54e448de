//! The light of the SH path kept where it was shaded in full: the exposed light as
//! pack_lighting's two words and the generation of the inputs it was shaded with; a frame
//! of the same generation reads it instead of walking the blockers. The generation (never
//! 0, which the images hold at first) changes whenever the surfaces or the soft light's
//! inputs do (`LowResolutionTargets::expect_inputs`), as the soft layer is kept.
//!
//! - At the full-resolution pixels cs_shade_listed_full shades (full_resolution.wgsl's
//!   kept_harmonic_light): three r32uint images read and written in place
//!   ([`KeptHarmonicImages`]).
//! - At the low-resolution samples shaded in full (fs_shade_low; with two levels
//!   cs_shade_listed_samples, listed_samples.wgsl): one image read and another written
//!   — as a second colour target, or a storage image — swapped every frame
//!   ([`KeptAtSamples`]). The
//!   samples it shades depend on the surfaces and the soft layer alone, so a frame of the
//!   last frame's generation shades the same ones and reads them all: one flag for the
//!   whole pass (lavapipe runs a branch for a block of fragments, those the depth test
//!   left out too, so a stamp per sample kept the walk). (Storage written by a fragment
//!   shader runs it before its depth test unless it is marked for early tests, a
//!   capability wgpu has only as a native feature: every sample, not only those left,
//!   paid for the walk.) Each texel is a sample of the soft light alone
//!   (reduced_shading.wgsl's format: view depth, lighting per unit reflectance, normal),
//!   and with two levels fs_shade_sharp_marking writes the soft layer upsampled at the
//!   samples it shades, so the image written holds the soft light at every sample: the
//!   listed pixels upsample it (full_resolution.wgsl's cs_shade_listed_sharp).

use super::surface_buffer::{cleared, image_extent};
use crate::render::descriptors::{buffer_type, frame_texture, layout_entry, slot_entries, texture_entry};
use crate::shading::wgsl::slots::{self, Slot};

/// The full-resolution images' format: one that every device reads and writes in place.
const FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::R32Uint;

/// The samples' kept light: a sample of the soft light (reduced_shading.wgsl's texel).
pub(super) const SAMPLES_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba32Uint;

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

/// Sets `buffer` (from [`generation_buffer`]) to `generation`, and whether the samples'
/// kept light read this frame is of that generation (`samples_current`).
pub(super) fn set_generation(queue: &wgpu::Queue, buffer: &wgpu::Buffer, generation: u32, samples_current: bool) {
    queue.write_buffer(
        buffer,
        0,
        bytemuck::bytes_of(&[generation, u32::from(samples_current), 0, 0]),
    );
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

/// The layout of fs_shade_low's group 3: the last frame's kept light read, the generation.
pub(super) fn samples_layout(device: &wgpu::Device) -> wgpu::BindGroupLayout {
    let fragment = wgpu::ShaderStages::FRAGMENT;
    device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
        label: Some("SH path's light kept at the samples"),
        entries: &[
            texture_entry(slots::KEPT_HARMONIC_READ, fragment, wgpu::TextureSampleType::Uint),
            layout_entry(
                slots::KEPT_HARMONIC_GENERATION,
                fragment,
                buffer_type(wgpu::BufferBindingType::Uniform),
            ),
        ],
    })
}

/// The samples' kept light: two images, one read and one written by each frame.
pub(super) struct KeptAtSamples {
    images: [wgpu::TextureView; 2],
    /// Group k reads image k (the other is written).
    groups: [wgpu::BindGroup; 2],
    /// The image the next frame reads.
    read: usize,
    /// The generation of the light the image written last holds, if one was written.
    written_generation: Option<u32>,
}

impl KeptAtSamples {
    pub(super) fn new(
        device: &wgpu::Device,
        layout: &wgpu::BindGroupLayout,
        size: [u32; 2],
        generation: &wgpu::Buffer,
    ) -> KeptAtSamples {
        let images: [wgpu::TextureView; 2] = std::array::from_fn(|_| {
            frame_texture(
                device,
                "SH path's light kept at the samples",
                image_extent(size),
                SAMPLES_FORMAT,
                1,
                wgpu::TextureUsages::RENDER_ATTACHMENT
                    | wgpu::TextureUsages::TEXTURE_BINDING
                    | wgpu::TextureUsages::STORAGE_BINDING,
                &[],
            )
            .create_view(&Default::default())
        });
        let groups = std::array::from_fn(|k| {
            device.create_bind_group(&wgpu::BindGroupDescriptor {
                label: Some("SH path's light kept at the samples"),
                layout,
                entries: &slot_entries([
                    (
                        slots::KEPT_HARMONIC_READ,
                        wgpu::BindingResource::TextureView(&images[k]),
                    ),
                    (slots::KEPT_HARMONIC_GENERATION, generation.as_entire_binding()),
                ]),
            })
        });
        KeptAtSamples {
            images,
            groups,
            read: 0,
            written_generation: None,
        }
    }

    /// Swaps the images for a frame of `generation`, which reads what the last frame
    /// wrote; true when that is of this generation.
    pub(super) fn next_frame(&mut self, generation: u32) -> bool {
        self.read = 1 - self.read;
        let current = self.written_generation == Some(generation);
        self.written_generation = Some(generation);
        current
    }

    /// fs_shade_low's group 3 this frame.
    pub(super) fn read_group(&self) -> &wgpu::BindGroup {
        &self.groups[self.read]
    }

    /// The colour target fs_shade_low writes this frame, cleared (view depth 0: no
    /// surface, where neither shading pass writes).
    pub(super) fn written(&self) -> Option<wgpu::RenderPassColorAttachment<'_>> {
        cleared(&self.images[self.written_index()])
    }

    /// Which of [`Self::images`] this frame reads.
    pub(super) fn read_index(&self) -> usize {
        self.read
    }

    /// Which of [`Self::images`] this frame writes.
    pub(super) fn written_index(&self) -> usize {
        1 - self.read
    }

    /// The two images, in the order [`Self::written_index`] counts.
    pub(super) fn images(&self) -> [&wgpu::TextureView; 2] {
        [&self.images[0], &self.images[1]]
    }
}
