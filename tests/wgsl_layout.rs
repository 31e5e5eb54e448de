//! Every WGSL struct shared with Rust has a `#[repr(C)]` twin whose size and field offsets
//! match naga's layout of the WGSL source.

use std::mem::{offset_of, size_of};

use lightpaint::shading::gpu_types::{
    GpuBlocker, GpuBlockerGroup, GpuFrame, GpuLight, GpuMaterial, GpuShadowParams, GpuTerrainParams, GpuUpsampleParams,
};
use lightpaint::shading::wgsl;

/// (size, [(member name, offset)]) of a WGSL struct, as naga lays it out.
fn wgsl_layout(source: &str, name: &str) -> (u32, Vec<(String, u32)>) {
    let module = naga::front::wgsl::parse_str(source).unwrap_or_else(|e| panic!("{}", e.emit_to_string(source)));
    let mut layouter = naga::proc::Layouter::default();
    layouter.update(module.to_ctx()).expect("layout");
    let (handle, ty) = module
        .types
        .iter()
        .find(|(_, ty)| ty.name.as_deref() == Some(name))
        .unwrap_or_else(|| panic!("struct {name} not found in WGSL"));
    match &ty.inner {
        naga::TypeInner::Struct { members, span } => {
            assert_eq!(*span, layouter[handle].size);
            (
                *span,
                members
                    .iter()
                    .map(|m| (m.name.clone().unwrap_or_default(), m.offset))
                    .collect(),
            )
        }
        _ => panic!("{name} is not a struct"),
    }
}

fn assert_twin(name: &str, rust_size: usize, rust_offsets: &[(&str, usize)]) {
    assert_twin_in(&wgsl::raster_source(), name, rust_size, rust_offsets);
}

/// [`assert_twin`] for a struct of `source`.
fn assert_twin_in(source: &str, name: &str, rust_size: usize, rust_offsets: &[(&str, usize)]) {
    let (size, members) = wgsl_layout(source, name);
    assert_eq!(size as usize, rust_size, "size of {name}");
    let wgsl_public: Vec<(String, u32)> = members.into_iter().filter(|(n, _)| !n.starts_with('_')).collect();
    assert_eq!(wgsl_public.len(), rust_offsets.len(), "{name}: fields {wgsl_public:?}");
    for ((wgsl_name, wgsl_offset), (rust_name, rust_offset)) in wgsl_public.iter().zip(rust_offsets) {
        assert_eq!(wgsl_name, rust_name, "{name}: field order");
        assert_eq!(*wgsl_offset as usize, *rust_offset, "{name}.{rust_name} offset");
    }
}

#[test]
fn frame_matches_wgsl() {
    assert_twin(
        "Frame",
        size_of::<GpuFrame>(),
        &[
            ("view_proj", offset_of!(GpuFrame, view_proj)),
            ("camera_position", offset_of!(GpuFrame, camera_position)),
            ("exposure", offset_of!(GpuFrame, exposure)),
            ("light_count", offset_of!(GpuFrame, light_count)),
            ("pixel_angle_rad", offset_of!(GpuFrame, pixel_angle_rad)),
            ("first_exact_light", offset_of!(GpuFrame, first_exact_light)),
            ("first_mapped_light", offset_of!(GpuFrame, first_mapped_light)),
            ("background_srgb8", offset_of!(GpuFrame, background_srgb8)),
            ("view_ray", offset_of!(GpuFrame, view_ray)),
            ("environment_irradiance", offset_of!(GpuFrame, environment_irradiance)),
            ("light_grid_origin", offset_of!(GpuFrame, light_grid_origin)),
            ("light_grid_boxes", offset_of!(GpuFrame, light_grid_boxes)),
        ],
    );
}

#[test]
fn light_matches_wgsl() {
    assert_twin(
        "Light",
        size_of::<GpuLight>(),
        &[
            ("position", offset_of!(GpuLight, position)),
            ("direction_range", offset_of!(GpuLight, direction_range)),
            ("intensity_rgb", offset_of!(GpuLight, intensity_rgb)),
            ("spot_cone", offset_of!(GpuLight, spot_cone)),
            ("kind", offset_of!(GpuLight, kind)),
            ("source_size", offset_of!(GpuLight, source_size)),
            ("shadow_path", offset_of!(GpuLight, shadow_path)),
            ("first_shadow_view", offset_of!(GpuLight, first_shadow_view)),
            ("shadow_view_count", offset_of!(GpuLight, shadow_view_count)),
            ("area_half_width_x", offset_of!(GpuLight, area_half_width_m)),
            ("area_half_width_y", offset_of!(GpuLight, area_half_width_m) + 4),
            ("area_half_width_z", offset_of!(GpuLight, area_half_width_m) + 8),
        ],
    );
}

