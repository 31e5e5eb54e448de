//! What the scene is on the GPU: its meshes, materials, lights and frame uniform
//! (`scene`), the bind group layouts they are read through (`layouts`), the sphere
//! blockers with their culling groups (`blockers`) and the terrain's heights and cache
//! (`terrain`).

mod blockers;
mod layouts;
mod scene;
mod terrain;

pub use blockers::{GpuBlockers, shadow_layout};
pub use layouts::{SceneLayouts, vertex_layout};
pub use scene::{GpuObject, GpuScene, draw_object, draw_objects};
