//! The terrain's shadow model for a frame's shadow settings (its order, azimuths and
//! pyramid levels), and the uniform and height array the GPU reads it from
//! (`TerrainParams` and bindings 3–4 of the shadow group in shaders/terrain.wgsl).

use bytemuck::Zeroable;

use super::ShadowSettings;
use super::gpu_types::{GPU_TERRAIN_LEVELS, GpuTerrainParams};
use crate::terrain::{HeightField, HeightPyramid, TerrainShadow};

/// The shadow model of `field` for `settings` (its order, azimuths and pyramid levels),
/// surface cache filled: what the CPU reference shades frames with and what
/// `render`'s `GpuTerrain` uploads.
pub fn terrain_shadow(field: &HeightField, settings: &ShadowSettings) -> TerrainShadow {
    let (pyramid, levels) = pyramid_for(field, settings);
    TerrainShadow::new(pyramid, settings.order, settings.terrain.azimuths as usize, levels)
}

/// [`terrain_shadow`] without the surface cache, for shading a few points.
pub fn terrain_march(field: &HeightField, settings: &ShadowSettings) -> TerrainShadow {
    let (pyramid, levels) = pyramid_for(field, settings);
    TerrainShadow::marching_only(pyramid, settings.order, settings.terrain.azimuths as usize, levels)
}

fn pyramid_for(field: &HeightField, settings: &ShadowSettings) -> (HeightPyramid, usize) {
    let levels = (settings.terrain.pyramid_levels as usize).clamp(1, GPU_TERRAIN_LEVELS);
    (HeightPyramid::new(field.clone(), levels), levels)
}

/// The uniform and the concatenated heights of `shadow` (None: no terrain).
pub fn terrain_params(shadow: Option<&TerrainShadow>) -> (GpuTerrainParams, Vec<f32>) {
    let mut params = GpuTerrainParams::zeroed();
    let mut heights = Vec::new();
    let Some(shadow) = shadow else {
        return (params, vec![0.0]);
    };
    params.present = 1;
    params.azimuths = shadow.azimuths() as u32;
    params.levels = shadow.march.levels as u32;
    params.sample_count = shadow.march.sample_count() as u32;
    params.first_step_m = shadow.march.first_step_m as f32;
    for (k, level) in shadow.pyramid.levels.iter().take(GPU_TERRAIN_LEVELS).enumerate() {
        params.level_frame[k] = [
            level.min_xz[0] as f32,
            level.min_xz[1] as f32,
            level.spacing_m[0] as f32,
            level.spacing_m[1] as f32,
        ];
        params.level_size[k] = [level.columns as u32, level.rows as u32, heights.len() as u32, 0];
        heights.extend_from_slice(&level.heights_m);
    }
    for (e, value) in shadow.operator.matrix.iter().enumerate().take(4 * params.wedge.len()) {
        params.wedge[e / 4][e % 4] = *value as f32;
    }
    let finest = shadow.pyramid.finest();
    params.surface_first = heights.len() as u32;
    // Without a cache (large terrains) no receiver counts as on the surface.
    params.surface_tolerance_m = if shadow.surface.is_empty() {
        -f32::MAX
    } else {
        (crate::terrain::SURFACE_TOLERANCE * finest.spacing_m[0].min(finest.spacing_m[1])) as f32
    };
    heights.extend(shadow.surface.iter().map(|v| *v as f32));
    (params, heights)
}
