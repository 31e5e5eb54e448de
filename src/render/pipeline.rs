//! The raster pipeline that draws a [`GpuScene`] into a [`RenderTarget`].

use super::gpu_scene::GpuScene;
use super::gpu_types::GpuVertex;
use super::shaders;
use super::target::RenderTarget;

/// Colour format of every render target: linear shader output, sRGB-encoded on store.
pub const COLOR_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba8UnormSrgb;
/// Storage format of the resolved image: the same bytes as [`COLOR_FORMAT`], read raw.
pub const DISPLAY_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba8Unorm;
pub const DEPTH_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Depth32Float;
/// Samples per pixel of multisampled targets ([`super::AntiAliasing::Multisample`]).
pub const SAMPLE_COUNT: u32 = 4;

/// Bind group layouts and the shared sampler.
#[derive(Clone)]
pub struct SceneLayouts {
    pub frame: wgpu::BindGroupLayout,
    pub material: wgpu::BindGroupLayout,
    pub sampler: wgpu::Sampler,
}

impl SceneLayouts {
    pub fn new(device: &wgpu::Device) -> SceneLayouts {
        let entry = |binding, visibility, ty| wgpu::BindGroupLayoutEntry {
            binding,
            visibility,
            ty,
            count: None,
        };
        let buffer = |ty| wgpu::BindingType::Buffer {
            ty,
            has_dynamic_offset: false,
            min_binding_size: None,
        };
        let both = wgpu::ShaderStages::VERTEX_FRAGMENT;
        let fragment = wgpu::ShaderStages::FRAGMENT;
        let frame = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("frame"),
            entries: &[
                entry(0, both, buffer(wgpu::BufferBindingType::Uniform)),
                entry(1, fragment, buffer(wgpu::BufferBindingType::Uniform)),
                entry(
                    2,
                    wgpu::ShaderStages::VERTEX,
                    buffer(wgpu::BufferBindingType::Storage { read_only: true }),
                ),
                entry(
                    3,
                    fragment,
                    buffer(wgpu::BufferBindingType::Storage { read_only: true }),
                ),
            ],
        });
        let material = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("material"),
            entries: &[
                entry(0, fragment, buffer(wgpu::BufferBindingType::Uniform)),
                entry(
                    1,
                    fragment,
                    wgpu::BindingType::Texture {
                        sample_type: wgpu::TextureSampleType::Float { filterable: true },
                        view_dimension: wgpu::TextureViewDimension::D2,
                        multisampled: false,
                    },
                ),
                entry(
                    2,
                    fragment,
                    wgpu::BindingType::Sampler(wgpu::SamplerBindingType::Filtering),
                ),
            ],
        });
        let sampler = device.create_sampler(&wgpu::SamplerDescriptor {
            label: Some("base colour"),
            address_mode_u: wgpu::AddressMode::Repeat,
            address_mode_v: wgpu::AddressMode::Repeat,
            mag_filter: wgpu::FilterMode::Linear,
            min_filter: wgpu::FilterMode::Linear,
            mipmap_filter: wgpu::MipmapFilterMode::Linear,
            // Trilinear, not anisotropic: lavapipe's anisotropic filter loops over a weight
            // table per sample and cost the studio's default frame 12 % (87 against 99 ms,
            // 2026-12-02), for floor textures a little sharper at grazing angles.
            anisotropy_clamp: 1,
            ..Default::default()
        });
        SceneLayouts {
            frame,
            material,
            sampler,
        }
    }
}

pub struct ScenePipeline {
    pub layouts: SceneLayouts,
    pipeline: wgpu::RenderPipeline,
}

impl ScenePipeline {
    /// The raster pipeline with [`SAMPLE_COUNT`] samples per pixel.
    pub fn new(device: &wgpu::Device) -> ScenePipeline {
        ScenePipeline::with_samples(device, SAMPLE_COUNT)
    }

    /// The raster pipeline with `samples` (1 or [`SAMPLE_COUNT`]) samples per pixel.
    pub fn with_samples(device: &wgpu::Device, samples: u32) -> ScenePipeline {
        let layouts = SceneLayouts::new(device);
        let module = shaders::create_module(device, "raster", &shaders::raster_source());
        let pipeline = mesh_pipeline(device, &layouts, &module, "fs_main", samples);
        ScenePipeline { layouts, pipeline }
    }

    /// Clears `target` to `background` (linear RGB) and draws every object.
    pub fn draw(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        target: &RenderTarget,
        scene: &GpuScene,
        background_linear: [f64; 3],
    ) {
        draw_meshes(
            encoder,
            target,
            &self.pipeline,
            &scene.frame_bind_group,
            scene,
            background_linear,
        );
    }
}

