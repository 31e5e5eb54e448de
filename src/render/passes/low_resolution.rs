//! The deferred passes of reduced-resolution shading (see `reduced_shading` and
//! shaders/low_resolution.wgsl): the surface buffer rasterised at full resolution, then
//! full-screen passes that shade samples of it at low resolution — in one level, or in
//! two, the light of soft shadows at twice the spacing and the sharp lights added at
//! every sample — and on single-sampled targets the full-resolution frame likewise: the
//! upsampling and the shading of the pixels it leaves (from the soft layer where there
//! is one, in full where it does not serve), in compute passes (`full_resolution`).

use super::full_resolution::{FullResolutionCompute, FullResolutionLayouts};
use super::kept_harmonic;
use super::listed_samples::ListedSamplesPipelines;
use super::reduced_shading::{
    LOW_RESOLUTION_FORMATS, LowResolutionTargets, SurfaceBuffer, low_resolution_layout, mapped_factors_writer_layout,
    surface_buffer_layout,
};
use super::scene_pipeline::{
    ByTexture, Stage, SurfaceBufferPipelines, Variant, path_constants, scene_pipeline, shades_unmatched_exactly,
};
use crate::render::descriptors::depth_test;
use crate::render::pass_timer::TimedEncoder;
use crate::render::resources::{GpuBlockers, GpuScene, SceneLayouts};
use crate::render::target::RenderTarget;
use crate::shading::CompiledPaths;
use crate::shading::wgsl::slots;

/// The passes of reduced-resolution shading (see `reduced_shading`).
pub(super) struct ReducedShadingPipelines {
    pub downsample: u32,
    pub low_resolution_layout: wgpu::BindGroupLayout,
    pub surface_buffer_layout: wgpu::BindGroupLayout,
    pub mapped_factors_writer_layout: wgpu::BindGroupLayout,
    /// Group 3 of fs_shade_low: the SH path's light the last frame kept at the samples.
    pub kept_samples_layout: wgpu::BindGroupLayout,
    pub full_resolution_layouts: FullResolutionLayouts,
    /// The full-resolution surfaces (fs_surface_buffer), rasterised, for textured objects
    /// and the others.
    surface_buffer: SurfaceBufferPipelines,
    /// The low-resolution samples on a surface marked in the low depth
    /// (fs_mark_surface_samples).
    mark_surface_samples: wgpu::RenderPipeline,
    /// With lights on the shadow-map path: the same marks, and each sample's visibility of
    /// those lights written for the shading passes to read, this frame and later ones
    /// (fs_mark_surface_samples_keeping_visibility).
    mark_keeping_visibility: Option<wgpu::RenderPipeline>,
    /// How the low-resolution samples are shaded: in one level or in two.
    samples: SampleShading,
    /// How the full-resolution frame is drawn from the samples.
    pub full_resolution: FullResolution,
}

/// The full-resolution frame's pipelines: deferred on single-sampled targets, rasterised
/// on multisampled ones (where lavapipe tests depth after the fragment shader, so no pass
/// could shade only the pixels the upsampling left: fs_upsample takes the best sample
/// nearby instead). Only the one a pipeline's targets use is compiled.
pub(super) enum FullResolution {
    Deferred(FullResolutionPipelines),
    /// The rasterised upsampling, for objects with a base colour texture and for the others.
    Rasterised(ByTexture),
}

/// How the low-resolution samples are shaded. Only the one a frame's paths use is
/// compiled: fs_shade_low inlines the blocker walk, and compiling it for two levels, which
/// never draw it, took lavapipe about a second of every variant's compile
/// (docs/performance.md).
pub(super) enum SampleShading {
    /// Every sample shaded in full (fs_shade_low), full-screen.
    OneLevel(wgpu::RenderPipeline),
    /// The soft layer, and the samples shaded from it.
    TwoLevels(SoftLayerPipelines),
}

/// Two-level reduced shading (see `reduced_shading`): the soft layer's samples
/// (fs_shade_soft) and the low-resolution samples upsampled from them with the sharp
/// lights added (fs_shade_sharp_marking; compute passes then list the samples it left
/// and shade them in full, `listed_samples`).
pub(super) struct SoftLayerPipelines {
    shade_soft: wgpu::RenderPipeline,
    shade_sharp: wgpu::RenderPipeline,
    listed: ListedSamplesPipelines,
}

