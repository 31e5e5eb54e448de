//! The full-resolution frame of deferred reduced shading on single-sampled targets, in
//! compute passes (see shaders/full_resolution.wgsl for why): the upsampling, a d × d
//! block of pixels per invocation, writes the pixels the samples match to an image of the
//! frame's colours and lists the rest; compute passes shade each list 64 pixels at a time
//! (dispatched indirectly, as many workgroups as a list holds) into the same image, which
//! (the background written where there is no surface) is then copied into the frame's
//! image through a buffer.
//!
//! The pipelines ([`FullResolutionCompute`]) belong to a scene pipeline; the lists and the
//! colours ([`FullResolutionImages`]) to the frame size's reduced-shading targets.

use super::kept_harmonic::{self, KeptHarmonicImages};
use super::surface_buffer::image_extent;
use super::{scene_compute_pass, scene_compute_pipeline};
use crate::render::RenderError;
use crate::render::descriptors::{
    buffer_type, frame_texture, layout_entry, list_counts_and_dispatch_args, slot_entries, storage_buffer_entry,
    texture_entry, written_texture_entry,
};
use crate::render::pass_timer::TimedEncoder;
use crate::render::readback::{padded_row_bytes, read_buffer};
use crate::shading::gpu_types::GpuUpsampleParams;
use crate::shading::wgsl::slots;
use wgpu::util::DeviceExt;

/// Where the frame's colours wait to be copied into it: the sRGB-encoded bytes the
/// frame's target stores, packed in one word (full_resolution.wgsl's store_colour).
const FRAME_COLOURS_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::R32Uint;

/// The most bytes the buffer between the colours and the frame holds: the copy goes by
/// bands of rows where a frame needs more (16 MiB holds 4 million pixels: a 2560 × 1440
/// frame in one band, within every device's buffer limits).
const MAX_COPY_BAND_BYTES: u64 = 16 << 20;

/// The lists' entries: a pixel's x | y << 16.
const LIST_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::R32Uint;

/// The upsampling's workgroups: BLOCK_WORKGROUP_SIDE² invocations, each a block of d × d
/// pixels (override constants of full_resolution.wgsl).
const BLOCK_WORKGROUP_SIDE: u32 = 8;

/// Byte offsets of the shading passes' workgroup counts in the dispatch arguments.
const SHARP_ARGS_OFFSET: u64 = 0;
const FULL_ARGS_OFFSET: u64 = 12;

/// The bind group layouts of the full-resolution passes (group 3 of each).
pub struct FullResolutionLayouts {
    /// The upsampling: the samples, the lists' lengths, the lists written, the colours.
    pub upsampling: wgpu::BindGroupLayout,
    /// The pass that turns the lists' lengths into workgroup counts.
    pub dispatch_args: wgpu::BindGroupLayout,
    /// The shading from the soft layer: the soft layer read at full resolution, the sharp
    /// list read, the full list written, the colours.
    pub sharp: wgpu::BindGroupLayout,
    /// The shading in full: the full list read, the colours, the SH path's light kept.
    pub full: wgpu::BindGroupLayout,
}

impl FullResolutionLayouts {
    pub fn new(device: &wgpu::Device) -> FullResolutionLayouts {
        let compute = wgpu::ShaderStages::COMPUTE;
        let uint_texture = |slot| texture_entry(slot, compute, wgpu::TextureSampleType::Uint);
        let written = |slot, format| written_texture_entry(slot, compute, format);
        let samples = layout_entry(slots::UPSAMPLE, compute, buffer_type(wgpu::BufferBindingType::Uniform));
        let counts = storage_buffer_entry(slots::LIST_COUNTS, compute, false);
        let colours = written(slots::FRAME_COLOURS, FRAME_COLOURS_FORMAT);
        let layout = |label, entries: &[wgpu::BindGroupLayoutEntry]| {
            device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
                label: Some(label),
                entries,
            })
        };
        FullResolutionLayouts {
            upsampling: layout(
                "upsampling",
                &[
                    samples,
                    uint_texture(slots::LOW_SAMPLES),
                    counts,
                    written(slots::SHARP_PIXELS_OUT, LIST_FORMAT),
                    written(slots::FULL_PIXELS_OUT, LIST_FORMAT),
                    colours,
                ],
            ),
            dispatch_args: layout(
                "listed pixels' dispatch arguments",
                &[counts, storage_buffer_entry(slots::DISPATCH_ARGS, compute, false)],
            ),
            sharp: layout(
                "listed pixels shaded from the soft layer",
                &[
                    samples,
                    uint_texture(slots::LOW_SAMPLES),
                    counts,
                    uint_texture(slots::SHARP_PIXELS),
                    written(slots::FULL_PIXELS_OUT, LIST_FORMAT),
                    colours,
                ],
            ),
            full: layout(
                "listed pixels shaded in full",
                &[
                    [counts, uint_texture(slots::FULL_PIXELS), colours].as_slice(),
                    &kept_harmonic::layout_entries(compute),
                ]
                .concat(),
            ),
        }
    }
}

