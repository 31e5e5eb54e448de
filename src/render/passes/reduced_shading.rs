//! Reduced-resolution log-SH shading (shaders/reduced_shading.wgsl): the costly shading
//! runs once per d × d block of pixels, and a cheap full-resolution pass rebuilds every
//! pixel from the samples on its own surface (joint bilateral upsampling guided by world
//! position and normal), multiplying its own material back in. Pixels no sample matches
//! (thin objects, silhouettes) are shaded in full on single-sampled targets, and take the
//! best sample nearby on multisampled ones (see `scene_pipeline::shades_unmatched_exactly`).
//!
//! A frame's passes (`low_resolution` draws them): the surfaces rasterised at full
//! resolution into a surface buffer ([`SURFACE_BUFFER_FORMATS`]) with a depth of its own
//! (kept, with the soft layer and the samples' visibility of the shadow-map path's
//! lights, for the next frame when only lights' intensities change: [`FrameInputs`],
//! `surface_buffer`); the low-resolution samples on a surface marked in a low-resolution
//! depth, each sample the surface of the middle pixel of its d × d block
//! (`upsample_params`); with two-level shading, the soft layer — the light
//! of soft shadows (the environment's and the SH path's lights) at twice the samples'
//! spacing; the samples ([`LOW_RESOLUTION_FORMATS`]) shaded by full-screen passes
//! reading the buffer (one level: in full; two levels: the soft layer upsampled plus the
//! sharp lights, and in full where the soft layer does not match or disagrees); then in
//! the frame's [`crate::render::RenderTarget`] the upsampling and the pixels it left, in
//! compute passes (`full_resolution`: the upsampling by blocks of pixels, the pixels it
//! leaves listed and shaded densely — two levels: the soft layer upsampled plus the sharp
//! lights, and in full where the soft layer does not match or disagrees; one level: in
//! full — and their colours copied into the frame). Multisampled targets draw the
//! full-resolution frame rasterised instead: a depth pre-pass, fs_upsample and nothing
//! shaded in full.
//!
//! Why deferred: rasterised at a third of the resolution, a figure's triangles are
//! smaller than a sample, and lavapipe runs a fragment shader over blocks of pixels per
//! triangle, so the full shading ran once per triangle for a pixel or less; a
//! full-screen pass runs it once per sample. At full resolution a fine mesh (a terrain)
//! paid likewise in the upsampling and the full shading of edge pixels. Why the samples
//! from the full-resolution buffer: a second geometry pass at low resolution cost about
//! as much as the passes that shade the samples. Why two levels: the soft shadows walk every
//! blocker in reach, the costliest part of the shading, and change slowly enough across
//! the image to be shaded at half the samples' resolution along each side. What each
//! step saved: docs/performance.md (`render --time-frames` prints each pass's time).

use wgpu::util::DeviceExt;

use super::full_resolution::{FullResolutionImages, FullResolutionLayouts};
use super::kept_harmonic::{self, KeptAtSamples};
use super::listed_samples::{ListedSamples, ListedSamplesPipelines, ListedSamplesTargets};
pub(crate) use super::surface_buffer::SurfaceBuffer;
pub use super::surface_buffer::{
    MAPPED_FACTORS_BUDGET_BYTES, MappedLightKey, MappedVisibilityKey, SURFACE_BUFFER_FORMATS,
    mapped_factors_writer_layout, surface_buffer_layout,
};
use super::surface_buffer::{SAMPLED_TARGET, cleared, depth_texture, image_extent};
use crate::render::descriptors::{
    buffer_type, depth_attachment, frame_texture, layout_entry, slot_entries, texture_entry,
};
use crate::shading::gpu_types::GpuUpsampleParams;
use crate::shading::wgsl::slots;

/// Formats of fs_shade_low's targets: one, holding view depth, lighting and the packed
/// normal (see reduced_shading.wgsl). 16 bytes a sample, read with one texel fetch.
pub const LOW_RESOLUTION_FORMATS: [wgpu::TextureFormat; 1] = [wgpu::TextureFormat::Rgba32Uint];

