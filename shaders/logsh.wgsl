// Log-SH soft shadows (Ren et al. 2006), per pixel, on the SH code generated for the
// chosen order and exponentiation method (`sh`, `lobes`: src/shading/wgsl/sh.rs, lobes.rs).
// shading::cpu is the f64 reference of exactly this shading:
//   F = Σ_blockers ln ε · fade · cap_zh(r/d) rotated toward the blocker (log-visibility)
//       + the terrain's log-visibility (terrain.wgsl)
//   G = exp*(F)                                                     (visibility SH)
//   L = emissive + ⟨G · cos⁺/π, L_env⟩ + Σ_lights direct · clamp(mean of G over the
//       light's cap, 0, 1) (the default separate BRDF; the log and product variants
//       below carry the BRDF in the SH), or, for lights on the exact path,
//       direct · Π_blockers (1 − share of the light's disc the blocker hides) · share of
//       the disc above the terrain's horizon
// Each light keeps its exact unshadowed shading; the SH only say how much of it arrives
// (shading-model.md §4b: never shade through an order-n triple product of light × cosine).
// #import blockers light_windows exact_lights terrain shadow_lookup lobes

// The discs' log-visibility at p (each shaded at every receiver, in their own loop so
// that the spheres' walk stays small), weighed by the light windows when `windowed`.
fn add_discs(f: Sh, p: vec3<f32>, n: vec3<f32>, windowed: bool) -> Sh {
    var sum = f;
    for (var i = 0u; i < shadow.disc_count; i++) {
        let disc = shadow.discs[i];
        let seen = disc_cap_seen(disc, p, n);
        if seen.ratio >= shadow.min_cap_ratio && seen.horizon > 0.0 {
            let mask = disc_window_mask(disc.center_radius.xyz, disc.disc_normal.xyz, p);
            sum = add_cap_within(sum, seen.direction, seen.ratio, seen.horizon, windowed, mask);
        }
    }
    return sum;
}

// Which surface property fs_surface writes (set by surface_pipeline in src/render/passes/logsh.rs).
override SURFACE_CHANNEL: u32 = 0u;

// false: no light of the frame is on the exact path, which is then left out of the
// pipeline (lavapipe runs the code of both sides of a branch at every pixel, taken or
// not). Set at pipeline creation (src/render/passes/logsh.rs, shading::compiled_paths).
override EXACT_LIGHT_PATH: bool = true;

// false: no light is on the SH path and no environment lights the scene, so the
// visibility SH would go unread and are not computed. Set likewise.
override SH_VISIBILITY: bool = true;

// Σ of the blockers' and the terrain's log-visibility seen from p with normal n: per
// cluster its stand-in, weighed by its share at p, and, within its hand-over distance,
// the spheres of its groups in reach (weighed against their group's stand-in) and the
// groups' stand-ins, all weighed 1 − the cluster's share; then every disc. Each
// cluster's caps come in one flat walk (cluster_walk, walk_next), a step per cap that
// can weigh anything at p, so that the far groups' and clusters' stand-ins, which
// weigh nothing outside the light windows, cost no cap there. Skipped:
// spheres that contain p (a sphere-fit artefact on the blocker's own surface), blockers
// too small in the sky to matter, and blockers wholly below the tangent plane; blockers
// straddling it are faded by smoothstep(−1, 1, (c − p)·n / h), h their half-extent
// along n. Walked with the light windows where they apply (open_light_windows), else
// without: with PER_POINT_WINDOWS both walks are compiled in and each point takes one.
fn log_visibility(p: vec3<f32>, n: vec3<f32>) -> Sh {
    if LIGHT_WINDOWS > 0u {
        open_light_windows(p);
        // Under an environment the walk weighs every cap for it, each window's in its own
        // sum besides (add_cap); a pipeline compiled with the environment compiles no walk
        // with windows, but one compiled for every frame (PER_POINT_WINDOWS) decides here.
        let environment = ENVIRONMENT_LIGHT && (!PER_POINT_WINDOWS || environment_lit);
        if !environment && (!PER_POINT_WINDOWS || windows_open) {
            return walked_log_visibility(p, n, true);
        }
    }
    return walked_log_visibility(p, n, false);
}

