//! Where every WGSL resource is bound, named once for the shaders and for Rust. The shaders
//! import the module [`wgsl_module`] writes from this table (`// #import slots`) and
//! declare each resource as `@group(SHADOW_GROUP) @binding(SHADOW_MAPS_BINDING) var
//! shadow_maps: …`; `render` builds its bind group layouts and bind groups from the same
//! [`Slot`]s. `tests/wgsl_slots.rs` checks, through naga's reflection of every shader,
//! that each resource sits at the slot of its name and that every slot is used.

use std::fmt::Write;

/// A resource's place: bind group, binding, and the name of its WGSL global variable.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct Slot {
    pub group: u32,
    pub binding: u32,
    pub name: &'static str,
}

const fn slot(group: u32, binding: u32, name: &'static str) -> Slot {
    Slot { group, binding, name }
}

/// The frame: camera, exposure, environment, the lights (scene.wgsl).
pub const FRAME_GROUP: u32 = 0;
/// An object's material, or the surface buffer in the deferred full-screen passes.
pub const MATERIAL_GROUP: u32 = 1;
/// The shadow settings, blockers, terrain and shadow maps (shadow_bindings.wgsl).
pub const SHADOW_GROUP: u32 = 2;
/// What one pass reads or writes of its own: per-vertex visibility, the low-resolution
/// samples, the kept visibility of the mapped lights.
pub const PASS_GROUP: u32 = 3;
/// The only group of the passes that draw a finished image (edge filter, viewport image)
/// and of the shadow-map depth pass.
pub const IMAGE_GROUP: u32 = 0;

pub const FRAME: Slot = slot(FRAME_GROUP, 0, "frame");
pub const LIGHTS: Slot = slot(FRAME_GROUP, 1, "lights");
pub const BAKED_INDIRECT: Slot = slot(FRAME_GROUP, 2, "baked_indirect");
pub const EVERY_LIGHT: Slot = slot(FRAME_GROUP, 3, "every_light");
pub const LIGHT_GRID: Slot = slot(FRAME_GROUP, 4, "light_grid");

pub const MATERIAL: Slot = slot(MATERIAL_GROUP, 0, "material");
pub const BASE_COLOR_TEXTURE: Slot = slot(MATERIAL_GROUP, 1, "base_color_texture");
pub const BASE_COLOR_SAMPLER: Slot = slot(MATERIAL_GROUP, 2, "base_color_sampler");
// The surface buffer's group replaces the material's in the full-screen passes; its
// bindings stay clear of the material's, which the same shader module declares.
pub const SURFACE_BUFFER_A: Slot = slot(MATERIAL_GROUP, 8, "surface_buffer_a");
pub const SURFACE_BUFFER_B: Slot = slot(MATERIAL_GROUP, 9, "surface_buffer_b");
pub const KEPT_MAPPED_FACTORS: Slot = slot(MATERIAL_GROUP, 10, "kept_mapped_factors");

pub const SHADOW: Slot = slot(SHADOW_GROUP, 0, "shadow");
pub const BLOCKERS: Slot = slot(SHADOW_GROUP, 1, "blockers");
pub const GROUPS: Slot = slot(SHADOW_GROUP, 2, "groups");
pub const TERRAIN: Slot = slot(SHADOW_GROUP, 3, "terrain");
pub const TERRAIN_HEIGHTS: Slot = slot(SHADOW_GROUP, 4, "terrain_heights");
pub const EVERY_BLOCKER: Slot = slot(SHADOW_GROUP, 5, "every_blocker");
pub const EVERY_GROUP: Slot = slot(SHADOW_GROUP, 6, "every_group");
pub const SHADOW_MAPS: Slot = slot(SHADOW_GROUP, 7, "shadow_maps");
pub const SHADOW_MAP_SAMPLER: Slot = slot(SHADOW_GROUP, 8, "shadow_map_sampler");
pub const SHADOW_VIEWS: Slot = slot(SHADOW_GROUP, 9, "shadow_views");

pub const VERTEX_DATA: Slot = slot(PASS_GROUP, 0, "vertex_data");
pub const VERTEX_VISIBILITY: Slot = slot(PASS_GROUP, 1, "vertex_visibility");
pub const VERTEX_LIGHT: Slot = slot(PASS_GROUP, 2, "vertex_light");
pub const UPSAMPLE: Slot = slot(PASS_GROUP, 0, "upsample");
pub const LOW_SAMPLES: Slot = slot(PASS_GROUP, 1, "low_samples");
pub const MAPPED_FACTORS_OUT: Slot = slot(PASS_GROUP, 4, "mapped_factors_out");
pub const STALE_LIGHTS: Slot = slot(PASS_GROUP, 5, "stale_lights");
// The deferred full-resolution frame's passes (full_resolution.wgsl): bindings clear of
// the samples' (0, 1), which their groups also hold.
pub const LIST_COUNTS: Slot = slot(PASS_GROUP, 6, "list_counts");
pub const SHARP_PIXELS: Slot = slot(PASS_GROUP, 7, "sharp_pixels");
pub const SHARP_PIXELS_OUT: Slot = slot(PASS_GROUP, 8, "sharp_pixels_out");
pub const FULL_PIXELS: Slot = slot(PASS_GROUP, 9, "full_pixels");
pub const FULL_PIXELS_OUT: Slot = slot(PASS_GROUP, 10, "full_pixels_out");
pub const FRAME_COLOURS: Slot = slot(PASS_GROUP, 11, "frame_colours");
pub const DISPATCH_ARGS: Slot = slot(PASS_GROUP, 13, "dispatch_args");
pub const KEPT_HARMONIC_X: Slot = slot(PASS_GROUP, 14, "kept_harmonic_x");
pub const KEPT_HARMONIC_Y: Slot = slot(PASS_GROUP, 15, "kept_harmonic_y");
pub const KEPT_HARMONIC_STAMP: Slot = slot(PASS_GROUP, 16, "kept_harmonic_stamp");
pub const KEPT_HARMONIC_GENERATION: Slot = slot(PASS_GROUP, 17, "kept_harmonic_generation");
pub const KEPT_HARMONIC_READ: Slot = slot(PASS_GROUP, 18, "kept_harmonic_read");
// The low-resolution samples the soft layer leaves, listed and shaded in compute passes
// (listed_samples.wgsl).
pub const LISTED_SAMPLES_OUT: Slot = slot(PASS_GROUP, 20, "listed_samples_out");
pub const LISTED_SAMPLES: Slot = slot(PASS_GROUP, 21, "listed_samples");
pub const LISTED_SAMPLES_COUNT: Slot = slot(PASS_GROUP, 22, "listed_samples_count");
pub const LISTED_SAMPLES_ARGS: Slot = slot(PASS_GROUP, 25, "listed_samples_args");
pub const LOW_SAMPLES_OUT: Slot = slot(PASS_GROUP, 23, "low_samples_out");
pub const KEPT_AT_SAMPLES_OUT: Slot = slot(PASS_GROUP, 24, "kept_at_samples_out");