/// The full-resolution frame from the surface buffer: the upsampling and the shading of
/// the pixels it leaves in compute passes (`full_resolution`), whose colours are then
/// copied into the frame.
pub(super) struct FullResolutionPipelines {
    compute: FullResolutionCompute,
}

impl ReducedShadingPipelines {
    /// The pipelines shading one sample per `downsample` × `downsample` pixels from
    /// `module`, for targets and code as `variant` says.
    pub fn new(
        device: &wgpu::Device,
        layouts: &SceneLayouts,
        shadow_layout: &wgpu::BindGroupLayout,
        module: &wgpu::ShaderModule,
        downsample: u32,
        variant: Variant,
    ) -> ReducedShadingPipelines {
        let paths = variant.paths;
        let low_resolution_layout = low_resolution_layout(device);
        let surface_buffer_layout = surface_buffer_layout(device);
        let mapped_factors_writer_layout = mapped_factors_writer_layout(device);
        let full_resolution_layouts = FullResolutionLayouts::new(device);
        let kept_samples_layout = kept_harmonic::samples_layout(device);
        let surface_variant = Variant { samples: 1, ..variant };
        let full_screen_keeping =
            |entry_point, (format, stride_px): (Option<wgpu::TextureFormat>, u32), samples, depth, kept| {
                full_screen_pipeline(
                    device,
                    [&layouts.frame, &surface_buffer_layout, shadow_layout],
                    module,
                    FullScreenPass {
                        entry_point,
                        samples,
                        depth,
                        format,
                        stride_px,
                        kept,
                    },
                    paths,
                )
            };
        let full_screen =
            |entry_point, target, samples, depth| full_screen_keeping(entry_point, target, samples, depth, None);
        let low_samples = Some(LOW_RESOLUTION_FORMATS[0]);
        ReducedShadingPipelines {
            downsample,
            surface_buffer: SurfaceBufferPipelines::new(|stage, textured| {
                let variant = Variant {
                    textured,
                    ..surface_variant
                };
                scene_pipeline(device, layouts, shadow_layout, module, stage, variant)
            }),
            mark_surface_samples: full_screen(
                "fs_mark_surface_samples",
                (None, downsample),
                None,
                FullScreenDepth::MarkSurfaces,
            ),
            mark_keeping_visibility: paths.maps.then(|| {
                full_screen(
                    "fs_mark_surface_samples_keeping_visibility",
                    (None, downsample),
                    Some(&mapped_factors_writer_layout),
                    FullScreenDepth::MarkSurfaces,
                )
            }),
            samples: if two_level(paths) {
                SampleShading::TwoLevels(SoftLayerPipelines {
                    shade_soft: full_screen(
                        "fs_shade_soft",
                        (low_samples, 2 * downsample),
                        None,
                        FullScreenDepth::None,
                    ),
                    // Writing the soft light at the samples it shades into its second target.
                    shade_sharp: full_screen_keeping(
                        "fs_shade_sharp_marking",
                        (low_samples, downsample),
                        Some(&low_resolution_layout),
                        FullScreenDepth::Unmarked,
                        Some(wgpu::ColorWrites::ALL),
                    ),
                    listed: ListedSamplesPipelines::new(
                        device,
                        module,
                        [&layouts.frame, &surface_buffer_layout, shadow_layout],
                        &[
                            path_constants(paths).as_slice(),
                            &[("LEVEL_STRIDE_PX", f64::from(downsample))],
                        ]
                        .concat(),
                    ),
                })
            } else {
                SampleShading::OneLevel(full_screen_keeping(
                    "fs_shade_low",
                    (low_samples, downsample),
                    Some(&kept_samples_layout),
                    FullScreenDepth::Unmarked,
                    Some(wgpu::ColorWrites::ALL),
                ))
            },
            full_resolution: if shades_unmatched_exactly(variant.samples) {
                FullResolution::Deferred(FullResolutionPipelines {
                    compute: FullResolutionCompute::new(
                        device,
                        module,
                        (
                            [&layouts.frame, &surface_buffer_layout, shadow_layout],
                            &full_resolution_layouts,
                        ),
                        &path_constants(paths),
                        (downsample, two_level(paths)),
                    ),
                })
            } else {
                FullResolution::Rasterised(ByTexture::new(|textured| {
                    scene_pipeline(
                        device,
                        layouts,
                        shadow_layout,
                        module,
                        Stage::Upsample(&low_resolution_layout),
                        Variant { textured, ..variant },
                    )
                }))
            },
            low_resolution_layout,
            surface_buffer_layout,
            mapped_factors_writer_layout,
            kept_samples_layout,
            full_resolution_layouts,
        }
    }
}

