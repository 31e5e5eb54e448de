// The depth of the scene's triangles seen from one shadow-map view (src/render/resources/
// shadow_maps.rs draws every view of every light on the shadow-map path; logsh.wgsl's
// shadow_map_visibility reads them). Depth only: no fragment stage; both faces are
// drawn, so open and single-sided meshes cast too.
// #import common slots

@group(IMAGE_GROUP) @binding(SHADOW_VIEW_BINDING) var<uniform> shadow_view: ShadowView;

@vertex
fn vs_shadow_map(@location(0) position: vec3<f32>) -> @builtin(position) vec4<f32> {
    return shadow_view.view_proj * vec4<f32>(position, 1.0);
}
