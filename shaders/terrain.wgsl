// Height-field terrain shadows in log-SH (Giraud & Nowrouzezahrai 2015), the f32 twin of
// src/terrain/visibility.rs, on the SH and terrain code generated for the
// order (`sh`, `terrain_sh`: src/shading/wgsl/sh.rs, terrain.rs):
//   F_terrain(p) = ln ε · R · Σ_k Rot_z(M_lin·[v̄(σ_k); v̄(σ_{k+1})], ϕ_k)
// with σ_k the horizon along azimuth ϕ_k = 2πk/W, marched over the prefiltered height
// pyramid, and R the turn from the terrain frame (polar axis world +y) to world axes.
// #import shadow_bindings terrain_sh scene

// false: the frame has no terrain, and its code is left out of the pipeline (lavapipe
// runs every branch at every pixel). Set at pipeline creation (shading::compiled_paths).
override TERRAIN_SHADOWS: bool = true;

// log2(2^(1/4) − 1): sample i is read from level round(i/4 + this) (terrain::March).
const TERRAIN_GAP_LOG2: f32 = -2.4019313;

fn terrain_sample(level: u32, i: i32, j: i32) -> f32 {
    let size = terrain.level_size[level];
    let ci = clamp(i, 0, i32(size.x) - 1);
    let cj = clamp(j, 0, i32(size.y) - 1);
    return terrain_heights[size.z + u32(cj) * size.x + u32(ci)];
}

// Height of `level` at world (x, z): linear on the render mesh's two triangles per cell
// (split from sample (i + 1, j) to (i, j + 1)), the border extended outward.
fn terrain_height(level: u32, x: f32, z: f32) -> f32 {
    let frame = terrain.level_frame[level];
    let size = terrain.level_size[level];
    let u = clamp((x - frame.x) / frame.z, 0.0, f32(size.x - 1u));
    let v = clamp((z - frame.y) / frame.w, 0.0, f32(size.y - 1u));
    let i = floor(u);
    let j = floor(v);
    let fu = u - i;
    let fv = v - j;
    let ii = i32(i);
    let jj = i32(j);
    let h10 = terrain_sample(level, ii + 1, jj);
    let h01 = terrain_sample(level, ii, jj + 1);
    if fu + fv <= 1.0 {
        let h00 = terrain_sample(level, ii, jj);
        return h00 + fu * (h10 - h00) + fv * (h01 - h00);
    }
    let h11 = terrain_sample(level, ii + 1, jj + 1);
    return h11 + (1.0 - fu) * (h01 - h11) + (1.0 - fv) * (h10 - h11);
}

fn terrain_level_of_sample(i: u32) -> u32 {
    let level = max(round(f32(i) * 0.25 + TERRAIN_GAP_LOG2), 0.0);
    return min(u32(level), terrain.levels - 1u);
}

// sin of the horizon's elevation from p along the horizontal unit direction (dx, dz),
// over the first `samples` samples; −1 when nothing is sampled. A receiver above the
// ground keeps its height above it at every level, so each level compares like with like.
fn terrain_horizon_sin(p: vec3<f32>, direction: vec2<f32>, samples: u32) -> f32 {
    if samples == 0u {
        return -1.0;
    }
    let offset = max(p.y - terrain_height(0u, p.x, p.z), 0.0);
    var best = -1.0e30;
    var level = 0xffffffffu;
    var base = 0.0;
    for (var i = 0u; i < samples; i++) {
        let l = terrain_level_of_sample(i);
        if l != level {
            level = l;
            base = terrain_height(l, p.x, p.z) + offset;
        }
        let t = terrain.first_step_m * exp2(f32(i) * 0.25);
        let h = terrain_height(l, p.x + t * direction.x, p.z + t * direction.y);
        best = max(best, (h - base) / t);
    }
    // Clamped so that the square below cannot overflow f32 (sin differs from ±1 by 5e-13).
    let slope = clamp(best, -1.0e6, 1.0e6);
    return slope / sqrt(1.0 + slope * slope);
}