impl ReducedShadingPipelines {
    /// Two levels: the pipelines of the samples the soft layer leaves, whose groups the
    /// targets hold.
    pub fn listed_samples(&self) -> Option<&ListedSamplesPipelines> {
        match &self.samples {
            SampleShading::TwoLevels(soft) => Some(&soft.listed),
            SampleShading::OneLevel(_) => None,
        }
    }

    /// What its targets need besides the samples ([`LowResolutionTargets::new`]): a soft
    /// layer, a full-resolution surface buffer.
    pub fn levels(&self) -> [bool; 2] {
        [
            matches!(self.samples, SampleShading::TwoLevels(_)),
            matches!(self.full_resolution, FullResolution::Deferred(_)),
        ]
    }
}

/// Whether reduced-resolution shading goes in two levels with `paths` compiled in: when
/// there is light of soft shadows (the SH path's), beside light of sharp ones (shadow
/// maps, the exact path) or alone, the first is shaded at twice the samples' spacing (see
/// `reduced_shading`). Alone too since 2026-12-07: on the blocker bench (its one light on
/// the SH path) the samples' passes took about 19 ms where shading every sample in full
/// took 24, the frame within RMSE 0.002 of the one-level frame and as far from exact
/// visibility (docs/performance.md).
fn two_level(paths: CompiledPaths) -> bool {
    paths.harmonics
}

/// The reduced-resolution samples: the surface buffer rasterised at full resolution
/// (unless it already shows this frame's surfaces: [`LowResolutionTargets::expect_inputs`]),
/// the samples on a surface marked in the low depth, then (two-level) the soft layer
/// (unless it already holds this frame's soft light) and the samples shaded from it, else
/// the samples shaded in full, by full-screen passes reading the buffer.
pub(super) fn shade_low_resolution(
    frame: &mut TimedEncoder,
    pipelines: &ReducedShadingPipelines,
    low: &LowResolutionTargets,
    (scene, blockers): (&GpuScene, &GpuBlockers),
) {
    // A frame after an edit of the lights alone sees the surfaces the last one drew.
    if !low.surfaces_current() {
        draw_surfaces(frame, &low.surface, &pipelines.surface_buffer, scene, blockers);
    }

    // A frame of new surfaces shades the mapped lights at its samples itself: it binds
    // a surface group without their factors (too short to hold them, so the shading
    // passes read the maps: low_resolution.wgsl's holds_mapped_lights).
    let surface_group = match low.keeps_mapped_factors() {
        true => &low.surface.bind_group,
        false => &low.surface.bind_group_without_factors,
    };
    let bound = Bound {
        scene,
        blockers,
        surface: surface_group,
    };
    // The samples' visibility of the mapped lights the last frames wrote holds while the
    // surfaces, those lights' geometry and their maps do; else the marking pass writes it
    // (in frames that keep it).
    let (mark, writing) = match &pipelines.mark_keeping_visibility {
        Some(keeping) if low.keeps_mapped_factors() && !low.mapped_factors_current() => (
            Some((keeping, Some(&low.surface.mapped_factors_writer))),
            // The buffer is written in this pass, so the surface group reads none.
            &low.surface.bind_group_without_factors,
        ),
        // With the surfaces the last marks were made on, the marks are copied back.
        _ if low.surfaces_current() => (None, surface_group),
        _ => (Some((&pipelines.mark_surface_samples, None)), surface_group),
    };
    match mark {
        Some(mark) => {
            Bound {
                surface: writing,
                ..bound
            }
            .full_screen(
                frame,
                "low-resolution depth",
                (&[], Some(low.low_depth_attachment(true))),
                &[mark],
            );
            low.keep_marked_samples(frame.encoder);
        }
        None => low.restore_marked_samples(frame.encoder),
    }
    // The samples, and the SH path's light fs_shade_low keeps at those it shades.
    let [sample_target] = low.samples.color_attachments();
    let samples = [sample_target, low.kept_at_samples.written()];
    let kept = Some(low.kept_at_samples.read_group());
    match (&pipelines.samples, &low.soft) {
        (SampleShading::TwoLevels(soft_pipelines), Some(soft)) => {
            // A frame after an edit of lights off the SH path sees the last soft layer.
            if !low.soft_layer_current() {
                bound.full_screen(
                    frame,
                    "soft layer shading",
                    (&soft.color_attachments(), None),
                    &[(&soft_pipelines.shade_soft, None)],
                );
            }
            // The sharp pass leaves the samples it does not serve without a surface in
            // the samples' image, which the compute passes list and shade.
            bound.full_screen(
                frame,
                "low-resolution shading",
                (&samples, Some(low.low_depth_attachment(false))),
                &[(&soft_pipelines.shade_sharp, Some(&soft.bind_group))],
            );
            if let Some(listed) = &low.listed_samples {
                soft_pipelines.listed.draw(
                    frame,
                    listed,
                    low.kept_at_samples.read_index(),
                    [&scene.frame_bind_group, bound.surface, &blockers.bind_group],
                );
            }
        }
        (SampleShading::OneLevel(shade_low), _) => bound.full_screen(
            frame,
            "low-resolution shading",
            (&samples, Some(low.low_depth_attachment(false))),
            &[(shade_low, kept)],
        ),
        // Targets are made for their pipelines' levels (`levels`), so they hold a soft
        // layer wherever the pipelines shade in two.
        (SampleShading::TwoLevels(_), None) => log::error!("two-level shading without a soft layer's targets"),
    }
}

