// Windows on the blockers for the SH path's lights (shading::light_windows and
// shading::cpu::windows are the twins), and the log-visibility of each windowed light
// (shading::cpu::harmonic_visibility).
// #import blockers sh

// Windows on the blockers for the SH path's lights: a light reads the visibility only
// inside its own cap, so for its visibility each cap is weighed by how near it comes to
// that light's cap and scaled for the light's mean (min(1, k(s) · gain)) instead of by
// k(s); blockers far from a light then no longer darken it through the band limit.
// With more than MAX_WINDOW_LIGHTS SH lights a point opens windows for those that reach
// it, when at most that many do (window_lights). The number of windows compiled in
// (shading::compiled_paths): 0 for a frame without SH lights; lavapipe pays for each
// window at every blocker, used or not. Where one visibility serves every light
// (PER_LIGHT_VISIBILITY false: per vertex) at most MAX_SHARED_WINDOW_LIGHTS open: one
// sum weighed by the largest of more windows darkened each light's penumbrae by its
// neighbours' blockers past the sum without windows (shading::light_windows).
// Under an environment at most MAX_SKY_WINDOW_LIGHTS: the walk without windows that the
// environment reads adds every cap to each window's sum (add_cap), so each window costs
// every cap (shading::light_windows::MAX_SKY_WINDOW_LIGHTS).
override LIGHT_WINDOWS: u32 = 8u;
const MAX_WINDOW_LIGHTS: u32 = 8u;
const MAX_SHARED_WINDOW_LIGHTS: u32 = 4u;
const MAX_SKY_WINDOW_LIGHTS: u32 = 4u;

// The receiver's windows, set by open_light_windows: per SH light the unit direction
// toward it and the cosine of the half-angle of the cap holding its emitter (w = 2: no
// such light), that half-angle's sine in window_sines and each window's gain on k(s) in
// window_gains (slots 0–3; slots 4–7 in the _hi vectors, compiled in past four
// windows). Variables rather than an array: lavapipe reads a private array lane by lane.
var<private> windows_open: bool;
var<private> window_0: vec4<f32>;
var<private> window_1: vec4<f32>;
var<private> window_2: vec4<f32>;
var<private> window_3: vec4<f32>;
var<private> window_4: vec4<f32>;
var<private> window_5: vec4<f32>;
var<private> window_6: vec4<f32>;
var<private> window_7: vec4<f32>;
var<private> window_sines: vec4<f32>;
var<private> window_half_angles: vec4<f32>;
var<private> window_gains: vec4<f32>;
var<private> window_sines_hi: vec4<f32>;
var<private> window_half_angles_hi: vec4<f32>;
var<private> window_gains_hi: vec4<f32>;
// The SH light in each window's slot (NO_WINDOW_LIGHT: none), set with the windows:
// slots 0–3, then 4–7.
var<private> window_light_indices: vec4<u32>;
var<private> window_light_indices_hi: vec4<u32>;

// No light in a window's slot.
const NO_WINDOW_LIGHT: u32 = 0xffffffffu;

// Whether an environment lights the frame (gpu_types::irradiance_lights).
fn environment_lights() -> bool {
    var lights = false;
    for (var k = 0u; k < 9u; k++) {
        lights = lights || any(frame.environment_irradiance[k].xyz != vec3<f32>(0.0));
    }
    return lights;
}

// Whether an environment lights the frame, as window_lights found.
var<private> environment_lit: bool;