/// A low-resolution sample counts as lying on a pixel's surface within this many pixel
/// footprints of the pixel's tangent plane (per unit of downsampling: samples lie up to
/// about d pixels away, where a curved surface has left its tangent plane farther).
const PLANE_TOLERANCE_PX_PER_DOWNSAMPLE: f32 = 1.0;

/// A pixel whose matching samples carry less than this share of their bilinear weight is
/// shaded in full: a lone matching sample in the far corner would smear its light. Where
/// an object stands on a floor, the floor's samples nearest the contact lie on the
/// object, and the floor's pixels there took their light from farther samples, outside
/// the contact shadow: 0.15 left the sample's contact shadows too light. Against
/// `render --reference --bounces 0 --spp 512` at 480 × 270 (shadowed pixels' RMSE of
/// `render --no-baked-indirect`, 2026-12-04): 0.15 → 0.4 took the sample from 0.0419 to
/// 0.0356 (0.7: 0.0335; every pixel shaded: 0.0328) and the studio from 0.0246 to 0.0245,
/// for about 4 % more frame time on the sample and 1 % on the studio (0.7: 7–10 %).
const MIN_MATCHED_WEIGHT: f32 = 0.4;

/// A pixel whose nearest samples on its surface differ in lighting by more than this
/// ratio (brightest over darkest, luminance of the exposed lighting per unit
/// reflectance, plus [`LIGHTING_FLOOR`]) lies where the light changes faster than the
/// samples' spacing — a hard shadow's edge, a rim — and is shaded in full rather than
/// interpolated; so is a pixel with fewer than two of them on its surface (a limb a few
/// pixels wide), where no disagreement can show. Measured against the path tracer by the
/// study (docs/speed-accuracy.md): 1.2 rather than 1.5 took the shipped frame's
/// shadowed-pixel RMSE from 0.0202 to 0.0170 on the studio, 0.0282 to 0.0279 on the
/// sample and 0.0180 to 0.0156 on the interior, for about 11 % more frame time on the
/// studio and 1 % on the sample (docs/performance.md).
const MAX_LIGHTING_RATIO: f32 = 1.2;

/// What [`MAX_LIGHTING_RATIO`] forgives in the dark, in exposed lighting per unit
/// reflectance: on a mid-grey surface (reflectance 0.5) 0.02 displays as about 12/255
/// after the tone curve and sRGB, so in deep shadow only differences larger than that
/// cost full shading.
const LIGHTING_FLOOR: f32 = 0.02;

/// [`MAX_LIGHTING_RATIO`] and [`LIGHTING_FLOOR`] of the soft light (two-level shading:
/// the soft layer read by the samples, the samples' soft light read by the listed
/// pixels), whose samples carry its share of the same light unshadowed (each reader
/// multiplies its own back in: low_resolution.wgsl's soft_share), so the floor is a share
/// of the unshadowed soft light. When they carried the soft light itself, these held the
/// studio's error to that of shading it in one level (compared with the study's
/// reference outside the study, so no figures in the docs) for 1 % more frame time; as
/// shares they were measured against the path tracer (docs/performance.md).
const SOFT_MAX_LIGHTING_RATIO: f32 = 1.25;
const SOFT_LIGHTING_FLOOR: f32 = 0.005;

/// The size of the shaded image for a `width` × `height` frame shaded once per
/// `downsample` × `downsample` pixels (rounded up, so it covers every pixel).
pub fn low_resolution_size(width: u32, height: u32, downsample: u32) -> [u32; 2] {
    let d = downsample.max(1);
    [width.div_ceil(d).max(1), height.div_ceil(d).max(1)]
}

/// The bind group layout through which fs_upsample reads the low-resolution samples.
pub fn low_resolution_layout(device: &wgpu::Device) -> wgpu::BindGroupLayout {
    let fragment = wgpu::ShaderStages::FRAGMENT;
    device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
        label: Some("low-resolution samples"),
        entries: &[
            layout_entry(slots::UPSAMPLE, fragment, buffer_type(wgpu::BufferBindingType::Uniform)),
            texture_entry(slots::LOW_SAMPLES, fragment, wgpu::TextureSampleType::Uint),
        ],
    })
}

