//! The shading model, free of wgpu: what a frame's shading is, written once and read by
//! `render` (which runs it on the GPU), `project` (which saves its settings) and `paint`
//! (which estimates a stroke's effect with it). Here live the settings, each light's
//! shadow path, the Rust twins of the WGSL structs (`gpu_types`) and the WGSL sources
//! with the code generated for them (`wgsl`), the f64 twin of the shaders (`cpu`), colour
//! transforms, the blockers' culling groups, the baked indirect light and the direct
//! estimate painting uses before a bake (`paint_estimate`).

mod baked_indirect;
pub mod blocker_groups;
pub mod blocker_reach;
mod color;
mod compiled_paths;
pub mod cpu;
pub mod frame_transfer;
pub mod gpu_types;
pub mod light_grid;
mod light_path_context;
mod light_paths;
pub mod light_windows;
pub mod paint_estimate;
mod settings;
pub mod shadow_atlas;
pub mod shadow_maps;
mod shadow_path;
pub mod sphere_casters;
pub mod stand_in;
pub mod terrain;
pub mod vertex_lighting;
pub mod wgsl;

pub use baked_indirect::BakedIndirect;
pub use color::{
    display_srgb8, displayed_radiance, linear_to_srgb, srgb_to_linear, tonemap_aces_fit, untonemap_aces_fit,
};
pub use light_paths::{CompiledPaths, LightPathContext, SceneLighting, compiled_paths, shading_lights};
pub use settings::{
    AUTO_EXACT_BELOW_HALF_ANGLE_DEG, BrdfShading, DEFAULT_SHADOW_MAP_SIZE, LightPaths, MAX_EXACT_LIGHT_BUDGET,
    MAX_SHADING_DOWNSAMPLE, MAX_TERRAIN_AZIMUTHS, MAX_TERRAIN_LEVELS, SHADOW_MAP_SIZES, SUGGESTED_SHADOW_MAP_SIZE,
    ShadowSettings, TerrainShading, parse_exp_method,
};
pub use shadow_path::{ShadowPath, light_paths_at, path_reason, paths_and_sizes_at};

/// Settings that change how a frame looks, not what the scene is. In a project file any
/// field left out takes its default.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
#[serde(deny_unknown_fields, default)]
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