/// Rasterises the visible surfaces into `surface` (its images and depth, cleared) by
/// fs_surface_buffer.
fn draw_surfaces(
    frame: &mut TimedEncoder,
    surface: &SurfaceBuffer,
    pipelines: &SurfaceBufferPipelines,
    scene: &GpuScene,
    blockers: &GpuBlockers,
) {
    const LABEL: &str = "surfaces";
    let surfaces = surface.color_attachments();
    let mut pass = frame.encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
        label: Some(LABEL),
        color_attachments: &surfaces,
        depth_stencil_attachment: Some(surface.depth_attachment()),
        timestamp_writes: None,
        occlusion_query_set: None,
        multiview_mask: None,
    });
    pass.set_bind_group(slots::FRAME_GROUP, &scene.frame_bind_group, &[]);
    pass.set_bind_group(slots::SHADOW_GROUP, &blockers.bind_group, &[]);
    pipelines.draw_objects(&mut pass, scene);
    drop(pass);
    frame.mark(LABEL);
}

/// The full-resolution frame deferred: from the surface buffer and the samples
/// `shade_low_resolution` drew, the compute passes (`full_resolution`), then their
/// colours (the frame's background where the buffer has no surface: the frame uniform's)
/// copied into `target`'s image. False, drawing nothing, where `pipelines` have no
/// deferred full-resolution frame or `target` is multisampled.
pub(super) fn draw_full_resolution(
    frame: &mut TimedEncoder,
    pipelines: &ReducedShadingPipelines,
    low: &LowResolutionTargets,
    target: &RenderTarget,
    scene: &GpuScene,
    blockers: &GpuBlockers,
) -> bool {
    let (FullResolution::Deferred(full), Some(images), Some(image)) = (
        &pipelines.full_resolution,
        low.full_resolution.as_ref(),
        target.single_sampled_image(),
    ) else {
        return false;
    };
    full.compute.draw(
        frame,
        (images, low.kept_at_samples.written_index()),
        [&scene.frame_bind_group, &low.surface.bind_group, &blockers.bind_group],
    );
    images.copy_colours(frame.encoder, image);
    // The edge filter reads where the surfaces break from the frame's depth.
    target.copy_depth_from(frame.encoder, &low.surface.depth);
    frame.mark("frame colours copied");
    true
}

/// What every full-screen pass binds: the frame, a surface buffer, the blockers.
#[derive(Clone, Copy)]
struct Bound<'a> {
    scene: &'a GpuScene,
    blockers: &'a GpuBlockers,
    /// The surface buffer's group (1).
    surface: &'a wgpu::BindGroup,
}