#[test]
fn shadow_view_matches_wgsl() {
    use lightpaint::shading::gpu_types::GpuShadowView;
    assert_twin(
        "ShadowView",
        size_of::<GpuShadowView>(),
        &[
            ("view_proj", offset_of!(GpuShadowView, view_proj)),
            ("texel", offset_of!(GpuShadowView, texel)),
            ("eye", offset_of!(GpuShadowView, eye)),
            ("depth_range", offset_of!(GpuShadowView, depth_range)),
            ("atlas", offset_of!(GpuShadowView, atlas)),
        ],
    );
}

#[test]
fn shadow_map_constants_match_wgsl() {
    use lightpaint::shading::gpu_types::{
        MAX_SHADOW_VIEWS, NO_SHADOW_VIEW, SHADOW_PATH_EXACT, SHADOW_PATH_MAP, SHADOW_PATH_SH,
    };
    use lightpaint::shading::shadow_maps::SINGLE_VIEW_SPOT_MIN_COS;
    let lines = [
        format!("const MAX_SHADOW_VIEWS: u32 = {MAX_SHADOW_VIEWS}u;"),
        format!("const SHADOW_PATH_SH: u32 = {SHADOW_PATH_SH}u;"),
        format!("const SHADOW_PATH_EXACT: u32 = {SHADOW_PATH_EXACT}u;"),
        format!("const SHADOW_PATH_MAP: u32 = {SHADOW_PATH_MAP}u;"),
        format!("const NO_SHADOW_VIEW: u32 = {NO_SHADOW_VIEW:#x}u;"),
        format!("const SINGLE_VIEW_SPOT_MIN_COS: f32 = {SINGLE_VIEW_SPOT_MIN_COS:?};"),
    ];
    for line in lines {
        assert!(wgsl::COMMON.contains(&line), "common.wgsl lacks `{line}`");
    }
}

#[test]
fn material_matches_wgsl() {
    assert_twin(
        "Material",
        size_of::<GpuMaterial>(),
        &[
            ("base_color", offset_of!(GpuMaterial, base_color)),
            ("params", offset_of!(GpuMaterial, params)),
            ("emissive", offset_of!(GpuMaterial, emissive)),
        ],
    );
}

#[test]
fn light_kind_tags_match_wgsl() {
    use lightpaint::shading::gpu_types::{LIGHT_AREA, LIGHT_DIRECTIONAL, LIGHT_POINT, LIGHT_SPOT};
    for (name, value) in [
        ("LIGHT_AREA", LIGHT_AREA),
        ("LIGHT_POINT", LIGHT_POINT),
        ("LIGHT_SPOT", LIGHT_SPOT),
        ("LIGHT_DIRECTIONAL", LIGHT_DIRECTIONAL),
    ] {
        let line = format!("const {name}: u32 = {value}u;");
        assert!(wgsl::COMMON.contains(&line), "common.wgsl lacks `{line}`");
    }
}

#[test]
fn uniform_array_capacities_match_wgsl() {
    use lightpaint::shading::gpu_types::{GROUP_FIRST_BITS, UNIFORM_BLOCKER_CAPACITY, UNIFORM_LIGHT_CAPACITY};
    for (name, value) in [
        ("UNIFORM_LIGHT_CAPACITY", UNIFORM_LIGHT_CAPACITY),
        ("UNIFORM_BLOCKER_CAPACITY", UNIFORM_BLOCKER_CAPACITY),
        ("GROUP_FIRST_BITS", GROUP_FIRST_BITS as usize),
    ] {
        let line = format!("const {name}: u32 = {value}u;");
        assert!(wgsl::COMMON.contains(&line), "common.wgsl lacks `{line}`");
    }
}

#[test]
fn the_stand_ins_blend_starts_where_the_twin_says() {
    use lightpaint::shading::blocker_groups::STAND_IN_BLEND_START;
    let line = format!("const STAND_IN_BLEND_START: f32 = {STAND_IN_BLEND_START:?};");
    assert!(wgsl::BLOCKERS.contains(&line), "blockers.wgsl lacks `{line}`");
}