/// The images of reduced-resolution shading for one frame size: the surface buffer at
/// full resolution, the low-resolution depth that marks which samples lie on a surface,
/// the samples fs_shade_low writes and the upsampling reads, and, with two-level shading,
/// the soft layer beneath them.
pub struct LowResolutionTargets {
    /// The full-resolution frame size these serve.
    pub full_size: [u32; 2],
    pub downsample: u32,
    pub size: [u32; 2],
    /// The surfaces at full resolution, of which each sample shades one pixel.
    pub(crate) surface: SurfaceBuffer,
    /// The low-resolution depth: 0 at samples on a surface, 1 elsewhere and where a
    /// marking pass has shaded.
    low_depth: wgpu::TextureView,
    low_depth_texture: wgpu::Texture,
    /// The low-resolution depth as the pass marking the samples on a surface left it:
    /// copied back in place of that pass while the surfaces stay the same (a stroke's
    /// frame), which saved its 1.7 ms on the studio.
    marked_samples: wgpu::Texture,
    pub(crate) samples: SampleImage,
    /// The soft layer (fs_shade_soft), one sample per 2 × 2 low-resolution samples,
    /// upsampled into them by fs_shade_sharp_marking: present when the pipeline shades
    /// in two levels.
    pub(crate) soft: Option<SampleImage>,
    /// With the soft layer: the list of the samples it leaves, which compute passes shade
    /// in full (`listed_samples`).
    pub(crate) listed_samples: Option<ListedSamples>,
    /// Where the full-resolution frame is deferred: its lists of the pixels the
    /// upsampling leaves and its colours (`full_resolution`).
    pub(crate) full_resolution: Option<FullResolutionImages>,
    /// The full-resolution frame is deferred (drawn by full-screen passes from the buffer).
    deferred_frame: bool,
    /// What the surface buffer and the soft layer show, if known
    /// ([`Self::expect_inputs`]).
    drawn_from: Option<FrameInputs>,
    /// The next frame's surfaces are those the buffer shows.
    surfaces_current: bool,
    /// The next frame's soft layer is the one drawn (its surfaces too).
    soft_layer_current: bool,
    /// The kept visibility of the mapped lights is the next frame's.
    mapped_factors_current: bool,
    /// The next frame keeps the samples' factors of the mapped lights: its surfaces are
    /// the last frame's. A frame of new surfaces (a new view) shades those lights at its
    /// samples directly, as keeping them would cost it a pass writing every light's
    /// factors at every sample (the studio's frame drawn anew 3–4 ms, the large sample's
    /// 6; docs/performance.md); the first frame
    /// after it on the same surfaces (a stroke's, an edit's) writes them.
    keeps_mapped_factors: bool,
    /// The generation of the SH path's light where it was shaded in full (never 0): a
    /// new one whenever the soft layer is not current, so that light, kept at the pixels
    /// and samples shaded in full (`kept_harmonic`), is read again only while the surfaces
    /// and the soft light's inputs stay those it was shaded with. (After 2³² − 1
    /// generations it wraps to 1, which pixels of generation 1 not shaded in full since
    /// would read as kept.)
    kept_harmonic_generation: u32,
    /// That generation, for the shaders.
    kept_generation: wgpu::Buffer,
    /// The SH path's light kept at the samples shaded in full (fs_shade_low).
    pub(super) kept_at_samples: KeptAtSamples,
}

/// What a surface buffer shows: the scene as uploaded at `scene_generation`
/// ([`crate::render::resources::GpuScene::surfaces_generation`]), its objects at the
/// levels of detail of `levels_generation` (`GpuScene::levels_generation`), seen by
/// `camera`.
/// Two frames with equal keys rasterise the same buffer, so the second keeps the first's:
/// a frame after an edit of the lights alone (a stroke, an intensity) skips the surfaces
/// pass. (A new pipeline comes with new targets, which show nothing yet.)
#[derive(Debug, Clone, PartialEq)]
pub struct SurfacesKey {
    pub camera: crate::scene::Camera,
    pub scene_generation: u64,
    pub levels_generation: u64,
}

