//! The scene's bind group layouts (group 0: frame, group 1: material), the shared
//! base-colour sampler and the vertex buffer layout of [`GpuVertex`].

use crate::render::descriptors::{buffer_type, filtered_texture_entries, layout_entry};
use crate::shading::gpu_types::GpuVertex;
use crate::shading::wgsl::slots;

const VERTEX_ATTRIBUTES: [wgpu::VertexAttribute; 3] =
    wgpu::vertex_attr_array![0 => Float32x3, 1 => Float32x3, 2 => Float32x2];

/// [`GpuVertex`] as scene.wgsl's vertex stage reads it: position, normal, UV at locations
/// 0, 1 and 2.
pub fn vertex_layout() -> wgpu::VertexBufferLayout<'static> {
    wgpu::VertexBufferLayout {
        array_stride: std::mem::size_of::<GpuVertex>() as u64,
        step_mode: wgpu::VertexStepMode::Vertex,
        attributes: &VERTEX_ATTRIBUTES,
    }
}

/// Bind group layouts and the shared sampler.
#[derive(Clone)]
pub struct SceneLayouts {
    pub frame: wgpu::BindGroupLayout,
    pub material: wgpu::BindGroupLayout,
    pub sampler: wgpu::Sampler,
}

impl SceneLayouts {
    pub fn new(device: &wgpu::Device) -> SceneLayouts {
        let uniform = buffer_type(wgpu::BufferBindingType::Uniform);
        let storage = buffer_type(wgpu::BufferBindingType::Storage { read_only: true });
        let every_stage = wgpu::ShaderStages::VERTEX_FRAGMENT | wgpu::ShaderStages::COMPUTE;
        // The shading reads the lights in fragment shaders and in the compute passes that
        // shade the pixels the upsampling leaves (full_resolution.wgsl).
        let shading = wgpu::ShaderStages::FRAGMENT | wgpu::ShaderStages::COMPUTE;
        let frame = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("frame"),
            entries: &[
                layout_entry(slots::FRAME, every_stage, uniform),
                layout_entry(slots::LIGHTS, shading, uniform),
                layout_entry(slots::BAKED_INDIRECT, wgpu::ShaderStages::VERTEX, storage),
                layout_entry(slots::EVERY_LIGHT, shading, storage),
                layout_entry(slots::LIGHT_GRID, shading, storage),
            ],
        });
        let material = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("material"),
            entries: &{
                let [texture, sampler] = filtered_texture_entries(slots::BASE_COLOR_TEXTURE, slots::BASE_COLOR_SAMPLER);
                // The vertex lighting pass reads the exponent (logsh_per_vertex.wgsl).
                [layout_entry(slots::MATERIAL, shading, uniform), texture, sampler]
            },
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
            // 2026-12-02). The shader sharpens grazing floors itself, at a third of that
            // cost (`sample_base_color` in shaders/scene.wgsl).
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
