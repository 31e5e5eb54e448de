// Log-SH soft shadows (Ren et al. 2006), per pixel. Included after common.wgsl,
// scene.wgsl and the generated SH module of the chosen order and exponentiation method
// (src/render/wgsl_sh.rs), and terrain.wgsl. render::cpu is the f64 reference of exactly
// this shading:
//   F = Σ_blockers ln ε · fade · cap_zh(r/d) rotated toward the blocker (log-visibility)
//       + the terrain's log-visibility (terrain.wgsl)
//   G = exp*(F)                                                     (visibility SH)
//   L = emissive + environment · ⟨G, cos⟩ + Σ_lights direct · clamp(mean of G over the
//       light's cap, 0, 1) (the default separate BRDF; the log and product variants
//       below carry the BRDF in the SH), or, for lights small enough for the exact path,
//       direct · Π_blockers (1 − share of the light's disc the blocker hides) · share of
//       the disc above the terrain's horizon
// Each light keeps its exact unshadowed shading; the SH only say how much of it arrives
// (design.md §4b: never shade through an order-n triple product of light × cosine).

@group(2) @binding(0) var<uniform> shadow: ShadowParams;
@group(2) @binding(1) var<storage, read> blockers: array<Blocker>;
@group(2) @binding(2) var<storage, read> groups: array<BlockerGroup>;

// Which surface property fs_surface writes (set by surface_pipeline in src/render/logsh.rs).
override SURFACE_CHANNEL: u32 = 0u;

// false: no light of the scene can take the exact path, which is then left out of the
// pipeline (lavapipe runs the code of both sides of a branch at every pixel, taken or
// not). Set at pipeline creation (src/render/logsh.rs, render::exact_path_possible).
override EXACT_LIGHT_PATH: bool = true;

// Σ of the blockers' and the terrain's log-visibility seen from p with normal n. Skipped: blockers that
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
    return sh_sum(f, terrain_log_visibility(p));
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

// The share (0–1) of a cap of angular radius a hidden by a cap of angular radius b whose
// centre is g away (src/penumbra/cap_overlap.rs, the f64 twin): the lens of the two caps,
// 2θ_L(1 − cos a) + 2θ_B(1 − cos b) − 2E, from half-angle formulas and L'Huilier's
// theorem so that tiny caps keep their digits, over the light's 2π(1 − cos a).
fn hidden_fraction(a: f32, b: f32, g: f32) -> f32 {
    if g >= a + b || b <= 0.0 {
        return 0.0;
    }
    if g + a <= b {
        return 1.0;
    }
    let ha = sin(0.5 * a);
    let light_area = 4.0 * PI * ha * ha;
    if g + b <= a {
        let hb = sin(0.5 * b);
        return min(4.0 * PI * hb * hb / light_area, 1.0);
    }
    let s = 0.5 * (a + b + g);
    let sin_s = sin(s);
    let sin_sa = sin(s - a);
    let sin_sb = sin(s - b);
    let sin_sg = sin(s - g);
    let theta_light = 2.0 * atan(sqrt(max(sin_sa * sin_sg / (sin_s * sin_sb), 0.0)));
    let theta_blocker = 2.0 * atan(sqrt(max(sin_sb * sin_sg / (sin_s * sin_sa), 0.0)));
    let t = tan(0.5 * s) * tan(0.5 * (s - a)) * tan(0.5 * (s - b)) * tan(0.5 * (s - g));
    let excess = 4.0 * atan(sqrt(max(t, 0.0)));
    let hb = sin(0.5 * b);
    let lens = 4.0 * theta_light * ha * ha + 4.0 * theta_blocker * hb * hb - 2.0 * excess;
    return clamp(lens / light_area, 0.0, 1.0);
}

