//! Plumbing of the light computed at the vertices (logsh_per_vertex.wgsl's
//! cs_vertex_light): per frame, for each mesh in view that `shading::vertex_lighting`
//! finds fine enough, a compute pass turns the visibility kept at its vertices into the
//! SH path's light there, which the scene pass binds as a second vertex buffer (fs_vertex_lit).
//! The glossy part depends on the camera, so the pass runs every frame; it costs a
//! vertex what a pixel's shading costs, for far fewer vertices than pixels.

use bytemuck::{Pod, Zeroable};
use glam::Vec3;

use crate::render::descriptors::{slot_entries, storage_buffer_entry};
use crate::render::resources::GpuScene;
use crate::shading::gpu_types::GpuLight;
use crate::shading::vertex_lighting::{MAX_NORMAL_TURN_RAD, lit_at_vertices};
use crate::shading::wgsl::slots;

/// One vertex's light of the SH path: radiance = k_d · diffuse + k_s · glossy (rgb; w 0),
/// on the side its normal faces and on the other. WGSL twin: `VertexLight` in
/// logsh_per_vertex.wgsl.
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, Pod, Zeroable)]
pub struct GpuVertexLight {
    pub front_diffuse: [f32; 4],
    pub front_glossy: [f32; 4],
    pub back_diffuse: [f32; 4],
    pub back_glossy: [f32; 4],
}

/// The compute pipeline and the layout of its per-object group (group 3: the vertices,
/// their visibility, their light).
pub struct VertexLightCompute {
    pipeline: wgpu::ComputePipeline,
    object_layout: wgpu::BindGroupLayout,
}

impl VertexLightCompute {
    pub fn new(
        device: &wgpu::Device,
        module: &wgpu::ShaderModule,
        [frame_layout, material_layout, shadow_layout]: [&wgpu::BindGroupLayout; 3],
        constants: &[(&str, f64)],
    ) -> VertexLightCompute {
        let storage = |slot, read_only| storage_buffer_entry(slot, wgpu::ShaderStages::COMPUTE, read_only);
        let object_layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("vertex light object"),
            entries: &[
                storage(slots::VERTEX_DATA, true),
                // Declared read_write in the module the visibility pass shares.
                storage(slots::VERTEX_VISIBILITY, false),
                storage(slots::VERTEX_LIGHT, false),
            ],
        });
        let layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some("vertex light"),
            bind_group_layouts: &[
                Some(frame_layout),
                Some(material_layout),
                Some(shadow_layout),
                Some(&object_layout),
            ],
            immediate_size: 0,
        });
        let pipeline = device.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
            label: Some("vertex light"),
            layout: Some(&layout),
            module,
            entry_point: Some("cs_vertex_light"),
            compilation_options: wgpu::PipelineCompilationOptions {
                constants,
                ..Default::default()
            },
            cache: None,
        });
        VertexLightCompute {
            pipeline,
            object_layout,
        }
    }

    /// Lights the vertices of the objects `light` planned ([`VertexLight::plan`]) that are
    /// drawn from the camera, from the visibility their buffers hold.
    pub fn run(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        [frame, blockers]: [&wgpu::BindGroup; 2],
        scene: &GpuScene,
        light: &VertexLight,
    ) {
        let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
            label: Some("vertex light"),
            timestamp_writes: None,
        });
        pass.set_pipeline(&self.pipeline);
        pass.set_bind_group(slots::FRAME_GROUP, frame, &[]);
        pass.set_bind_group(slots::SHADOW_GROUP, blockers, &[]);
        for (k, object) in scene.objects.iter().enumerate() {
            let Some(bind_group) = light.bind_group(k) else {
                continue;
            };
            if !object.drawn_in_view() {
                continue;
            }
            pass.set_bind_group(slots::MATERIAL_GROUP, &scene.material_bind_groups[object.material], &[]);
            pass.set_bind_group(slots::PASS_GROUP, bind_group, &[]);
            pass.dispatch_workgroups(object.vertex_count.div_ceil(64), 1, 1);
        }
    }

    /// The vertex buffer layout's attributes (locations 4 to 7 of vs_vertex_lit).
    pub fn attributes() -> [wgpu::VertexAttribute; 4] {
        wgpu::vertex_attr_array![4 => Float32x4, 5 => Float32x4, 6 => Float32x4, 7 => Float32x4]
    }
}