/// The compute pipelines of the full-resolution frame.
pub(super) struct FullResolutionCompute {
    upsample: wgpu::ComputePipeline,
    dispatch_args: wgpu::ComputePipeline,
    /// Two-level shading: the listed pixels from the soft layer and the sharp lights.
    shade_sharp: Option<wgpu::ComputePipeline>,
    shade_full: wgpu::ComputePipeline,
}

impl FullResolutionCompute {
    /// The pipelines from `module` with `constants` (the compiled paths), the scene's
    /// groups 0–2 `groups`, for samples `downsample` pixels apart; `two_level`: with the
    /// sharp list.
    pub fn new(
        device: &wgpu::Device,
        module: &wgpu::ShaderModule,
        (groups, layouts): ([&wgpu::BindGroupLayout; 3], &FullResolutionLayouts),
        constants: &[(&str, f64)],
        (downsample, two_level): (u32, bool),
    ) -> FullResolutionCompute {
        let mut constants = constants.to_vec();
        let pipeline = |entry_point: &str, group_3: &wgpu::BindGroupLayout, constants: &[(&str, f64)]| {
            scene_compute_pipeline(device, module, entry_point, (groups, group_3), constants)
        };
        let shade_sharp = two_level.then(|| pipeline("cs_shade_listed_sharp", &layouts.sharp, &constants));
        let dispatch_args = pipeline("cs_dispatch_args", &layouts.dispatch_args, &[]);
        // The samples' blocks: the upsampling's, and those within which the pixels shaded
        // in full share their blocker walks.
        constants.push(("BLOCK_PX", f64::from(downsample)));
        let shade_full = pipeline("cs_shade_listed_full", &layouts.full, &constants);
        constants.extend([
            ("LIST_FOR_SHARP", if two_level { 1.0 } else { 0.0 }),
            ("BLOCK_WORKGROUP_SIDE", f64::from(BLOCK_WORKGROUP_SIDE)),
        ]);
        FullResolutionCompute {
            upsample: pipeline("cs_upsample_blocks", &layouts.upsampling, &constants),
            dispatch_args,
            shade_sharp,
            shade_full,
        }
    }

