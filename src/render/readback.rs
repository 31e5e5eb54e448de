//! Frames and textures read back from the GPU: submit, wait, copy rows out of wgpu's
//! 256-byte row alignment.

use super::RenderError;
use super::descriptors::COLOR_FORMAT;
use super::target::RenderTarget;

/// Submits `encoder` and reads `target`'s displayed (resolved, sRGB) colour back as an
/// image — what the editor's viewport shows, for exporting it.
pub fn read_target_image(
    device: &wgpu::Device,
    queue: &wgpu::Queue,
    encoder: wgpu::CommandEncoder,
    target: &RenderTarget,
) -> Result<image::RgbaImage, RenderError> {
    debug_assert_eq!(COLOR_FORMAT.block_copy_size(None), Some(4));
    let pixels = read_texture(device, queue, encoder, &target.color, 4, target.width, target.height)?;
    image::RgbaImage::from_raw(target.width, target.height, pixels)
        .ok_or_else(|| RenderError::Readback("image size mismatch".into()))
}

/// `row_bytes` rounded up to wgpu's alignment of rows in copies between buffers and
/// images (256 bytes).
pub(crate) fn padded_row_bytes(row_bytes: u32) -> u32 {
    row_bytes.div_ceil(wgpu::COPY_BYTES_PER_ROW_ALIGNMENT) * wgpu::COPY_BYTES_PER_ROW_ALIGNMENT
}

/// Submits `encoder` plus a copy of `texture` to the CPU (rows padded to wgpu's 256-byte
/// alignment on the way, unpadded here) and returns its bytes.
pub fn read_texture(
    device: &wgpu::Device,
    queue: &wgpu::Queue,
    mut encoder: wgpu::CommandEncoder,
    texture: &wgpu::Texture,
    bytes_per_pixel: u32,
    width: u32,
    height: u32,
) -> Result<Vec<u8>, RenderError> {
    let row_bytes = bytes_per_pixel * width;
    let padded_row_bytes = padded_row_bytes(row_bytes);
    let buffer = device.create_buffer(&wgpu::BufferDescriptor {
        label: Some("readback"),
        size: (padded_row_bytes * height) as u64,
        usage: wgpu::BufferUsages::COPY_DST | wgpu::BufferUsages::MAP_READ,
        mapped_at_creation: false,
    });
    encoder.copy_texture_to_buffer(
        texture.as_image_copy(),
        wgpu::TexelCopyBufferInfo {
            buffer: &buffer,
            layout: wgpu::TexelCopyBufferLayout {
                offset: 0,
                bytes_per_row: Some(padded_row_bytes),
                rows_per_image: Some(height),
            },
        },
        wgpu::Extent3d {
            width,
            height,
            depth_or_array_layers: 1,
        },
    );
    queue.submit([encoder.finish()]);
    read_mapped(device, &buffer, |mapped| {
        let mut bytes = Vec::with_capacity((row_bytes * height) as usize);
        for row in mapped.chunks_exact(padded_row_bytes as usize) {
            bytes.extend_from_slice(&row[..row_bytes as usize]);
        }
        bytes
    })
}

/// Copies the first `bytes` of `buffer` (made with `COPY_SRC`) to the CPU and returns them,
/// after the work submitted so far.
pub fn read_buffer(
    device: &wgpu::Device,
    queue: &wgpu::Queue,
    buffer: &wgpu::Buffer,
    bytes: u64,
) -> Result<Vec<u8>, RenderError> {
    let staging = device.create_buffer(&wgpu::BufferDescriptor {
        label: Some("buffer readback"),
        size: bytes,
        usage: wgpu::BufferUsages::COPY_DST | wgpu::BufferUsages::MAP_READ,
        mapped_at_creation: false,
    });
    let mut encoder = device.create_command_encoder(&Default::default());
    encoder.copy_buffer_to_buffer(buffer, 0, &staging, 0, bytes);
    queue.submit([encoder.finish()]);
    read_mapped(device, &staging, <[u8]>::to_vec)
}

/// Maps `buffer` (`MAP_READ`, its copies submitted) once the GPU is done with them and
/// returns what `read` takes from its bytes.
fn read_mapped<T>(
    device: &wgpu::Device,
    buffer: &wgpu::Buffer,
    read: impl FnOnce(&[u8]) -> T,
) -> Result<T, RenderError> {
    let (sender, receiver) = std::sync::mpsc::channel();
    buffer.map_async(wgpu::MapMode::Read, .., move |result| {
        let _ = sender.send(result);
    });
    device
        .poll(wgpu::PollType::wait_indefinitely())
        .map_err(|e| RenderError::Readback(e.to_string()))?;
    receiver
        .recv()
        .map_err(|e| RenderError::Readback(e.to_string()))?
        .map_err(|e| RenderError::Readback(e.to_string()))?;
    let mapped = buffer
        .get_mapped_range(..)
        .map_err(|e| RenderError::Readback(e.to_string()))?;
    let value = read(&mapped);
    drop(mapped);
    buffer.unmap();
    Ok(value)
}
