//! The log-SH soft-shadow pipeline (shaders/logsh.wgsl): a depth pre-pass, then one
//! shading pass in which every visible pixel sums its blockers' log-visibility,
//! exponentiates it and shades each light through it — or, with reduced-resolution
//! shading (`reduced_shading`), the same for one pixel in d × d and an upsampling pass.
//! The SH order and exponentiation method are baked into the module at creation
//! (generated WGSL, `shading::wgsl::sh`).

use super::per_vertex::{PerVertexCompute, VertexVisibility};
use super::reduced_shading::{LOW_RESOLUTION_FORMATS, LowResolutionTargets, low_resolution_layout};
use crate::render::descriptors::{create_module, depth_test, scene_triangles};
use crate::render::pass_timer::TimedEncoder;
use crate::render::resources::{
    GpuBlockers, GpuScene, SceneLayouts, draw_object, draw_objects, shadow_layout, vertex_layout,
};
use crate::render::target::RenderTarget;
use crate::sh::ExpMethod;
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
    pub per_vertex: Option<(PerVertexCompute, wgpu::RenderPipeline)>,
    /// Reduced-resolution shading, when the settings ask for it.
    reduced: Option<ReducedShadingPipelines>,
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

/// The passes of reduced-resolution shading (see `reduced_shading`).
struct ReducedShadingPipelines {
    downsample: u32,
    low_resolution_layout: wgpu::BindGroupLayout,
    low_depth: wgpu::RenderPipeline,
    shade_low: wgpu::RenderPipeline,
    /// The upsampling, for objects with a base colour texture and for the others.
    upsample: ByTexture,
}

/// A pipeline for textured objects and its twin for untextured ones, compiled without the
/// texture sample (BASE_COLOR_TEXTURE in scene.wgsl).
struct ByTexture {
    textured: wgpu::RenderPipeline,
    untextured: wgpu::RenderPipeline,
}

impl ByTexture {
    fn new(make: impl Fn(bool) -> wgpu::RenderPipeline) -> ByTexture {
        ByTexture {
            textured: make(true),
            untextured: make(false),
        }
    }

    /// Draws every visible object with the pipeline for its material.
    fn draw_objects(&self, pass: &mut wgpu::RenderPass<'_>, scene: &GpuScene) {
        for textured in [true, false] {
            pass.set_pipeline(if textured { &self.textured } else { &self.untextured });
            for object in scene.objects.iter().filter(|o| !o.hidden && o.textured == textured) {
                draw_object(pass, scene, object);
            }
        }
    }
}

/// What a pipeline's fragment stage is for.
#[derive(Clone, Copy)]
enum Stage<'a> {
    DepthOnly,
    Shade,
    /// Shading through per-vertex visibility attributes of this order.
    ShadePerVertex(usize),
    /// One surface channel (fs_surface) as raw f32.
    Surface(u32, &'a str),
    /// Depth only, without a fragment stage (the reduced-resolution pre-pass).
    LowDepthOnly,
    /// The reduced-resolution samples (fs_shade_low) into [`LOW_RESOLUTION_FORMATS`].
    ShadeLow,
    /// Full-resolution pixels from the reduced-resolution samples (fs_upsample), which
    /// reads them through bind group 3 of this layout.
    Upsample(&'a wgpu::BindGroupLayout),
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
        let make = |stage| scene_pipeline(device, layouts, &shadow_layout, &module, stage, variant);
        let per_vertex = wgsl_sh::supports_per_vertex(settings.order).then(|| {
            (
                PerVertexCompute::new(device, &module, &shadow_layout, settings.order, &path_constants(paths)),
                make(Stage::ShadePerVertex(settings.order)),
            )
        });
        let reduced = (settings.shading_downsample > 1).then(|| {
            let low_resolution_layout = low_resolution_layout(device);
            let low_variant = Variant { samples: 1, ..variant };
            let low = |stage| scene_pipeline(device, layouts, &shadow_layout, &module, stage, low_variant);
            ReducedShadingPipelines {
                downsample: settings.shading_downsample,
                low_depth: low(Stage::LowDepthOnly),
                shade_low: low(Stage::ShadeLow),
                upsample: ByTexture::new(|textured| {
                    scene_pipeline(
                        device,
                        layouts,
                        &shadow_layout,
                        &module,
                        Stage::Upsample(&low_resolution_layout),
                        Variant { textured, ..variant },
                    )
                }),
                low_resolution_layout,
            }
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
            Some(targets) if targets.fits(full_size, reduced.downsample) => Some(targets),
            _ => Some(LowResolutionTargets::new(
                device,
                &reduced.low_resolution_layout,
                full_size,
                reduced.downsample,
            )),
        }
    }

    /// The per-vertex visibility buffers for `scene`, if this order supports them.
    pub fn vertex_visibility(&self, device: &wgpu::Device, scene: &GpuScene) -> Option<VertexVisibility> {
        self.per_vertex
            .as_ref()
            .map(|(compute, _)| VertexVisibility::new(device, compute, scene))
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
        if let Some((visibility, (compute, _))) = per_vertex {
            compute.run(frame.encoder, &blockers.bind_group, visibility);
            frame.mark("per-vertex visibility");
        }
        if let Some((low, pipelines)) = reduced {
            shade_low_resolution(frame, pipelines, low, scene, blockers);
        }
        let mut pass = frame.encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
            label: Some("log-SH scene"),
            color_attachments: &[Some(target.color_attachment(background_linear))],
            depth_stencil_attachment: Some(target.depth_attachment()),
            timestamp_writes: None,
            occlusion_query_set: None,
            multiview_mask: None,
        });
        pass.set_bind_group(0, &scene.frame_bind_group, &[]);
        pass.set_bind_group(2, &blockers.bind_group, &[]);
        // The pre-pass settles depth, so the costly shading runs once per visible pixel.
        pass.set_pipeline(&self.depth_prepass);
        draw_objects(&mut pass, scene);
        match (per_vertex, reduced) {
            (Some((visibility, (_, shade))), _) => {
                pass.set_pipeline(shade);
                for (object, buffer) in scene.objects.iter().zip(&visibility.buffers) {
                    if object.hidden {
                        continue;
                    }
                    pass.set_vertex_buffer(1, buffer.slice(..));
                    draw_object(&mut pass, scene, object);
                }
            }
            (None, Some((low, pipelines))) => {
                pass.set_bind_group(3, &low.bind_group, &[]);
                pipelines.upsample.draw_objects(&mut pass, scene);
                // The pixels the upsampling left (it moved the others' depth nearer).
                if shades_unmatched_exactly(self.samples) {
                    pass.set_pipeline(&self.shade);
                    draw_objects(&mut pass, scene);
                }
            }
            (None, None) => {
                pass.set_pipeline(&self.shade);
                draw_objects(&mut pass, scene);
            }
        }
        drop(pass);
        frame.mark("scene pass (depth, upsampling, shading)");
        target.finish(frame.encoder);
        if target.has_edge_filter() {
            frame.mark("edge filter");
        }
    }
}