    /// Upsamples the samples into `images`' colours, lists the pixels they leave and
    /// shades those (two levels: from the soft light at the samples in image
    /// `soft_index`, the one this frame wrote), with groups 0–2 `groups` (frame, surface
    /// buffer, shadow).
    pub fn draw(
        &self,
        frame: &mut TimedEncoder,
        (images, soft_index): (&FullResolutionImages, usize),
        groups: [&wgpu::BindGroup; 3],
    ) {
        frame.encoder.clear_buffer(&images.counts, 0, None);
        let pass = |frame: &mut TimedEncoder, label, run: &dyn Fn(&mut wgpu::ComputePass<'_>)| {
            scene_compute_pass(frame, label, groups, run)
        };
        let dispatch_args = |pass: &mut wgpu::ComputePass<'_>| {
            pass.set_pipeline(&self.dispatch_args);
            pass.set_bind_group(slots::PASS_GROUP, &images.dispatch_args_group, &[]);
            pass.dispatch_workgroups(1, 1, 1);
        };
        pass(frame, "upsampling", &|pass| {
            pass.set_pipeline(&self.upsample);
            pass.set_bind_group(slots::PASS_GROUP, &images.upsampling_group, &[]);
            let [blocks_x, blocks_y] = images.blocks;
            pass.dispatch_workgroups(
                blocks_x.div_ceil(BLOCK_WORKGROUP_SIDE),
                blocks_y.div_ceil(BLOCK_WORKGROUP_SIDE),
                1,
            );
            dispatch_args(pass);
        });
        if let (Some(shade_sharp), Some(sharp_groups)) = (&self.shade_sharp, &images.sharp_groups) {
            let sharp_group = &sharp_groups[soft_index];
            pass(frame, "listed pixels shaded from the soft layer", &|pass| {
                pass.set_pipeline(shade_sharp);
                pass.set_bind_group(slots::PASS_GROUP, sharp_group, &[]);
                pass.dispatch_workgroups_indirect(&images.dispatch_args, SHARP_ARGS_OFFSET);
                dispatch_args(pass);
            });
        }
        pass(frame, "listed pixels shaded in full", &|pass| {
            pass.set_pipeline(&self.shade_full);
            pass.set_bind_group(slots::PASS_GROUP, &images.full_group, &[]);
            pass.dispatch_workgroups_indirect(&images.dispatch_args, FULL_ARGS_OFFSET);
        });
    }
}

/// Blocks of `downsample` × `downsample` pixels, each sharing its 2 × 2 nearest samples,
/// that cover a frame of `size` (full_resolution.wgsl's cs_upsample_blocks): block i
/// along an axis starts at pixel downsample · (i − 1) + ⌊downsample / 2⌋, block 0 taking
/// the pixels before the first sample.
pub fn upsampling_blocks(size: [u32; 2], downsample: u32) -> [u32; 2] {
    let d = downsample.max(1);
    size.map(|side| (side + d - d / 2).div_ceil(d))
}

/// One frame size's lists and colours.
pub(crate) struct FullResolutionImages {
    /// Upsampling blocks along each side ([`upsampling_blocks`]).
    blocks: [u32; 2],
    counts: wgpu::Buffer,
    dispatch_args: wgpu::Buffer,
    upsampling_group: wgpu::BindGroup,
    dispatch_args_group: wgpu::BindGroup,
    /// Present with a soft layer: one for each of the images the soft light at the
    /// samples alternates between (`kept_harmonic::KeptAtSamples`).
    sharp_groups: Option<[wgpu::BindGroup; 2]>,
    full_group: wgpu::BindGroup,
    /// Every pixel's colour (full_resolution.wgsl's frame_colours).
    colours: wgpu::Texture,
    /// Between the colours and the frame's image: a band of rows of 256-byte multiples.
    copy_band: wgpu::Buffer,
}

impl FullResolutionImages {
    /// How many pixels the last frame listed: those the upsampling left to the soft
    /// layer and the sharp lights (two-level shading), and those shaded in full.
    pub(crate) fn listed_pixels(
        &self,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
    ) -> Result<ListedPixels, RenderError> {
        let bytes = read_buffer(device, queue, &self.counts, 8)?;
        let count = |k: usize| u32::from_le_bytes([bytes[4 * k], bytes[4 * k + 1], bytes[4 * k + 2], bytes[4 * k + 3]]);
        Ok(ListedPixels {
            from_soft_layer: count(0),
            in_full: count(1),
            samples_in_full: 0,
        })
    }
}

/// How many pixels a frame's upsampling left to be shaded another way
/// ([`crate::render::SceneRenderer::listed_pixels`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct ListedPixels {
    /// Listed by the upsampling for the soft layer and the sharp lights (0 in one level).
    pub from_soft_layer: u32,
    /// Shaded in full: left by the upsampling in one level, by the soft layer in two.
    pub in_full: u32,
    /// Low-resolution samples the soft layer left, shaded in full (two levels; else 0).
    pub samples_in_full: u32,
}

