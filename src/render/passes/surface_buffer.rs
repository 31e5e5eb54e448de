//! The full-resolution surface buffer of deferred reduced shading (`reduced_shading`):
//! the two images fs_surface_buffer writes and their depth, the bind group (group 1 of
//! the full-screen passes) that reads them, and the kept factors of the shadow-map
//! path's lights at the low-resolution samples (lobes × falloff × visibility at unit
//! intensity) (written by
//! fs_mark_surface_samples_keeping_visibility, read by the samples' shading; see
//! low_resolution.wgsl), with the key that says when it still holds.

use crate::render::descriptors::{
    DEPTH_FORMAT, depth_attachment, frame_texture, slot_entries, storage_buffer_entry, texture_entry,
};
use crate::shading::wgsl::slots;

/// Formats of the surface buffer fs_surface_buffer writes (see low_resolution.wgsl).
pub const SURFACE_BUFFER_FORMATS: [wgpu::TextureFormat; 2] = [wgpu::TextureFormat::Rgba32Uint; 2];

/// The bind group layout (group 1 of the full-screen passes, in place of the material)
/// through which the low-resolution shading reads the surface buffer.
pub fn surface_buffer_layout(device: &wgpu::Device) -> wgpu::BindGroupLayout {
    // Read by the full-screen passes and by the compute passes shading the pixels the
    // upsampling leaves (full_resolution.wgsl) and the samples the soft layer leaves
    // (listed_samples.wgsl, the kept factors too).
    let stages = wgpu::ShaderStages::FRAGMENT | wgpu::ShaderStages::COMPUTE;
    let texture = |slot| texture_entry(slot, stages, wgpu::TextureSampleType::Uint);
    device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
        label: Some("surface buffer"),
        entries: &[
            texture(slots::SURFACE_BUFFER_A),
            texture(slots::SURFACE_BUFFER_B),
            storage_buffer_entry(slots::KEPT_MAPPED_FACTORS, stages, true),
        ],
    })
}

/// The bind group layout (group 3 of fs_mark_surface_samples_keeping_visibility) through
/// which the samples' factors of the mapped lights are written.
pub fn mapped_factors_writer_layout(device: &wgpu::Device) -> wgpu::BindGroupLayout {
    let storage = |slot, read_only| storage_buffer_entry(slot, wgpu::ShaderStages::FRAGMENT, read_only);
    device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
        label: Some("kept factors of the mapped lights, written"),
        entries: &[
            storage(slots::MAPPED_FACTORS_OUT, false),
            storage(slots::STALE_LIGHTS, true),
        ],
    })
}

/// The most memory the kept factors of the shadow-map path's lights may take (the
/// low-resolution samples × the mapped lights × 8 bytes; wgpu's default limit on a
/// storage buffer's binding): past it the shading passes read the maps every frame. The
/// studio at 960 × 540 (320 × 180 samples) with its nine mapped lights takes 4.1 MB.
pub const MAPPED_FACTORS_BUDGET_BYTES: u64 = 128 << 20;

/// The full-resolution surfaces: two images, their depth (which the pass drawing the
/// deferred full-resolution frame's colours tests), and the bind group through which the
/// full-screen passes read them.
pub(crate) struct SurfaceBuffer {
    views: [wgpu::TextureView; 2],
    /// The surfaces' depth, which the frame's edge filter reads too (copied into the
    /// target's depth: `RenderTarget::copy_depth_from`).
    pub(crate) depth: wgpu::Texture,
    depth_view: wgpu::TextureView,
    pub bind_group: wgpu::BindGroup,
    layouts: [wgpu::BindGroupLayout; 2],
    /// Entries per light of the kept factors: the low-resolution samples.
    samples: u64,
    /// The diffuse and glossy factors (two f32) of each light on the shadow-map path at
    /// each low-resolution sample, at unit intensity and shadowed (low_resolution.wgsl,
    /// `kept_mapped_factors`), written by the pass marking the samples on a surface when
    /// the surfaces, those lights or their maps changed, and read by the shading passes:
    /// a stroke's frame reads no map and evaluates no lobe at the samples. At least 8
    /// bytes; too short for the frame's lights, the passes read the maps instead.
    mapped_factors: wgpu::Buffer,
    /// 1 for each mapped light whose factors the writing pass computes anew, 0 for
    /// those it keeps (`MappedVisibilityKey::stale_lights`).
    stale_lights: wgpu::Buffer,
    /// Group 3 of the marking pass that writes it.
    pub(crate) mapped_factors_writer: wgpu::BindGroup,
    /// The surface group with an 8-byte buffer in its place, for that pass (a buffer
    /// written in a pass may not be bound for reading in it too).
    pub(crate) bind_group_without_factors: wgpu::BindGroup,
}

