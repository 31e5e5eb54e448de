//! The formats and descriptor pieces every pass shares: target formats, the scene's
//! triangle and depth states, frame textures, bind group entries at their slots
//! (`shading::wgsl::slots`), shader modules.

use crate::shading::wgsl::slots::{self, Slot};

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

/// A bind group layout entry at `slot`, seen by `stages`.
pub fn layout_entry(slot: Slot, stages: wgpu::ShaderStages, ty: wgpu::BindingType) -> wgpu::BindGroupLayoutEntry {
    wgpu::BindGroupLayoutEntry {
        binding: slot.binding,
        visibility: stages,
        ty,
        count: None,
    }
}

/// A buffer binding of type `ty` (uniform or storage), without dynamic offsets.
pub fn buffer_type(ty: wgpu::BufferBindingType) -> wgpu::BindingType {
    wgpu::BindingType::Buffer {
        ty,
        has_dynamic_offset: false,
        min_binding_size: None,
    }
}

/// A bind group layout entry for a storage buffer at `slot`, seen by `stages`, read only
/// or read and written.
pub fn storage_buffer_entry(slot: Slot, stages: wgpu::ShaderStages, read_only: bool) -> wgpu::BindGroupLayoutEntry {
    layout_entry(
        slot,
        stages,
        buffer_type(wgpu::BufferBindingType::Storage { read_only }),
    )
}

/// A bind group layout entry for a 2-D, single-sampled texture at `slot`, seen by
/// `stages`, whose texels read as `sample_type`.
pub fn texture_entry(
    slot: Slot,
    stages: wgpu::ShaderStages,
    sample_type: wgpu::TextureSampleType,
) -> wgpu::BindGroupLayoutEntry {
    layout_entry(
        slot,
        stages,
        wgpu::BindingType::Texture {
            sample_type,
            view_dimension: wgpu::TextureViewDimension::D2,
            multisampled: false,
        },
    )
}

/// Bind group entries binding each resource at its slot (all of one bind group).
pub fn slot_entries<'a, const N: usize>(
    resources: [(Slot, wgpu::BindingResource<'a>); N],
) -> [wgpu::BindGroupEntry<'a>; N] {
    debug_assert!(resources.iter().all(|(slot, _)| slot.group == resources[0].0.group));
    resources.map(|(slot, resource)| wgpu::BindGroupEntry {
        binding: slot.binding,
        resource,
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

/// A bind group layout of a filterable 2-D image and its filtering sampler (the slots
/// `FRAME_IMAGE` and `FRAME_SAMPLER`), read by a fragment stage: what a pass that draws a
/// finished frame from an image binds (the edge filter, the editor's viewport image).
pub fn image_and_sampler_layout(device: &wgpu::Device, label: &str) -> wgpu::BindGroupLayout {
    device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
        label: Some(label),
        entries: &image_and_sampler_entries(),
    })
}

/// The entries of [`image_and_sampler_layout`].
pub fn image_and_sampler_entries() -> [wgpu::BindGroupLayoutEntry; 2] {
    filtered_texture_entries(slots::FRAME_IMAGE, slots::FRAME_SAMPLER)
}

/// A filterable 2D float texture at `texture` and a filtering sampler at `sampler`, read
/// by fragment shaders.
pub fn filtered_texture_entries(texture: Slot, sampler: Slot) -> [wgpu::BindGroupLayoutEntry; 2] {
    let fragment = wgpu::ShaderStages::FRAGMENT;
    [
        texture_entry(texture, fragment, wgpu::TextureSampleType::Float { filterable: true }),
        layout_entry(
            sampler,
            fragment,
            wgpu::BindingType::Sampler(wgpu::SamplerBindingType::Filtering),
        ),
    ]
}

/// A layout entry at `slot` for a 2D storage texture of `format` that `stages` write.
pub fn written_texture_entry(
    slot: Slot,
    stages: wgpu::ShaderStages,
    format: wgpu::TextureFormat,
) -> wgpu::BindGroupLayoutEntry {
    layout_entry(
        slot,
        stages,
        wgpu::BindingType::StorageTexture {
            access: wgpu::StorageTextureAccess::WriteOnly,
            format,
            view_dimension: wgpu::TextureViewDimension::D2,
        },
    )
}

/// The compute pipeline of `entry_point` in `module` with override `constants`, over bind
/// groups laid out as `groups` (group k: `groups[k]`).
pub fn compute_pipeline(
    device: &wgpu::Device,
    module: &wgpu::ShaderModule,
    entry_point: &str,
    groups: &[&wgpu::BindGroupLayout],
    constants: &[(&str, f64)],
) -> wgpu::ComputePipeline {
    let bind_group_layouts: Vec<Option<&wgpu::BindGroupLayout>> = groups.iter().copied().map(Some).collect();
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
}

/// The buffers of `lists` lists shaded by indirect dispatches: their lengths (4 bytes
/// each, cleared and read back), and their dispatches' workgroup counts (12 bytes each),
/// labelled after `what` is listed.
pub fn list_counts_and_dispatch_args(device: &wgpu::Device, what: &str, lists: u64) -> (wgpu::Buffer, wgpu::Buffer) {
    let buffer = |label: String, bytes, usage| {
        device.create_buffer(&wgpu::BufferDescriptor {
            label: Some(&label),
            size: bytes,
            usage,
            mapped_at_creation: false,
        })
    };
    let storage = wgpu::BufferUsages::STORAGE;
    (
        buffer(
            format!("{what}: counts"),
            4 * lists,
            storage | wgpu::BufferUsages::COPY_DST | wgpu::BufferUsages::COPY_SRC,
        ),
        buffer(
            format!("{what}: dispatch arguments"),
            12 * lists,
            storage | wgpu::BufferUsages::INDIRECT,
        ),
    )
}