/// Samples as a reader finds them: their image and the reader's upsampling parameters.
pub(crate) type SampleReader<'a> = (&'a wgpu::TextureView, GpuUpsampleParams);

/// The soft light at the samples as the listed pixels find it: the two images frames
/// write in turn, and the reader's upsampling parameters.
pub(crate) type SoftReader<'a> = ([&'a wgpu::TextureView; 2], GpuUpsampleParams);

impl FullResolutionImages {
    /// Lists and colours for frames of `size` upsampled from `samples`, spaced
    /// `downsample` pixels apart; `soft_light`: with two-level shading, the soft light at
    /// the samples the listed pixels upsample; `kept_generation`: the generation of the SH
    /// path's light kept at the pixels shaded in full (`kept_harmonic`).
    pub fn new(
        device: &wgpu::Device,
        layouts: &FullResolutionLayouts,
        (size, downsample): ([u32; 2], u32),
        (samples, soft_light): (SampleReader<'_>, Option<SoftReader<'_>>),
        kept_generation: &wgpu::Buffer,
    ) -> FullResolutionImages {
        // The sharp list's and the full list's.
        let (counts, dispatch_args) = list_counts_and_dispatch_args(device, "listed pixels", 2);
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
        let colours = frame_texture(
            device,
            "frame colours",
            image_extent(size),
            FRAME_COLOURS_FORMAT,
            1,
            wgpu::TextureUsages::STORAGE_BINDING | wgpu::TextureUsages::COPY_SRC,
            &[],
        );
        let copy_band = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("frame colours' copy"),
            size: copy_band_rows(size) as u64 * row_bytes(size[0]),
            usage: wgpu::BufferUsages::COPY_SRC | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        let colours_view = colours.create_view(&Default::default());
        let kept = KeptHarmonicImages::new(device, size);
        let [kept_x, kept_y, kept_stamp, kept_generation] = kept.entries(kept_generation);
        let view = wgpu::BindingResource::TextureView;
        let group = |label, layout, entries: &[wgpu::BindGroupEntry<'_>]| {
            device.create_bind_group(&wgpu::BindGroupDescriptor {
                label: Some(label),
                layout,
                entries,
            })
        };
        let params = |params: GpuUpsampleParams| {
            device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
                label: Some("upsampling parameters"),
                contents: bytemuck::bytes_of(&params),
                usage: wgpu::BufferUsages::UNIFORM,
            })
        };
        let sample_params = params(samples.1);
        let sharp_groups = soft_light.map(|(images, soft_params)| {
            let soft_params = params(soft_params);
            images.map(|image| {
                group(
                    "listed pixels shaded from the soft layer",
                    &layouts.sharp,
                    &slot_entries([
                        (slots::UPSAMPLE, soft_params.as_entire_binding()),
                        (slots::LOW_SAMPLES, view(image)),
                        (slots::LIST_COUNTS, counts.as_entire_binding()),
                        (slots::SHARP_PIXELS, view(&sharp_pixels)),
                        (slots::FULL_PIXELS_OUT, view(&full_pixels)),
                        (slots::FRAME_COLOURS, view(&colours_view)),
                    ]),
                )
            })
        });
        FullResolutionImages {
            blocks: upsampling_blocks(size, downsample),
            upsampling_group: group(
                "upsampling",
                &layouts.upsampling,
                &slot_entries([
                    (slots::UPSAMPLE, sample_params.as_entire_binding()),
                    (slots::LOW_SAMPLES, view(samples.0)),
                    (slots::LIST_COUNTS, counts.as_entire_binding()),
                    (slots::SHARP_PIXELS_OUT, view(&sharp_pixels)),
                    (slots::FULL_PIXELS_OUT, view(&full_pixels)),
                    (slots::FRAME_COLOURS, view(&colours_view)),
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
            sharp_groups,
            full_group: group(
                "listed pixels shaded in full",
                &layouts.full,
                &slot_entries([
                    (slots::LIST_COUNTS, counts.as_entire_binding()),
                    (slots::FULL_PIXELS, view(&full_pixels)),
                    (slots::FRAME_COLOURS, view(&colours_view)),
                    kept_x,
                    kept_y,
                    kept_stamp,
                    kept_generation,
                ]),
            ),
            colours,
            copy_band,
            counts,
            dispatch_args,
        }
    }
}

/// Bytes per row of the copy between the colours and the frame: 4 a pixel, rounded up
/// to 256 (what a copy between a buffer and an image takes).
fn row_bytes(width: u32) -> u64 {
    u64::from(padded_row_bytes(4 * width.max(1)))
}

/// Rows of a frame of `size` per band of the copy.
fn copy_band_rows(size: [u32; 2]) -> u32 {
    let rows = (MAX_COPY_BAND_BYTES / row_bytes(size[0])).max(1);
    u32::try_from(rows).unwrap_or(u32::MAX).min(size[1].max(1))
}

impl FullResolutionImages {
    /// Copies every pixel's colour into `image` (the frame's single-sampled image,
    /// `Rgba8Unorm` bytes, of the colours' size), a band of rows at a time through the
    /// copy buffer: the bytes are the ones a fragment shader would have left there.
    pub(crate) fn copy_colours(&self, encoder: &mut wgpu::CommandEncoder, image: &wgpu::Texture) {
        let size = self.colours.size();
        let band_rows = copy_band_rows([size.width, size.height]);
        let layout = wgpu::TexelCopyBufferLayout {
            offset: 0,
            bytes_per_row: Some(row_bytes(size.width) as u32),
            rows_per_image: Some(band_rows),
        };
        let mut first_row = 0;
        while first_row < size.height {
            let rows = band_rows.min(size.height - first_row);
            let origin = wgpu::Origin3d {
                x: 0,
                y: first_row,
                z: 0,
            };
            let extent = wgpu::Extent3d {
                width: size.width,
                height: rows,
                depth_or_array_layers: 1,
            };
            let band = wgpu::TexelCopyBufferInfo {
                buffer: &self.copy_band,
                layout,
            };
            let source = wgpu::TexelCopyTextureInfo {
                origin,
                ..self.colours.as_image_copy()
            };
            encoder.copy_texture_to_buffer(source, band, extent);
            let destination = wgpu::TexelCopyTextureInfo {
                origin,
                ..image.as_image_copy()
            };
            encoder.copy_buffer_to_texture(band, destination, extent);
            first_row += rows;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The corner of the 2 × 2 samples nearest to pixel `p` for samples at pixels
    /// d·k + ⌊d/2⌋ (exact arithmetic: (p − ⌊d/2⌋) / d rounded down).
    fn nearest_corner(p: i64, d: i64) -> i64 {
        (p - d / 2).div_euclid(d)
    }

    #[test]
    fn the_copy_bands_cover_every_row_within_their_buffer() {
        for size in [[1, 1], [960, 540], [2560, 1440], [16384, 16384], [17, 100_000]] {
            let rows = copy_band_rows(size);
            assert!(rows >= 1 && rows <= size[1]);
            assert!(u64::from(rows) * row_bytes(size[0]) <= MAX_COPY_BAND_BYTES.max(row_bytes(size[0])));
            assert_eq!(row_bytes(size[0]) % 256, 0);
            assert!(row_bytes(size[0]) >= 4 * u64::from(size[0]));
        }
    }

    #[test]
    fn each_block_holds_exactly_the_pixels_of_its_corner() {
        for d in 1..=8u32 {
            for side in [1u32, 2, 3, 7, 540, 541, 960] {
                let blocks = upsampling_blocks([side, side], d)[0];
                let mut covered = vec![0u32; side as usize];
                for block in 0..blocks {
                    let (d, block) = (i64::from(d), i64::from(block));
                    let first = d * (block - 1) + d / 2;
                    for p in first..first + d {
                        if (0..i64::from(side)).contains(&p) {
                            assert_eq!(nearest_corner(p, d), block - 1, "d {d}, pixel {p}");
                            covered[p as usize] += 1;
                        }
                    }
                }
                assert!(covered.iter().all(|&n| n == 1), "d {d}, side {side}: {covered:?}");
            }
        }
    }
}
