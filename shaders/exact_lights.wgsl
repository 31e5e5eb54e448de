// The exact path for small lights (src/penumbra/mod.rs is the f64 twin): a light's
// visibility from p is 1 − the share of its disc hidden by the union of the blockers'
// caps (each share faded below the horizon; src/penumbra/union.rs), skipping what
// log_visibility skips and blockers wholly beyond the light; the discs' shares multiply
// in after.
//
// Shaped for lavapipe, which runs every statement of a branch at every pixel whether
// taken or not, and every loop at least once: lights go eight at a time (a vec4 lane
// each, in two halves), so each blocker is loaded and measured once per eight lights;
// cheap tests of every blocker only list the few that may cut a disc, and the lens (three
// arctangents per light) runs in a second loop over that list alone, with the overlaps of
// each listed blocker with the listed ones before it.
// #import blockers scene

// Four exact-path lights seen from one receiver, one per lane (half of an eight-light
// batch); unused lanes have distance 0, so that every blocker counts as beyond them.
struct ExactBatch {
    to_light_x: vec4<f32>,
    to_light_y: vec4<f32>,
    to_light_z: vec4<f32>,
    // sin of each light's angular radius, clamped to [0, 1].
    sin_light: vec4<f32>,
    distance: vec4<f32>,
};

// A blocker as seen from the receiver, with the tests shared by every light.
struct BlockerCap {
    direction: vec3<f32>,
    distance: f32,
    // sin of the cap's angular radius, r/d.
    ratio: f32,
    // √(1 − ratio²), the cosine of the cap's angular radius.
    cos_b: f32,
    // smoothstep fade below the tangent plane (as in add_walked).
    horizon: f32,
    // false: skipped for every light (contains p, too small, or below the horizon).
    counts: bool,
};

fn blocker_cap(b: Blocker, p: vec3<f32>, n: vec3<f32>) -> BlockerCap {
    let seen = blocker_seen(b, p, n);
    let ratio = max(seen.x, 0.0);
    let counts = seen.x >= shadow.min_cap_ratio && seen.y > 0.0;
    let direction = (b.center_radius.xyz - p) / seen.z;
    return BlockerCap(direction, seen.z, ratio, sqrt(max(1.0 - ratio * ratio, 0.0)), seen.y, counts);
}

fn cos_to_lights(direction: vec3<f32>, batch: ExactBatch) -> vec4<f32> {
    return direction.x * batch.to_light_x + direction.y * batch.to_light_y + direction.z * batch.to_light_z;
}

// sin of each light's angular radius against a blocker at `distance`: at least half a
// pixel's footprint over the distance, so that a point light's hard edge ramps over about
// one pixel instead of stepping (penumbra::light_visibility).
fn disc_sines(batch: ExactBatch, half_footprint: f32, distance: f32) -> vec4<f32> {
    return min(max(batch.sin_light, vec4<f32>(half_footprint / distance)), vec4<f32>(1.0));
}

