// The depth of the scene's triangles seen from one shadow-map view (src/render/resources/
// shadow_maps.rs draws every view of every light on the shadow-map path; logsh.wgsl's
// shadow_map_visibility reads them), and the far depth over one view's square, which
// clears it alone. Depth only: no fragment stage; both faces are
// drawn, so open and single-sided meshes cast too.
// #import common slots full_screen

@group(IMAGE_GROUP) @binding(SHADOW_VIEW_BINDING) var<uniform> shadow_view: ShadowView;

@vertex
fn vs_shadow_map(@location(0) position: vec3<f32>) -> @builtin(position) vec4<f32> {
    return shadow_view.view_proj * vec4<f32>(position, 1.0);
}

// A triangle over the whole viewport at depth 0, the far plane of the reversed depth.
@vertex
fn vs_clear_view(@builtin(vertex_index) index: u32) -> @builtin(position) vec4<f32> {
    return vec4<f32>(full_screen_corner(index) * 2.0 - 1.0, 0.0, 1.0);
}