// The SH lights whose windows p opens, one per slot (NO_WINDOW_LIGHT: none) in
// window_light_indices and window_light_indices_hi, and whether any window applies there
// (windows_open; light_windows::light_window_indices is the twin): the frame's SH lights
// when there are 1 to max_window_lights() (the first frame.first_mapped_light), else
// those that reach p (light_reaches, among its box's: harmonic_lights_at) when at most
// that many do — none at a point no SH light reaches. With an environment's light only
// where each light reads a visibility of its own (per_light_visibility): one visibility
// for every reader (per vertex) must be the environment's, which sees every blocker.
fn window_lights(p: vec3<f32>) {
    let slots = vec4<u32>(0u, 1u, 2u, 3u);
    let slots_hi = slots + vec4<u32>(4u);
    windows_open = false;
    window_light_indices = vec4<u32>(NO_WINDOW_LIGHT);
    window_light_indices_hi = vec4<u32>(NO_WINDOW_LIGHT);
    environment_lit = environment_lights();
    if (environment_lit && !per_light_visibility()) || frame.first_mapped_light == 0u {
        return;
    }
    let most = max_window_lights();
    if frame.first_mapped_light <= most {
        windows_open = true;
        let count = vec4<u32>(frame.first_mapped_light);
        window_light_indices = select(vec4<u32>(NO_WINDOW_LIGHT), slots, slots < count);
        window_light_indices_hi = select(vec4<u32>(NO_WINDOW_LIGHT), slots_hi, slots_hi < count);
        return;
    }
    var chosen = vec4<u32>(NO_WINDOW_LIGHT);
    var chosen_hi = vec4<u32>(NO_WINDOW_LIGHT);
    var count = 0u;
    let run = harmonic_lights_at(p);
    for (var k = run.first; k < run.end; k++) {
        if count > most {
            // No window opens: the rest need not be looked at.
            break;
        }
        let i = run_light(k);
        if light_reaches(light_at(i), p) {
            chosen = select(chosen, vec4<u32>(i), vec4<u32>(count) == slots);
            chosen_hi = select(chosen_hi, vec4<u32>(i), vec4<u32>(count) == slots_hi);
            count += 1u;
        }
    }
    windows_open = count <= most;
    window_light_indices = chosen;
    window_light_indices_hi = chosen_hi;
}

// The most windows a point opens (light_windows::most_windows): those compiled in, with
// one visibility for every reader at most MAX_SHARED_WINDOW_LIGHTS, under an environment
// at most MAX_SKY_WINDOW_LIGHTS (environment_lit is set).
fn max_window_lights() -> u32 {
    let own = select(MAX_WINDOW_LIGHTS, MAX_SKY_WINDOW_LIGHTS, environment_lit);
    return min(LIGHT_WINDOWS, select(MAX_SHARED_WINDOW_LIGHTS, own, per_light_visibility()));
}

// SH light i's window seen from p (LightWindows::at): its cap grown to hold the emitter,
// as (direction, half-angle); half-angle −1 for NO_WINDOW_LIGHT.
fn light_window(i: u32, p: vec3<f32>) -> vec4<f32> {
    if i == NO_WINDOW_LIGHT {
        return vec4<f32>(0.0, 0.0, 0.0, -1.0);
    }
    let light = light_at(i);
    let inc = incidence(light, p);
    let bound = light_bounding_radius_m(light) / inc.distance;
    return vec4<f32>(inc.to_light, asin(clamp(max(inc.cap_ratio, bound), 0.0, 1.0)));
}

// A window's gain on k(s), max(1, (4π/n²)/Ω) (LightWindow::new); 1 − cos α = 2 sin²(α/2).
fn window_gain(half_angle: f32) -> f32 {
    let half = sin(0.5 * half_angle);
    let solid_angle_sr = 4.0 * PI * half * half;
    return max(4.0 * PI / f32(SH_ORDER * SH_ORDER) / max(solid_angle_sr, 1e-12), 1.0);
}

// A window from light_window as read per blocker: (direction, cos α), 2 for none.
fn window_cosine(window: vec4<f32>) -> vec4<f32> {
    return vec4<f32>(window.xyz, select(cos(window.w), 2.0, window.w < 0.0));
}

// Four windows (slots of one bank) as the walk reads them: each window_cosine, the
// half-angles' sines, the half-angles (−10 for an empty slot) and the gains.
struct WindowBank {
    cosines: array<vec4<f32>, 4>,
    sines: vec4<f32>,
    half_angles: vec4<f32>,
    gains: vec4<f32>,
};