impl SurfaceBuffer {
    pub(super) fn new(
        device: &wgpu::Device,
        [layout, writer_layout]: [&wgpu::BindGroupLayout; 2],
        size: [u32; 2],
        samples: [u32; 2],
    ) -> SurfaceBuffer {
        let views = SURFACE_BUFFER_FORMATS.map(|format| {
            frame_texture(
                device,
                "surface buffer",
                image_extent(size),
                format,
                1,
                SAMPLED_TARGET,
                &[],
            )
            .create_view(&Default::default())
        });
        let mapped_factors = mapped_factors_buffer(device, 8);
        let stale_lights = stale_lights_buffer(device, 1);
        let bind_group = surface_bind_group(device, layout, &views, &mapped_factors);
        let depth = depth_texture(device, "surface buffer depth", size, wgpu::TextureUsages::COPY_SRC);
        SurfaceBuffer {
            depth_view: depth.create_view(&Default::default()),
            depth,
            bind_group,
            layouts: [layout.clone(), writer_layout.clone()],
            samples: u64::from(samples[0]) * u64::from(samples[1]),
            mapped_factors_writer: writer_group(device, writer_layout, [&mapped_factors, &stale_lights]),
            stale_lights,
            bind_group_without_factors: surface_bind_group(device, layout, &views, &mapped_factors_buffer(device, 8)),
            mapped_factors,
            views,
        }
    }

    /// Makes the kept factors hold `lights` mapped lights at every sample where that
    /// fits [`MAPPED_FACTORS_BUDGET_BYTES`] and the device's limits on a storage
    /// binding and a buffer; true when the buffer is new (it holds nothing yet).
    pub(super) fn reserve_mapped_factors(&mut self, device: &wgpu::Device, lights: usize) -> bool {
        let bytes = self.samples * lights as u64 * 8;
        let limits = device.limits();
        let budget = MAPPED_FACTORS_BUDGET_BYTES
            .min(limits.max_storage_buffer_binding_size)
            .min(limits.max_buffer_size);
        if bytes <= self.mapped_factors.size() || bytes > budget {
            return false;
        }
        self.mapped_factors = mapped_factors_buffer(device, bytes);
        self.bind_group = surface_bind_group(device, &self.layouts[0], &self.views, &self.mapped_factors);
        self.mapped_factors_writer = writer_group(device, &self.layouts[1], [&self.mapped_factors, &self.stale_lights]);
        true
    }

    /// Has the writing pass compute the factors of the lights `stale` marks (1) and
    /// keep the others'.
    pub(super) fn write_stale_lights(&mut self, device: &wgpu::Device, queue: &wgpu::Queue, stale: &[u32]) {
        let bytes = (stale.len().max(1) * 4) as u64;
        if bytes > self.stale_lights.size() {
            self.stale_lights = stale_lights_buffer(device, stale.len());
            self.mapped_factors_writer =
                writer_group(device, &self.layouts[1], [&self.mapped_factors, &self.stale_lights]);
        }
        if !stale.is_empty() {
            queue.write_buffer(&self.stale_lights, 0, bytemuck::cast_slice(stale));
        }
    }

    /// The surface images, cleared (view depth 0 marks "no surface").
    pub(crate) fn color_attachments(&self) -> Vec<Option<wgpu::RenderPassColorAttachment<'_>>> {
        self.views.iter().map(cleared).collect()
    }

    /// Its depth attachment, cleared and kept (later frames may reuse it).
    pub(crate) fn depth_attachment(&self) -> wgpu::RenderPassDepthStencilAttachment<'_> {
        depth_attachment(&self.depth_view, Some(1.0), true)
    }
}

fn mapped_factors_buffer(device: &wgpu::Device, bytes: u64) -> wgpu::Buffer {
    device.create_buffer(&wgpu::BufferDescriptor {
        label: Some("kept factors of the mapped lights"),
        size: bytes.max(8),
        usage: wgpu::BufferUsages::STORAGE,
        mapped_at_creation: false,
    })
}

fn stale_lights_buffer(device: &wgpu::Device, lights: usize) -> wgpu::Buffer {
    device.create_buffer(&wgpu::BufferDescriptor {
        label: Some("mapped lights whose factors are written"),
        size: (lights.max(1) * 4) as u64,
        usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_DST,
        mapped_at_creation: false,
    })
}

fn writer_group(
    device: &wgpu::Device,
    layout: &wgpu::BindGroupLayout,
    [visibility, stale_lights]: [&wgpu::Buffer; 2],
) -> wgpu::BindGroup {
    device.create_bind_group(&wgpu::BindGroupDescriptor {
        label: Some("kept factors of the mapped lights, written"),
        layout,
        entries: &slot_entries([
            (slots::MAPPED_FACTORS_OUT, visibility.as_entire_binding()),
            (slots::STALE_LIGHTS, stale_lights.as_entire_binding()),
        ]),
    })
}

