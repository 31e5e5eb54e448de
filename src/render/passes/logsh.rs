//! The log-SH soft-shadow pipeline (shaders/logsh.wgsl): a depth pre-pass, then one
//! shading pass in which every visible pixel sums its blockers' log-visibility,
//! exponentiates it and shades each light through it — or, with reduced-resolution
//! shading (`reduced_shading`), the same for one pixel in d × d and an upsampling pass.
//! The SH order and exponentiation method are baked into the module at creation
//! (generated WGSL, `shading::wgsl::sh`).

use super::low_resolution::{FullResolution, ReducedShadingPipelines, draw_full_resolution, shade_low_resolution};
use super::per_vertex::{PerVertexCompute, VertexVisibility};
use super::reduced_shading::LowResolutionTargets;
pub use super::scene_pipeline::SURFACE_FORMAT;
use super::scene_pipeline::{BySides, Stage, Variant, path_constants, scene_pipeline};
use crate::render::descriptors::create_module;
use crate::render::pass_timer::TimedEncoder;
use crate::render::resources::{GpuBlockers, GpuScene, SceneLayouts, draw_object, draw_objects, shadow_layout};
use crate::render::target::RenderTarget;
use crate::sh::ExpMethod;
use crate::shading::wgsl::slots;
use crate::shading::wgsl::{self, sh as wgsl_sh};
use crate::shading::{BrdfShading, CompiledPaths, ShadowSettings};

/// Pipelines drawing a scene with log-SH shadows at one order and method.
pub struct LogShPipeline {
    pub order: usize,
    pub exp: ExpMethod,
    pub brdf: BrdfShading,
    pub samples: u32,
    /// The shading paths compiled in.
    pub paths: CompiledPaths,
    pub shadow_layout: wgpu::BindGroupLayout,
    depth_prepass: wgpu::RenderPipeline,
    shade: wgpu::RenderPipeline,
    /// Per-vertex shading, where the order allows it.
    pub per_vertex: Option<PerVertexPipelines>,
    /// Reduced-resolution shading, when the settings ask for it.
    reduced: Option<ReducedShadingPipelines>,
}

/// The passes of per-vertex shading: the compute passes of the vertices' visibility and
/// light, and the scene pass's pipelines through each.
pub struct PerVertexPipelines {
    pub compute: PerVertexCompute,
    /// Shading each pixel through the interpolated visibility (fs_per_vertex).
    pub shade: BySides,
    /// The interpolated light of meshes lit at their vertices (fs_vertex_lit).
    pub lit: BySides,
}