fn window_bank(lights: vec4<u32>, p: vec3<f32>) -> WindowBank {
    let w = array<vec4<f32>, 4>(light_window(lights.x, p), light_window(lights.y, p), light_window(lights.z, p), light_window(lights.w, p));
    let angles = vec4<f32>(w[0].w, w[1].w, w[2].w, w[3].w);
    let half_angles = max(angles, vec4<f32>(0.0));
    return WindowBank(
        array<vec4<f32>, 4>(window_cosine(w[0]), window_cosine(w[1]), window_cosine(w[2]), window_cosine(w[3])),
        sin(half_angles),
        select(half_angles, vec4<f32>(-10.0), angles < vec4<f32>(0.0)),
        vec4<f32>(
            window_gain(half_angles.x),
            window_gain(half_angles.y),
            window_gain(half_angles.z),
            window_gain(half_angles.w),
        ),
    );
}

fn open_light_windows(p: vec3<f32>) {
    window_lights(p);
    clear_window_logs();
    if windows_open {
        let bank = window_bank(window_light_indices, p);
        window_0 = bank.cosines[0];
        window_1 = bank.cosines[1];
        window_2 = bank.cosines[2];
        window_3 = bank.cosines[3];
        window_sines = bank.sines;
        window_half_angles = bank.half_angles;
        window_gains = bank.gains;
    }
    if LIGHT_WINDOWS > 4u && windows_open {
        let bank = window_bank(window_light_indices_hi, p);
        window_4 = bank.cosines[0];
        window_5 = bank.cosines[1];
        window_6 = bank.cosines[2];
        window_7 = bank.cosines[3];
        window_sines_hi = bank.sines;
        window_half_angles_hi = bank.half_angles;
        window_gains_hi = bank.gains;
    }
}

// Whether a group's blockers or its stand-in can have any weight in the windows: a
// sphere bounding them all (the group's extent or the stand-in's radius, the larger)
// seen under half-angle γ, its centre θ from a window of half-angle α, holds none beyond
// it unless θ < α + 3γ/2 (a cap of half-angle β ≤ γ inside it reaches the window's ramp
// only within α + 3β/2 of it; 1e-3 rad more for rounding). Those skipped, the walk costs
// the windows nothing where no light can be hidden; their weights were 0 (the twin,
// which walks them all, adds nothing for them). Of a cluster, likewise for its groups.
fn group_in_windows(group: BlockerGroup, p: vec3<f32>, windowed: bool) -> bool {
    if !windowed || LIGHT_WINDOWS == 0u || !windows_open {
        return true;
    }
    let to_group = group.center_extent.xyz - p;
    let distance = length(to_group);
    // The bounding sphere holds the stand-in's too.
    let bound_m = max(group.center_extent.w, group.stand_in_radius_m);
    if distance <= bound_m {
        return true;
    }
    let reaches = window_half_angles + vec4<f32>(1.5 * asin(bound_m / distance) + 1e-3);
    let direction = to_group / distance;
    var inside = angle_between(direction, window_0.xyz) < reaches.x;
    if LIGHT_WINDOWS >= 2u {
        inside = inside || angle_between(direction, window_1.xyz) < reaches.y;
    }
    if LIGHT_WINDOWS >= 3u {
        inside = inside || angle_between(direction, window_2.xyz) < reaches.z;
    }
    if LIGHT_WINDOWS >= 4u {
        inside = inside || angle_between(direction, window_3.xyz) < reaches.w;
    }
    if LIGHT_WINDOWS > 4u {
        let reaches_hi = window_half_angles_hi + vec4<f32>(1.5 * asin(bound_m / distance) + 1e-3);
        inside = inside || angle_between(direction, window_4.xyz) < reaches_hi.x;
        if LIGHT_WINDOWS >= 6u {
            inside = inside || angle_between(direction, window_5.xyz) < reaches_hi.y;
        }
        if LIGHT_WINDOWS >= 7u {
            inside = inside || angle_between(direction, window_6.xyz) < reaches_hi.z;
        }
        if LIGHT_WINDOWS >= 8u {
            inside = inside || angle_between(direction, window_7.xyz) < reaches_hi.w;
        }
    }
    return inside;
}

