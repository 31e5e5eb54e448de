//! GPU rendering with wgpu, and nothing else: the device (`context`), the formats and
//! descriptor pieces every pass shares (`descriptors`), the scene's GPU resources
//! (`resources`), render targets and their antialiasing (`target`), the passes that draw
//! (`passes`), the scene renderer the editor and the CLI share (`renderer`), and headless
//! rendering into images (`offscreen`). What a frame computes —
//! settings, light paths, WGSL sources, the f64 twin — is `crate::shading`. Colour
//! pipeline (docs/architecture.md): linear radiance × 2^EV exposure → per-channel ACES fit
//! tone curve → sRGB encode by the target format.

mod context;
pub mod descriptors;
mod offscreen;
pub mod pass_timer;
pub mod passes;
mod readback;
pub mod renderer;
pub mod resources;
pub mod target;

pub use context::{GpuContext, describe_adapter};
pub use descriptors::{COLOR_FORMAT, SAMPLE_COUNT};
pub use offscreen::{
    RasterRenderer, Redraw, ShadowFrame, ShadowRenderer, capture_surfaces, capture_surfaces_at, filter_edges,
    render_cpu_image, render_image, render_logsh_image, shade_surfaces,
};
pub use passes::ListedPixels;
pub use passes::raster::ScenePipeline;
pub use readback::read_target_image;
pub use renderer::{Compilation, FrameQuality, SceneRenderer};
pub use resources::{Detail, GpuScene};
pub use target::{AntiAliasing, RenderTarget};

#[derive(Debug, thiserror::Error)]
pub enum RenderError {
    #[error("no GPU adapter found (on a machine without a GPU, install Mesa's lavapipe: mesa-vulkan-drivers): {0}")]
    NoAdapter(String),
    #[error("the GPU device could not be created: {0}")]
    Device(String),
    #[error("image size {width}×{height} is not supported (1 to {max} pixels per side)")]
    BadSize { width: u32, height: u32, max: u32 },
    #[error("invalid shadow settings: {0}")]
    BadSettings(String),
    #[error("reading the rendered image back from the GPU failed: {0}")]
    Readback(String),
}
