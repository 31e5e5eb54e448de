// Per-vertex log-SH shadows: a compute pass exponentiates every vertex's log-visibility
// (log_visibility of logsh.wgsl at the vertex position and normal) into a buffer. Meshes
// fine enough for it (shading::vertex_lighting) then have the SH path's light itself
// computed at their vertices by a second compute pass (cs_vertex_light), which the
// rasteriser interpolates: a fragment only multiplies it by its material and adds the
// lights of the other paths. Coarser meshes read the visibility as vertex attributes;
// the rasteriser interpolates the visibility SH and each fragment shades its lights
// through it exactly as fs_logsh does. Shading cost follows the vertex count instead of
// the pixel count. Composed with logsh.wgsl for the orders whose visibility fits the
// varyings (wgsl_sh::supports_per_vertex).
// #import logsh slots

// GpuVertex as plain floats (position xyz, normal xyz, uv): 8 per vertex.
@group(PASS_GROUP) @binding(VERTEX_DATA_BINDING) var<storage, read> vertex_data: array<f32>;
// The visibility SH of every vertex, as consecutive Sh.
@group(PASS_GROUP) @binding(VERTEX_VISIBILITY_BINDING) var<storage, read_write> vertex_visibility: array<Sh>;
// The SH path's light at every vertex as the separate BRDF splits it (VertexLight).
@group(PASS_GROUP) @binding(VERTEX_LIGHT_BINDING) var<storage, read_write> vertex_light: array<VertexLight>;

// The light of the SH path (the environment and the lights before frame.first_mapped_light,
// through the vertex's visibility) at a vertex, split by what a fragment multiplies it by
// (BRDF_SEPARATE: light_through and environment_through): radiance = k_d · diffuse +
// k_s · glossy, for the side the normal faces (front) and the other (back): a fragment
// of a back face turns its normal, so it takes the back's, as fs_per_vertex would (the
// side cannot be told at a vertex: on a closed mesh's rim a front face's vertex normal may
// face away from the eye). rgb used, w 0 (vec4 for the storage and vertex layouts
// alike). Rust twin: render::passes::vertex_light::GpuVertexLight; f64 twin
// shading::cpu::vertex_light.
struct VertexLight {
    front_diffuse: vec4<f32>,
    front_glossy: vec4<f32>,
    back_diffuse: vec4<f32>,
    back_glossy: vec4<f32>,
};

@compute @workgroup_size(64)
fn cs_vertex_visibility(@builtin(global_invocation_id) id: vec3<u32>) {
    let i = id.x;
    if i >= arrayLength(&vertex_data) / 8u {
        return;
    }
    let b = 8u * i;
    let p = vec3<f32>(vertex_data[b], vertex_data[b + 1u], vertex_data[b + 2u]);
    let n = normalize(vec3<f32>(vertex_data[b + 3u], vertex_data[b + 4u], vertex_data[b + 5u]));
    vertex_visibility[i] = sh_exp(log_visibility(p, n));
}

// The SH path's light at a vertex of surface s (its position, its normal for the side lit,
// its mirrored view and its exponent) through its visibility g: diffuse and glossy parts
// (VertexLight).
fn side_light(s: Surface, g: Sh) -> array<vec3<f32>, 2> {
    // The environment's light per unit diffuse albedo: environment_through with k_d = 1.
    var unit_albedo = s;
    unit_albedo.k_d = vec3<f32>(1.0);
    var diffuse = environment_through(unit_albedo, LobeVisibility(g, g, false));
    var glossy = vec3<f32>(0.0);
    let run = harmonic_lights_at(s.position);
    for (var k = run.first; k < run.end; k++) {
        let inc = incidence(light_at(run_light(k)), s.position);
        let direct = direct_lobes(s, inc);
        let seen = inc.irradiance * clamp(sh_visibility_toward(g, inc.to_light, inc.cap_ratio), 0.0, 1.0);
        diffuse += seen * direct.x;
        glossy += seen * direct.y;
    }
    return array<vec3<f32>, 2>(diffuse, glossy);
}

// The SH path's light at every vertex of one object, both sides, from the visibility
// cs_vertex_visibility wrote there, for the frame's camera (the glossy lobe's axis) and
// the object's material (its exponent).
@compute @workgroup_size(64)
fn cs_vertex_light(@builtin(global_invocation_id) id: vec3<u32>) {
    let i = id.x;
    if i >= arrayLength(&vertex_data) / 8u {
        return;
    }
    let b = 8u * i;
    var s: Surface;
    s.position = vec3<f32>(vertex_data[b], vertex_data[b + 1u], vertex_data[b + 2u]);
    s.phong_exponent = material.params.z;
    let to_eye = normalize(frame.camera_position.xyz - s.position);
    let g = vertex_visibility[i];
    let normal = normalize(vec3<f32>(vertex_data[b + 3u], vertex_data[b + 4u], vertex_data[b + 5u]));
    s.normal = normal;
    s.mirrored_view = reflect(-to_eye, s.normal);
    let front = side_light(s, g);
    s.normal = -normal;
    s.mirrored_view = reflect(-to_eye, s.normal);
    let back = side_light(s, g);
    vertex_light[i] = VertexLight(
        vec4<f32>(front[0], 0.0),
        vec4<f32>(front[1], 0.0),
        vec4<f32>(back[0], 0.0),
        vec4<f32>(back[1], 0.0),
    );
}