fn surface_bind_group(
    device: &wgpu::Device,
    layout: &wgpu::BindGroupLayout,
    views: &[wgpu::TextureView; 2],
    mapped_factors: &wgpu::Buffer,
) -> wgpu::BindGroup {
    device.create_bind_group(&wgpu::BindGroupDescriptor {
        label: Some("surface buffer"),
        layout,
        entries: &slot_entries([
            (slots::SURFACE_BUFFER_A, wgpu::BindingResource::TextureView(&views[0])),
            (slots::SURFACE_BUFFER_B, wgpu::BindingResource::TextureView(&views[1])),
            (slots::KEPT_MAPPED_FACTORS, mapped_factors.as_entire_binding()),
        ]),
    })
}

/// What the kept visibility of the shadow-map path's lights was computed from besides the
/// surfaces: each light's geometry (`GpuScene::mapped_light_geometry`) and its maps' views
/// as drawn (`ShadowMaps::drawn`), and the settings the pipeline was made for. A light
/// whose own entry is unchanged keeps its visibility when another moves.
#[derive(Debug, Clone, PartialEq)]
pub struct MappedVisibilityKey {
    pub lights: Vec<MappedLightKey>,
    pub settings: crate::shading::ShadowSettings,
}

/// One mapped light's part of [`MappedVisibilityKey`].
#[derive(Debug, Clone, PartialEq)]
pub struct MappedLightKey {
    pub geometry: crate::shading::gpu_types::GpuLight,
    pub views: Vec<crate::shading::gpu_types::GpuShadowView>,
}

impl MappedVisibilityKey {
    /// 1 for each light whose visibility must be computed anew after frames drawn from
    /// `last` (None: unknown, all of them), 0 for each that holds.
    pub fn stale_lights(&self, last: Option<&MappedVisibilityKey>) -> Vec<u32> {
        self.lights
            .iter()
            .enumerate()
            .map(|(k, light)| {
                let holds = last.is_some_and(|l| l.settings == self.settings && l.lights.get(k) == Some(light));
                u32::from(!holds)
            })
            .collect()
    }
}

// Texture helpers the deferred shading's targets share (here and in reduced_shading).

pub(super) fn image_extent(size: [u32; 2]) -> wgpu::Extent3d {
    wgpu::Extent3d {
        width: size[0],
        height: size[1],
        depth_or_array_layers: 1,
    }
}

pub(super) const SAMPLED_TARGET: wgpu::TextureUsages =
    wgpu::TextureUsages::RENDER_ATTACHMENT.union(wgpu::TextureUsages::TEXTURE_BINDING);

pub(super) fn depth_texture(
    device: &wgpu::Device,
    label: &str,
    size: [u32; 2],
    usage: wgpu::TextureUsages,
) -> wgpu::Texture {
    frame_texture(
        device,
        label,
        image_extent(size),
        DEPTH_FORMAT,
        1,
        wgpu::TextureUsages::RENDER_ATTACHMENT | usage,
        &[],
    )
}

/// An attachment cleared to zero.
pub(super) fn cleared(view: &wgpu::TextureView) -> Option<wgpu::RenderPassColorAttachment<'_>> {
    Some(wgpu::RenderPassColorAttachment {
        view,
        depth_slice: None,
        resolve_target: None,
        ops: wgpu::Operations {
            load: wgpu::LoadOp::Clear(wgpu::Color::TRANSPARENT),
            store: wgpu::StoreOp::Store,
        },
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::shading::gpu_types::{GpuLight, GpuShadowView};

    fn key(positions: &[f32], view_texel: f32) -> MappedVisibilityKey {
        let lights = positions
            .iter()
            .map(|&x| {
                let mut geometry: GpuLight = bytemuck::Zeroable::zeroed();
                geometry.position = [x, 1.0, 0.0, 1.0];
                let mut view: GpuShadowView = bytemuck::Zeroable::zeroed();
                view.texel[0] = view_texel;
                MappedLightKey {
                    geometry,
                    views: vec![view],
                }
            })
            .collect();
        MappedVisibilityKey {
            lights,
            settings: Default::default(),
        }
    }

    #[test]
    fn only_the_lights_that_moved_or_whose_maps_changed_are_written_again() {
        let before = key(&[0.0, 1.0, 2.0], 0.01);
        assert_eq!(before.stale_lights(None), vec![1, 1, 1], "nothing known: every light");
        assert_eq!(before.stale_lights(Some(&before)), vec![0, 0, 0]);
        assert_eq!(key(&[0.0, 1.5, 2.0], 0.01).stale_lights(Some(&before)), vec![0, 1, 0]);
        // The same lights drawn into finer maps (a draft refined): every light anew.
        assert_eq!(key(&[0.0, 1.0, 2.0], 0.005).stale_lights(Some(&before)), vec![1, 1, 1]);
        // A light added: it alone.
        assert_eq!(
            key(&[0.0, 1.0, 2.0, 3.0], 0.01).stale_lights(Some(&before)),
            vec![0, 0, 0, 1]
        );
        // New settings: every light.
        let mut resettled = before.clone();
        resettled.settings.order += 1;
        assert_eq!(resettled.stale_lights(Some(&before)), vec![1, 1, 1]);
    }
}
