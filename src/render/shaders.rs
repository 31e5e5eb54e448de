//! WGSL sources. WGSL has no `#include`: each module is `common.wgsl` followed by its own
//! file, so shared structs and functions live in exactly one place.

pub const COMMON: &str = include_str!("../../shaders/common.wgsl");
pub const RASTER: &str = include_str!("../../shaders/raster.wgsl");

/// The complete source of a shader module: the shared prelude, then `body`.
pub fn with_common(body: &str) -> String {
    format!("{COMMON}\n{body}")
}

pub fn create_module(device: &wgpu::Device, label: &str, body: &str) -> wgpu::ShaderModule {
    device.create_shader_module(wgpu::ShaderModuleDescriptor {
        label: Some(label),
        source: wgpu::ShaderSource::Wgsl(with_common(body).into()),
    })
}
