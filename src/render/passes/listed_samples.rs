//! Two-level reduced shading's low-resolution samples that the soft layer does not serve,
//! listed and shaded in full in compute passes (shaders/listed_samples.wgsl says why):
//! after the sharp pass, which leaves them without a surface in the samples' image, one
//! pass lists them and turns the list's length into workgroup counts, and one shades
//! them, 64 at a time, into the samples and the SH path's light kept at them.

use super::kept_harmonic::SAMPLES_FORMAT;
use super::surface_buffer::image_extent;
use super::{scene_compute_pass, scene_compute_pipeline};
use crate::render::RenderError;
use crate::render::descriptors::{
    buffer_type, frame_texture, layout_entry, list_counts_and_dispatch_args, slot_entries, storage_buffer_entry,
    texture_entry, written_texture_entry,
};
use crate::render::pass_timer::TimedEncoder;
use crate::render::readback::read_buffer;
use crate::shading::wgsl::slots;

/// The list's entries: a sample's x | y << 16.
const LIST_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::R32Uint;

/// The listing's square workgroups' side (listed_samples.wgsl's LISTING_SIDE).
const LISTING_SIDE: u32 = 8;

/// The pipelines and the layouts of their group 3.
pub(super) struct ListedSamplesPipelines {
    /// The listing and the dispatch arguments: the samples read, the list written, the
    /// count, the arguments, the generation (whether the last frame's kept light is this
    /// frame's goes on the list: listed_samples.wgsl's KEPT_CURRENT_BIT says why).
    list_layout: wgpu::BindGroupLayout,
    /// The shading: the list, the count, the samples and the kept light written, the last
    /// frame's kept light read.
    shade_layout: wgpu::BindGroupLayout,
    list: wgpu::ComputePipeline,
    dispatch_args: wgpu::ComputePipeline,
    shade: wgpu::ComputePipeline,
}

impl ListedSamplesPipelines {
    /// The pipelines from `module` with `constants` (the compiled paths and the samples'
    /// spacing, LEVEL_STRIDE_PX) and the scene's groups 0–2 `groups`.
    pub fn new(
        device: &wgpu::Device,
        module: &wgpu::ShaderModule,
        groups: [&wgpu::BindGroupLayout; 3],
        constants: &[(&str, f64)],
    ) -> ListedSamplesPipelines {
        let compute = wgpu::ShaderStages::COMPUTE;
        let written = |slot, format| written_texture_entry(slot, compute, format);
        let uint_texture = |slot| texture_entry(slot, compute, wgpu::TextureSampleType::Uint);
        let count = storage_buffer_entry(slots::LISTED_SAMPLES_COUNT, compute, false);
        let layout = |label, entries: &[wgpu::BindGroupLayoutEntry]| {
            device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
                label: Some(label),
                entries,
            })
        };
        let list_layout = layout(
            "low-resolution samples listed",
            &[
                uint_texture(slots::LOW_SAMPLES),
                written(slots::LISTED_SAMPLES_OUT, LIST_FORMAT),
                count,
                storage_buffer_entry(slots::LISTED_SAMPLES_ARGS, compute, false),
                layout_entry(
                    slots::KEPT_HARMONIC_GENERATION,
                    compute,
                    buffer_type(wgpu::BufferBindingType::Uniform),
                ),
            ],
        );
        let shade_layout = layout(
            "listed samples shaded in full",
            &[
                uint_texture(slots::LISTED_SAMPLES),
                count,
                written(slots::LOW_SAMPLES_OUT, SAMPLES_FORMAT),
                written(slots::KEPT_AT_SAMPLES_OUT, SAMPLES_FORMAT),
                uint_texture(slots::KEPT_HARMONIC_READ),
            ],
        );
        let pipeline = |entry_point: &str, group_3: &wgpu::BindGroupLayout| {
            scene_compute_pipeline(device, module, entry_point, (groups, group_3), constants)
        };
        ListedSamplesPipelines {
            list: pipeline("cs_list_unshaded_samples", &list_layout),
            dispatch_args: pipeline("cs_listed_samples_dispatch_args", &list_layout),
            shade: pipeline("cs_shade_listed_samples", &shade_layout),
            list_layout,
            shade_layout,
        }
    }

    /// Lists the samples on a surface the sharp pass left and shades them in full, the
    /// kept light read from image `read` of the samples' pair (`KeptAtSamples`) and
    /// written to the other; `groups`: groups 0–2 (frame, surface buffer, shadow).
    pub fn draw(&self, frame: &mut TimedEncoder, listed: &ListedSamples, read: usize, groups: [&wgpu::BindGroup; 3]) {
        frame.encoder.clear_buffer(&listed.count, 0, None);
        let pass = |frame: &mut TimedEncoder, label, run: &dyn Fn(&mut wgpu::ComputePass<'_>)| {
            scene_compute_pass(frame, label, groups, run)
        };
        pass(frame, "low-resolution samples listed", &|pass| {
            pass.set_pipeline(&self.list);
            pass.set_bind_group(slots::PASS_GROUP, &listed.list_group, &[]);
            let [width, height] = listed.size;
            pass.dispatch_workgroups(width.div_ceil(LISTING_SIDE), height.div_ceil(LISTING_SIDE), 1);
            pass.set_pipeline(&self.dispatch_args);
            pass.dispatch_workgroups(1, 1, 1);
        });
        pass(frame, "listed samples shaded in full", &|pass| {
            pass.set_pipeline(&self.shade);
            pass.set_bind_group(slots::PASS_GROUP, &listed.shade_groups[read], &[]);
            pass.dispatch_workgroups_indirect(&listed.args, 0);
        });
    }
}