// false: every point of a frame walks alike, with the windows when LIGHT_WINDOWS > 0
// (1–8 SH lights, no environment), else without. true: more than max_window_lights() SH
// lights and no environment, where each point opens the windows of the lights that reach
// it when at most that many do (window_lights): the walk with windows and the one
// without are both compiled in, each specialised, so that the points where no window
// opens — past that many lights reaching them — do not pay the windows' tests at every
// blocker (lavapipe runs a branch's both sides, but a loop no lane enters only once).
// Set by shading::compiled_paths.
override PER_POINT_WINDOWS: bool = false;

// log_visibility's walk, with the light windows when `windowed` (a constant at each
// call, so each walk is compiled for one case). Whether the stand-ins come as steps of
// the walk (only where they weigh anything) or are added at every group and cluster
// tested: with light windows most far stand-ins weigh nothing and the walk saves their
// caps (blocker bench, 20,000 spheres: 370 → 312 ms); without, most weigh something, and
// the walk's larger state costs every blocker's step more than it saves (the large
// sample's pixels shaded in full: 133 → 148 ms).
fn walked_log_visibility(p: vec3<f32>, n: vec3<f32>, windowed: bool) -> Sh {
    var f = sh_zero();
    for (var c = 0u; c < shadow.cluster_count; c++) {
        let cluster = group_at(c);
        let in_windows = group_in_windows(cluster, p, windowed);
        let walked = cluster_groups(cluster, group_in_reach(cluster, p, n) && in_windows);
        let share = stand_in_share(cluster, p);
        let passing = groups_to_walk(walked, p, n, 1.0 - share, &f, windowed);
        if !windowed {
            f = add_stand_in(f, cluster, p, n, 1.0);
        }
        let cluster_stand_in = windowed && in_windows && stand_in_weighs(cluster, p, n, 1.0);
        var walk = cluster_walk(cluster, share, passing, p, cluster_stand_in);
        loop {
            let i = walk_next(&walk);
            if i == WALK_DONE {
                break;
            }
            f = add_walked(f, &walk, i, p, n, windowed);
        }
    }
    f = add_discs(f, p, n, windowed);
    walk_terrain_log = terrain_log_visibility(p);
    return sh_sum(f, walk_terrain_log);
}

// A group's (or a cluster's) stand-in, one sphere at its centre covering the area its
// spheres cover, weighed by stand_in_share times `weight` times its depth (so it keeps
// their summed log-visibility) and faded below the tangent plane over the group's extent
// (when the walk does not take it: the walk without windows).
fn add_stand_in(f: Sh, group: BlockerGroup, p: vec3<f32>, n: vec3<f32>, weight: f32) -> Sh {
    if !stand_in_weighs(group, p, n, weight) {
        return f;
    }
    let offset = group.center_extent.xyz - p;
    let distance = sqrt(max(dot(offset, offset), 1e-30));
    let horizon = smoothstep(-1.0, 1.0, dot(offset, n) / max(group.center_extent.w, 1e-30));
    let share = stand_in_share(group, p) * weight;
    return add_cap(f, offset / distance, group.stand_in_radius_m / distance, horizon * share * group.stand_in_depth, false);
}

// The groups of `walked` whose blockers p walks (in reach, short of their stand-in's
// whole share, and within a light window) and whose stand-in weighs anything at p (its
// share times `weight`, the groups' share against their cluster's stand-in, above 0,
// as large in the sky as min_cap_ratio, not wholly below the tangent plane, within a
// window): their blockers and stand-ins then come in the walk, and a group with neither
// costs no cap. Without windows the walk takes no stand-in: each group's is added to *f
// here.
fn groups_to_walk(walked: ClusterGroups, p: vec3<f32>, n: vec3<f32>, weight: f32, f: ptr<function, Sh>, windowed: bool) -> GroupsToWalk {
    var passing = GroupsToWalk(0u, 0u);
    for (var g = walked.first; g < walked.end; g++) {
        let group = group_at(g);
        if !windowed {
            *f = add_stand_in(*f, group, p, n, weight);
        }
        let bit = 1u << (g - walked.first);
        let in_windows = group_in_windows(group, p, windowed);
        if group_in_reach(group, p, n) && stand_in_share(group, p) < 1.0 && in_windows {
            passing.blockers |= bit;
        }
        if windowed && in_windows && stand_in_weighs(group, p, n, weight) {
            passing.stand_ins |= bit;
        }
    }
    return passing;
}

