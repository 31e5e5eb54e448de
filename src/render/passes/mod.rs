//! The passes that draw a frame: the raster preview without shadows (`raster`), the
//! log-SH shading with its reduced-resolution (`reduced_shading`) and per-vertex
//! (`per_vertex`) forms (`logsh`) and its deferred full-resolution frame in compute
//! passes (`full_resolution`; the low-resolution samples the soft layer leaves likewise,
//! `listed_samples`), and the importance heat map (`heat_map`).

mod full_resolution;
pub mod heat_map;
mod kept_harmonic;
mod listed_samples;
pub mod logsh;
mod low_resolution;
pub mod per_vertex;
pub mod raster;
pub mod reduced_shading;
mod scene_pipeline;
pub mod vertex_light;

pub use full_resolution::ListedPixels;
mod surface_buffer;

use crate::render::descriptors::compute_pipeline;
use crate::render::pass_timer::TimedEncoder;
use crate::shading::wgsl::slots;

/// One compute pass named `label` (timed under that name) with the scene's groups 0–2
/// `groups` (frame, surface buffer, shadow) set, in which `run` sets group 3, pipelines
/// and dispatches.
fn scene_compute_pass(
    frame: &mut TimedEncoder,
    label: &'static str,
    groups: [&wgpu::BindGroup; 3],
    run: &dyn Fn(&mut wgpu::ComputePass<'_>),
) {
    let mut pass = frame.encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
        label: Some(label),
        timestamp_writes: None,
    });
    for (group, bind_group) in [slots::FRAME_GROUP, slots::MATERIAL_GROUP, slots::SHADOW_GROUP]
        .into_iter()
        .zip(groups)
    {
        pass.set_bind_group(group, bind_group, &[]);
    }
    run(&mut pass);
    drop(pass);
    frame.mark(label);
}

/// The compute pipeline of `entry_point` over the scene's groups 0–2 `groups` (frame,
/// surface buffer, shadow) and its pass's `group_3`.
fn scene_compute_pipeline(
    device: &wgpu::Device,
    module: &wgpu::ShaderModule,
    entry_point: &str,
    ([frame, surfaces, shadow], group_3): ([&wgpu::BindGroupLayout; 3], &wgpu::BindGroupLayout),
    constants: &[(&str, f64)],
) -> wgpu::ComputePipeline {
    compute_pipeline(
        device,
        module,
        entry_point,
        &[frame, surfaces, shadow, group_3],
        constants,
    )
}