impl Bound<'_> {
    /// One render pass named `label` into `targets` (colour, depth) drawing the full-screen
    /// triangle with each of `shading` in turn, each with the coarser samples it reads
    /// bound as group 3.
    fn full_screen(
        &self,
        frame: &mut TimedEncoder,
        label: &'static str,
        targets: (
            &[Option<wgpu::RenderPassColorAttachment<'_>>],
            Option<wgpu::RenderPassDepthStencilAttachment<'_>>,
        ),
        shading: &[(&wgpu::RenderPipeline, Option<&wgpu::BindGroup>)],
    ) {
        let mut pass = frame.encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
            label: Some(label),
            color_attachments: targets.0,
            depth_stencil_attachment: targets.1,
            timestamp_writes: None,
            occlusion_query_set: None,
            multiview_mask: None,
        });
        pass.set_bind_group(slots::FRAME_GROUP, &self.scene.frame_bind_group, &[]);
        pass.set_bind_group(slots::MATERIAL_GROUP, self.surface, &[]);
        pass.set_bind_group(slots::SHADOW_GROUP, &self.blockers.bind_group, &[]);
        for &(pipeline, coarser) in shading {
            if let Some(coarser) = coarser {
                pass.set_bind_group(slots::PASS_GROUP, coarser, &[]);
            }
            pass.set_pipeline(pipeline);
            pass.draw(0..3, 0..1);
        }
        drop(pass);
        frame.mark(label);
    }
}

/// How a full-screen pass of the low-resolution shading meets the surfaces' depth (its
/// triangle lies at depth 1; see low_resolution.wgsl).
#[derive(Clone, Copy)]
enum FullScreenDepth {
    /// No depth attachment (the soft layer, which reads the buffer itself).
    None,
    /// Writes depth 0 wherever it does not discard (fs_mark_surface_samples).
    MarkSurfaces,
    /// Only where the marks say a surface was drawn (depth < 1); it writes no depth.
    Unmarked,
}

/// A full-screen pass of the deferred shading.
struct FullScreenPass<'a> {
    entry_point: &'static str,
    /// Its one target's format, if it has one.
    format: Option<wgpu::TextureFormat>,
    /// Full-resolution pixels per pixel of its image along each side (LEVEL_STRIDE_PX).
    stride_px: u32,
    /// The coarser samples it reads (group 3), if any.
    samples: Option<&'a wgpu::BindGroupLayout>,
    depth: FullScreenDepth,
    /// A second target, the soft light at the samples (`kept_harmonic`), written with
    /// these writes: the passes of fs_shade_low's render pass have it.
    kept: Option<wgpu::ColorWrites>,
}

/// A pipeline drawing vs_full_screen's triangle into one target with `pass.entry_point`, bind groups `groups` (frame, surface buffer, shadow)
/// and the coarser samples, with `paths` compiled in.
fn full_screen_pipeline(
    device: &wgpu::Device,
    groups: [&wgpu::BindGroupLayout; 3],
    module: &wgpu::ShaderModule,
    pass: FullScreenPass,
    paths: CompiledPaths,
) -> wgpu::RenderPipeline {
    let mut bind_group_layouts: Vec<Option<&wgpu::BindGroupLayout>> = groups.into_iter().map(Some).collect();
    if let Some(samples) = pass.samples {
        bind_group_layouts.push(Some(samples));
    }
    let layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
        label: Some(pass.entry_point),
        bind_group_layouts: &bind_group_layouts,
        immediate_size: 0,
    });
    let depth_stencil = match pass.depth {
        FullScreenDepth::None => None,
        FullScreenDepth::MarkSurfaces => Some(depth_test(true, wgpu::CompareFunction::Always)),
        FullScreenDepth::Unmarked => Some(depth_test(false, wgpu::CompareFunction::Greater)),
    };
    let mut constants = path_constants(paths);
    constants.push(("LEVEL_STRIDE_PX", f64::from(pass.stride_px)));
    let target = |format, write_mask| {
        Some(wgpu::ColorTargetState {
            format,
            blend: None,
            write_mask,
        })
    };
    let targets: Vec<Option<wgpu::ColorTargetState>> = pass
        .format
        .map(|format| target(format, wgpu::ColorWrites::ALL))
        .into_iter()
        .chain(pass.kept.map(|writes| target(kept_harmonic::SAMPLES_FORMAT, writes)))
        .collect();
    device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
        label: Some(pass.entry_point),
        layout: Some(&layout),
        vertex: wgpu::VertexState {
            module,
            entry_point: Some("vs_full_screen"),
            compilation_options: Default::default(),
            buffers: &[],
        },
        primitive: wgpu::PrimitiveState::default(),
        depth_stencil,
        multisample: Default::default(),
        fragment: Some(wgpu::FragmentState {
            module,
            entry_point: Some(pass.entry_point),
            compilation_options: wgpu::PipelineCompilationOptions {
                constants: &constants,
                ..Default::default()
            },
            targets: &targets,
        }),
        multiview_mask: None,
        cache: None,
    })
}
