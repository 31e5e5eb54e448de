//! The buffers the scene's lights are read from on the GPU.

use crate::shading::gpu_types::{GpuLight, UNIFORM_LIGHT_CAPACITY};

/// The lights as scene.wgsl reads them: the first [`UNIFORM_LIGHT_CAPACITY`] in a uniform
/// buffer of that many, and every light in a storage buffer (read past the capacity).
pub(super) struct LightBuffers {
    pub(super) uniform: wgpu::Buffer,
    pub(super) every: wgpu::Buffer,
    /// Lights `every` holds.
    pub(super) every_capacity: usize,
    /// The lights' grid's words (`shading::light_grid`), and how many it holds.
    pub(super) grid: wgpu::Buffer,
    grid_capacity: usize,
}

impl LightBuffers {
    pub(super) fn new(device: &wgpu::Device, every_capacity: usize) -> LightBuffers {
        let every_capacity = every_capacity.max(1);
        let buffer = |label, count: usize, usage| {
            device.create_buffer(&wgpu::BufferDescriptor {
                label: Some(label),
                size: (count * std::mem::size_of::<GpuLight>()) as u64,
                usage: usage | wgpu::BufferUsages::COPY_DST,
                mapped_at_creation: false,
            })
        };
        LightBuffers {
            uniform: buffer("lights", UNIFORM_LIGHT_CAPACITY, wgpu::BufferUsages::UNIFORM),
            every: buffer("every light", every_capacity, wgpu::BufferUsages::STORAGE),
            every_capacity,
            grid: grid_buffer(device, GRID_WORDS_AT_FIRST),
            grid_capacity: GRID_WORDS_AT_FIRST,
        }
    }

    /// Writes the grid's `words`, in a larger buffer when they do not fit (true: the
    /// frame's bind group must be made again).
    pub(super) fn write_grid(&mut self, device: &wgpu::Device, queue: &wgpu::Queue, words: &[u32]) -> bool {
        let grown = words.len() > self.grid_capacity;
        if grown {
            self.grid_capacity = words.len().next_power_of_two();
            self.grid = grid_buffer(device, self.grid_capacity);
        }
        queue.write_buffer(&self.grid, 0, bytemuck::cast_slice(words));
        grown
    }

    /// Writes `lights` (at most the capacity `every` was made with).
    pub(super) fn write(&self, queue: &wgpu::Queue, lights: &[GpuLight]) {
        if lights.is_empty() {
            return;
        }
        let first = &lights[..lights.len().min(UNIFORM_LIGHT_CAPACITY)];
        queue.write_buffer(&self.uniform, 0, bytemuck::cast_slice(first));
        queue.write_buffer(&self.every, 0, bytemuck::cast_slice(lights));
    }
}

/// Words of the lights' grid buffer made with the scene (grown when a grid needs more).
const GRID_WORDS_AT_FIRST: usize = 1024;

fn grid_buffer(device: &wgpu::Device, words: usize) -> wgpu::Buffer {
    device.create_buffer(&wgpu::BufferDescriptor {
        label: Some("lights' grid"),
        size: (words.max(1) * std::mem::size_of::<u32>()) as u64,
        usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_DST,
        mapped_at_creation: false,
    })
}