// The walk's step i — blocker i, or the current group's stand-in (WALK_STAND_IN) — added
// to f with one cap (lavapipe runs both sides of a branch, so the two share one add_cap):
// a blocker weighed walk.weight, skipped when it contains p (a sphere-fit artefact on
// the blocker's own surface) and faded below the tangent plane over its radius (so a
// sphere straddling the surface it approximates does not darken its own receivers in
// blotches where they leave it); a stand-in — one sphere of its group's (or cluster's)
// spheres' covered area at its centre — weighed walk.stand_in_weight and faded
// over the group's extent.
fn add_walked(f: Sh, walk: ptr<function, BlockerWalk>, i: u32, p: vec3<f32>, n: vec3<f32>, windowed: bool) -> Sh {
    let is_stand_in = windowed && i == WALK_STAND_IN;
    let b = blocker_at(select(i, 0u, is_stand_in));
    let sphere = select(b.center_radius, (*walk).stand_in, is_stand_in);
    let fade_m = select(b.center_radius.w, (*walk).stand_in_extent, is_stand_in);
    let weight = select((*walk).weight, (*walk).stand_in_weight, is_stand_in);
    let offset = sphere.xyz - p;
    let distance2 = dot(offset, offset);
    let distance = sqrt(max(distance2, 1e-30));
    let inside = !is_stand_in && distance2 <= sphere.w * sphere.w;
    let ratio = sphere.w / distance;
    let horizon = smoothstep(-1.0, 1.0, dot(offset, n) / max(fade_m, 1e-30));
    if inside || ratio < shadow.min_cap_ratio || horizon <= 0.0 || weight <= 0.0 {
        return f;
    }
    return add_cap(f, offset / distance, ratio, horizon * weight, windowed);
}

// k(s): the scale of a cap's log-visibility that keeps the light it blocks through the
// band limit, linearly interpolated in shadow.cap_mass_scale (sh::interpolate_cap_mass_scale).
fn cap_mass_scale(s: f32) -> f32 {
    let t = clamp(s, 0.0, 1.0) * 31.0;
    let i = min(u32(t), 30u);
    let a = t - f32(i);
    let j = i + 1u;
    return mix(shadow.cap_mass_scale[i / 4u][i % 4u], shadow.cap_mass_scale[j / 4u][j % 4u], a);
}

// A blocker's cap of sine `ratio` toward unit `direction`, weighed by `weight` (its fade
// below the tangent plane, and its share against a stand-in): ln ε · weight · k(s)
// [· s with ratio attenuation] times the cap's ZH rotated there (shading::cpu::visibility's
// add_cap is the twin). In the walk with windows, where they are open, k(s) gives way to
// the windows' scales: the largest, or, with a log-visibility per light, each window's in
// its own sum (add_to_window_logs; f is then left as it was).
fn add_cap(f: Sh, direction: vec3<f32>, ratio: f32, weight: f32, windowed: bool) -> Sh {
    return add_cap_within(f, direction, ratio, weight, windowed, WindowScales(vec4<f32>(1.0), vec4<f32>(1.0)));
}

// add_cap with each window's scale times `mask` (1: the window's light may be hidden by
// the cap; 0: not — a disc whose plane the light does not reach from p's side,
// disc_window_mask). add_cap's mask of ones folds away.
fn add_cap_within(f: Sh, direction: vec3<f32>, ratio: f32, weight: f32, windowed: bool, mask: WindowScales) -> Sh {
    var scale = shadow.ln_epsilon * weight;
    if LIGHT_WINDOWS > 0u && per_light_visibility() {
        if shadow.ratio_attenuation != 0u {
            scale *= ratio;
        }
        // One rotation for every sum (lavapipe runs both sides of a branch).
        let rotated = sh_add_zonal(sh_zero(), sh_cap_zh(ratio), 1.0, direction);
        let mass_scale = cap_mass_scale(ratio);
        // The windows' sums: in the walk with windows, and in the one without under an
        // environment (compiled out of it otherwise: no window opens where it is taken).
        if windows_open && (windowed || ENVIRONMENT_LIGHT) {
            let scales = windowed_cap_scales(direction, ratio, mass_scale);
            add_to_window_logs(rotated, scaled_window_scales(WindowScales(scales.lo * mask.lo, scales.hi * mask.hi), scale));
            if windowed {
                return f;
            }
        }
        return sh_sum(f, sh_scaled(rotated, scale * mass_scale));
    }
    if windowed && LIGHT_WINDOWS > 0u && windows_open {
        scale *= windowed_cap_scale_within(direction, ratio, cap_mass_scale(ratio), mask);
    } else {
        scale *= cap_mass_scale(ratio);
    }
    if shadow.ratio_attenuation != 0u {
        scale *= ratio;
    }
    return sh_add_zonal(f, sh_cap_zh(ratio), scale, direction);
}