/// What the soft layer (two-level shading) shows besides the surfaces: the light of the
/// SH path and the environment through the blockers (`blockers_generation`) with
/// `settings`, at `exposure_ev`. A frame whose surfaces and soft inputs equal the last
/// one's keeps its soft layer: with every light on the shadow-map path, an edit of any
/// light's intensity does.
#[derive(Debug, Clone, PartialEq)]
pub struct SoftLayerKey {
    pub lighting: crate::render::resources::HarmonicLighting,
    pub settings: crate::shading::ShadowSettings,
    pub exposure_ev: f32,
    pub blockers_generation: u64,
}

/// What a frame's reduced shading reads that a later frame may find unchanged.
#[derive(Debug, Clone, PartialEq)]
pub struct FrameInputs {
    pub surfaces: SurfacesKey,
    pub soft_layer: SoftLayerKey,
    pub mapped_visibility: MappedVisibilityKey,
}

/// Where the samples of one image sit and how a finer image's pixels find them (see
/// low_resolution.wgsl's `level_pixel`): sample texel i shades full-resolution pixel
/// `stride_px` · i + ⌊`stride_px` / 2⌋ (clamped into the frame), and a reader whose pixel
/// k shades full-resolution pixel `reader_stride_px` · k + ⌊`reader_stride_px` / 2⌋
/// finds it at sample texel (that pixel − the sample's offset) / `stride_px`.
fn upsample_params(
    full_size: [u32; 2],
    [reader_stride_px, stride_px]: [u32; 2],
    [max_lighting_ratio, lighting_floor]: [f32; 2],
) -> GpuUpsampleParams {
    let [width, height] = full_size.map(|v| v.max(1) as f32);
    let reader_stride = reader_stride_px.max(1);
    let stride = stride_px.max(1);
    let reader_offset_px = (reader_stride / 2) as f32;
    let offset_px = (stride / 2) as f32;
    let (reader_stride, stride) = (reader_stride as f32, stride as f32);
    // Reader pixel centre p = k + 0.5 shades full-resolution pixel R(p − 0.5) + h_R, at
    // sample texel (R(p − 0.5) + h_R − h_s) / s = p · R/s − (R/2 − h_R + h_s) / s.
    let sample_offset = (0.5 * reader_stride - reader_offset_px + offset_px) / stride;
    GpuUpsampleParams {
        full_to_low: [reader_stride / stride; 2],
        plane_tolerance_px: PLANE_TOLERANCE_PX_PER_DOWNSAMPLE * stride,
        min_matched_weight: MIN_MATCHED_WEIGHT,
        max_lighting_ratio,
        lighting_floor,
        sample_offset: [sample_offset; 2],
        sample_pixel: [stride, offset_px, width - 1.0, height - 1.0],
        pixel_to_ndc: [2.0 / width, -2.0 / height, 1.0 / width - 1.0, 1.0 - 1.0 / height],
    }
}

/// One image of samples (see reduced_shading.wgsl) and the bind group through which the
/// next finer level reads it.
pub(crate) struct SampleImage {
    view: wgpu::TextureView,
    pub bind_group: wgpu::BindGroup,
}

/// A bind group through which a reader finds `view`'s samples by `params`.
fn sample_reader(
    device: &wgpu::Device,
    layout: &wgpu::BindGroupLayout,
    label: &str,
    view: &wgpu::TextureView,
    params: GpuUpsampleParams,
) -> wgpu::BindGroup {
    let params = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
        label: Some("upsample parameters"),
        contents: bytemuck::bytes_of(&params),
        usage: wgpu::BufferUsages::UNIFORM,
    });
    device.create_bind_group(&wgpu::BindGroupDescriptor {
        label: Some(label),
        layout,
        entries: &slot_entries([
            (slots::UPSAMPLE, params.as_entire_binding()),
            (slots::LOW_SAMPLES, wgpu::BindingResource::TextureView(view)),
        ]),
    })
}