// The share (0–1) of a light's disc hidden by a blocker's cap, for four lights at once
// (src/penumbra/cap_overlap.rs is the f64 twin, by another formula). The lens where the
// caps meet is 2θ_L·v_a + 2θ_B·v_b − 2E (cap sectors minus the two triangles of the
// centres and a crossing point, E their spherical excess) over the disc's 2π·v_a, every
// term from the versines v = 1 − cos of the three sides (light radius a, blocker radius
// b, separation g), so nothing cancels for tiny discs and no angle is ever taken:
// - the triangle's volume det = L·(B × X), det² = v_a(2(v_b + v_g) − v_a − 2v_b·v_g)
//   − (v_b − v_g)² (the Gram determinant written in versines);
// - θ_L = atan2(det, cos b − cos a·cos g) (the law of cosines' numerator, again in
//   versines), θ_B likewise;
// - tan(E/2) = det / (1 + cos a + cos b + cos g) (Van Oosterom and Strackee).
// Where the circles do not cross (det² ≤ 0) the caps are apart or one holds the other.
fn hidden_fractions(sin_a: vec4<f32>, cap: BlockerCap, v_g: vec4<f32>) -> vec4<f32> {
    let cos_a = sqrt(max(vec4<f32>(1.0) - sin_a * sin_a, vec4<f32>(0.0)));
    let v_a = sin_a * sin_a / (vec4<f32>(1.0) + cos_a);
    let v_b = cap.ratio * cap.ratio / (1.0 + cap.cos_b);
    let det2 = v_a * (2.0 * (v_b + v_g) - v_a - 2.0 * v_b * v_g) - (v_b - v_g) * (v_b - v_g);
    let det = sqrt(max(det2, vec4<f32>(0.0)));
    let theta_light = atan2(det, v_a + v_g - v_a * v_g - v_b);
    let theta_blocker = atan2(det, v_b + v_g - v_b * v_g - v_a);
    let excess = 2.0 * atan2(det, vec4<f32>(4.0) - v_a - v_b - v_g);
    let lens = 2.0 * theta_light * v_a + 2.0 * theta_blocker * v_b - 2.0 * excess;
    let crossing = clamp(lens / (2.0 * PI * v_a), vec4<f32>(0.0), vec4<f32>(1.0));
    // Without a crossing, cos g lies beyond cos(a ± b), on either side of cos a·cos b.
    let nested = v_g < v_a + v_b - v_a * v_b;
    let inside_blocker = vec4<f32>(cap.ratio) >= sin_a;
    let whole = select(vec4<f32>(0.0), select(min(v_b / v_a, vec4<f32>(1.0)), vec4<f32>(1.0), inside_blocker), nested);
    return select(crossing, whole, det2 <= vec4<f32>(0.0));
}

// The share of each light's disc the blocker hides, fade included (0 for lights it is
// beyond).
fn hidden_by(cap: BlockerCap, radius: f32, batch: ExactBatch, half_footprint: f32) -> vec4<f32> {
    let sin_a = disc_sines(batch, half_footprint, cap.distance);
    // 1 − cos g as half the squared chord, which keeps its digits for tiny separations.
    let chord_x = cap.direction.x - batch.to_light_x;
    let chord_y = cap.direction.y - batch.to_light_y;
    let chord_z = cap.direction.z - batch.to_light_z;
    let v_g = 0.5 * (chord_x * chord_x + chord_y * chord_y + chord_z * chord_z);
    let hidden = cap.horizon * hidden_fractions(sin_a, cap, v_g);
    let beyond = vec4<f32>(cap.distance - radius) >= batch.distance;
    return select(hidden, vec4<f32>(0.0), beyond | vec4<bool>(!cap.counts));
}

// Per lane, whether a disc with unit `normal`, p `side_p` in front of its plane, may stand
// between p and the lane's light, the lights first.. of the batch half: not where the
// light's emitter lies wholly on p's side of the plane (emitter_beside_plane; unused
// lanes have distance 0, and hidden_by gives them nothing anyway).
// Written out lane by lane: lavapipe makes a loop writing vector lanes by index costly.
fn disc_plane_between(side_p: f32, normal: vec3<f32>, batch: ExactBatch, first: u32) -> vec4<bool> {
    return !vec4<bool>(
        lane_beside_plane(side_p, normal, batch, first, 0u),
        lane_beside_plane(side_p, normal, batch, first, 1u),
        lane_beside_plane(side_p, normal, batch, first, 2u),
        lane_beside_plane(side_p, normal, batch, first, 3u),
    );
}

fn lane_beside_plane(side_p: f32, normal: vec3<f32>, batch: ExactBatch, first: u32, k: u32) -> bool {
    let light = light_at(min(first + k, max(frame.light_count, 1u) - 1u));
    let to_light = vec3<f32>(batch.to_light_x[k], batch.to_light_y[k], batch.to_light_z[k]);
    return emitter_beside_plane(light, side_p, normal, to_light, batch.distance[k], batch.sin_light[k]);
}