// How each light's BRDF meets the visibility (BRDF_SHADING, generated from the settings'
// BrdfShading by src/shading/wgsl/lobes.rs; shading::cpu::lobes is the f64 twin):
//   separate: each light's exact unshadowed BRDF times the visibility G = exp*(F)
//             averaged over the light;
//   log:      the diffuse and Phong lobes' logs added to F before exponentiating, one
//             exponentiation per lobe (Ren et al. 2006);
//   product:  G times each lobe by the SH product.
// In log and product each lobe's SH averaged over the light is clamped to [0, unshadowed]
// (shading-model.md §4b); lobes sharper than the order carries stay out of the SH and are
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
            specular_log = sh_add_zonal(f, sh_log_phong_lobe_zh(s.phong_exponent, shadow.ln_epsilon), 1.0, s.mirrored_view);
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
            specular = sh_times_lobe(g, sh_add_zonal(sh_zero(), sh_phong_lobe_zh(s.phong_exponent), 1.0, s.mirrored_view));
        }
        return LobeVisibility(diffuse, specular, carried);
    }
    return LobeVisibility(g, g, false);
}

fn shadowed_radiance(s: Surface) -> vec3<f32> {
    return soft_shadowed_radiance(s) + mapped_lights_radiance(s);
}

// shadowed_radiance without the lights on the shadow-map path.
fn soft_shadowed_radiance(s: Surface) -> vec3<f32> {
    return s.emissive + harmonic_radiance(s) + exact_path_radiance(s);
}

