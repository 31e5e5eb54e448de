// Log-SH soft shadows (Ren et al. 2006), per pixel. Included after common.wgsl,
// scene.wgsl and the generated SH module of the chosen order and exponentiation method
// (src/render/wgsl_sh.rs). render::cpu is the f64 reference of exactly this shading:
//   F = Σ_blockers ln ε · fade · cap_zh(r/d) rotated toward the blocker (log-visibility)
//   G = exp*(F)                                                     (visibility SH)
//   L = emissive + environment · ⟨G, cos⟩ + Σ_lights direct · clamp(mean of G over the
//       light's cap, 0, 1)
// Each light keeps its exact unshadowed shading; the SH only say how much of it arrives
// (design.md §4b: never shade through an order-n triple product of light × cosine).

@group(2) @binding(0) var<uniform> shadow: ShadowParams;
@group(2) @binding(1) var<storage, read> blockers: array<Blocker>;
@group(2) @binding(2) var<storage, read> groups: array<BlockerGroup>;

// Which surface property fs_surface writes (set by surface_pipeline in src/render/logsh.rs).
override SURFACE_CHANNEL: u32 = 0u;

// Σ of the blockers' log-visibility seen from p with normal n. Skipped: blockers that
// contain p (a sphere-fit artefact on the blocker's own surface), blockers too small in
// the sky to matter, and blockers wholly below the tangent plane; blockers straddling it
// are faded by smoothstep(−1, 1, (c − p)·n / r).
fn log_visibility(p: vec3<f32>, n: vec3<f32>) -> Sh {
    var f = sh_zero();
    for (var g = 0u; g < shadow.group_count; g++) {
        let group = groups[g];
        let to_group = group.center_extent.xyz - p;
        // Conservative group tests (see blocker_groups.rs): every sphere of a skipped group
        // would be skipped by the tests below.
        if dot(to_group, to_group) > group.influence_m * group.influence_m
            || dot(to_group, n) + group.center_extent.w <= 0.0 {
            continue;
        }
        for (var i = group.first; i < group.first + group.count; i++) {
            f = add_blocker(f, blockers[i].center_radius, p, n);
        }
    }
    return f;
}

fn add_blocker(f: Sh, b: vec4<f32>, p: vec3<f32>, n: vec3<f32>) -> Sh {
    let offset = b.xyz - p;
    let distance2 = dot(offset, offset);
    let radius = b.w;
    if distance2 <= radius * radius {
        return f;
    }
    let distance = sqrt(distance2);
    let ratio = radius / distance;
    // Fades out a blocker as it sinks below the tangent plane (0 once wholly below):
    // a sphere straddling the surface it approximates would otherwise darken its own
    // receivers in blotches where they leave it.
    let horizon = smoothstep(-1.0, 1.0, dot(offset, n) / radius);
    if ratio < shadow.min_cap_ratio || horizon <= 0.0 {
        return f;
    }
    var scale = shadow.ln_epsilon * horizon;
    if shadow.ratio_attenuation != 0u {
        scale *= ratio;
    }
    return sh_add_zonal(f, sh_cap_zh(ratio), scale, offset / distance);
}

fn shadowed_radiance(s: Surface) -> vec3<f32> {
    return radiance_through(s, sh_exp(log_visibility(s.position, s.normal)));
}

// Radiance of surface s lit through the visibility SH g.
fn radiance_through(s: Surface, g: Sh) -> vec3<f32> {
    let environment_visibility = clamp(sh_visibility_cosine(g, s.normal), 0.0, 1.0);
    var radiance = s.emissive + environment_radiance(s) * environment_visibility;
    for (var i = 0u; i < frame.light_count; i++) {
        let inc = incidence(lights[i], s.position);
        let unshadowed = direct_radiance(s, inc);
        if all(unshadowed == vec3<f32>(0.0)) {
            continue;
        }
        let visibility = clamp(sh_visibility_toward(g, inc.to_light, inc.cap_ratio), 0.0, 1.0);
        radiance += unshadowed * visibility;
    }
    return radiance;
}

@fragment
fn fs_logsh(in: VertexOut, @builtin(front_facing) front_facing: bool) -> @location(0) vec4<f32> {
    let radiance = shadowed_radiance(surface(in, front_facing));
    return vec4<f32>(tonemap_aces_fit(frame.exposure * radiance), 1.0);
}

// One property of the visible surface as raw f32, for the CPU reference to shade the very
// same points: 0 position (w = 1 where covered), 1 normal (w = Phong exponent), 2 k_d,
// 3 k_s, 4 emissive.
@fragment
fn fs_surface(in: VertexOut, @builtin(front_facing) front_facing: bool) -> @location(0) vec4<f32> {
    let s = surface(in, front_facing);
    switch SURFACE_CHANNEL {
        case 0u: { return vec4<f32>(s.position, 1.0); }
        case 1u: { return vec4<f32>(s.normal, s.phong_exponent); }
        case 2u: { return vec4<f32>(s.k_d, 0.0); }
        case 3u: { return vec4<f32>(s.k_s, 0.0); }
        default: { return vec4<f32>(s.emissive, 0.0); }
    }
}
