//! A material's base colour texture on the GPU, with its mip chain.

use crate::scene::TextureImage;

/// Uploads an sRGB texture with a full mip chain (averaged in linear light on the CPU:
/// [`crate::scene::texture_mips`]), so distant and grazing texels average instead of
/// aliasing.
pub(super) fn upload_texture(device: &wgpu::Device, queue: &wgpu::Queue, texture: &TextureImage) -> wgpu::TextureView {
    let levels = crate::scene::texture_mips::mip_chain(texture);
    let gpu_texture = device.create_texture(&wgpu::TextureDescriptor {
        label: Some(&texture.name),
        size: wgpu::Extent3d {
            width: levels[0].width(),
            height: levels[0].height(),
            depth_or_array_layers: 1,
        },
        mip_level_count: levels.len() as u32,
        sample_count: 1,
        dimension: wgpu::TextureDimension::D2,
        format: wgpu::TextureFormat::Rgba8UnormSrgb,
        usage: wgpu::TextureUsages::TEXTURE_BINDING | wgpu::TextureUsages::COPY_DST,
        view_formats: &[],
    });
    for (level, image) in levels.iter().enumerate() {
        queue.write_texture(
            wgpu::TexelCopyTextureInfo {
                texture: &gpu_texture,
                mip_level: level as u32,
                origin: wgpu::Origin3d::ZERO,
                aspect: wgpu::TextureAspect::All,
            },
            image.as_raw(),
            wgpu::TexelCopyBufferLayout {
                offset: 0,
                bytes_per_row: Some(4 * image.width()),
                rows_per_image: Some(image.height()),
            },
            wgpu::Extent3d {
                width: image.width(),
                height: image.height(),
                depth_or_array_layers: 1,
            },
        );
    }
    gpu_texture.create_view(&wgpu::TextureViewDescriptor::default())
}
