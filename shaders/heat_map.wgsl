// The importance heat map: each vertex's heat colour (linear RGB) arrives where the baked
// indirect light usually does (group 0, binding 2 is bound to the heat colours instead),
// shaded by a little facing ratio so the shapes stay readable.
// #import scene

@fragment
fn fs_heat(in: VertexOut) -> @location(0) vec4<f32> {
    let to_eye = normalize(frame.camera_position.xyz - in.world_position);
    let facing = abs(dot(normalize(in.normal), to_eye));
    return vec4<f32>(in.indirect_irradiance * (0.45 + 0.55 * facing), 1.0);
}
