//! lightpaint: a lighting editor in which artists light a 3D scene by painting on it.
//!
//! The crate is organised by domain (see `docs/architecture.md`):
//! - [`scene`]: meshes, materials, lights and cameras; glTF import and validation.
//! - [`shading`]: the shading model without wgpu: settings, light paths, the WGSL sources
//!   and their Rust struct twins, the f64 twin of the shaders.
//! - [`render`]: wgpu only: device, the scene's GPU resources, passes, offscreen targets.
//! - [`ui`]: the eframe editor shell.
//! - [`samples`]: the generator of the bundled sample scene.

pub mod bake;
pub mod blockers;
pub mod paint;
pub mod panic_guard;
pub mod penumbra;
pub mod project;
pub mod random;
pub mod reference;
pub mod render;
pub mod samples;
pub mod scene;
pub mod session;
pub mod sh;
pub mod shading;
pub mod study;
pub mod terrain;
pub mod ui;