fn angle_between(a: vec3<f32>, b: vec3<f32>) -> f32 {
    return acos(clamp(dot(a, b), -1.0, 1.0));
}

// A blocker cap's half-angle β as the windows read it: cos and sin of β/2 (xy) and of
// 3β/2 (zw), from its sine s by half- and triple-angle formulas.
fn cap_angles(ratio: f32) -> vec4<f32> {
    let cos_cap = sqrt(max(1.0 - ratio * ratio, 0.0));
    let c = sqrt(0.5 + 0.5 * cos_cap);
    let s = 0.5 * ratio / c;
    return vec4<f32>(c, s, c * (4.0 * c * c - 3.0), s * (3.0 - 4.0 * s * s));
}

// The weight a window (direction, cos α; sine sin α) gives a cap toward unit `direction`
// of angles `cap` (cap_angles) (LightWindow::weight): smoothstep in cos θ from
// cos(α + 3β/2) to cos(α + β/2), by angle-sum formulas (an angle past π counts as π); 0
// for no window (cos α = 2).
fn window_weight(window: vec4<f32>, sine: f32, direction: vec3<f32>, cap: vec4<f32>) -> f32 {
    let whole = window.w * cap.x - sine * cap.y;
    let past_pi = sine * cap.z + window.w * cap.w < 0.0;
    let none = select(window.w * cap.z - sine * cap.w, -1.0, past_pi);
    let cos_between = dot(direction, window.xyz);
    let weight = select(select(0.0, 1.0, cos_between >= whole), smoothstep(none, whole, cos_between), none < whole);
    return select(weight, 0.0, window.w > 1.5);
}

// The factor on a cap's ln ε · f_n that each of the LIGHT_WINDOWS windows compiled in
// gives it, weight × min(1, k(s) · gain) (0 for the windows not compiled in): slots 0–3
// (lo) and 4–7 (hi).
struct WindowScales {
    lo: vec4<f32>,
    hi: vec4<f32>,
};

fn windowed_cap_scales(direction: vec3<f32>, ratio: f32, mass_scale: f32) -> WindowScales {
    let cap = cap_angles(ratio);
    var weights_hi = vec4<f32>(0.0);
    if LIGHT_WINDOWS > 4u {
        weights_hi.x = window_weight(window_4, window_sines_hi.x, direction, cap);
        if LIGHT_WINDOWS >= 6u {
            weights_hi.y = window_weight(window_5, window_sines_hi.y, direction, cap);
        }
        if LIGHT_WINDOWS >= 7u {
            weights_hi.z = window_weight(window_6, window_sines_hi.z, direction, cap);
        }
        if LIGHT_WINDOWS >= 8u {
            weights_hi.w = window_weight(window_7, window_sines_hi.w, direction, cap);
        }
    }
    var weights = vec4<f32>(window_weight(window_0, window_sines.x, direction, cap), 0.0, 0.0, 0.0);
    if LIGHT_WINDOWS >= 2u {
        weights.y = window_weight(window_1, window_sines.y, direction, cap);
    }
    if LIGHT_WINDOWS >= 3u {
        weights.z = window_weight(window_2, window_sines.z, direction, cap);
    }
    if LIGHT_WINDOWS >= 4u {
        weights.w = window_weight(window_3, window_sines.w, direction, cap);
    }
    return WindowScales(
        weights * min(vec4<f32>(1.0), mass_scale * window_gains),
        weights_hi * min(vec4<f32>(1.0), mass_scale * window_gains_hi),
    );
}