// The solid angle where two caps meet (versines v_a, of cap b's, v_g of their
// separation): hidden_fractions' lens for one pair of caps, before its division by the
// first cap's area.
fn lens_solid_angle(v_a: f32, cap: BlockerCap, v_g: f32) -> f32 {
    let v_b = cap.ratio * cap.ratio / (1.0 + cap.cos_b);
    let det2 = v_a * (2.0 * (v_b + v_g) - v_a - 2.0 * v_b * v_g) - (v_b - v_g) * (v_b - v_g);
    let det = sqrt(max(det2, 0.0));
    let theta_a = atan2(det, v_a + v_g - v_a * v_g - v_b);
    let theta_b = atan2(det, v_b + v_g - v_b * v_g - v_a);
    let excess = 2.0 * atan2(det, 4.0 - v_a - v_b - v_g);
    let crossing = max(2.0 * theta_a * v_a + 2.0 * theta_b * v_b - 2.0 * excess, 0.0);
    let nested = v_g < v_a + v_b - v_a * v_b;
    return select(crossing, select(0.0, 2.0 * PI * min(v_a, v_b), nested), det2 <= 0.0);
}

// The share of each light's disc hidden by both blockers m and k (hidden_m, hidden_k
// their own shares; src/penumbra/union.rs's pair_overlap): the share hidden by one cap
// of the solid angle of the lens where their caps meet, centred midway across the lens
// on the arc from m's centre to k's, kept within both shares. The disc is the wider of
// the two blockers' (disc_sines at the nearer).
fn pair_overlap(m: BlockerCap, k: BlockerCap, hidden_m: vec4<f32>, hidden_k: vec4<f32>, batch: ExactBatch, half_footprint: f32) -> vec4<f32> {
    let chord = k.direction - m.direction;
    let v_mk = 0.5 * dot(chord, chord);
    let v_m = m.ratio * m.ratio / (1.0 + m.cos_b);
    let lens = lens_solid_angle(v_m, k, v_mk);
    // Along the arc from m's centre toward k's, the lens spans from the nearer of k's far
    // edge and m's back edge to the nearer of m's front edge and k's.
    let radius_m = asin(min(m.ratio, 1.0));
    let radius_k = asin(min(k.ratio, 1.0));
    let separation = 2.0 * asin(min(0.5 * sqrt(2.0 * v_mk), 1.0));
    let middle = 0.5 * (max(separation - radius_k, -radius_m) + min(radius_m, separation + radius_k));
    let across = k.direction - m.direction * dot(m.direction, k.direction);
    let across_length = length(across);
    let sideways = select(vec3<f32>(0.0), across / across_length, across_length > 0.0);
    let lens_direction = m.direction * cos(middle) + sideways * sin(middle);
    // The cap of the lens's solid angle, 2π·v = Ω, built from its versine v.
    let v = min(lens / (2.0 * PI), 2.0);
    let lens_cap = BlockerCap(lens_direction, 0.0, sqrt(max(v * (2.0 - v), 0.0)), 1.0 - v, 1.0, true);
    let sin_a = disc_sines(batch, half_footprint, min(m.distance, k.distance));
    let to_x = lens_direction.x - batch.to_light_x;
    let to_y = lens_direction.y - batch.to_light_y;
    let to_z = lens_direction.z - batch.to_light_z;
    let v_g = 0.5 * (to_x * to_x + to_y * to_y + to_z * to_z);
    let overlap = min(m.horizon, k.horizon) * hidden_fractions(sin_a, lens_cap, v_g);
    return select(min(overlap, min(hidden_m, hidden_k)), vec4<f32>(0.0), lens <= 0.0);
}

// false: the frame has at most four exact-path lights, and the second half of each
// batch is left out of the pipeline. Set at pipeline creation (shading::compiled_paths).
override EXACT_WIDE: bool = true;