/// Whether reduced-resolution shading shades the pixels no sample matches in full, after
/// the upsampling (see reduced_shading.wgsl): only where lavapipe tests depth before the
/// fragment shader, which it does without multisampling; with it, they take the best
/// sample nearby.
fn shades_unmatched_exactly(samples: u32) -> bool {
    samples == 1
}

/// The reduced-resolution samples: a depth pass, then the shading of the visible
/// surface into `low`'s images.
fn shade_low_resolution(
    frame: &mut TimedEncoder,
    pipelines: &ReducedShadingPipelines,
    low: &LowResolutionTargets,
    scene: &GpuScene,
    blockers: &GpuBlockers,
) {
    let attachments = low.color_attachments();
    // First the depth alone, so that the costly shading runs once per visible sample.
    let passes = [
        ("low-resolution depth", &[][..], true, &pipelines.low_depth),
        ("low-resolution shading", &attachments[..], false, &pipelines.shade_low),
    ];
    for (label, color_attachments, depth_pass, pipeline) in passes {
        let mut pass = frame.encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
            label: Some(label),
            color_attachments,
            depth_stencil_attachment: Some(low.depth_attachment(depth_pass)),
            timestamp_writes: None,
            occlusion_query_set: None,
            multiview_mask: None,
        });
        pass.set_bind_group(0, &scene.frame_bind_group, &[]);
        pass.set_bind_group(2, &blockers.bind_group, &[]);
        pass.set_pipeline(pipeline);
        draw_objects(&mut pass, scene);
        drop(pass);
        frame.mark(label);
    }
}

/// Format of the surface channels read back for the CPU reference.
pub const SURFACE_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba32Float;

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

/// What a pipeline is compiled for besides its stage.
#[derive(Clone, Copy)]
struct Variant {
    samples: u32,
    /// The shading paths compiled in ([`path_constants`]).
    paths: CompiledPaths,
    /// false: compiled without the base colour texture, for untextured objects.
    textured: bool,
}

/// The override constants that compile `paths` in (see [`CompiledPaths`]).
fn path_constants(paths: CompiledPaths) -> Vec<(&'static str, f64)> {
    let flag = |on: bool| f64::from(u8::from(on));
    vec![
        ("EXACT_LIGHT_PATH", flag(paths.exact)),
        ("EXACT_WIDE", flag(paths.exact_wide)),
        ("SHADOW_MAPS", flag(paths.maps)),
        ("SOFT_SHADOW_MAPS", flag(paths.soft_maps)),
        ("SH_VISIBILITY", flag(paths.harmonics)),
        ("TERRAIN_SHADOWS", flag(paths.terrain)),
        ("AREA_LIGHTS", flag(paths.area_lights)),
        ("LIGHT_OVERFLOW", flag(paths.light_overflow)),
        ("BLOCKER_OVERFLOW", flag(paths.blocker_overflow)),
    ]
}