/// How a frame's pixels are shaded, with the buffers that way needs.
#[derive(Clone, Copy)]
pub enum Shading<'a> {
    /// Every pixel in full.
    PerPixel,
    /// Through visibility exponentiated at the vertices ([`LogShPipeline::vertex_visibility`]
    /// for the same scene).
    PerVertex(&'a VertexVisibility),
    /// One pixel in d × d, the others upsampled
    /// ([`LogShPipeline::low_resolution_targets`] for the target's size).
    Reduced(&'a LowResolutionTargets),
}

impl<'a> Shading<'a> {
    /// Per vertex when there is visibility, else at a reduced resolution when there are
    /// low-resolution targets, else per pixel.
    pub fn first_of(
        per_vertex: Option<&'a VertexVisibility>,
        low_resolution: Option<&'a LowResolutionTargets>,
    ) -> Self {
        match (per_vertex, low_resolution) {
            (Some(visibility), _) => Shading::PerVertex(visibility),
            (None, Some(low)) => Shading::Reduced(low),
            (None, None) => Shading::PerPixel,
        }
    }
}

impl LogShPipeline {
    /// Pipelines for `settings.order` and `settings.exp` drawing into targets of `samples`
    /// samples (the settings must be valid: see [`ShadowSettings::gpu_problems`]), with
    /// the shading `paths` compiled in (see [`crate::shading::compiled_paths`]: lavapipe pays for
    /// a path's code at every pixel whether or not a light takes it).
    pub fn new(
        device: &wgpu::Device,
        layouts: &SceneLayouts,
        settings: &ShadowSettings,
        samples: u32,
        paths: CompiledPaths,
    ) -> LogShPipeline {
        let shadow_layout = shadow_layout(device);
        let source = wgsl::logsh_source(settings.order, settings.exp, settings.brdf);
        let module = create_module(device, "log-SH shadows", &source);
        let variant = Variant {
            samples,
            paths,
            textured: true,
        };
        let make_variant = |stage, variant| scene_pipeline(device, layouts, &shadow_layout, &module, stage, variant);
        let make = |stage| make_variant(stage, variant);
        let per_vertex = wgsl_sh::supports_per_vertex(settings.order).then(|| PerVertexPipelines {
            compute: PerVertexCompute::new(
                device,
                &module,
                [&layouts.frame, &layouts.material, &shadow_layout],
                settings.order,
                &path_constants(paths.with_one_visibility()),
            ),
            shade: BySides::new(variant, |variant| {
                make_variant(
                    Stage::ShadePerVertex(settings.order, !per_vertex_prepass(paths)),
                    variant,
                )
            }),
            lit: BySides::new(variant, |variant| {
                make_variant(Stage::VertexLit(!per_vertex_prepass(paths)), variant)
            }),
        });
        let reduced = (settings.shading_downsample > 1).then(|| {
            ReducedShadingPipelines::new(
                device,
                layouts,
                &shadow_layout,
                &module,
                settings.shading_downsample,
                variant,
            )
        });
        LogShPipeline {
            order: settings.order,
            exp: settings.exp,
            brdf: settings.brdf,
            samples,
            paths,
            depth_prepass: make(Stage::DepthOnly),
            shade: make(Stage::Shade),
            per_vertex,
            reduced,
            shadow_layout,
        }
    }

    /// Whether this pipeline was built for `settings`' order, method, BRDF and shading
    /// resolution, and with `paths`.
    pub fn matches(&self, settings: &ShadowSettings, paths: CompiledPaths) -> bool {
        self.paths == paths
            && self.order == settings.order
            && self.exp == settings.exp
            && self.brdf == settings.brdf
            && self.shading_downsample() == settings.shading_downsample
    }

    /// Pixels per shaded sample along each side (1: every pixel is shaded).
    pub fn shading_downsample(&self) -> u32 {
        self.reduced.as_ref().map_or(1, |r| r.downsample)
    }

    /// The low-resolution images for frames of `full_size` when this pipeline shades at a
    /// reduced resolution; `reuse` is returned as it is when it still fits.
    pub fn low_resolution_targets(
        &self,
        device: &wgpu::Device,
        full_size: [u32; 2],
        reuse: Option<LowResolutionTargets>,
    ) -> Option<LowResolutionTargets> {
        let reduced = self.reduced.as_ref()?;
        match reuse {
            Some(targets) if targets.fits(full_size, reduced.downsample, reduced.levels()) => Some(targets),
            _ => Some(LowResolutionTargets::new(
                device,
                (
                    [
                        &reduced.low_resolution_layout,
                        &reduced.surface_buffer_layout,
                        &reduced.mapped_factors_writer_layout,
                        &reduced.kept_samples_layout,
                    ],
                    &reduced.full_resolution_layouts,
                    reduced.listed_samples(),
                ),
                full_size,
                reduced.downsample,
                reduced.levels(),
            )),
        }
    }

    /// The per-vertex visibility buffers for `scene`, if this order supports them.
    pub fn vertex_visibility(&self, device: &wgpu::Device, scene: &GpuScene) -> Option<VertexVisibility> {
        self.per_vertex
            .as_ref()
            .map(|pipelines| VertexVisibility::new(device, &pipelines.compute, scene))
    }

    /// Clears `target` to `background` (linear RGB) and draws every object with shadows,
    /// the way `shading` says (per pixel where this pipeline cannot do it that way).
    pub fn draw(
        &self,
        frame: &mut TimedEncoder,
        target: &RenderTarget,
        scene: &GpuScene,
        blockers: &GpuBlockers,
        background_linear: [f64; 3],
        shading: Shading,
    ) {
        let per_vertex = match shading {
            Shading::PerVertex(visibility) => Some(visibility).zip(self.per_vertex.as_ref()),
            _ => None,
        };
        let reduced = match shading {
            Shading::Reduced(low) => Some(low)
                .zip(self.reduced.as_ref())
                .filter(|(low, _)| low.full_size == [target.width, target.height]),
            _ => None,
        };
        if let Some((visibility, pipelines)) = per_vertex {
            let groups = [&scene.frame_bind_group, &blockers.bind_group];
            pipelines.compute.run(frame.encoder, groups, scene, visibility);
            frame.mark("per-vertex visibility");
            pipelines
                .compute
                .light
                .run(frame.encoder, groups, scene, &visibility.light);
            frame.mark("vertex light");
        }
        if let Some((low, pipelines)) = reduced {
            shade_low_resolution(frame, pipelines, low, (scene, blockers));
            if draw_full_resolution(frame, pipelines, low, target, scene, blockers) {
                finish(frame, target);
                return;
            }
        }
        let mut pass = frame.encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
            label: Some("log-SH scene"),
            color_attachments: &[Some(target.color_attachment(background_linear))],
            depth_stencil_attachment: Some(target.depth_attachment()),
            timestamp_writes: None,
            occlusion_query_set: None,
            multiview_mask: None,
        });
        pass.set_bind_group(slots::FRAME_GROUP, &scene.frame_bind_group, &[]);
        pass.set_bind_group(slots::SHADOW_GROUP, &blockers.bind_group, &[]);
        // The pre-pass settles depth, so the costly shading runs once per visible pixel
        // (per vertex only where `per_vertex_prepass` says).
        if per_vertex.is_none() || per_vertex_prepass(self.paths) {
            pass.set_pipeline(&self.depth_prepass);
            draw_objects(&mut pass, scene);
        }
        match (per_vertex, reduced) {
            (Some((visibility, pipelines)), _) => {
                // The meshes lit at their vertices, then those shaded through their
                // vertices' visibility, each with their back faces culled where the
                // camera cannot see them.
                for (lit, back_faces_hidden) in [(true, false), (true, true), (false, false), (false, true)] {
                    let sides = if lit { &pipelines.lit } else { &pipelines.shade };
                    pass.set_pipeline(sides.for_back_faces_hidden(back_faces_hidden));
                    for (k, (object, buffer)) in scene.objects.iter().zip(&visibility.buffers).enumerate() {
                        let light = visibility.light.buffer(k);
                        if !object.drawn_in_view()
                            || light.is_some() != lit
                            || object.back_faces_hidden != back_faces_hidden
                        {
                            continue;
                        }
                        pass.set_vertex_buffer(1, light.unwrap_or(buffer).slice(..));
                        draw_object(&mut pass, scene, object);
                    }
                }
            }
            (None, Some((low, pipelines))) => {
                // Multisampled: every pixel from the samples, the best match nearby where
                // none matches (single-sampled frames were drawn deferred above).
                if let FullResolution::Rasterised(upsample) = &pipelines.full_resolution {
                    pass.set_bind_group(slots::PASS_GROUP, low.bind_group(), &[]);
                    upsample.draw_objects(&mut pass, scene);
                }
            }
            (None, None) => {
                pass.set_pipeline(&self.shade);
                draw_objects(&mut pass, scene);
            }
        }
        drop(pass);
        frame.mark("scene pass (depth, upsampling, shading)");
        finish(frame, target);
    }
}