#[test]
fn shadow_params_match_wgsl() {
    assert_twin(
        "ShadowParams",
        size_of::<GpuShadowParams>(),
        &[
            ("ln_epsilon", offset_of!(GpuShadowParams, ln_epsilon)),
            ("min_cap_ratio", offset_of!(GpuShadowParams, min_cap_ratio)),
            ("blocker_count", offset_of!(GpuShadowParams, blocker_count)),
            ("ratio_attenuation", offset_of!(GpuShadowParams, ratio_attenuation)),
            ("group_count", offset_of!(GpuShadowParams, group_count)),
            ("disc_count", offset_of!(GpuShadowParams, disc_count)),
            ("cluster_count", offset_of!(GpuShadowParams, cluster_count)),
            ("cap_mass_scale", offset_of!(GpuShadowParams, cap_mass_scale)),
            ("discs", offset_of!(GpuShadowParams, discs)),
        ],
    );
}

#[test]
fn vertex_light_matches_wgsl() {
    use lightpaint::render::passes::vertex_light::GpuVertexLight;
    use lightpaint::sh::ExpMethod;
    use lightpaint::shading::BrdfShading;
    assert_twin_in(
        &wgsl::logsh_source(4, ExpMethod::Hyb, BrdfShading::Separate),
        "VertexLight",
        size_of::<GpuVertexLight>(),
        &[
            ("front_diffuse", offset_of!(GpuVertexLight, front_diffuse)),
            ("front_glossy", offset_of!(GpuVertexLight, front_glossy)),
            ("back_diffuse", offset_of!(GpuVertexLight, back_diffuse)),
            ("back_glossy", offset_of!(GpuVertexLight, back_glossy)),
        ],
    );
}

#[test]
fn upsample_params_match_wgsl() {
    assert_twin(
        "UpsampleParams",
        size_of::<GpuUpsampleParams>(),
        &[
            ("full_to_low", offset_of!(GpuUpsampleParams, full_to_low)),
            ("plane_tolerance_px", offset_of!(GpuUpsampleParams, plane_tolerance_px)),
            ("min_matched_weight", offset_of!(GpuUpsampleParams, min_matched_weight)),
            ("max_lighting_ratio", offset_of!(GpuUpsampleParams, max_lighting_ratio)),
            ("lighting_floor", offset_of!(GpuUpsampleParams, lighting_floor)),
            ("sample_offset", offset_of!(GpuUpsampleParams, sample_offset)),
            ("sample_pixel", offset_of!(GpuUpsampleParams, sample_pixel)),
            ("pixel_to_ndc", offset_of!(GpuUpsampleParams, pixel_to_ndc)),
        ],
    );
}

#[test]
fn terrain_params_match_wgsl() {
    assert_twin(
        "TerrainParams",
        size_of::<GpuTerrainParams>(),
        &[
            ("present", offset_of!(GpuTerrainParams, present)),
            ("azimuths", offset_of!(GpuTerrainParams, azimuths)),
            ("levels", offset_of!(GpuTerrainParams, levels)),
            ("sample_count", offset_of!(GpuTerrainParams, sample_count)),
            ("first_step_m", offset_of!(GpuTerrainParams, first_step_m)),
            ("surface_first", offset_of!(GpuTerrainParams, surface_first)),
            ("surface_tolerance_m", offset_of!(GpuTerrainParams, surface_tolerance_m)),
            ("level_frame", offset_of!(GpuTerrainParams, level_frame)),
            ("level_size", offset_of!(GpuTerrainParams, level_size)),
            ("wedge", offset_of!(GpuTerrainParams, wedge)),
        ],
    );
}

#[test]
fn blocker_matches_wgsl() {
    assert_twin(
        "Blocker",
        size_of::<GpuBlocker>(),
        &[
            ("center_radius", offset_of!(GpuBlocker, center_radius)),
            ("disc_normal", offset_of!(GpuBlocker, disc_normal)),
        ],
    );
}

#[test]
fn blocker_group_matches_wgsl() {
    assert_twin(
        "PackedBlockerGroup",
        size_of::<GpuBlockerGroup>(),
        &[
            ("center_extent", offset_of!(GpuBlockerGroup, center_extent)),
            ("hand_over_m", offset_of!(GpuBlockerGroup, hand_over_m)),
            ("first_count", offset_of!(GpuBlockerGroup, first_count)),
            ("stand_in_radius_m", offset_of!(GpuBlockerGroup, stand_in_radius_m)),
            ("stand_in_depth", offset_of!(GpuBlockerGroup, stand_in_depth)),
        ],
    );
}