/// The light of every vertex of the objects that may be lit at their vertices, one
/// buffer each, and which of them the frame planned lights so.
pub struct VertexLight {
    /// Per object: its buffer and group, for meshes whose normals turn little enough to
    /// be lit at their vertices under some light (None for the others).
    objects: Vec<Option<(wgpu::Buffer, wgpu::BindGroup)>>,
    /// Per object: whether the planned frame lights it at its vertices.
    lit: Vec<bool>,
}

impl VertexLight {
    pub fn new(
        device: &wgpu::Device,
        compute: &VertexLightCompute,
        scene: &GpuScene,
        visibility: &[wgpu::Buffer],
    ) -> VertexLight {
        let objects: Vec<_> = scene
            .objects
            .iter()
            .zip(visibility)
            .map(|(object, visibility)| {
                // Whatever the lights, a mesh whose normals turn more than the bound (or by
                // NaN) is shaded per pixel: no buffer for it.
                let smooth = object.fineness.widest_normal_turn_rad <= MAX_NORMAL_TURN_RAD;
                if !smooth {
                    return None;
                }
                let buffer = device.create_buffer(&wgpu::BufferDescriptor {
                    label: Some("vertex light"),
                    size: std::mem::size_of::<GpuVertexLight>() as u64 * u64::from(object.vertex_count.max(1)),
                    usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::VERTEX | wgpu::BufferUsages::COPY_SRC,
                    mapped_at_creation: false,
                });
                let bind_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
                    label: Some("vertex light object"),
                    layout: &compute.object_layout,
                    entries: &slot_entries([
                        (slots::VERTEX_DATA, object.vertex_buffer.as_entire_binding()),
                        (slots::VERTEX_VISIBILITY, visibility.as_entire_binding()),
                        (slots::VERTEX_LIGHT, buffer.as_entire_binding()),
                    ]),
                });
                Some((buffer, bind_group))
            })
            .collect();
        let lit = vec![false; objects.len()];
        VertexLight { objects, lit }
    }

    /// Plans a frame seen from `eye` with `harmonic_lights` on the SH path: each object
    /// with a buffer is lit at its vertices where `shading::vertex_lighting` says its mesh
    /// is fine enough for them; `enabled` false (a BRDF the light cannot be split for)
    /// plans none. Returns how many objects are lit so.
    pub fn plan(&mut self, scene: &GpuScene, harmonic_lights: &[GpuLight], eye: Vec3, enabled: bool) -> usize {
        for (k, object) in scene.objects.iter().enumerate().take(self.lit.len()) {
            self.lit[k] = enabled
                && self.objects[k].is_some()
                && lit_at_vertices(
                    object.fineness,
                    &object.bounds,
                    object.phong_exponent,
                    harmonic_lights,
                    eye,
                );
        }
        self.lit.iter().filter(|lit| **lit).count()
    }

    /// The buffer of object `k`'s light when the planned frame lights it at its vertices.
    pub fn buffer(&self, k: usize) -> Option<&wgpu::Buffer> {
        self.planned(k).map(|(buffer, _)| buffer)
    }

    fn bind_group(&self, k: usize) -> Option<&wgpu::BindGroup> {
        self.planned(k).map(|(_, group)| group)
    }

    fn planned(&self, k: usize) -> Option<&(wgpu::Buffer, wgpu::BindGroup)> {
        self.objects
            .get(k)
            .and_then(Option::as_ref)
            .filter(|_| self.lit.get(k).copied().unwrap_or(false))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The vertex buffer's attributes read the storage array's elements (whose layout
    /// tests/wgsl_layout.rs checks against WGSL), in order from location 4.
    #[test]
    fn the_attributes_read_the_fields() {
        use std::mem::offset_of;
        let offsets = [
            offset_of!(GpuVertexLight, front_diffuse),
            offset_of!(GpuVertexLight, front_glossy),
            offset_of!(GpuVertexLight, back_diffuse),
            offset_of!(GpuVertexLight, back_glossy),
        ];
        for (k, (attribute, offset)) in VertexLightCompute::attributes().iter().zip(offsets).enumerate() {
            assert_eq!(attribute.offset as usize, offset);
            assert_eq!(attribute.shader_location, 4 + k as u32);
        }
    }
}
