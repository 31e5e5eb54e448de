//! The pixels the deferred upsampling leaves, listed and shaded densely (see
//! shaders/listed_pixels.wgsl for why): a compute pass lists the surface pixels whose depth
//! the upsampling left below 1, compute passes shade each list 64 pixels at a time
//! (dispatched indirectly, as many workgroups as a list holds) into an image at those
//! pixels, and a full-screen pass with the upsampling's depth test copies that image into
//! the frame where the upsampling did not draw.
//!
//! The pipelines ([`ListedPixelsPipelines`]) belong to a scene pipeline; the lists, the
//! colours and the depth the upsampling marks ([`ListedPixels`]) to the frame size's
//! reduced-shading targets.

use super::surface_buffer::{depth_texture, image_extent};
use crate::render::descriptors::{buffer_type, frame_texture, layout_entry, slot_entries, storage_buffer_entry};
use crate::render::pass_timer::TimedEncoder;
use crate::shading::gpu_types::GpuUpsampleParams;
use crate::shading::wgsl::slots;
use wgpu::util::DeviceExt;

/// Where the colours of listed pixels wait to be drawn: full f32, so a pixel's colour
/// reaches the frame exactly as a fragment shader would have written it.
const LISTED_COLOURS_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba32Float;

/// The lists' entries: a pixel's x | y << 16.
const LIST_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::R32Uint;

/// The listing pass's workgroup: LIST_WORKGROUP_SIDE² invocations, each looking at
/// LIST_RUN_PX pixels along a row (override constants of listed_pixels.wgsl).
const LIST_WORKGROUP_SIDE: u32 = 8;
const LIST_RUN_PX: u32 = 4;

/// Byte offsets of the shading passes' workgroup counts in the dispatch arguments.
const SHARP_ARGS_OFFSET: u64 = 0;
const FULL_ARGS_OFFSET: u64 = 12;

/// The bind group layouts of the listed pixels' passes (group 3 of each).
pub struct ListedPixelsLayouts {
    /// The listing: the marked depth, the lists' lengths and the lists written.
    pub listing: wgpu::BindGroupLayout,
    /// The pass that turns the lists' lengths into workgroup counts.
    pub dispatch_args: wgpu::BindGroupLayout,
    /// The shading from the soft layer: the soft layer read at full resolution, the sharp
    /// list read, the full list written, the colours.
    pub sharp: wgpu::BindGroupLayout,
    /// The shading in full: the full list read, the colours.
    pub full: wgpu::BindGroupLayout,
    /// The full-screen pass that draws the colours.
    pub colours: wgpu::BindGroupLayout,
}

impl ListedPixelsLayouts {
    pub fn new(device: &wgpu::Device) -> ListedPixelsLayouts {
        let compute = wgpu::ShaderStages::COMPUTE;
        let texture = |slot, stages, sample_type| {
            layout_entry(
                slot,
                stages,
                wgpu::BindingType::Texture {
                    sample_type,
                    view_dimension: wgpu::TextureViewDimension::D2,
                    multisampled: false,
                },
            )
        };
        let uint_texture = |slot| texture(slot, compute, wgpu::TextureSampleType::Uint);
        let written = |slot, format| {
            layout_entry(
                slot,
                compute,
                wgpu::BindingType::StorageTexture {
                    access: wgpu::StorageTextureAccess::WriteOnly,
                    format,
                    view_dimension: wgpu::TextureViewDimension::D2,
                },
            )
        };
        let counts = storage_buffer_entry(slots::LIST_COUNTS, compute, false);
        let layout = |label, entries: &[wgpu::BindGroupLayoutEntry]| {
            device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
                label: Some(label),
                entries,
            })
        };
        ListedPixelsLayouts {
            listing: layout(
                "pixels left listed",
                &[
                    texture(slots::FRAME_DEPTH, compute, wgpu::TextureSampleType::Depth),
                    counts,
                    written(slots::SHARP_PIXELS_OUT, LIST_FORMAT),
                    written(slots::FULL_PIXELS_OUT, LIST_FORMAT),
                ],
            ),
            dispatch_args: layout(
                "listed pixels' dispatch arguments",
                &[counts, storage_buffer_entry(slots::DISPATCH_ARGS, compute, false)],
            ),
            sharp: layout(
                "listed pixels shaded from the soft layer",
                &[
                    layout_entry(slots::UPSAMPLE, compute, buffer_type(wgpu::BufferBindingType::Uniform)),
                    uint_texture(slots::LOW_SAMPLES),
                    counts,
                    uint_texture(slots::SHARP_PIXELS),
                    written(slots::FULL_PIXELS_OUT, LIST_FORMAT),
                    written(slots::LISTED_COLOURS, LISTED_COLOURS_FORMAT),
                ],
            ),
            full: layout(
                "listed pixels shaded in full",
                &[
                    counts,
                    uint_texture(slots::FULL_PIXELS),
                    written(slots::LISTED_COLOURS, LISTED_COLOURS_FORMAT),
                ],
            ),
            colours: layout(
                "listed pixels' colours",
                &[texture(
                    slots::LISTED_COLOURS_READ,
                    wgpu::ShaderStages::FRAGMENT,
                    wgpu::TextureSampleType::Float { filterable: false },
                )],
            ),
        }
    }
}