// The lobes' visibility at s through the blockers and the terrain (log_visibility).
fn soft_lobes(s: Surface) -> LobeVisibility {
    if !SH_VISIBILITY {
        // Read only by a light the viewport draws before its pipeline with the SH path is
        // compiled: it shows unshadowed meanwhile.
        return LobeVisibility(sh_one(), sh_one(), false);
    }
    return lobes_from_log_visibility(s, log_visibility(s.position, s.normal));
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

// The environment's diffuse light at s through the lobes' SH, ⟨V · cos⁺/π, L_env⟩: the
// visibility weighted by where the environment is bright. (Scaling the unshadowed light
// by the cosine-weighted mean of V, as the separate BRDF does for each light, dimmed a
// wall standing on a floor by as much again as the floor really hides under a sky
// brighter above than below: the floor hides the dim half.) Clamped to the unshadowed
// light, which it equals where nothing blocks.
fn environment_through(s: Surface, lobes: LobeVisibility) -> vec3<f32> {
    if !ENVIRONMENT_LIGHT {
        return vec3<f32>(0.0);
    }
    let unshadowed = environment_irradiance_at(s) / PI;
    if BRDF_SHADING == BRDF_SEPARATE {
        return s.k_d * clamp(sh_environment_through_cosine(lobes.diffuse, s.normal), vec3<f32>(0.0), unshadowed);
    }
    return s.k_d * clamp(sh_dot_environment(lobes.diffuse), vec3<f32>(0.0), unshadowed);
}

// Radiance of surface s with every light: soft_radiance_through plus the lights on the
// shadow-map path.
fn radiance_through(s: Surface, lobes: LobeVisibility) -> vec3<f32> {
    return soft_radiance_through(s, lobes) + mapped_lights_radiance(s);
}

// The lights from frame.first_mapped_light to frame.first_exact_light, each shadowed by
// its shadow maps.
fn mapped_lights_radiance(s: Surface) -> vec3<f32> {
    var radiance = vec3<f32>(0.0);
    if SHADOW_MAPS {
        let run = mapped_lights_at(s.position);
        for (var k = run.first; k < run.end; k++) {
            let light = light_at(run_light(k));
            radiance += mapped_light_radiance(light.intensity_rgb.rgb, s, mapped_light_factors(light, s));
        }
    }
    return radiance;
}

// A light on the shadow-map path seen from s at unit intensity, shadowed: its diffuse
// and glossy factors (direct_lobes) times its falloff and its maps' visibility, which
// depend on where the light is but not on how bright: the samples keep them across the
// frames of a stroke, which change intensities alone (low_resolution.wgsl).
fn mapped_light_factors(light: Light, s: Surface) -> vec2<f32> {
    var unit_light = light;
    unit_light.intensity_rgb = vec4<f32>(1.0);
    let inc = incidence(unit_light, s.position);
    return inc.irradiance.x * direct_lobes(s, inc) * shadow_map_visibility(light, inc, s);
}

// The radiance of a light of intensity `intensity_rgb` (colour × intensity) whose factors
// at s are `factors` (mapped_light_factors).
fn mapped_light_radiance(intensity_rgb: vec3<f32>, s: Surface, factors: vec2<f32>) -> vec3<f32> {
    return intensity_rgb * (s.k_d * factors.x + s.k_s * factors.y);
}

// Radiance of surface s: its emission, the light the SH carries
// (harmonic_radiance_through) and the lights on the exact path (exact_path_radiance).
// The lights on the shadow-map path are left to mapped_lights_radiance.
fn soft_radiance_through(s: Surface, lobes: LobeVisibility) -> vec3<f32> {
    return s.emissive + harmonic_radiance_through(s, lobes) + exact_path_radiance(s);
}

// Radiance of surface s lit through the lobes' SH: the environment and the lights before
// frame.first_mapped_light.
fn harmonic_radiance_through(s: Surface, lobes: LobeVisibility) -> vec3<f32> {
    var radiance = environment_through(s, lobes);
    let run = harmonic_lights_at(s.position);
    for (var k = run.first; k < run.end; k++) {
        radiance += light_through(s, lobes, incidence(light_at(run_light(k)), s.position));
    }
    return radiance;
}

// harmonic_radiance_through with the blockers' and the terrain's visibility at s: the
// light of soft shadows, which reduced_shading.wgsl may shade more coarsely than the rest.
// With a log-visibility per light (per_light_visibility) and the windows open at s, each
// windowed light is shaded through its own (window_log_visibility; the SH lights without
// a window there do not reach s) and the environment through the walk's own sum; else
// every light and the environment through the one.
fn harmonic_radiance(s: Surface) -> vec3<f32> {
    if !SH_VISIBILITY || !per_light_visibility() {
        return harmonic_radiance_through(s, soft_lobes(s));
    }
    let unwindowed = log_visibility(s.position, s.normal);
    let run = harmonic_lights_at(s.position);
    // One pass per visibility: each open window's and, under an environment, the walk's
    // own for it; or the walk's own for every reader. Written as one loop rather than
    // branches, which lavapipe would all run.
    let window_count = open_window_count();
    let environment_pass = ENVIRONMENT_LIGHT && environment_lit;
    let passes = select(1u, window_count + u32(environment_pass), windows_open);
    var radiance = vec3<f32>(0.0);
    for (var k = 0u; k < passes; k++) {
        // The walk's own sum, read by the environment and by the run's lights...
        let unwindowed_pass = !windows_open || k == window_count;
        var sum = unwindowed;
        var first = run.first;
        var end = run.end;
        if windows_open {
            // ...or by the environment alone; or window k's, read by its light.
            end = first;
            if !unwindowed_pass {
                sum = window_log_visibility(k);
                first = slot_light(k);
                end = first + 1u;
            }
        }
        // Where nothing weighs in the sum (no blocker in this light's window, no terrain)
        // exp*(0) is 1 exactly for every method (sh.rs: OL's a(0) = 1), which with the
        // separate BRDF is the lobes' visibility: the exponentiation — most of the cost of
        // a light's own visibility — is left out. A loop no lane enters costs lavapipe its
        // test alone, where a branch would be run anyway.
        var lobes = LobeVisibility(sh_one(), sh_one(), false);
        for (var pending = BRDF_SHADING != BRDF_SEPARATE || sh_norm_squared(sum) > 0.0; pending; pending = false) {
            lobes = lobes_from_log_visibility(s, sum);
        }
        if unwindowed_pass {
            radiance += environment_through(s, lobes);
        }
        for (var j = first; j < end; j++) {
            var light = j;
            if !windows_open {
                light = run_light(j);
            }
            radiance += light_through(s, lobes, incidence(light_at(light), s.position));
        }
    }
    return radiance;
}

// The light harmonic_radiance shades at s as if nothing blocked it: the environment's
// diffuse light and each SH light's exact unshadowed radiance. Two-level shading
// interpolates the soft light's share of it (low_resolution.wgsl's soft_share).
fn unshadowed_harmonic_radiance(s: Surface) -> vec3<f32> {
    var radiance = vec3<f32>(0.0);
    if ENVIRONMENT_LIGHT {
        radiance = environment_radiance(s);
    }
    let run = harmonic_lights_at(s.position);
    for (var k = run.first; k < run.end; k++) {
        radiance += direct_radiance(s, incidence(light_at(run_light(k)), s.position));
    }
    return radiance;
}

// The lights from frame.first_exact_light on, eight at a time: their exact visibility
// (times the share above the terrain's horizon) times their unshadowed radiance.
fn exact_path_radiance(s: Surface) -> vec3<f32> {
    var radiance = vec3<f32>(0.0);
    if EXACT_LIGHT_PATH {
        for (var first = frame.first_exact_light; first < frame.light_count; first += select(4u, 8u, EXACT_WIDE)) {
            radiance += exact_lights_radiance(s, first);
        }
    }
    return radiance;
}

// The shadowed radiance of the exact-path lights first..first + 7 (those that exist;
// first..first + 3 without EXACT_WIDE). Written out lane by lane: lavapipe makes a loop
// writing vector lanes by index costly.
fn exact_lights_radiance(s: Surface, first: u32) -> vec3<f32> {
    let lo = exact_lights(s, first);
    var hi = ExactLights(no_exact_batch(), array<vec3<f32>, 4>());
    if EXACT_WIDE {
        hi = exact_lights(s, first + 4u);
    }
    let v = exact_batch_visibility(s.position, s.normal, lo.batch, hi.batch, first);
    return lo.unshadowed[0] * v.lo.x + lo.unshadowed[1] * v.lo.y + lo.unshadowed[2] * v.lo.z
        + lo.unshadowed[3] * v.lo.w + hi.unshadowed[0] * v.hi.x + hi.unshadowed[1] * v.hi.y
        + hi.unshadowed[2] * v.hi.z + hi.unshadowed[3] * v.hi.w;
}

// Four lights as a batch half, with their unshadowed radiance (times the share of their
// disc above the terrain's horizon).
struct ExactLights {
    batch: ExactBatch,
    unshadowed: array<vec3<f32>, 4>,
};

fn no_exact_batch() -> ExactBatch {
    return ExactBatch(vec4<f32>(0.0), vec4<f32>(0.0), vec4<f32>(0.0), vec4<f32>(0.0), vec4<f32>(0.0));
}

fn exact_lights(s: Surface, first: u32) -> ExactLights {
    let l0 = exact_light(s, first);
    let l1 = exact_light(s, first + 1u);
    let l2 = exact_light(s, first + 2u);
    let l3 = exact_light(s, first + 3u);
    let batch = ExactBatch(
        vec4<f32>(l0.to_light.x, l1.to_light.x, l2.to_light.x, l3.to_light.x),
        vec4<f32>(l0.to_light.y, l1.to_light.y, l2.to_light.y, l3.to_light.y),
        vec4<f32>(l0.to_light.z, l1.to_light.z, l2.to_light.z, l3.to_light.z),
        vec4<f32>(l0.sin_light, l1.sin_light, l2.sin_light, l3.sin_light),
        vec4<f32>(l0.distance, l1.distance, l2.distance, l3.distance),
    );
    return ExactLights(batch, array<vec3<f32>, 4>(l0.unshadowed, l1.unshadowed, l2.unshadowed, l3.unshadowed));
}

// One lane of an ExactBatch, with the light's unshadowed radiance (times the share of its
// disc above the terrain's horizon).
struct ExactLight {
    to_light: vec3<f32>,
    sin_light: f32,
    // 0 for a light that does not exist or does not light s: every blocker counts as
    // beyond it, so it costs no lens.
    distance: f32,
    unshadowed: vec3<f32>,
};

fn exact_light(s: Surface, index: u32) -> ExactLight {
    let exists = index < frame.light_count;
    let inc = incidence(light_at(min(index, frame.light_count - 1u)), s.position);
    let unshadowed = select(vec3<f32>(0.0), direct_radiance(s, inc), exists)
        * terrain_light_visibility(s.position, inc.to_light, inc.cap_ratio);
    let lit = any(unshadowed != vec3<f32>(0.0));
    return ExactLight(inc.to_light, clamp(inc.cap_ratio, 0.0, 1.0), select(0.0, inc.distance, lit), unshadowed);
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