// Visibility of a light's disc (sin of its angular radius: inc.cap_ratio) from p with
// normal n: Π over blockers of (1 − fade · hidden share), skipping what log_visibility
// skips and blockers wholly beyond the light (src/penumbra/mod.rs, the f64 twin).
// Anti-aliasing: against each blocker at distance d the disc's sine is at least
// footprint/(2d) (footprint one pixel's width at p), so a point light's hard edge ramps
// over about one pixel instead of stepping.
fn exact_light_visibility(p: vec3<f32>, n: vec3<f32>, inc: Incidence) -> f32 {
    let sin_light = clamp(inc.cap_ratio, 0.0, 1.0);
    let half_footprint = 0.5 * pixel_footprint(p);
    var log_v = 0.0;
    for (var g = 0u; g < shadow.group_count; g++) {
        let group = groups[g];
        let to_group = group.center_extent.xyz - p;
        let group_distance2 = dot(to_group, to_group);
        if group_distance2 > group.influence_m * group.influence_m
            || dot(to_group, n) + group.center_extent.w <= 0.0 {
            continue;
        }
        // The group's bounding sphere outside the light's cone: none of its spheres can
        // hide any of the light (cos γ ≤ cos(α + β) with sin β = extent/distance, α at its
        // widest for the group's nearest sphere). No trigonometry: lavapipe pays for it
        // at every pixel.
        let group_distance = sqrt(group_distance2);
        let extent = group.center_extent.w;
        if group_distance > extent {
            let sin_a = min(max(sin_light, half_footprint / (group_distance - extent)), 1.0);
            let cos_a = sqrt(1.0 - sin_a * sin_a);
            let sin_g = extent / group_distance;
            let cos_g = sqrt(max(1.0 - sin_g * sin_g, 0.0));
            if dot(to_group, inc.to_light) / group_distance <= cos_a * cos_g - sin_a * sin_g {
                continue;
            }
        }
        for (var i = group.first; i < group.first + group.count; i++) {
            let b = blockers[i].center_radius;
            let offset = b.xyz - p;
            let distance2 = dot(offset, offset);
            let radius = b.w;
            if distance2 <= radius * radius {
                continue;
            }
            let distance = sqrt(distance2);
            let ratio = radius / distance;
            let horizon = smoothstep(-1.0, 1.0, dot(offset, n) / radius);
            if ratio < shadow.min_cap_ratio || horizon <= 0.0 || distance - radius >= inc.distance {
                continue;
            }
            let direction = offset / distance;
            let sin_a = min(max(sin_light, half_footprint / distance), 1.0);
            let cos_a = sqrt(1.0 - sin_a * sin_a);
            // Disjoint caps (the common case) are rejected before any trigonometry.
            let cos_separation = dot(direction, inc.to_light);
            if cos_separation <= cos_a * sqrt(max(1.0 - ratio * ratio, 0.0)) - sin_a * ratio {
                continue;
            }
            let separation = atan2(length(cross(direction, inc.to_light)), cos_separation);
            let hidden = horizon * hidden_fraction(asin(sin_a), asin(ratio), separation);
            if hidden >= 1.0 {
                return 0.0;
            }
            log_v += log(1.0 - hidden);
        }
    }
    return exp(log_v);
}

// How each light's BRDF meets the visibility (BRDF_SHADING, generated from the settings'
// BrdfShading by src/render/wgsl_lobes.rs; render::cpu_lobes is the f64 twin):
//   separate: each light's exact unshadowed BRDF times the visibility G = exp*(F)
//             averaged over the light;
//   log:      the diffuse and Phong lobes' logs added to F before exponentiating, one
//             exponentiation per lobe (Ren et al. 2006);
//   product:  G times each lobe by the SH product.
// In log and product each lobe's SH averaged over the light is clamped to [0, unshadowed]
// (design.md §4b); lobes sharper than the order carries stay out of the SH and are
// shaded as in separate.
const BRDF_SEPARATE: u32 = 0u;
const BRDF_LOG: u32 = 1u;
const BRDF_PRODUCT: u32 = 2u;

// The SH each lobe is shaded through: the visibility (separate), or the visibility times
// the diffuse and the Phong lobe. specular_in_sh false: `specular` is the plain visibility.
struct LobeVisibility {
    diffuse: Sh,
    specular: Sh,
    specular_in_sh: bool,
};

fn specular_carried(s: Surface) -> bool {
    return BRDF_SHADING != BRDF_SEPARATE && s.phong_exponent <= SH_MAX_PHONG_EXPONENT;
}