fn scaled_window_scales(scales: WindowScales, factor: f32) -> WindowScales {
    return WindowScales(factor * scales.lo, factor * scales.hi);
}

// Per window slot, 1 where a disc blocker at `center` with unit `normal` may stand
// between p and the slot's light, 0 where the light's emitter lies wholly on p's side of
// the disc's plane (exact_lights' disc_plane_between for one light; LightWindow::
// may_be_hidden_by_disc is the twin); 1 for a slot without a light. Each slot's light is
// looked up again: discs are few, and shaded at every receiver in their own loop.
fn disc_window_mask(center: vec3<f32>, normal: vec3<f32>, p: vec3<f32>) -> WindowScales {
    let side_p = dot(p - center, normal);
    var lo = vec4<f32>(1.0);
    var hi = vec4<f32>(1.0);
    if windows_open {
        lo = vec4<f32>(
            disc_may_hide(side_p, normal, p, window_light_indices.x),
            disc_may_hide(side_p, normal, p, window_light_indices.y),
            disc_may_hide(side_p, normal, p, window_light_indices.z),
            disc_may_hide(side_p, normal, p, window_light_indices.w),
        );
        if LIGHT_WINDOWS > 4u {
            hi = vec4<f32>(
                disc_may_hide(side_p, normal, p, window_light_indices_hi.x),
                disc_may_hide(side_p, normal, p, window_light_indices_hi.y),
                disc_may_hide(side_p, normal, p, window_light_indices_hi.z),
                disc_may_hide(side_p, normal, p, window_light_indices_hi.w),
            );
        }
    }
    return WindowScales(lo, hi);
}

fn disc_may_hide(side_p: f32, normal: vec3<f32>, p: vec3<f32>, index: u32) -> f32 {
    let light = light_at(min(index, max(frame.light_count, 1u) - 1u));
    let inc = incidence(light, p);
    let beside = emitter_beside_plane(light, side_p, normal, inc.to_light, inc.distance, clamp(inc.cap_ratio, 0.0, 1.0));
    return select(1.0, 0.0, beside && index != NO_WINDOW_LIGHT);
}

// The factor on a cap's ln ε · f_n when one log-visibility serves every window
// (LightWindows::cap_scale): the largest of windowed_cap_scales.
fn windowed_cap_scale(direction: vec3<f32>, ratio: f32, mass_scale: f32) -> f32 {
    return windowed_cap_scale_within(direction, ratio, mass_scale, WindowScales(vec4<f32>(1.0), vec4<f32>(1.0)));
}

// windowed_cap_scale over the windows `mask` keeps (disc_window_mask).
fn windowed_cap_scale_within(direction: vec3<f32>, ratio: f32, mass_scale: f32, mask: WindowScales) -> f32 {
    let scales = windowed_cap_scales(direction, ratio, mass_scale);
    let most = max(scales.lo * mask.lo, scales.hi * mask.hi);
    return max(max(most.x, most.y), max(most.z, most.w));
}

// Each windowed light's own log-visibility (shading::cpu::harmonic_log_visibility): each
// SH light reads the visibility over its own cap alone; one log-visibility weighed by
// the largest window's weight makes each light read its neighbours' blockers too,
// spread over the band limit's width (under a few lights spread over the sky, lit
// ground dimmed and penumbrae blurred), and one with every blocker at k(s), which an
// environment needs, drags a light's lit ground down by every blocker's ringing. So the
// walk sums each cap into one log-visibility per window, weighed by that window alone
// (window_log_0..3), beside, under an environment, the walk's own sum at k(s) for the
// environment; each light is shaded through its own (harmonic_radiance). Compiled in
// with two windows or more, or one under an environment (one window without an
// environment gives the walk's own sum the same weights). false: one log-visibility
// for every reader (the per-vertex pass, which keeps one visibility per vertex).
override PER_LIGHT_VISIBILITY: bool = true;