impl SampleImage {
    /// An image of `size` samples with `params` ([`upsample_params`]).
    fn new(
        device: &wgpu::Device,
        layout: &wgpu::BindGroupLayout,
        label: &str,
        size: [u32; 2],
        params: GpuUpsampleParams,
    ) -> SampleImage {
        let view = frame_texture(
            device,
            label,
            image_extent(size),
            LOW_RESOLUTION_FORMATS[0],
            1,
            // Written by fs_shade_low's pass, and by cs_shade_listed_samples in two levels.
            SAMPLED_TARGET | wgpu::TextureUsages::STORAGE_BINDING,
            &[],
        )
        .create_view(&Default::default());
        let bind_group = sample_reader(device, layout, label, &view, params);
        SampleImage { view, bind_group }
    }

    /// The sample attachment, cleared (view depth 0 marks "no surface").
    pub(crate) fn color_attachments(&self) -> [Option<wgpu::RenderPassColorAttachment<'_>>; 1] {
        [cleared(&self.view)]
    }
}

impl LowResolutionTargets {
    /// Targets for frames of `full_size` shaded once per `downsample` × `downsample`
    /// pixels, the samples read through `layout` ([`low_resolution_layout`]) and the
    /// surfaces through `surface_layout` ([`surface_buffer_layout`]), the full-resolution
    /// frame's through `full_layouts`, the samples the soft layer leaves through
    /// `listed_pipelines`' groups; `soft_layer`: with
    /// the soft layer at twice the spacing (two-level shading; then `listed_pipelines`
    /// is present); `deferred_frame`: the
    /// full-resolution frame is deferred too (its passes start from the buffer's depth).
    pub(super) fn new(
        device: &wgpu::Device,
        ([layout, surface_layout, writer_layout, kept_layout], full_layouts, listed_pipelines): (
            [&wgpu::BindGroupLayout; 4],
            &FullResolutionLayouts,
            Option<&ListedSamplesPipelines>,
        ),
        full_size: [u32; 2],
        downsample: u32,
        [soft_layer, deferred_frame]: [bool; 2],
    ) -> LowResolutionTargets {
        let size = low_resolution_size(full_size[0], full_size[1], downsample);
        // How the full-resolution frame finds the samples.
        let full_resolution_reader = upsample_params(full_size, [1, downsample], [MAX_LIGHTING_RATIO, LIGHTING_FLOOR]);
        let samples = SampleImage::new(device, layout, "low-resolution samples", size, full_resolution_reader);
        let soft = soft_layer.then(|| {
            SampleImage::new(
                device,
                layout,
                "soft layer samples",
                low_resolution_size(size[0], size[1], 2),
                upsample_params(
                    full_size,
                    [downsample, 2 * downsample],
                    [SOFT_MAX_LIGHTING_RATIO, SOFT_LIGHTING_FLOOR],
                ),
            )
        });
        let kept_generation = kept_harmonic::generation_buffer(device);
        let kept_at_samples = KeptAtSamples::new(device, kept_layout, size, &kept_generation);
        let full_resolution = deferred_frame.then(|| {
            let reader = (&samples.view, full_resolution_reader);
            // The listed pixels upsample the soft light at the samples (the image the
            // frame's low-resolution shading writes), read at full resolution: the soft
            // layer where it matched them, their own where it did not, so the rims of
            // objects a few dozen pixels across, which no soft layer sample lies on, find
            // their soft light at the samples' spacing rather than being shaded in full.
            let soft_layer = soft.is_some().then(|| {
                let params = upsample_params(
                    full_size,
                    [1, downsample],
                    [SOFT_MAX_LIGHTING_RATIO, SOFT_LIGHTING_FLOOR],
                );
                (kept_at_samples.images(), params)
            });
            FullResolutionImages::new(
                device,
                full_layouts,
                (full_size, downsample),
                (reader, soft_layer),
                &kept_generation,
            )
        });
        let copied = wgpu::TextureUsages::COPY_SRC | wgpu::TextureUsages::COPY_DST;
        let low_depth_texture = depth_texture(device, "low-resolution depth", size, copied);
        let low_depth = low_depth_texture.create_view(&Default::default());
        let listed_samples = listed_pipelines.filter(|_| soft.is_some()).map(|pipelines| {
            let targets = ListedSamplesTargets {
                samples: &samples.view,
                kept: kept_at_samples.images(),
                generation: &kept_generation,
            };
            ListedSamples::new(device, pipelines, size, targets)
        });
        LowResolutionTargets {
            full_size,
            downsample,
            size,
            full_resolution,
            surface: SurfaceBuffer::new(device, [surface_layout, writer_layout], full_size, size),
            deferred_frame,
            drawn_from: None,
            surfaces_current: false,
            soft_layer_current: false,
            mapped_factors_current: false,
            keeps_mapped_factors: false,
            kept_harmonic_generation: 0,
            kept_at_samples,
            kept_generation,
            low_depth,
            low_depth_texture,
            listed_samples,
            marked_samples: depth_texture(device, "marked samples", size, copied),
            samples,
            soft,
        }
    }