/// Clears `target` to `background` (linear RGB) and draws every shown object of `scene`
/// with `pipeline` (a [`mesh_pipeline`]) and `frame_group` as bind group 0.
pub fn draw_meshes(
    encoder: &mut wgpu::CommandEncoder,
    target: &RenderTarget,
    pipeline: &wgpu::RenderPipeline,
    frame_group: &wgpu::BindGroup,
    scene: &GpuScene,
    background_linear: [f64; 3],
) {
    let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
        label: Some("scene"),
        color_attachments: &[Some(target.color_attachment(background_linear))],
        depth_stencil_attachment: Some(target.depth_attachment()),
        timestamp_writes: None,
        occlusion_query_set: None,
        multiview_mask: None,
    });
    pass.set_pipeline(pipeline);
    pass.set_bind_group(0, frame_group, &[]);
    super::logsh::draw_objects(&mut pass, scene);
    drop(pass);
    target.finish(encoder);
}

/// A pipeline drawing the scene's meshes with scene.wgsl's vertex stage and `fragment`
/// of `module` (which has the scene's bind groups 0 and 1), depth-tested, both faces,
/// into a [`COLOR_FORMAT`] target of `samples` samples.
pub fn mesh_pipeline(
    device: &wgpu::Device,
    layouts: &SceneLayouts,
    module: &wgpu::ShaderModule,
    fragment: &str,
    samples: u32,
) -> wgpu::RenderPipeline {
    let layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
        label: Some(fragment),
        bind_group_layouts: &[Some(&layouts.frame), Some(&layouts.material)],
        immediate_size: 0,
    });
    device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
        label: Some(fragment),
        layout: Some(&layout),
        vertex: wgpu::VertexState {
            module,
            entry_point: Some("vs_main"),
            compilation_options: Default::default(),
            buffers: &[Some(GpuVertex::layout())],
        },
        // The preview without shadows draws both faces of every mesh.
        primitive: scene_triangles(false),
        depth_stencil: Some(depth_test(true, wgpu::CompareFunction::Less)),
        multisample: wgpu::MultisampleState {
            count: samples,
            ..Default::default()
        },
        fragment: Some(wgpu::FragmentState {
            module,
            entry_point: Some(fragment),
            compilation_options: Default::default(),
            targets: &[Some(wgpu::ColorTargetState {
                format: COLOR_FORMAT,
                blend: None,
                write_mask: wgpu::ColorWrites::ALL,
            })],
        }),
        multiview_mask: None,
        cache: None,
    })
}

/// Triangle lists, counter-clockwise front faces (glTF's winding); back faces culled when
/// `cull_back_faces` (every material single-sided), else drawn, with the shading normal
/// turned toward the viewer (glTF meshes are often open: planes, cards).
pub(super) fn scene_triangles(cull_back_faces: bool) -> wgpu::PrimitiveState {
    wgpu::PrimitiveState {
        topology: wgpu::PrimitiveTopology::TriangleList,
        front_face: wgpu::FrontFace::Ccw,
        cull_mode: cull_back_faces.then_some(wgpu::Face::Back),
        ..Default::default()
    }
}

/// A [`DEPTH_FORMAT`] depth test with `compare`, writing depth if `write`.
pub(super) fn depth_test(write: bool, compare: wgpu::CompareFunction) -> wgpu::DepthStencilState {
    wgpu::DepthStencilState {
        format: DEPTH_FORMAT,
        depth_write_enabled: Some(write),
        depth_compare: Some(compare),
        stencil: Default::default(),
        bias: Default::default(),
    }
}

/// A 2-D texture of one mip level, `samples` per texel: what frames are drawn into and
/// read from (render targets, the edge filter's image, the low-resolution samples).
pub(super) fn frame_texture(
    device: &wgpu::Device,
    label: &str,
    size: wgpu::Extent3d,
    format: wgpu::TextureFormat,
    samples: u32,
    usage: wgpu::TextureUsages,
    view_formats: &[wgpu::TextureFormat],
) -> wgpu::Texture {
    device.create_texture(&wgpu::TextureDescriptor {
        label: Some(label),
        size,
        mip_level_count: 1,
        sample_count: samples,
        dimension: wgpu::TextureDimension::D2,
        format,
        usage,
        view_formats,
    })
}

/// Bind group entries binding each of `resources` at its position (0, 1, …), the order
/// in which the shaders and the layout declare them.
pub(super) fn numbered_entries<'a, const N: usize>(
    resources: [wgpu::BindingResource<'a>; N],
) -> [wgpu::BindGroupEntry<'a>; N] {
    let mut binding = 0;
    resources.map(|resource| {
        let entry = wgpu::BindGroupEntry { binding, resource };
        binding += 1;
        entry
    })
}