pub const FRAME_IMAGE: Slot = slot(IMAGE_GROUP, 0, "frame_image");
pub const FRAME_SAMPLER: Slot = slot(IMAGE_GROUP, 1, "frame_sampler");
pub const FRAME_DEPTH: Slot = slot(IMAGE_GROUP, 2, "frame_depth");
pub const SHADOW_VIEW: Slot = slot(IMAGE_GROUP, 0, "shadow_view");

/// Every slot.
pub const ALL: [Slot; 50] = [
    FRAME,
    LIGHTS,
    BAKED_INDIRECT,
    EVERY_LIGHT,
    LIGHT_GRID,
    MATERIAL,
    BASE_COLOR_TEXTURE,
    BASE_COLOR_SAMPLER,
    SURFACE_BUFFER_A,
    SURFACE_BUFFER_B,
    KEPT_MAPPED_FACTORS,
    SHADOW,
    BLOCKERS,
    GROUPS,
    TERRAIN,
    TERRAIN_HEIGHTS,
    EVERY_BLOCKER,
    EVERY_GROUP,
    SHADOW_MAPS,
    SHADOW_MAP_SAMPLER,
    SHADOW_VIEWS,
    VERTEX_DATA,
    VERTEX_VISIBILITY,
    VERTEX_LIGHT,
    UPSAMPLE,
    LOW_SAMPLES,
    MAPPED_FACTORS_OUT,
    STALE_LIGHTS,
    LIST_COUNTS,
    SHARP_PIXELS,
    SHARP_PIXELS_OUT,
    FULL_PIXELS,
    FULL_PIXELS_OUT,
    FRAME_COLOURS,
    DISPATCH_ARGS,
    KEPT_HARMONIC_X,
    KEPT_HARMONIC_Y,
    KEPT_HARMONIC_STAMP,
    KEPT_HARMONIC_GENERATION,
    KEPT_HARMONIC_READ,
    LISTED_SAMPLES_OUT,
    LISTED_SAMPLES,
    LISTED_SAMPLES_COUNT,
    LISTED_SAMPLES_ARGS,
    LOW_SAMPLES_OUT,
    KEPT_AT_SAMPLES_OUT,
    FRAME_IMAGE,
    FRAME_SAMPLER,
    FRAME_DEPTH,
    SHADOW_VIEW,
];

/// The groups by their WGSL names.
pub const GROUPS_BY_NAME: [(&str, u32); 5] = [
    ("FRAME_GROUP", FRAME_GROUP),
    ("MATERIAL_GROUP", MATERIAL_GROUP),
    ("SHADOW_GROUP", SHADOW_GROUP),
    ("PASS_GROUP", PASS_GROUP),
    ("IMAGE_GROUP", IMAGE_GROUP),
];

/// The WGSL constant that holds `slot`'s binding: its name in capitals, then `_BINDING`.
pub fn binding_constant(slot: Slot) -> String {
    format!("{}_BINDING", slot.name.to_uppercase())
}

/// The WGSL module of the groups' and the slots' constants.
pub fn wgsl_module() -> String {
    let mut out = String::from("// Generated from src/shading/wgsl/slots.rs. Do not edit.\n");
    for (name, group) in GROUPS_BY_NAME {
        writeln!(out, "const {name}: u32 = {group}u;").unwrap();
    }
    for slot in ALL {
        writeln!(out, "const {}: u32 = {}u;", binding_constant(slot), slot.binding).unwrap();
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::collections::HashSet;

    #[test]
    fn names_are_unique() {
        let names: HashSet<&str> = ALL.iter().map(|s| s.name).collect();
        assert_eq!(names.len(), ALL.len());
    }

    #[test]
    fn the_module_declares_every_slot_with_its_binding() {
        let module = wgsl_module();
        assert!(module.contains("const SHADOW_GROUP: u32 = 2u;"));
        assert!(module.contains("const SHADOW_MAPS_BINDING: u32 = 7u;"));
        assert_eq!(module.matches("_BINDING: u32").count(), ALL.len());
    }
}