/// The compute pipelines of the listed pixels (the full-screen pass that draws them is
/// built with the other full-screen passes).
pub(super) struct ListedPixelsPipelines {
    list: wgpu::ComputePipeline,
    dispatch_args: wgpu::ComputePipeline,
    /// Two-level shading: the listed pixels from the soft layer and the sharp lights.
    shade_sharp: Option<wgpu::ComputePipeline>,
    shade_full: wgpu::ComputePipeline,
}

impl ListedPixelsPipelines {
    /// The pipelines from `module` with `constants` (the compiled paths), the scene's
    /// groups 0–2 `groups`; `two_level`: with the sharp list.
    pub fn new(
        device: &wgpu::Device,
        module: &wgpu::ShaderModule,
        (groups, layouts): ([&wgpu::BindGroupLayout; 3], &ListedPixelsLayouts),
        constants: &[(&str, f64)],
        two_level: bool,
    ) -> ListedPixelsPipelines {
        let mut constants = constants.to_vec();
        let pipeline = |entry_point: &str, group_3: &wgpu::BindGroupLayout, constants: &[(&str, f64)]| {
            let bind_group_layouts: Vec<Option<&wgpu::BindGroupLayout>> =
                groups.iter().copied().chain([group_3]).map(Some).collect();
            let layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
                label: Some(entry_point),
                bind_group_layouts: &bind_group_layouts,
                immediate_size: 0,
            });
            device.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
                label: Some(entry_point),
                layout: Some(&layout),
                module,
                entry_point: Some(entry_point),
                compilation_options: wgpu::PipelineCompilationOptions {
                    constants,
                    ..Default::default()
                },
                cache: None,
            })
        };
        let shade_sharp = two_level.then(|| pipeline("cs_shade_listed_sharp", &layouts.sharp, &constants));
        let shade_full = pipeline("cs_shade_listed_full", &layouts.full, &constants);
        let dispatch_args = pipeline("cs_dispatch_args", &layouts.dispatch_args, &[]);
        constants.extend([
            ("LIST_FOR_SHARP", if two_level { 1.0 } else { 0.0 }),
            ("LIST_WORKGROUP_SIDE", f64::from(LIST_WORKGROUP_SIDE)),
            ("LIST_RUN_PX", f64::from(LIST_RUN_PX)),
        ]);
        ListedPixelsPipelines {
            list: pipeline("cs_list_unshaded", &layouts.listing, &constants),
            dispatch_args,
            shade_sharp,
            shade_full,
        }
    }

    /// Lists the pixels `listed`'s depth leaves unmarked and shades them into its colours,
    /// with groups 0–2 `groups` (frame, surface buffer, shadow).
    pub fn shade(&self, frame: &mut TimedEncoder, listed: &ListedPixels, groups: [&wgpu::BindGroup; 3]) {
        frame.encoder.clear_buffer(&listed.counts, 0, None);
        let [width, height] = listed.size;
        let pass = |frame: &mut TimedEncoder, label: &'static str, run: &dyn Fn(&mut wgpu::ComputePass<'_>)| {
            let mut pass = frame.encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
                label: Some(label),
                timestamp_writes: None,
            });
            for (group, bind_group) in [slots::FRAME_GROUP, slots::MATERIAL_GROUP, slots::SHADOW_GROUP]
                .into_iter()
                .zip(groups)
            {
                pass.set_bind_group(group, bind_group, &[]);
            }
            run(&mut pass);
            drop(pass);
            frame.mark(label);
        };
        let dispatch_args = |pass: &mut wgpu::ComputePass<'_>| {
            pass.set_pipeline(&self.dispatch_args);
            pass.set_bind_group(slots::PASS_GROUP, &listed.dispatch_args_group, &[]);
            pass.dispatch_workgroups(1, 1, 1);
        };
        pass(frame, "pixels left listed", &|pass| {
            pass.set_pipeline(&self.list);
            pass.set_bind_group(slots::PASS_GROUP, &listed.listing_group, &[]);
            pass.dispatch_workgroups(
                width.div_ceil(LIST_RUN_PX * LIST_WORKGROUP_SIDE),
                height.div_ceil(LIST_WORKGROUP_SIDE),
                1,
            );
            dispatch_args(pass);
        });
        if let (Some(shade_sharp), Some(sharp_group)) = (&self.shade_sharp, &listed.sharp_group) {
            pass(frame, "listed pixels shaded from the soft layer", &|pass| {
                pass.set_pipeline(shade_sharp);
                pass.set_bind_group(slots::PASS_GROUP, sharp_group, &[]);
                pass.dispatch_workgroups_indirect(&listed.dispatch_args, SHARP_ARGS_OFFSET);
                dispatch_args(pass);
            });
        }
        pass(frame, "listed pixels shaded in full", &|pass| {
            pass.set_pipeline(&self.shade_full);
            pass.set_bind_group(slots::PASS_GROUP, &listed.full_group, &[]);
            pass.dispatch_workgroups_indirect(&listed.dispatch_args, FULL_ARGS_OFFSET);
        });
    }
}