/// One size's list of samples, its count and dispatch arguments, and the bind groups.
pub(crate) struct ListedSamples {
    /// The samples' image's size.
    size: [u32; 2],
    count: wgpu::Buffer,
    args: wgpu::Buffer,
    list_group: wgpu::BindGroup,
    /// Group k reads the kept light's image k and writes the other.
    shade_groups: [wgpu::BindGroup; 2],
}

/// What the listed samples are read from and written to: the samples' image, the pair of
/// images of the SH path's light kept at the samples, and the generation that light is
/// kept with.
pub(crate) struct ListedSamplesTargets<'a> {
    pub samples: &'a wgpu::TextureView,
    pub kept: [&'a wgpu::TextureView; 2],
    pub generation: &'a wgpu::Buffer,
}

impl ListedSamples {
    /// The list for samples of `size` and the bind groups of `pipelines` over `targets`.
    pub(super) fn new(
        device: &wgpu::Device,
        pipelines: &ListedSamplesPipelines,
        size: [u32; 2],
        targets: ListedSamplesTargets<'_>,
    ) -> ListedSamples {
        let (count, args) = list_counts_and_dispatch_args(device, "listed samples", 1);
        let list = frame_texture(
            device,
            "low-resolution samples to shade in full",
            image_extent(size),
            LIST_FORMAT,
            1,
            wgpu::TextureUsages::STORAGE_BINDING | wgpu::TextureUsages::TEXTURE_BINDING,
            &[],
        )
        .create_view(&Default::default());
        let view = wgpu::BindingResource::TextureView;
        let list_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("low-resolution samples listed"),
            layout: &pipelines.list_layout,
            entries: &slot_entries([
                (slots::LOW_SAMPLES, view(targets.samples)),
                (slots::LISTED_SAMPLES_OUT, view(&list)),
                (slots::LISTED_SAMPLES_COUNT, count.as_entire_binding()),
                (slots::LISTED_SAMPLES_ARGS, args.as_entire_binding()),
                (slots::KEPT_HARMONIC_GENERATION, targets.generation.as_entire_binding()),
            ]),
        });
        let shade_groups = std::array::from_fn(|read| {
            device.create_bind_group(&wgpu::BindGroupDescriptor {
                label: Some("listed samples shaded in full"),
                layout: &pipelines.shade_layout,
                entries: &slot_entries([
                    (slots::LISTED_SAMPLES, view(&list)),
                    (slots::LISTED_SAMPLES_COUNT, count.as_entire_binding()),
                    (slots::LOW_SAMPLES_OUT, view(targets.samples)),
                    (slots::KEPT_AT_SAMPLES_OUT, view(targets.kept[1 - read])),
                    (slots::KEPT_HARMONIC_READ, view(targets.kept[read])),
                ]),
            })
        });
        ListedSamples {
            size,
            count,
            args,
            list_group,
            shade_groups,
        }
    }
}

impl ListedSamples {
    /// How many samples the last frame listed.
    pub(crate) fn count(&self, device: &wgpu::Device, queue: &wgpu::Queue) -> Result<u32, RenderError> {
        let bytes = read_buffer(device, queue, &self.count, 4)?;
        Ok(u32::from_le_bytes([bytes[0], bytes[1], bytes[2], bytes[3]]))
    }
}
