use super::pipeline::{COLOR_FORMAT, RenderTarget, ScenePipeline};
use super::{GpuContext, GpuScene, RenderError, RenderSettings};
use crate::scene::{Camera, Scene};

/// Largest image side accepted by [`render_image`] (lavapipe's 2D texture limit).
pub const MAX_IMAGE_SIDE: u32 = 16384;

/// Renders `scene` seen by `camera` into an sRGB image of `width` × `height` pixels.
pub fn render_image(
    gpu: &GpuContext,
    scene: &Scene,
    camera: &Camera,
    settings: &RenderSettings,
    width: u32,
    height: u32,
) -> Result<image::RgbaImage, RenderError> {
    let max = MAX_IMAGE_SIDE.min(gpu.device.limits().max_texture_dimension_2d);
    if width == 0 || height == 0 || width > max || height > max {
        return Err(RenderError::BadSize { width, height, max });
    }
    let pipeline = ScenePipeline::new(&gpu.device);
    let gpu_scene = GpuScene::upload(&gpu.device, &gpu.queue, &pipeline.layouts, scene);
    let target = RenderTarget::new(&gpu.device, width, height);
    gpu_scene.write_frame(&gpu.queue, camera, width as f32 / height as f32, settings.exposure_ev);

    let mut encoder = gpu.device.create_command_encoder(&Default::default());
    pipeline.draw(&mut encoder, &target, &gpu_scene, settings.background_linear());
    read_back(gpu, encoder, &target)
}

/// Copies the resolved colour texture to the CPU (rows padded to wgpu's 256-byte
/// alignment on the way, unpadded here).
fn read_back(
    gpu: &GpuContext,
    mut encoder: wgpu::CommandEncoder,
    target: &RenderTarget,
) -> Result<image::RgbaImage, RenderError> {
    debug_assert_eq!(COLOR_FORMAT.block_copy_size(None), Some(4));
    let row_bytes = 4 * target.width;
    let padded_row_bytes = row_bytes.div_ceil(wgpu::COPY_BYTES_PER_ROW_ALIGNMENT) * wgpu::COPY_BYTES_PER_ROW_ALIGNMENT;
    let buffer = gpu.device.create_buffer(&wgpu::BufferDescriptor {
        label: Some("readback"),
        size: (padded_row_bytes * target.height) as u64,
        usage: wgpu::BufferUsages::COPY_DST | wgpu::BufferUsages::MAP_READ,
        mapped_at_creation: false,
    });
    encoder.copy_texture_to_buffer(
        target.color.as_image_copy(),
        wgpu::TexelCopyBufferInfo {
            buffer: &buffer,
            layout: wgpu::TexelCopyBufferLayout {
                offset: 0,
                bytes_per_row: Some(padded_row_bytes),
                rows_per_image: Some(target.height),
            },
        },
        wgpu::Extent3d {
            width: target.width,
            height: target.height,
            depth_or_array_layers: 1,
        },
    );
    gpu.queue.submit([encoder.finish()]);

    let (sender, receiver) = std::sync::mpsc::channel();
    buffer.map_async(wgpu::MapMode::Read, .., move |result| {
        let _ = sender.send(result);
    });
    gpu.device
        .poll(wgpu::PollType::wait_indefinitely())
        .map_err(|e| RenderError::Readback(e.to_string()))?;
    receiver
        .recv()
        .map_err(|e| RenderError::Readback(e.to_string()))?
        .map_err(|e| RenderError::Readback(e.to_string()))?;
    let mapped = buffer
        .get_mapped_range(..)
        .map_err(|e| RenderError::Readback(e.to_string()))?;
    let mut pixels = Vec::with_capacity((row_bytes * target.height) as usize);
    for row in mapped.chunks_exact(padded_row_bytes as usize) {
        pixels.extend_from_slice(&row[..row_bytes as usize]);
    }
    drop(mapped);
    buffer.unmap();
    image::RgbaImage::from_raw(target.width, target.height, pixels)
        .ok_or_else(|| RenderError::Readback("image size mismatch".into()))
}
