// Rasterised direct lighting without shadows: every light's direct_radiance (scene.wgsl),
// the environment's diffuse light and emission, exposed and tone mapped.
// #import scene

@fragment
fn fs_main(in: VertexOut, @builtin(front_facing) front_facing: bool) -> @location(0) vec4<f32> {
    let s = surface(in, front_facing);
    var radiance = s.emissive + environment_radiance(s);
    for (var i = 0u; i < frame.light_count; i++) {
        radiance += direct_radiance(s, incidence(light_at(i), s.position));
    }
    return vec4<f32>(tonemap_aces_fit(frame.exposure * radiance), 1.0);
}