/// The upsampling that leaves unmatched pixels to a full shading pass marks the pixels it
/// writes by moving their depth this many depth steps nearer (see reduced_shading.wgsl):
/// a constant bias, so its shader need not write depth, which would have lavapipe test
/// depth only after running it on every hidden fragment as well.
const MARKED_DEPTH_STEPS: i32 = 8;

fn depth_bias(stage: Stage, samples: u32) -> wgpu::DepthBiasState {
    match stage {
        Stage::Upsample(_) if shades_unmatched_exactly(samples) => wgpu::DepthBiasState {
            constant: -MARKED_DEPTH_STEPS,
            slope_scale: 0.0,
            clamp: 0.0,
        },
        _ => wgpu::DepthBiasState::default(),
    }
}

fn scene_pipeline(
    device: &wgpu::Device,
    layouts: &SceneLayouts,
    shadow_layout: &wgpu::BindGroupLayout,
    module: &wgpu::ShaderModule,
    stage: Stage,
    variant: Variant,
) -> wgpu::RenderPipeline {
    let samples = variant.samples;
    let mut bind_group_layouts = vec![Some(&layouts.frame), Some(&layouts.material), Some(shadow_layout)];
    if let Stage::Upsample(low_resolution) = stage {
        bind_group_layouts.push(Some(low_resolution));
    }
    let layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
        label: Some("log-SH"),
        bind_group_layouts: &bind_group_layouts,
        immediate_size: 0,
    });
    let visibility_attributes = match stage {
        Stage::ShadePerVertex(order) => PerVertexCompute::attributes(order),
        _ => Vec::new(),
    };
    let visibility_layout = wgpu::VertexBufferLayout {
        array_stride: 16 * visibility_attributes.len() as u64,
        step_mode: wgpu::VertexStepMode::Vertex,
        attributes: &visibility_attributes,
    };
    let (vertex_entry, buffers) = match stage {
        Stage::ShadePerVertex(_) => ("vs_per_vertex", vec![Some(vertex_layout()), Some(visibility_layout)]),
        _ => ("vs_main", vec![Some(vertex_layout())]),
    };
    let color = |format| {
        Some(wgpu::ColorTargetState {
            format,
            blend: None,
            write_mask: wgpu::ColorWrites::ALL,
        })
    };
    let depth_only = Some(wgpu::ColorTargetState {
        format: crate::render::descriptors::COLOR_FORMAT,
        blend: None,
        write_mask: wgpu::ColorWrites::empty(),
    });
    let shaded = color(crate::render::descriptors::COLOR_FORMAT);
    let (entry_point, targets, depth_write, compare) = match stage {
        Stage::DepthOnly => ("fs_depth_only", vec![depth_only], true, wgpu::CompareFunction::Less),
        Stage::ShadePerVertex(_) => ("fs_per_vertex", vec![shaded], false, wgpu::CompareFunction::LessEqual),
        Stage::Shade => ("fs_logsh", vec![shaded], false, wgpu::CompareFunction::LessEqual),
        // Marks the pixels it did by moving their depth nearer (see reduced_shading.wgsl).
        Stage::Upsample(_) if shades_unmatched_exactly(samples) => (
            "fs_upsample_marking",
            vec![shaded],
            true,
            wgpu::CompareFunction::LessEqual,
        ),
        Stage::Upsample(_) => ("fs_upsample", vec![shaded], false, wgpu::CompareFunction::LessEqual),
        Stage::ShadeLow => (
            "fs_shade_low",
            LOW_RESOLUTION_FORMATS.map(color).to_vec(),
            false,
            wgpu::CompareFunction::LessEqual,
        ),
        Stage::LowDepthOnly => ("", Vec::new(), true, wgpu::CompareFunction::Less),
        Stage::Surface(..) => (
            "fs_surface",
            vec![color(SURFACE_FORMAT)],
            true,
            wgpu::CompareFunction::Less,
        ),
    };
    let mut constants = path_constants(variant.paths);
    if let Stage::Surface(channel, name) = stage {
        constants.push((name, channel as f64));
    }
    if !variant.textured {
        constants.push(("BASE_COLOR_TEXTURE", 0.0));
    }
    device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
        label: Some(entry_point),
        layout: Some(&layout),
        vertex: wgpu::VertexState {
            module,
            entry_point: Some(vertex_entry),
            compilation_options: Default::default(),
            buffers: &buffers,
        },
        primitive: scene_triangles(variant.paths.cull_back_faces),
        depth_stencil: Some(wgpu::DepthStencilState {
            bias: depth_bias(stage, samples),
            ..depth_test(depth_write, compare)
        }),
        multisample: wgpu::MultisampleState {
            count: samples,
            ..Default::default()
        },
        // A depth-only pass needs no fragment stage.
        fragment: (!entry_point.is_empty()).then(|| wgpu::FragmentState {
            module,
            entry_point: Some(entry_point),
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