    /// Whether these serve frames of `full_size` at `downsample`, with a soft layer and a
    /// deferred full-resolution frame or without.
    pub fn fits(&self, full_size: [u32; 2], downsample: u32, [soft_layer, deferred_frame]: [bool; 2]) -> bool {
        self.full_size == full_size
            && self.downsample == downsample
            && self.soft.is_some() == soft_layer
            && self.deferred_frame == deferred_frame
    }

    /// Says what the next frame reads (None: unknown, draw everything anew) and how many
    /// lights it shades through shadow maps; the frame keeps the surface buffer, the soft
    /// layer and the samples' visibility of those lights where they come from the same as
    /// the last frame's.
    pub fn expect_inputs(
        &mut self,
        (device, queue): (&wgpu::Device, &wgpu::Queue),
        inputs: Option<FrameInputs>,
        mapped_lights: usize,
    ) {
        let last = self.drawn_from.take();
        self.surfaces_current = matches!((&inputs, &last), (Some(i), Some(l)) if i.surfaces == l.surfaces);
        self.soft_layer_current =
            self.surfaces_current && matches!((&inputs, &last), (Some(i), Some(l)) if i.soft_layer == l.soft_layer);
        if !self.soft_layer_current {
            self.kept_harmonic_generation = self.kept_harmonic_generation.wrapping_add(1).max(1);
        }
        let samples_current = self.kept_at_samples.next_frame(self.kept_harmonic_generation);
        kept_harmonic::set_generation(
            queue,
            &self.kept_generation,
            self.kept_harmonic_generation,
            samples_current,
        );
        // The last frame kept the factors (wrote or held them) for the surfaces the buffer
        // shows.
        let factors_held = self.keeps_mapped_factors;
        self.keeps_mapped_factors = self.surfaces_current;
        self.mapped_factors_current = false;
        if self.keeps_mapped_factors {
            let reallocated = self.surface.reserve_mapped_factors(device, mapped_lights);
            // Every light anew where the buffer is new or holds no factors of these
            // surfaces; else those whose geometry or maps changed.
            let kept_from = last
                .as_ref()
                .filter(|_| factors_held && !reallocated)
                .map(|l| &l.mapped_visibility);
            let stale = match &inputs {
                Some(i) => i.mapped_visibility.stale_lights(kept_from),
                None => vec![1; mapped_lights],
            };
            self.mapped_factors_current = stale.iter().all(|&flag| flag == 0);
            if !self.mapped_factors_current {
                self.surface.write_stale_lights(device, queue, &stale);
            }
        }
        self.drawn_from = inputs;
    }

    /// Whether the kept visibility of the mapped lights holds this frame's (else the
    /// pass marking the samples on a surface writes it, where the frame keeps it).
    pub(crate) fn mapped_factors_current(&self) -> bool {
        self.mapped_factors_current
    }

    /// Whether this frame keeps the samples' factors of the mapped lights (else its
    /// samples' shading evaluates those lights itself).
    pub(crate) fn keeps_mapped_factors(&self) -> bool {
        self.keeps_mapped_factors
    }

    /// Whether the surface buffer already shows the next frame's surfaces.
    pub(crate) fn surfaces_current(&self) -> bool {
        self.surfaces_current
    }

    /// Whether the soft layer already holds the next frame's soft light.
    pub(crate) fn soft_layer_current(&self) -> bool {
        self.soft_layer_current
    }

