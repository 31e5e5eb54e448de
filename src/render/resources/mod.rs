//! What the scene is on the GPU: its meshes, materials, lights and frame uniform
//! (`scene`), the bind group layouts they are read through (`layouts`), the sphere
//! blockers with their culling groups (`blockers`), the terrain's heights and cache
//! (`terrain`) and the lights' shadow maps (`shadow_maps`).

mod blockers;
mod layouts;
mod light_buffers;
mod scene;
mod shadow_maps;
mod terrain;
mod texture;

pub use blockers::{GpuBlockers, shadow_layout};
pub use layouts::{SceneLayouts, vertex_layout};
pub use scene::{Detail, GpuObject, GpuScene, HarmonicLighting, draw_object, draw_objects};
pub use shadow_maps::{ShadowMapBinding, ShadowMaps};