// Whether a blocker group, seen `distance` away toward `direction` with every sphere
// within `extent` of its centre, can hide any of a batch's lights: its bounding sphere
// meets some light's cone (cos γ > cos(α + β) with sin β = extent/distance, α at its
// widest for the group's nearest sphere).
fn group_may_cut(batch: ExactBatch, direction: vec3<f32>, distance: f32, extent: f32, half_footprint: f32) -> bool {
    if distance <= extent {
        return true;
    }
    let sin_a = disc_sines(batch, half_footprint, distance - extent);
    let cos_a = sqrt(vec4<f32>(1.0) - sin_a * sin_a);
    let sin_g = extent / distance;
    let cos_g = sqrt(max(1.0 - sin_g * sin_g, 0.0));
    return any(cos_to_lights(direction, batch) > cos_a * cos_g - sin_a * sin_g);
}

// Whether a group (or a cluster: its bounds hold its groups') may hold a sphere that cuts
// one of the batch's discs: in reach (group_in_influence) and meeting some light's cone.
fn group_in_batch_reach(group: BlockerGroup, p: vec3<f32>, n: vec3<f32>, lo: ExactBatch, hi: ExactBatch, half_footprint: f32) -> bool {
    let to_group = group.center_extent.xyz - p;
    let group_distance = sqrt(dot(to_group, to_group));
    let direction = to_group / max(group_distance, 1e-30);
    let extent = group.center_extent.w;
    var may_cut = group_may_cut(lo, direction, group_distance, extent, half_footprint);
    if EXACT_WIDE {
        may_cut = may_cut || group_may_cut(hi, direction, group_distance, extent, half_footprint);
    }
    return may_cut && group_in_influence(group, p, n);
}

// The groups of `walked` (as BlockerWalk bits from walked.first) with a sphere that may
// cut one of the batch's discs.
fn groups_that_may_cut(walked: ClusterGroups, p: vec3<f32>, n: vec3<f32>, lo: ExactBatch, hi: ExactBatch, half_footprint: f32) -> u32 {
    var passing = 0u;
    for (var g = walked.first; g < walked.end; g++) {
        if group_in_batch_reach(group_at(g), p, n, lo, hi, half_footprint) {
            passing |= 1u << (g - walked.first);
        }
    }
    return passing;
}

// The cheap tests of one blocker against a batch's lights: which discs it surely covers
// whole (added to `covered`) and which it may cut partly.
struct CutTests {
    covered: vec4<bool>,
    cuts: vec4<bool>,
};

fn cut_tests(cap: BlockerCap, radius: f32, batch: ExactBatch, half_footprint: f32, covered: vec4<bool>) -> CutTests {
    let sin_a = disc_sines(batch, half_footprint, cap.distance);
    // cos a = √(1 − x), x = sin² a, bounded without a square root: 1 − x/2 − x²/2 below
    // it, 1 − x/2 above. The tests then list a sphere that might cut a disc and call a
    // disc covered only when it surely is; the lens loop decides exactly.
    let x = sin_a * sin_a;
    let cos_a_high = vec4<f32>(1.0) - 0.5 * x;
    let cos_a_low = cos_a_high - 0.5 * x * x;
    let cos_separation = cos_to_lights(cap.direction, batch);
    let nearer = vec4<f32>(cap.distance - radius) < batch.distance;
    // Separation below a + b (the caps meet), and below b − a (the blocker's cap holds
    // the whole disc).
    let meets = cos_separation > cos_a_low * cap.cos_b - sin_a * cap.ratio;
    let holds = (vec4<f32>(cap.ratio) >= sin_a) & (cos_separation >= cos_a_high * cap.cos_b + sin_a * cap.ratio);
    let counts = vec4<bool>(cap.counts) & nearer & !covered;
    let now_covered = covered | (counts & holds & vec4<bool>(cap.horizon >= 1.0));
    return CutTests(now_covered, counts & meets & !now_covered);
}

// No entry past the cut list's eight (the list did not overflow).
const NO_OVERFLOW: u32 = 0xffffffffu;