/// Whether per-vertex frames with `paths` compiled in draw a depth pre-pass: only with
/// lights on the shadow-map or exact paths, which cost each pixel a lookup or a walk.
/// Without them a pixel only meets the interpolated visibility with the SH lights,
/// cheaper than a second pass over the geometry (the blocker bench's per-vertex frame
/// 62–74 → 50–61 ms, the same pixels; the studio's, with shadow maps, had gone 105 →
/// 109–112 ms without it: docs/performance.md).
fn per_vertex_prepass(paths: CompiledPaths) -> bool {
    paths.maps || paths.exact
}

/// Resolves or filters `target`'s frame (see [`RenderTarget::finish`]), timed.
fn finish(frame: &mut TimedEncoder, target: &RenderTarget) {
    target.finish(frame.encoder);
    if target.has_edge_filter() {
        frame.mark("edge filter");
    }
}

/// Number of surface channels fs_surface writes (position, normal, k_d, k_s, emissive).
pub const SURFACE_CHANNELS: u32 = 5;

/// One pipeline per surface channel (see fs_surface), each writing that property of every
/// visible pixel into an [`SURFACE_FORMAT`] target with one sample, all from one module;
/// `cull_back_faces` as the shading pipelines of the same scene
/// ([`crate::scene::Scene::every_material_single_sided`]).
pub fn surface_pipelines(
    device: &wgpu::Device,
    layouts: &SceneLayouts,
    shadow_layout: &wgpu::BindGroupLayout,
    cull_back_faces: bool,
) -> Vec<wgpu::RenderPipeline> {
    // Any order and method: fs_surface uses no SH.
    let source = wgsl::logsh_source(2, ExpMethod::Dc, BrdfShading::Separate);
    let module = create_module(device, "surface channels", &source);
    (0..SURFACE_CHANNELS)
        .map(|channel| {
            scene_pipeline(
                device,
                layouts,
                shadow_layout,
                &module,
                Stage::Surface(channel, "SURFACE_CHANNEL"),
                // fs_surface shades no light; it sees the faces the shading passes see.
                Variant {
                    samples: 1,
                    paths: CompiledPaths {
                        cull_back_faces,
                        ..CompiledPaths::NONE
                    },
                    textured: true,
                },
            )
        })
        .collect()
}