fn per_light_visibility() -> bool {
    return PER_LIGHT_VISIBILITY && (LIGHT_WINDOWS >= 2u || (ENVIRONMENT_LIGHT && LIGHT_WINDOWS >= 1u));
}

// The terrain's log-visibility at the point the walk last walked (walked_log_visibility),
// which every window's light reads besides its blockers.
var<private> walk_terrain_log: Sh;

// The blockers' log-visibility of the light in each window's slot (the rest of its
// log-visibility, the terrain's, is in the walk's own sum). Four variables rather than an
// array, as the windows.
var<private> window_log_0: Sh;
var<private> window_log_1: Sh;
var<private> window_log_2: Sh;
var<private> window_log_3: Sh;
var<private> window_log_4: Sh;
var<private> window_log_5: Sh;
var<private> window_log_6: Sh;
var<private> window_log_7: Sh;

fn clear_window_logs() {
    window_log_0 = sh_zero();
    window_log_1 = sh_zero();
    window_log_2 = sh_zero();
    window_log_3 = sh_zero();
    if LIGHT_WINDOWS > 4u {
        window_log_4 = sh_zero();
        window_log_5 = sh_zero();
        window_log_6 = sh_zero();
        window_log_7 = sh_zero();
    }
}

// A cap's rotated log-visibility, `rotated`, added to each window's sum at its scale.
fn add_to_window_logs(rotated: Sh, scales: WindowScales) {
    window_log_0 = sh_sum(window_log_0, sh_scaled(rotated, scales.lo.x));
    if LIGHT_WINDOWS >= 2u {
        window_log_1 = sh_sum(window_log_1, sh_scaled(rotated, scales.lo.y));
    }
    if LIGHT_WINDOWS >= 3u {
        window_log_2 = sh_sum(window_log_2, sh_scaled(rotated, scales.lo.z));
    }
    if LIGHT_WINDOWS >= 4u {
        window_log_3 = sh_sum(window_log_3, sh_scaled(rotated, scales.lo.w));
    }
    if LIGHT_WINDOWS >= 5u {
        window_log_4 = sh_sum(window_log_4, sh_scaled(rotated, scales.hi.x));
    }
    if LIGHT_WINDOWS >= 6u {
        window_log_5 = sh_sum(window_log_5, sh_scaled(rotated, scales.hi.y));
    }
    if LIGHT_WINDOWS >= 7u {
        window_log_6 = sh_sum(window_log_6, sh_scaled(rotated, scales.hi.z));
    }
    if LIGHT_WINDOWS >= 8u {
        window_log_7 = sh_sum(window_log_7, sh_scaled(rotated, scales.hi.w));
    }
}

// The log-visibility of the light in window slot k: the terrain's plus the window's.
fn window_log_visibility(k: u32) -> Sh {
    var own = window_log_0;
    if k == 1u {
        own = window_log_1;
    } else if k == 2u {
        own = window_log_2;
    } else if k == 3u {
        own = window_log_3;
    }
    if LIGHT_WINDOWS > 4u {
        if k == 4u {
            own = window_log_4;
        } else if k == 5u {
            own = window_log_5;
        } else if k == 6u {
            own = window_log_6;
        } else if k == 7u {
            own = window_log_7;
        }
    }
    return sh_sum(walk_terrain_log, own);
}

// The SH light in window slot k (NO_WINDOW_LIGHT: none).
fn slot_light(k: u32) -> u32 {
    if k >= 4u {
        return window_light_indices_hi[min(k - 4u, 3u)];
    }
    return window_light_indices[k];
}

// How many window slots hold a light.
fn open_window_count() -> u32 {
    let none = vec4<u32>(NO_WINDOW_LIGHT);
    let opened = select(vec4<u32>(0u), vec4<u32>(1u), window_light_indices != none)
        + select(vec4<u32>(0u), vec4<u32>(1u), window_light_indices_hi != none);
    return opened.x + opened.y + opened.z + opened.w;
}
