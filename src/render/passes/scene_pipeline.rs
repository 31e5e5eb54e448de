//! The log-SH scene pipelines, one per stage of a frame (depth, shading, per-vertex
//! shading, surface channels, the surface buffer, the upsampling), built
//! from one module with the shading paths compiled in: what `logsh` and
//! `low_resolution` share.

use super::per_vertex::PerVertexCompute;
use super::reduced_shading::SURFACE_BUFFER_FORMATS;
use super::vertex_light::VertexLightCompute;
use crate::render::descriptors::{depth_test, scene_triangles};
use crate::render::resources::{GpuObject, GpuScene, SceneLayouts, draw_object, vertex_layout};
use crate::shading::CompiledPaths;

/// A pipeline for textured objects and its twin for untextured ones, compiled without the
/// texture sample (BASE_COLOR_TEXTURE in scene.wgsl).
pub(super) struct ByTexture {
    textured: wgpu::RenderPipeline,
    untextured: wgpu::RenderPipeline,
}

impl ByTexture {
    pub(super) fn new(make: impl Fn(bool) -> wgpu::RenderPipeline) -> ByTexture {
        ByTexture {
            textured: make(true),
            untextured: make(false),
        }
    }

    /// Draws every visible object with the pipeline for its material.
    pub(super) fn draw_objects(&self, pass: &mut wgpu::RenderPass<'_>, scene: &GpuScene) {
        self.draw_objects_where(pass, scene, |_| true);
    }

    /// Draws the visible objects `drawn` picks, each with the pipeline for its material.
    fn draw_objects_where(
        &self,
        pass: &mut wgpu::RenderPass<'_>,
        scene: &GpuScene,
        drawn: impl Fn(&GpuObject) -> bool,
    ) {
        for (pipeline, textured) in [(&self.textured, true), (&self.untextured, false)] {
            draw_picked(pass, scene, pipeline, |o| o.textured == textured && drawn(o));
        }
    }
}

/// A pipeline that draws both faces of each triangle and its twin that culls back faces,
/// for the objects whose back faces the camera cannot see
/// ([`GpuObject::back_faces_hidden`]): lavapipe rasterises back faces, and without a depth
/// pre-pass shades those drawn before the front faces that hide them.
pub struct BySides {
    both: wgpu::RenderPipeline,
    front: wgpu::RenderPipeline,
}

impl BySides {
    /// `make(variant)`, and `make` of it with back faces culled (the same pipeline where
    /// `variant` culls them already).
    pub(super) fn new(variant: Variant, make: impl Fn(Variant) -> wgpu::RenderPipeline) -> BySides {
        let both = make(variant);
        let front = match variant.paths.cull_back_faces {
            true => both.clone(),
            false => make(Variant {
                paths: CompiledPaths {
                    cull_back_faces: true,
                    ..variant.paths
                },
                ..variant
            }),
        };
        BySides { both, front }
    }

    /// The pipeline for objects whose back faces are hidden (`true`) or may show.
    pub fn for_back_faces_hidden(&self, hidden: bool) -> &wgpu::RenderPipeline {
        if hidden { &self.front } else { &self.both }
    }
}

/// Draws the visible objects `picked` picks with `pipeline`.
fn draw_picked(
    pass: &mut wgpu::RenderPass<'_>,
    scene: &GpuScene,
    pipeline: &wgpu::RenderPipeline,
    picked: impl Fn(&GpuObject) -> bool,
) {
    pass.set_pipeline(pipeline);
    for object in scene.objects.iter().filter(|o| o.drawn_in_view() && picked(o)) {
        draw_object(pass, scene, object);
    }
}

/// The surface buffer's pipelines: [`ByTexture`]'s pair, and for an untextured object
/// without baked indirect light one whose vertex stage passes its view depth and normal
/// alone (vs_plain_surface in low_resolution.wgsl: lavapipe sets up every varying of
/// each triangle).
pub(super) struct SurfaceBufferPipelines {
    by_texture: ByTexture,
    plain: wgpu::RenderPipeline,
}