// The lobes' SH from the log-visibility f.
fn lobes_from_log_visibility(s: Surface, f: Sh) -> LobeVisibility {
    if BRDF_SHADING == BRDF_LOG {
        let diffuse = sh_exp(sh_add_zonal(f, sh_log_phong_lobe_zh(1.0, shadow.ln_epsilon), 1.0, s.normal));
        let carried = specular_carried(s);
        var specular_log = f;
        if carried {
            specular_log = sh_add_zonal(f, sh_log_phong_lobe_zh(s.phong_exponent, shadow.ln_epsilon), 1.0, mirrored_view(s));
        }
        return LobeVisibility(diffuse, sh_exp(specular_log), carried);
    }
    return lobes_through(s, sh_exp(f));
}

// The lobes' SH from the visibility SH g (per-vertex shading interpolates g).
fn lobes_through(s: Surface, g: Sh) -> LobeVisibility {
    if BRDF_SHADING == BRDF_PRODUCT {
        let diffuse = sh_times_lobe(g, sh_add_zonal(sh_zero(), sh_phong_lobe_zh(1.0), 1.0, s.normal));
        let carried = specular_carried(s);
        var specular = g;
        if carried {
            specular = sh_times_lobe(g, sh_add_zonal(sh_zero(), sh_phong_lobe_zh(s.phong_exponent), 1.0, mirrored_view(s)));
        }
        return LobeVisibility(diffuse, specular, carried);
    }
    return LobeVisibility(g, g, false);
}

fn shadowed_radiance(s: Surface) -> vec3<f32> {
    return radiance_through(s, lobes_from_log_visibility(s, log_visibility(s.position, s.normal)));
}

// Whether the light seen as inc takes the exact path at this receiver: allowed by the
// budget and small enough here (render::cpu::takes_exact_path).
fn takes_exact_path(inc: Incidence) -> bool {
    return inc.exact_allowed && inc.cap_ratio < shadow.exact_below_cap_ratio
        && (inc.cap_ratio > 0.0 || shadow.exact_point_lights != 0u);
}

// A light's shadowed radiance at s through the lobes' SH.
fn light_through(s: Surface, lobes: LobeVisibility, inc: Incidence) -> vec3<f32> {
    let direct = direct_lobes(s, inc);
    let diffuse_mean = sh_visibility_toward(lobes.diffuse, inc.to_light, inc.cap_ratio);
    if BRDF_SHADING == BRDF_SEPARATE {
        return inc.irradiance * (s.k_d * direct.x + s.k_s * direct.y) * clamp(diffuse_mean, 0.0, 1.0);
    }
    let specular_mean = sh_visibility_toward(lobes.specular, inc.to_light, inc.cap_ratio);
    var specular = direct.y * clamp(specular_mean, 0.0, 1.0);
    if lobes.specular_in_sh {
        specular = clamp(specular_mean, 0.0, direct.y);
    }
    return inc.irradiance * (s.k_d * clamp(diffuse_mean, 0.0, direct.x) + s.k_s * specular);
}

// The environment's diffuse light at s through the lobes' SH.
fn environment_through(s: Surface, lobes: LobeVisibility) -> vec3<f32> {
    let unshadowed = environment_irradiance_at(s) / PI;
    if BRDF_SHADING == BRDF_SEPARATE {
        return s.k_d * unshadowed * clamp(sh_visibility_cosine(lobes.diffuse, s.normal), 0.0, 1.0);
    }
    return s.k_d * clamp(sh_dot_environment(lobes.diffuse), vec3<f32>(0.0), unshadowed);
}

// Radiance of surface s lit through the lobes' SH; lights small enough take the exact
// path instead: their exact visibility (times the share above the terrain's horizon)
// times their unshadowed radiance.
fn radiance_through(s: Surface, lobes: LobeVisibility) -> vec3<f32> {
    var radiance = s.emissive + environment_through(s, lobes);
    for (var i = 0u; i < frame.light_count; i++) {
        let inc = incidence(lights[i], s.position);
        let unshadowed = direct_radiance(s, inc);
        if all(unshadowed == vec3<f32>(0.0)) {
            continue;
        }
        if EXACT_LIGHT_PATH {
            if takes_exact_path(inc) {
                radiance += unshadowed * exact_light_visibility(s.position, s.normal, inc)
                    * terrain_light_visibility(s.position, inc.to_light, inc.cap_ratio);
                continue;
            }
        }
        radiance += light_through(s, lobes, inc);
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
