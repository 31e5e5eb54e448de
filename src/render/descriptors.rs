//! The formats and descriptor pieces every pass shares: target formats, the scene's
//! triangle and depth states, frame textures, numbered bind group entries, shader modules.

/// Colour format of every render target: linear shader output, sRGB-encoded on store.
pub const COLOR_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba8UnormSrgb;
/// Storage format of the resolved image: the same bytes as [`COLOR_FORMAT`], read raw.
pub const DISPLAY_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba8Unorm;
pub const DEPTH_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Depth32Float;
/// Samples per pixel of multisampled targets ([`super::AntiAliasing::Multisample`]).
pub const SAMPLE_COUNT: u32 = 4;

/// Triangle lists, counter-clockwise front faces (glTF's winding); back faces culled when
/// `cull_back_faces` (every material single-sided), else drawn, with the shading normal
/// turned toward the viewer (glTF meshes are often open: planes, cards).
pub fn scene_triangles(cull_back_faces: bool) -> wgpu::PrimitiveState {
    wgpu::PrimitiveState {
        topology: wgpu::PrimitiveTopology::TriangleList,
        front_face: wgpu::FrontFace::Ccw,
        cull_mode: cull_back_faces.then_some(wgpu::Face::Back),
        ..Default::default()
    }
}

/// A depth attachment of `view`: cleared to `clear`, or as the previous pass left it
/// (None), and stored for a later pass if `keep`.
pub fn depth_attachment(
    view: &wgpu::TextureView,
    clear: Option<f32>,
    keep: bool,
) -> wgpu::RenderPassDepthStencilAttachment<'_> {
    wgpu::RenderPassDepthStencilAttachment {
        view,
        depth_ops: Some(wgpu::Operations {
            load: clear.map_or(wgpu::LoadOp::Load, wgpu::LoadOp::Clear),
            store: if keep {
                wgpu::StoreOp::Store
            } else {
                wgpu::StoreOp::Discard
            },
        }),
        stencil_ops: None,
    }
}

/// A [`DEPTH_FORMAT`] depth test with `compare`, writing depth if `write`.
pub fn depth_test(write: bool, compare: wgpu::CompareFunction) -> wgpu::DepthStencilState {
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
pub fn frame_texture(
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

/// A bind group layout entry for a storage buffer at `binding`, seen by `stages`, read
/// only or read and written.
pub fn storage_buffer_entry(binding: u32, stages: wgpu::ShaderStages, read_only: bool) -> wgpu::BindGroupLayoutEntry {
    wgpu::BindGroupLayoutEntry {
        binding,
        visibility: stages,
        ty: wgpu::BindingType::Buffer {
            ty: wgpu::BufferBindingType::Storage { read_only },
            has_dynamic_offset: false,
            min_binding_size: None,
        },
        count: None,
    }
}

/// Bind group entries binding each of `resources` at its position (0, 1, …), the order
/// in which the shaders and the layout declare them.
pub fn numbered_entries<'a, const N: usize>(
    resources: [wgpu::BindingResource<'a>; N],
) -> [wgpu::BindGroupEntry<'a>; N] {
    let mut binding = 0;
    resources.map(|resource| {
        let entry = wgpu::BindGroupEntry { binding, resource };
        binding += 1;
        entry
    })
}

/// A shader module from WGSL `source` (assembled by `shading::wgsl`).
pub fn create_module(device: &wgpu::Device, label: &str, source: &str) -> wgpu::ShaderModule {
    device.create_shader_module(wgpu::ShaderModuleDescriptor {
        label: Some(label),
        source: wgpu::ShaderSource::Wgsl(source.into()),
    })
}

/// A bilinear sampler, clamped at the border: how a pass that draws a finished frame from
/// an image reads it between texels (the edge filter, the editor's viewport image).
pub fn bilinear_sampler(device: &wgpu::Device, label: &str) -> wgpu::Sampler {
    device.create_sampler(&wgpu::SamplerDescriptor {
        label: Some(label),
        mag_filter: wgpu::FilterMode::Linear,
        min_filter: wgpu::FilterMode::Linear,
        ..Default::default()
    })
}

/// A bind group layout of a filterable 2-D image (binding 0) and its filtering sampler
/// (binding 1), read by a fragment stage: what a pass that draws a finished frame from an
/// image binds (the edge filter, the editor's viewport image).
pub fn image_and_sampler_layout(device: &wgpu::Device, label: &str) -> wgpu::BindGroupLayout {
    device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
        label: Some(label),
        entries: &[
            wgpu::BindGroupLayoutEntry {
                binding: 0,
                visibility: wgpu::ShaderStages::FRAGMENT,
                ty: wgpu::BindingType::Texture {
                    sample_type: wgpu::TextureSampleType::Float { filterable: true },
                    view_dimension: wgpu::TextureViewDimension::D2,
                    multisampled: false,
                },
                count: None,
            },
            wgpu::BindGroupLayoutEntry {
                binding: 1,
                visibility: wgpu::ShaderStages::FRAGMENT,
                ty: wgpu::BindingType::Sampler(wgpu::SamplerBindingType::Filtering),
                count: None,
            },
        ],
    })
}