// The vertex output of a mesh lit at its vertices: scene.wgsl's VertexOut but for the
// baked indirect light, which joins the diffuse light of both sides (k_d/π · E_indirect,
// as material_surface adds it to the emission), and with the vertex's light.
struct VertexOutLit {
    @builtin(position) @invariant clip: vec4<f32>,
    @location(0) world_position: vec3<f32>,
    @location(1) normal: vec3<f32>,
    @location(2) uv: vec2<f32>,
    @location(4) front_diffuse: vec3<f32>,
    @location(5) front_glossy: vec3<f32>,
    @location(6) back_diffuse: vec3<f32>,
    @location(7) back_glossy: vec3<f32>,
};

@vertex
fn vs_vertex_lit(v: VertexIn, light: VertexLightIn) -> VertexOutLit {
    return vertex_lit(v, light);
}

fn vertex_lit(v: VertexIn, light: VertexLightIn) -> VertexOutLit {
    let o = transform_vertex(v);
    let indirect = max(o.indirect_irradiance, vec3<f32>(0.0)) / PI;
    return VertexOutLit(
        o.clip, o.world_position, o.normal, o.uv,
        light.front_diffuse.rgb + indirect, light.front_glossy.rgb,
        light.back_diffuse.rgb + indirect, light.back_glossy.rgb,
    );
}

// VertexLight as vertex attributes.
struct VertexLightIn {
    @location(4) front_diffuse: vec4<f32>,
    @location(5) front_glossy: vec4<f32>,
    @location(6) back_diffuse: vec4<f32>,
    @location(7) back_glossy: vec4<f32>,
};

// A fragment of a mesh lit at its vertices: the interpolated light of the SH path (and the
// baked light) of the side it shows times the fragment's material, its texture included,
// plus what soft_radiance_through and radiance_through add per pixel (emission, the exact
// path's and the shadow maps' lights).
@fragment
fn fs_vertex_lit(in: VertexOutLit, @builtin(front_facing) front_facing: bool) -> @location(0) vec4<f32> {
    let s = surface(VertexOut(in.clip, in.world_position, in.normal, in.uv, vec3<f32>(0.0)), front_facing);
    let light = array<vec3<f32>, 4>(in.front_diffuse, in.front_glossy, in.back_diffuse, in.back_glossy);
    let radiance = vertex_lit_radiance(s, light, front_facing) + exact_path_radiance(s) + mapped_lights_radiance(s);
    return vec4<f32>(tonemap_aces_fit(frame.exposure * radiance), 1.0);
}

// The emission and the interpolated light of the side a fragment shows (`light`: front
// diffuse, front glossy, back diffuse, back glossy) times surface s's material.
fn vertex_lit_radiance(s: Surface, light: array<vec3<f32>, 4>, front_facing: bool) -> vec3<f32> {
    let diffuse = select(light[2], light[0], front_facing);
    let glossy = select(light[3], light[1], front_facing);
    return s.emissive + s.k_d * diffuse + s.k_s * glossy;
}

// A mesh lit at its vertices in a frame without lights on the shadow-map or exact paths:
// nothing but the material is shaded per pixel, so the fragment needs neither position
// nor normal (lavapipe sets up every varying of each triangle).
struct VertexOutLitAlone {
    @builtin(position) @invariant clip: vec4<f32>,
    @location(2) uv: vec2<f32>,
    @location(4) front_diffuse: vec3<f32>,
    @location(5) front_glossy: vec3<f32>,
    @location(6) back_diffuse: vec3<f32>,
    @location(7) back_glossy: vec3<f32>,
};

@vertex
fn vs_vertex_lit_alone(v: VertexIn, light: VertexLightIn) -> VertexOutLitAlone {
    let o = vertex_lit(v, light);
    return VertexOutLitAlone(o.clip, o.uv, o.front_diffuse, o.front_glossy, o.back_diffuse, o.back_glossy);
}

// fs_vertex_lit where exact_path_radiance and mapped_lights_radiance add nothing.
@fragment
fn fs_vertex_lit_alone(in: VertexOutLitAlone, @builtin(front_facing) front_facing: bool) -> @location(0) vec4<f32> {
    // The normal only turns the surface toward the viewer, which the material ignores.
    let s = material_surface(vec3<f32>(0.0, 0.0, 1.0), in.uv, vec3<f32>(0.0), front_facing);
    let light = array<vec3<f32>, 4>(in.front_diffuse, in.front_glossy, in.back_diffuse, in.back_glossy);
    let radiance = vertex_lit_radiance(s, light, front_facing);
    return vec4<f32>(tonemap_aces_fit(frame.exposure * radiance), 1.0);
}

@vertex
fn vs_per_vertex(v: VertexIn, visibility: Visibility) -> VertexOutWithVisibility {
    return with_visibility(transform_vertex(v), visibility);
}

@fragment
fn fs_per_vertex(
    in: VertexOut,
    visibility: Visibility,
    @builtin(front_facing) front_facing: bool,
) -> @location(0) vec4<f32> {
    let s = surface(in, front_facing);
    let radiance = radiance_through(s, lobes_through(s, sh_from_visibility(visibility)));
    return vec4<f32>(tonemap_aces_fit(frame.exposure * radiance), 1.0);
}