/// One frame size's lists, colours and the depth the full-resolution passes mark.
pub(crate) struct ListedPixels {
    size: [u32; 2],
    /// The frame's depth for the upsampling and the drawing of the colours: a copy of the
    /// surface buffer's, set to 1 where the upsampling draws.
    pub(crate) marks_texture: wgpu::Texture,
    pub(crate) marks: wgpu::TextureView,
    counts: wgpu::Buffer,
    dispatch_args: wgpu::Buffer,
    listing_group: wgpu::BindGroup,
    dispatch_args_group: wgpu::BindGroup,
    /// Present with a soft layer.
    sharp_group: Option<wgpu::BindGroup>,
    full_group: wgpu::BindGroup,
    /// Group 3 of the pass that draws the colours into the frame.
    pub(crate) colours_group: wgpu::BindGroup,
}

impl ListedPixels {
    /// Lists and images for frames of `size`; `soft_layer`: the soft layer the listed
    /// pixels upsample (its view and how a full-resolution reader finds its samples),
    /// with two-level shading.
    pub fn new(
        device: &wgpu::Device,
        layouts: &ListedPixelsLayouts,
        size: [u32; 2],
        soft_layer: Option<(&wgpu::TextureView, GpuUpsampleParams)>,
    ) -> ListedPixels {
        let marks = depth_texture(
            device,
            "frame marks",
            size,
            wgpu::TextureUsages::COPY_DST | wgpu::TextureUsages::TEXTURE_BINDING,
        );
        let marks_view = marks.create_view(&Default::default());
        let buffer = |label, bytes: u64, usage| {
            device.create_buffer(&wgpu::BufferDescriptor {
                label: Some(label),
                size: bytes,
                usage,
                mapped_at_creation: false,
            })
        };
        let storage = wgpu::BufferUsages::STORAGE;
        let counts = buffer("listed pixels' counts", 8, storage | wgpu::BufferUsages::COPY_DST);
        let dispatch_args = buffer("listed pixels' dispatch arguments", 24, storage | wgpu::BufferUsages::INDIRECT);
        let image = |label, format| {
            frame_texture(
                device,
                label,
                image_extent(size),
                format,
                1,
                wgpu::TextureUsages::STORAGE_BINDING | wgpu::TextureUsages::TEXTURE_BINDING,
                &[],
            )
            .create_view(&Default::default())
        };
        let sharp_pixels = image("pixels to shade from the soft layer", LIST_FORMAT);
        let full_pixels = image("pixels to shade in full", LIST_FORMAT);
        let colours = image("listed pixels' colours", LISTED_COLOURS_FORMAT);
        let view = wgpu::BindingResource::TextureView;
        let group = |label, layout, entries: &[wgpu::BindGroupEntry<'_>]| {
            device.create_bind_group(&wgpu::BindGroupDescriptor {
                label: Some(label),
                layout,
                entries,
            })
        };
        let sharp_group = soft_layer.map(|(soft_view, params)| {
            let params = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
                label: Some("soft layer at full resolution"),
                contents: bytemuck::bytes_of(&params),
                usage: wgpu::BufferUsages::UNIFORM,
            });
            group(
                "listed pixels shaded from the soft layer",
                &layouts.sharp,
                &slot_entries([
                    (slots::UPSAMPLE, params.as_entire_binding()),
                    (slots::LOW_SAMPLES, view(soft_view)),
                    (slots::LIST_COUNTS, counts.as_entire_binding()),
                    (slots::SHARP_PIXELS, view(&sharp_pixels)),
                    (slots::FULL_PIXELS_OUT, view(&full_pixels)),
                    (slots::LISTED_COLOURS, view(&colours)),
                ]),
            )
        });
        ListedPixels {
            size,
            listing_group: group(
                "pixels left listed",
                &layouts.listing,
                &slot_entries([
                    (slots::FRAME_DEPTH, view(&marks_view)),
                    (slots::LIST_COUNTS, counts.as_entire_binding()),
                    (slots::SHARP_PIXELS_OUT, view(&sharp_pixels)),
                    (slots::FULL_PIXELS_OUT, view(&full_pixels)),
                ]),
            ),
            dispatch_args_group: group(
                "listed pixels' dispatch arguments",
                &layouts.dispatch_args,
                &slot_entries([
                    (slots::LIST_COUNTS, counts.as_entire_binding()),
                    (slots::DISPATCH_ARGS, dispatch_args.as_entire_binding()),
                ]),
            ),
            sharp_group,
            full_group: group(
                "listed pixels shaded in full",
                &layouts.full,
                &slot_entries([
                    (slots::LIST_COUNTS, counts.as_entire_binding()),
                    (slots::FULL_PIXELS, view(&full_pixels)),
                    (slots::LISTED_COLOURS, view(&colours)),
                ]),
            ),
            colours_group: group(
                "listed pixels' colours",
                &layouts.colours,
                &slot_entries([(slots::LISTED_COLOURS_READ, view(&colours))]),
            ),
            marks_texture: marks,
            marks: marks_view,
            counts,
            dispatch_args,
        }
    }
}
