//! The terrain's shadow model on the GPU: `TerrainParams` (the pyramid's layout, the march
//! and M_lin) and every pyramid level's heights followed by the surface cache, bindings 3
//! and 4 of the shadow group (shaders/terrain.wgsl).

use wgpu::util::DeviceExt;

use crate::shading::ShadowSettings;
use crate::shading::terrain::{terrain_params, terrain_shadow};
use crate::terrain::HeightField;

/// The terrain's buffers, and what they were built for.
pub struct GpuTerrain {
    pub params: wgpu::Buffer,
    pub heights: wgpu::Buffer,
    /// (order, azimuths, pyramid levels) of the uploaded model.
    built_for: (usize, u32, u32),
}

impl GpuTerrain {
    pub fn upload(device: &wgpu::Device, field: Option<&HeightField>, settings: &ShadowSettings) -> GpuTerrain {
        let shadow = field.map(|f| terrain_shadow(f, settings));
        let (params, heights) = terrain_params(shadow.as_ref());
        GpuTerrain {
            params: device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
                label: Some("terrain params"),
                contents: bytemuck::bytes_of(&params),
                usage: wgpu::BufferUsages::UNIFORM,
            }),
            heights: device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
                label: Some("terrain heights"),
                contents: bytemuck::cast_slice(&heights),
                usage: wgpu::BufferUsages::STORAGE,
            }),
            built_for: Self::key(settings),
        }
    }

    fn key(settings: &ShadowSettings) -> (usize, u32, u32) {
        (
            settings.order,
            settings.terrain.azimuths,
            settings.terrain.pyramid_levels,
        )
    }

    /// Whether `settings` need a new upload (a new order changes M_lin's size).
    pub fn is_stale_for(&self, settings: &ShadowSettings) -> bool {
        self.built_for != Self::key(settings)
    }
}