// The terrain's log-visibility at p in world axes (zero without a terrain): the surface
// cache on the terrain inside its footprint, marched elsewhere (TerrainShadow::log_visibility).
fn terrain_log_visibility(p: vec3<f32>) -> Sh {
    if !TERRAIN_SHADOWS || terrain.present == 0u {
        return sh_zero();
    }
    let frame = terrain.level_frame[0];
    let size = terrain.level_size[0];
    let u = (p.x - frame.x) / frame.z;
    let v = (p.z - frame.y) / frame.w;
    let inside = u >= 0.0 && v >= 0.0 && u <= f32(size.x - 1u) && v <= f32(size.y - 1u);
    let on_surface = inside && p.y - terrain_height(0u, p.x, p.z) <= terrain.surface_tolerance_m;
    // lavapipe runs both sides of a branch for its SIMD lanes, masked, but leaves a loop
    // once no lane continues: the march is skipped by giving it no azimuths, not by `if`.
    let marched = terrain_marched_sh(p, select(terrain.azimuths, 0u, on_surface));
    if on_surface {
        return sh_scaled(terrain_surface_sh(u, v), shadow.ln_epsilon);
    }
    return sh_scaled(marched, shadow.ln_epsilon);
}

// The surface cache at grid coordinates (u, v) inside the footprint, interpolated on the
// mesh triangle (as terrain_height).
fn terrain_surface_sh(u: f32, v: f32) -> Sh {
    let size = terrain.level_size[0];
    let i = min(floor(u), f32(size.x - 2u));
    let j = min(floor(v), f32(size.y - 2u));
    let fu = u - i;
    let fv = v - j;
    let base = u32(j) * size.x + u32(i);
    let n = SH_COEFFICIENTS;
    let first = terrain.surface_first;
    let s10 = sh_scaled(sh_from_terrain_cache(first + (base + 1u) * n), select(1.0 - fv, fu, fu + fv <= 1.0));
    let s01 = sh_scaled(sh_from_terrain_cache(first + (base + size.x) * n), select(1.0 - fu, fv, fu + fv <= 1.0));
    if fu + fv <= 1.0 {
        return sh_sum(sh_sum(sh_scaled(sh_from_terrain_cache(first + base * n), 1.0 - fu - fv), s10), s01);
    }
    let s11 = sh_scaled(sh_from_terrain_cache(first + (base + size.x + 1u) * n), fu + fv - 1.0);
    return sh_sum(sh_sum(s11, s10), s01);
}

// R·Σ_k Rot_z(M_lin·[v̄(σ_k); v̄(σ_{k+1})], ϕ_k) marched from p (no ln ε) over W =
// terrain.azimuths directions; zero when `azimuths` is 0 (no march).
fn terrain_marched_sh(p: vec3<f32>, azimuths: u32) -> Sh {
    let step = 2.0 * PI / f32(terrain.azimuths);
    let samples = select(terrain.sample_count, 0u, azimuths == 0u);
    let first = sh_slice(terrain_horizon_sin(p, vec2<f32>(0.0, 1.0), samples));
    var left = first;
    var sum = sh_zero();
    for (var k = 0u; k < azimuths; k++) {
        var right = first;
        let next = f32(k + 1u) * step;
        let next_samples = select(samples, 0u, k + 1u >= azimuths);
        let horizon = terrain_horizon_sin(p, vec2<f32>(sin(next), cos(next)), next_samples);
        if k + 1u < azimuths {
            right = sh_slice(horizon);
        }
        let phi = f32(k) * step;
        sum = sh_sum(sum, sh_rotate_z(sh_wedge(left, right), cos(phi), sin(phi)));
        left = right;
    }
    return sh_terrain_to_world(sum);
}

// The share of a light's disc (sin of its angular radius: cap_ratio) above the terrain's
// horizon along the light's azimuth (TerrainShadow::light_visibility).
fn terrain_light_visibility(p: vec3<f32>, to_light: vec3<f32>, cap_ratio: f32) -> f32 {
    if !TERRAIN_SHADOWS || terrain.present == 0u {
        return 1.0;
    }
    let horizontal = length(to_light.xz);
    var direction = vec2<f32>(0.0, 1.0);
    if horizontal > 0.0 {
        direction = to_light.xz / horizontal;
    }
    let horizon = asin(terrain_horizon_sin(p, direction, terrain.sample_count));
    let elevation = asin(clamp(to_light.y, -1.0, 1.0));
    let radius = asin(clamp(cap_ratio, 0.0, 1.0));
    if radius <= 0.0 {
        return select(0.0, 1.0, elevation > horizon);
    }
    let h = clamp((elevation - horizon) / radius, -1.0, 1.0);
    return 0.5 + (h * sqrt(1.0 - h * h) + asin(h)) / PI;
}
