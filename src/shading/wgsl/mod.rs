//! WGSL sources and the code generated for them (no wgpu here: `render` compiles them).
//! WGSL has no `#include`: a module is assembled from `common.wgsl` (shared
//! structs and colour functions), `scene.wgsl` (bindings, vertex stage, lights, surfaces)
//! and its own file, so shared code lives in exactly one place. The log-SH module also
//! takes the SH code generated for its order and method (`sh`), the terrain's
//! (`terrain`, then `terrain.wgsl`) and the shadow maps' lookup (`shadow_lookup.wgsl`).

pub mod lobes;
pub mod sh;
pub mod terrain;

use super::BrdfShading;
use crate::sh::ExpMethod;

pub const COMMON: &str = include_str!("../../../shaders/common.wgsl");
pub const SCENE: &str = include_str!("../../../shaders/scene.wgsl");
pub const RASTER: &str = include_str!("../../../shaders/raster.wgsl");
pub const LOGSH: &str = include_str!("../../../shaders/logsh.wgsl");
pub const EXACT_LIGHTS: &str = include_str!("../../../shaders/exact_lights.wgsl");
pub const TERRAIN: &str = include_str!("../../../shaders/terrain.wgsl");
pub const REDUCED_SHADING: &str = include_str!("../../../shaders/reduced_shading.wgsl");
pub const LOW_RESOLUTION: &str = include_str!("../../../shaders/low_resolution.wgsl");
pub const LOGSH_PER_VERTEX: &str = include_str!("../../../shaders/logsh_per_vertex.wgsl");
pub const HEAT_MAP: &str = include_str!("../../../shaders/heat_map.wgsl");
pub const SHADOW_MAP: &str = include_str!("../../../shaders/shadow_map.wgsl");
pub const SHADOW_LOOKUP: &str = include_str!("../../../shaders/shadow_lookup.wgsl");
/// Standalone: it reads a finished frame, not the scene.
pub const EDGE_FILTER: &str = include_str!("../../../shaders/edge_filter.wgsl");
/// Standalone: the editor's viewport image drawn into egui's frame.
pub const VIEWPORT_IMAGE: &str = include_str!("../../../shaders/viewport_image.wgsl");

/// The shared prelude, then `body`.
pub fn with_common(body: &str) -> String {
    format!("{COMMON}\n{body}")
}

/// The unshadowed raster module.
pub fn raster_source() -> String {
    format!("{COMMON}\n{SCENE}\n{RASTER}")
}

/// The shadow-map depth pass's module.
pub fn shadow_map_source() -> String {
    format!("{COMMON}\n{SHADOW_MAP}")
}

/// The importance heat map module.
pub fn heat_map_source() -> String {
    format!("{COMMON}\n{SCENE}\n{HEAT_MAP}")
}

/// The log-SH shadow module at `order` with `method` (not `Reference`, which has no GPU
/// form) and the `brdf` variant, with the reduced-resolution entry points and the
/// per-vertex ones where the order allows them.
pub fn logsh_source(order: usize, method: ExpMethod, brdf: BrdfShading) -> String {
    let generated = sh::sh_module(order, method) + &lobes::lobes_module(order, method, brdf);
    let per_vertex = if sh::supports_per_vertex(order) {
        LOGSH_PER_VERTEX
    } else {
        ""
    };
    let terrain = terrain::terrain_module(order);
    format!(
        "{COMMON}\n{SCENE}\n{generated}\n{terrain}\n{TERRAIN}\n{SHADOW_LOOKUP}\n{LOGSH}\n{EXACT_LIGHTS}\n{REDUCED_SHADING}\n{LOW_RESOLUTION}\n{per_vertex}"
    )
}