impl SurfaceBufferPipelines {
    pub(super) fn new(make: impl Fn(Stage<'_>, bool) -> wgpu::RenderPipeline) -> SurfaceBufferPipelines {
        SurfaceBufferPipelines {
            by_texture: ByTexture::new(|textured| make(Stage::SurfaceBuffer, textured)),
            plain: make(Stage::PlainSurfaceBuffer, false),
        }
    }

    /// Draws every visible object with the pipeline for its material and baked light.
    pub(super) fn draw_objects(&self, pass: &mut wgpu::RenderPass<'_>, scene: &GpuScene) {
        let plain = |o: &GpuObject| !o.textured && !o.baked_light;
        self.by_texture.draw_objects_where(pass, scene, |o| !plain(o));
        draw_picked(pass, scene, &self.plain, plain);
    }
}

/// What a pipeline's fragment stage is for.
#[derive(Clone, Copy)]
pub(super) enum Stage<'a> {
    DepthOnly,
    Shade,
    /// Shading through per-vertex visibility attributes of this order, writing depth
    /// (drawn without a pre-pass) or not.
    ShadePerVertex(usize, bool),
    /// Shading through the SH path's light computed at the vertices, writing depth or
    /// not as [`Stage::ShadePerVertex`]: drawn without a pre-pass, no light is shaded per
    /// pixel (`logsh::per_vertex_prepass`), and fs_vertex_lit_alone needs fewer varyings
    /// than fs_vertex_lit.
    VertexLit(bool),
    /// One surface channel (fs_surface) as raw f32.
    Surface(u32, &'a str),
    /// The surface buffer of deferred reduced shading (fs_surface_buffer) into [`SURFACE_BUFFER_FORMATS`].
    SurfaceBuffer,
    /// The same for objects without texture or baked light (vs_plain_surface,
    /// fs_plain_surface_buffer).
    PlainSurfaceBuffer,
    /// Full-resolution pixels from the reduced-resolution samples (fs_upsample), which
    /// reads them through bind group 3 of this layout.
    Upsample(&'a wgpu::BindGroupLayout),
}

/// Whether reduced-resolution shading shades the pixels no sample matches in full, after
/// the upsampling (see reduced_shading.wgsl): only where lavapipe tests depth before the
/// fragment shader, which it does without multisampling; with it, they take the best
/// sample nearby.
pub(super) fn shades_unmatched_exactly(samples: u32) -> bool {
    samples == 1
}

/// Format of the surface channels read back for the CPU reference.
pub const SURFACE_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba32Float;

/// What a pipeline is compiled for besides its stage.
#[derive(Clone, Copy)]
pub(super) struct Variant {
    pub samples: u32,
    /// The shading paths compiled in ([`path_constants`]).
    pub paths: CompiledPaths,
    /// false: compiled without the base colour texture, for untextured objects.
    pub textured: bool,
}

/// The override constants that compile `paths` in (see [`CompiledPaths`]).
pub(super) fn path_constants(paths: CompiledPaths) -> Vec<(&'static str, f64)> {
    let flag = |on: bool| f64::from(u8::from(on));
    vec![
        ("EXACT_LIGHT_PATH", flag(paths.exact)),
        ("EXACT_WIDE", flag(paths.exact_wide)),
        ("SHADOW_MAPS", flag(paths.maps)),
        ("SOFT_SHADOW_MAPS", flag(paths.soft_maps)),
        ("SINGLE_VIEW_MAPS", flag(paths.single_view_maps)),
        ("SH_VISIBILITY", flag(paths.harmonics)),
        ("ENVIRONMENT_LIGHT", flag(paths.environment)),
        ("TERRAIN_SHADOWS", flag(paths.terrain)),
        ("RECT_LIGHTS", flag(paths.rect_lights)),
        ("DISK_LIGHTS", flag(paths.disk_lights)),
        ("LIGHT_OVERFLOW", flag(paths.light_overflow)),
        ("BLOCKER_OVERFLOW", flag(paths.blocker_overflow)),
        ("LIGHT_WINDOWS", f64::from(paths.light_windows)),
        ("PER_POINT_WINDOWS", flag(paths.per_point_windows)),
        ("LIGHT_GRID", flag(paths.light_grid)),
    ]
}

pub(super) fn scene_pipeline(
    device: &wgpu::Device,
    layouts: &SceneLayouts,
    shadow_layout: &wgpu::BindGroupLayout,
    module: &wgpu::ShaderModule,
    stage: Stage,
    variant: Variant,
) -> wgpu::RenderPipeline {
    let samples = variant.samples;
    let mut bind_group_layouts = vec![Some(&layouts.frame), Some(&layouts.material), Some(shadow_layout)];
    if let Stage::Upsample(samples) = stage {
        bind_group_layouts.push(Some(samples));
    }
    let layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
        label: Some("log-SH"),
        bind_group_layouts: &bind_group_layouts,
        immediate_size: 0,
    });
    let visibility_attributes = match stage {
        Stage::ShadePerVertex(order, _) => PerVertexCompute::attributes(order),
        Stage::VertexLit(_) => VertexLightCompute::attributes().to_vec(),
        _ => Vec::new(),
    };
    let visibility_layout = wgpu::VertexBufferLayout {
        array_stride: 16 * visibility_attributes.len() as u64,
        step_mode: wgpu::VertexStepMode::Vertex,
        attributes: &visibility_attributes,
    };
    let (vertex_entry, buffers) = match stage {
        Stage::ShadePerVertex(..) => ("vs_per_vertex", vec![Some(vertex_layout()), Some(visibility_layout)]),
        // Alone (writing its depth: no pre-pass, no lights shaded per pixel): without the
        // varyings only those lights read.
        Stage::VertexLit(true) => (
            "vs_vertex_lit_alone",
            vec![Some(vertex_layout()), Some(visibility_layout)],
        ),
        Stage::VertexLit(false) => ("vs_vertex_lit", vec![Some(vertex_layout()), Some(visibility_layout)]),
        Stage::PlainSurfaceBuffer => ("vs_plain_surface", vec![Some(vertex_layout())]),
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
        // Writes depth where it is drawn without a pre-pass (`LogShPipeline::draw`).
        Stage::ShadePerVertex(_, writes_depth) => (
            "fs_per_vertex",
            vec![shaded],
            writes_depth,
            wgpu::CompareFunction::LessEqual,
        ),
        Stage::VertexLit(writes_depth) => (
            if writes_depth {
                "fs_vertex_lit_alone"
            } else {
                "fs_vertex_lit"
            },
            vec![shaded],
            writes_depth,
            wgpu::CompareFunction::LessEqual,
        ),
        Stage::Shade => ("fs_logsh", vec![shaded], false, wgpu::CompareFunction::LessEqual),
        Stage::Upsample(_) => ("fs_upsample", vec![shaded], false, wgpu::CompareFunction::LessEqual),
        Stage::SurfaceBuffer => (
            "fs_surface_buffer",
            SURFACE_BUFFER_FORMATS.map(color).to_vec(),
            true,
            wgpu::CompareFunction::Less,
        ),
        Stage::PlainSurfaceBuffer => (
            "fs_plain_surface_buffer",
            SURFACE_BUFFER_FORMATS.map(color).to_vec(),
            true,
            wgpu::CompareFunction::Less,
        ),
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