    /// The bind group through which the full-resolution pass reads the samples.
    pub(crate) fn bind_group(&self) -> &wgpu::BindGroup {
        &self.samples.bind_group
    }

    /// The low-resolution depth: cleared and written by the pass marking the samples on
    /// a surface (`clear`), then tested, and written by the marking passes, in the
    /// shading passes.
    pub(crate) fn low_depth_attachment(&self, clear: bool) -> wgpu::RenderPassDepthStencilAttachment<'_> {
        depth_attachment(&self.low_depth, clear.then_some(1.0), true)
    }

    /// Records a copy of the low-resolution depth just marked, for later frames with the
    /// same surfaces ([`Self::restore_marked_samples`]).
    pub(crate) fn keep_marked_samples(&self, encoder: &mut wgpu::CommandEncoder) {
        copy_whole(encoder, &self.low_depth_texture, &self.marked_samples);
    }

    /// Records the low-resolution depth as the last marking pass left it: what that pass
    /// would draw again where the surfaces are current.
    pub(crate) fn restore_marked_samples(&self, encoder: &mut wgpu::CommandEncoder) {
        copy_whole(encoder, &self.marked_samples, &self.low_depth_texture);
    }
}

/// Records a copy of all of `from` into `to` (of the same size and format).
fn copy_whole(encoder: &mut wgpu::CommandEncoder, from: &wgpu::Texture, to: &wgpu::Texture) {
    encoder.copy_texture_to_texture(from.as_image_copy(), to.as_image_copy(), from.size());
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

    /// The full-resolution pixel a sample shades (low_resolution.wgsl's level_pixel,
    /// unclamped).
    fn shaded_pixel(texel: u32, stride_px: u32) -> u32 {
        texel * stride_px + stride_px / 2
    }

    #[test]
    fn a_reader_on_a_samples_pixel_finds_that_sample_exactly() {
        for (reader_stride, stride) in [(1, 1), (1, 2), (1, 3), (1, 4), (2, 4), (3, 6), (4, 8), (5, 10)] {
            let params = upsample_params([960, 540], [reader_stride, stride], [1.5, 0.02]);
            for sample in 0..20 {
                let pixel = shaded_pixel(sample, stride);
                // The reader pixel on that full-resolution pixel, where one exists.
                let Some(reader) = (0..200).find(|&k| shaded_pixel(k, reader_stride) == pixel) else {
                    continue;
                };
                let at = (reader as f32 + 0.5) * params.full_to_low[0] - params.sample_offset[0];
                assert!(
                    (at - sample as f32).abs() < 1e-5,
                    "reader stride {reader_stride}, stride {stride}, sample {sample}: {at}"
                );
                // And the sample's point is rebuilt on that pixel's ray.
                let rebuilt = sample as f32 * params.sample_pixel[0] + params.sample_pixel[1];
                assert_eq!(rebuilt, pixel as f32);
            }
        }
    }

    #[test]
    fn pixel_centres_map_to_the_frames_normalised_device_coordinates() {
        let params = upsample_params([960, 540], [1, 3], [1.5, 0.02]);
        let ndc = |pixel: [f32; 2]| {
            [
                pixel[0] * params.pixel_to_ndc[0] + params.pixel_to_ndc[2],
                pixel[1] * params.pixel_to_ndc[1] + params.pixel_to_ndc[3],
            ]
        };
        // The first pixel's centre lies half a pixel inside the top-left corner (−1, 1),
        // the last one's half a pixel inside the bottom-right corner (1, −1).
        let first = ndc([0.0, 0.0]);
        let last = ndc([959.0, 539.0]);
        assert!((first[0] - (-1.0 + 1.0 / 960.0)).abs() < 1e-6 && (first[1] - (1.0 - 1.0 / 540.0)).abs() < 1e-6);
        assert!((last[0] - (1.0 - 1.0 / 960.0)).abs() < 1e-6 && (last[1] - (-1.0 + 1.0 / 540.0)).abs() < 1e-6);
        assert_eq!(&params.sample_pixel[2..], &[959.0, 539.0]);
    }
}