// Batch halves per blocker in a CutList's entries.
fn batch_halves() -> u32 {
    return select(1u, 2u, EXACT_WIDE);
}

// The (blocker, batch half) pairs whose lens the second loop measures, in increasing
// order of entry = batch_halves() · blocker + half (0 lo, 1 hi): a blocker usually cuts
// the disc of one light, so its lens is measured for that light's half alone. Up to
// eight entries, then every entry from overflow_from on.
struct CutList {
    low: vec4<u32>,
    high: vec4<u32>,
    count: u32,
    overflow_from: u32,
};

fn add_cut(list: ptr<function, CutList>, entry: u32, cuts: bool) {
    let add = cuts && (*list).overflow_from == NO_OVERFLOW;
    let slot = vec4<u32>((*list).count);
    (*list).low = select((*list).low, vec4<u32>(entry), vec4<bool>(add) & (slot == vec4<u32>(0u, 1u, 2u, 3u)));
    (*list).high = select((*list).high, vec4<u32>(entry), vec4<bool>(add) & (slot == vec4<u32>(4u, 5u, 6u, 7u)));
    if add {
        if (*list).count == 8u {
            (*list).overflow_from = entry;
        } else {
            (*list).count += 1u;
        }
    }
}

// The list's k-th entry, counting on past the eighth through the overflow range.
fn cut_entry(list: CutList, k: u32) -> u32 {
    if k < 4u {
        return list.low[k];
    }
    if k < list.count {
        return list.high[k & 3u];
    }
    return list.overflow_from + (k - list.count);
}

// How many entries the lens loop walks: the listed ones, and for a crowded receiver
// (more than eight cuts) every entry from the first unlisted one on.
fn cut_entries(list: CutList) -> u32 {
    if list.overflow_from == NO_OVERFLOW {
        return list.count;
    }
    return list.count + batch_halves() * shadow.blocker_count - list.overflow_from;
}

// The visibility of each light of an eight-light batch (lo, and hi when EXACT_WIDE).
struct ExactVisibility {
    lo: vec4<f32>,
    hi: vec4<f32>,
};

