//! GPU rendering with wgpu: device set-up, buffers mirroring the WGSL structs, the scene
//! pipeline and offscreen targets. Colour pipeline (docs/architecture.md): linear radiance
//! × 2^EV exposure → per-channel ACES fit tone curve → sRGB encode by the target format.

mod baked_indirect;
pub mod blocker_groups;
mod color;
mod context;
pub mod cpu;
pub mod cpu_lobes;
pub mod edge_filter;
mod gpu_blockers;
mod gpu_scene;
mod gpu_terrain;
pub mod gpu_types;
pub mod heat_map;
mod light_paths;
pub mod logsh;
mod offscreen;
pub mod paint_estimate;
pub mod per_vertex;
mod pipeline;
pub mod reduced_shading;
pub mod shaders;
mod shadow_settings;
mod target;
pub mod wgsl_lobes;
pub mod wgsl_sh;
pub mod wgsl_terrain;

pub use baked_indirect::BakedIndirect;
pub use color::{display_srgb8, linear_to_srgb, srgb_to_linear, tonemap_aces_fit};
pub use context::{GpuContext, describe_adapter};
pub use gpu_scene::GpuScene;
pub use gpu_types::GpuFrame;
pub use light_paths::{
    CompiledPaths, LightPathContext, SceneLighting, compiled_paths, light_paths_at, paths_and_sizes_at, shading_lights,
};
pub use offscreen::{
    RasterRenderer, ShadowFrame, ShadowRenderer, capture_surfaces, filter_edges, read_target_image, render_cpu_image,
    render_image, render_logsh_image, shade_surfaces,
};
pub use pipeline::{COLOR_FORMAT, SAMPLE_COUNT, ScenePipeline};
pub use shadow_settings::{
    AUTO_EXACT_BELOW_HALF_ANGLE_DEG, BrdfShading, LightPaths, MAX_EXACT_LIGHT_BUDGET, MAX_TERRAIN_AZIMUTHS,
    MAX_TERRAIN_LEVELS, ShadowSettings, TerrainShading, parse_exp_method,
};
pub use target::{AntiAliasing, RenderTarget};

/// Settings that change how a frame looks, not what the scene is.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RenderSettings {
    /// Exposure in stops: radiance is multiplied by 2^EV before tone mapping.
    pub exposure_ev: f32,
    /// Colour where no geometry is seen, as 8-bit sRGB.
    pub background_srgb8: [u8; 3],
    /// Log-SH shadow knobs (project format 2).
    pub shadows: ShadowSettings,
    /// How meshes are approximated by sphere blockers (project format 2).
    pub blockers: crate::blockers::BlockerSettings,
    /// Share of the editor viewport's pixels along each side that are shaded (0.25–1):
    /// 0.5 shades a quarter of the pixels, for slow GPUs (project format 2).
    pub viewport_resolution_scale: f32,
    /// Add the bake's indirect light when baked maps exist (project format 4).
    pub baked_indirect: bool,
}

impl Default for RenderSettings {
    fn default() -> Self {
        RenderSettings {
            exposure_ev: 0.0,
            background_srgb8: [46, 50, 58],
            shadows: ShadowSettings::default(),
            blockers: crate::blockers::BlockerSettings::default(),
            viewport_resolution_scale: 1.0,
            baked_indirect: true,
        }
    }
}

impl RenderSettings {
    pub fn background_linear(&self) -> [f64; 3] {
        self.background_srgb8.map(|c| srgb_to_linear(c as f64 / 255.0))
    }
}

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