// Visibility of each light of the batch (the lights first.., first + 4.. for hi) from p
// with normal n (the f32 twin of
// penumbra::light_visibility).
fn exact_batch_visibility(p: vec3<f32>, n: vec3<f32>, lo: ExactBatch, hi: ExactBatch, first: u32) -> ExactVisibility {
    let half_footprint = 0.5 * pixel_footprint(p);
    // Lights a blocker hides wholly (visibility 0).
    var covered_lo = vec4<bool>(false);
    var covered_hi = vec4<bool>(false);
    var list = CutList(vec4<u32>(0u), vec4<u32>(0u), 0u, NO_OVERFLOW);
    for (var c = 0u; c < shadow.cluster_count; c++) {
        let cluster = group_at(c);
        let walked = cluster_groups(cluster, group_in_batch_reach(cluster, p, n, lo, hi, half_footprint));
        var walk = blocker_walk(walked.first, groups_that_may_cut(walked, p, n, lo, hi, half_footprint));
        loop {
            let i = walk_next(&walk);
            if i == WALK_DONE {
                break;
            }
            let b = blocker_at(i);
            let cap = blocker_cap(b, p, n);
            let tests_lo = cut_tests(cap, b.center_radius.w, lo, half_footprint, covered_lo);
            covered_lo = tests_lo.covered;
            add_cut(&list, batch_halves() * i, any(tests_lo.cuts));
            if EXACT_WIDE {
                let tests_hi = cut_tests(cap, b.center_radius.w, hi, half_footprint, covered_hi);
                covered_hi = tests_hi.covered;
                add_cut(&list, 2u * i + 1u, any(tests_hi.cuts));
            }
        }
    }
    // One loop over every entry, as lavapipe runs the body of even an empty loop once:
    // each adds the share it hides that the listed entries of its half before it do not
    // (src/penumbra/union.rs). An entry past the list's eight is compared with those eight.
    var union_lo = vec4<f32>(0.0);
    var union_hi = vec4<f32>(0.0);
    var largest_lo = vec4<f32>(0.0);
    var largest_hi = vec4<f32>(0.0);
    for (var k = 0u; k < cut_entries(list); k++) {
        let entry = cut_entry(list, k);
        let upper = EXACT_WIDE && (entry & 1u) == 1u;
        let batch = ExactBatch(
            select(lo.to_light_x, hi.to_light_x, upper),
            select(lo.to_light_y, hi.to_light_y, upper),
            select(lo.to_light_z, hi.to_light_z, upper),
            select(lo.sin_light, hi.sin_light, upper),
            select(lo.distance, hi.distance, upper),
        );
        let b = blocker_at(entry / batch_halves());
        let cap = blocker_cap(b, p, n);
        let hidden = hidden_by(cap, b.center_radius.w, batch, half_footprint);
        var left_open = vec4<f32>(1.0);
        let earlier = select(0u, min(k, list.count), any(hidden > vec4<f32>(0.0)));
        for (var m = 0u; m < earlier; m++) {
            let entry_m = cut_entry(list, m);
            let b_m = blocker_at(entry_m / batch_halves());
            let cap_m = blocker_cap(b_m, p, n);
            let hidden_m = hidden_by(cap_m, b_m.center_radius.w, batch, half_footprint);
            let overlap = pair_overlap(cap_m, cap, hidden_m, hidden, batch, half_footprint);
            let same_half = (entry_m & 1u) == (entry & 1u) || !EXACT_WIDE;
            left_open *= select(vec4<f32>(1.0), vec4<f32>(1.0) - overlap / max(hidden, vec4<f32>(1e-30)), same_half);
        }
        let added = hidden * clamp(left_open, vec4<f32>(0.0), vec4<f32>(1.0));
        union_lo += select(added, vec4<f32>(0.0), upper);
        union_hi += select(vec4<f32>(0.0), added, upper);
        largest_lo = max(largest_lo, select(hidden, vec4<f32>(0.0), upper));
        largest_hi = max(largest_hi, select(vec4<f32>(0.0), hidden, upper));
    }
    var visible_lo = vec4<f32>(1.0) - clamp(union_lo, largest_lo, vec4<f32>(1.0));
    var visible_hi = vec4<f32>(1.0) - clamp(union_hi, largest_hi, vec4<f32>(1.0));
    // The discs, at every receiver (their own list; logsh.wgsl's add_discs), each for the
    // lights that reach its plane from p's side (disc_plane_between).
    for (var d = 0u; d < shadow.disc_count; d++) {
        let disc = shadow.discs[d];
        let seen = disc_cap_seen(disc, p, n);
        let counts = seen.ratio >= shadow.min_cap_ratio && seen.horizon > 0.0;
        let cap = BlockerCap(seen.direction, seen.distance, seen.ratio, sqrt(max(1.0 - seen.ratio * seen.ratio, 0.0)), seen.horizon, counts);
        let side_p = dot(p - disc.center_radius.xyz, disc.disc_normal.xyz);
        let between_lo = disc_plane_between(side_p, disc.disc_normal.xyz, lo, first);
        visible_lo *= vec4<f32>(1.0) - select(vec4<f32>(0.0), hidden_by(cap, disc.center_radius.w, lo, half_footprint), between_lo);
        if EXACT_WIDE {
            let between_hi = disc_plane_between(side_p, disc.disc_normal.xyz, hi, first + 4u);
            visible_hi *= vec4<f32>(1.0) - select(vec4<f32>(0.0), hidden_by(cap, disc.center_radius.w, hi, half_footprint), between_hi);
        }
    }
    return ExactVisibility(select(visible_lo, vec4<f32>(0.0), covered_lo), select(visible_hi, vec4<f32>(0.0), covered_hi));
}
