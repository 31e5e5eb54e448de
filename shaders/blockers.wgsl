// Sphere and disc blockers and their groups (src/blockers/, shading::blocker_groups): how a
// receiver sees one, the groups in its reach, and the flat walk over the blockers of the
// groups that pass, shared by the log-SH path (logsh.wgsl) and the exact path
// (exact_lights.wgsl). shading::cpu::visibility is the f64 twin.
// #import shadow_bindings scene

// false: the frame has at most UNIFORM_BLOCKER_CAPACITY blockers (and so as many groups),
// and every_blocker and every_group are never read (shading::compiled_paths). Blockers
// past the capacity then cast no shadow.
override BLOCKER_OVERFLOW: bool = true;

// A sphere around every receiver, which every test skips as one containing its receiver
// (its radius squared overflows to infinity): what blockers past the capacity read as.
const NO_BLOCKER: Blocker = Blocker(vec4<f32>(0.0, 0.0, 0.0, 1e30), vec4<f32>(0.0));

// Blocker i.
fn blocker_at(i: u32) -> Blocker {
    if BLOCKER_OVERFLOW {
        if i >= UNIFORM_BLOCKER_CAPACITY {
            return every_blocker[i];
        }
    }
    if i >= UNIFORM_BLOCKER_CAPACITY {
        return NO_BLOCKER;
    }
    return blockers[min(i, UNIFORM_BLOCKER_CAPACITY - 1u)];
}

// Sphere b as a receiver at p with unit normal n sees it (blockers::Sphere::cap_from is
// the f64 twin): x = sin of its cap's angular radius r/d, or −1 for a sphere containing
// p; y = the fade below the tangent plane, smoothstep(−1, 1, (c − p)·n / r); z = distance.
fn blocker_seen(b: Blocker, p: vec3<f32>, n: vec3<f32>) -> vec3<f32> {
    let offset = b.center_radius.xyz - p;
    let distance2 = dot(offset, offset);
    let distance = sqrt(max(distance2, 1e-30));
    let radius = b.center_radius.w;
    let ratio = select(radius / distance, -1.0, distance2 <= radius * radius);
    return vec3<f32>(ratio, smoothstep(-1.0, 1.0, dot(offset, n) / radius), distance);
}

// A disc blocker as a receiver sees it: the cap of its solid angle around the mean
// direction over it (disc_seen), faded below the tangent plane over the disc's
// half-extent along n.
struct SeenDisc {
    direction: vec3<f32>,
    ratio: f32,
    horizon: f32,
    distance: f32,
};

// The circumradius over the disc's radius of the square of the disc's area that stands
// for it near by, √(π/2); beyond NEAR_FIELD_RADII radii the far-field cap
// (src/blockers/disc.rs).
const POLYGON_SCALE: f32 = 1.2533141373155003;
const NEAR_FIELD_RADII: f32 = 4.0;
const DISC_PLANE_TOLERANCE_M: f32 = 1e-3;

// Signed solid angle of the triangle a, b, c seen from the origin (Van Oosterom and
// Strackee: tan(Ω/2) = a·(b × c) / (abc + (a·b)c + (a·c)b + (b·c)a)).
fn triangle_solid_angle(a: vec3<f32>, b: vec3<f32>, c: vec3<f32>) -> f32 {
    let la = length(a);
    let lb = length(b);
    let lc = length(c);
    let numerator = dot(a, cross(b, c));
    let denominator = la * lb * lc + dot(a, b) * lc + dot(a, c) * lb + dot(b, c) * la;
    return 2.0 * atan2(numerator, denominator);
}

// The solid angle a disc subtends from p (w, steradians) and the unit mean direction over
// it (xyz); 0 from its own plane (blockers::disc::disc_seen).
fn disc_seen(center: vec3<f32>, radius: f32, normal: vec3<f32>, p: vec3<f32>) -> vec4<f32> {
    let to_center = center - p;
    let height = abs(dot(to_center, normal));
    let distance = length(to_center);
    if height <= DISC_PLANE_TOLERANCE_M * max(radius, 1.0) {
        return vec4<f32>(normal, 0.0);
    }
    let toward = to_center / max(distance, 1e-30);
    if distance > NEAR_FIELD_RADII * radius {
        let seen_radius2 = radius * radius * height / distance;
        return vec4<f32>(toward, 2.0 * PI * (1.0 - distance * inverseSqrt(distance * distance + seen_radius2)));
    }
    // Duff et al.'s orthonormal pair, as disc_frame.
    let sign = select(-1.0, 1.0, normal.z >= 0.0);
    let a = -1.0 / (sign + normal.z);
    let b = normal.x * normal.y * a;
    let reach = radius * POLYGON_SCALE;
    let frame_u = vec3<f32>(1.0 + sign * normal.x * normal.x * a, sign * b, -sign * normal.x);
    let frame_v = vec3<f32>(b, sign + normal.y * normal.y * a, -normal.y);
    // Corners on the frame's diagonals: the square's edges along its axes (disc_seen).
    let u = (reach * 0.70710678) * (frame_u + frame_v);
    let v = (reach * 0.70710678) * (frame_v - frame_u);
    let q0 = to_center + u;
    let q1 = to_center + v;
    let q2 = to_center - u;
    let q3 = to_center - v;
    let solid_angle = triangle_solid_angle(q0, q1, q2) + triangle_solid_angle(q0, q2, q3);
    let form_factor = edge_form_factor(q0, q1) + edge_form_factor(q1, q2) + edge_form_factor(q2, q3)
        + edge_form_factor(q3, q0);
    var direction = toward;
    if dot(form_factor, form_factor) > 0.0 {
        direction = normalize(form_factor);
    }
    direction = select(direction, -direction, dot(direction, to_center) < 0.0);
    return vec4<f32>(direction, min(abs(solid_angle), 2.0 * PI));
}

fn disc_cap_seen(b: Blocker, p: vec3<f32>, n: vec3<f32>) -> SeenDisc {
    let normal = b.disc_normal.xyz;
    let radius = b.center_radius.w;
    let seen = disc_seen(b.center_radius.xyz, radius, normal, p);
    // The cap of that solid angle: cos = 1 − Ω/2π.
    let cos_cap = 1.0 - seen.w / (2.0 * PI);
    let ratio = sqrt(max(1.0 - cos_cap * cos_cap, 0.0));
    let tilt = sqrt(max(1.0 - dot(n, normal) * dot(n, normal), 0.0));
    let offset = b.center_radius.xyz - p;
    // Unfaded while any of it can be above the tangent plane (Sphere::cap_from says why).
    let horizon = select(0.0, 1.0, dot(offset, n) > -radius * max(tilt, 1e-4));
    return SeenDisc(seen.xyz, ratio, horizon, length(offset));
}

// Blocker group g, unpacked.
fn group_at(g: u32) -> BlockerGroup {
    var packed: PackedBlockerGroup;
    if BLOCKER_OVERFLOW && g >= UNIFORM_BLOCKER_CAPACITY {
        packed = every_group[g];
    } else {
        packed = groups[min(g, UNIFORM_BLOCKER_CAPACITY - 1u)];
        // Empty past the capacity.
        packed.first_count = select(packed.first_count, 0u, g >= UNIFORM_BLOCKER_CAPACITY);
    }
    return BlockerGroup(
        packed.center_extent,
        packed.hand_over_m,
        packed.first_count & ((1u << GROUP_FIRST_BITS) - 1u),
        packed.first_count >> GROUP_FIRST_BITS,
        packed.stand_in_radius_m,
        packed.stand_in_depth,
    );
}

// The blockers of chosen groups, one per call of walk_next, so that one flat loop visits
// them: lavapipe runs a loop's body at least once even when no pixel enters it, so a
// loop over the blockers nested in a loop over the groups pays one blocker's work for
// every group a receiver skips. Bit k of `blockers` and `stand_ins` stands for group
// first_group + k: its blockers are walked (a group with at least one blocker), and its
// stand-in comes after them as one more step (WALK_STAND_IN; log_visibility's walk), so
// that a group whose stand-in weighs nothing at p costs no cap.
struct BlockerWalk {
    first_group: u32,
    blockers: u32,
    stand_ins: u32,
    next: u32,
    end: u32,
    // The receiver, and the weight of the current group's blockers there:
    // cluster_weight · (1 − stand_in_share) (log_visibility's walk; the exact path
    // ignores it), cluster_weight the groups' share against their cluster's stand-in.
    receiver: vec3<f32>,
    weight: f32,
    cluster_weight: f32,
    // The current group's stand-in, when it is still to come: its sphere (centre, radius),
    // the extent it fades below the tangent plane over, and its weight,
    // cluster_weight · stand_in_share · stand_in_depth.
    stand_in_pending: bool,
    stand_in: vec4<f32>,
    stand_in_extent: f32,
    stand_in_weight: f32,
};

// No blocker left to walk.
const WALK_DONE: u32 = 0xffffffffu;
// The current group's stand-in (walk.stand_in) is the next step.
const WALK_STAND_IN: u32 = 0xfffffffeu;

fn blocker_walk(first_group: u32, passing: u32) -> BlockerWalk {
    return BlockerWalk(first_group, passing, 0u, 0u, 0u, vec3<f32>(0.0), 1.0, 1.0, false, vec4<f32>(0.0), 0.0, 0.0);
}

// A walk of a cluster's groups that weighs each group's blockers and stand-in at
// receiver p, the groups together weighed 1 − `share`, the cluster's stand-in share
// there (stand_in_share); the
// cluster's own stand-in is its first step when `cluster_stand_in` (it takes the one
// pass lavapipe runs of a walk with nothing else to visit).
fn cluster_walk(cluster: BlockerGroup, share: f32, passing: GroupsToWalk, p: vec3<f32>, cluster_stand_in: bool) -> BlockerWalk {
    return BlockerWalk(
        cluster.first,
        passing.blockers,
        passing.stand_ins,
        0u,
        0u,
        p,
        1.0,
        1.0 - share,
        cluster_stand_in,
        vec4<f32>(cluster.center_extent.xyz, cluster.stand_in_radius_m),
        cluster.center_extent.w,
        share * cluster.stand_in_depth,
    );
}

// The groups of a cluster a walk visits: bit k for group first + k.
struct GroupsToWalk {
    blockers: u32,
    stand_ins: u32,
};

// The index of the walk's next blocker, WALK_STAND_IN, or WALK_DONE.
fn walk_next(walk: ptr<function, BlockerWalk>) -> u32 {
    if (*walk).next == (*walk).end {
        if (*walk).stand_in_pending {
            (*walk).stand_in_pending = false;
            return WALK_STAND_IN;
        }
        let passing = (*walk).blockers | (*walk).stand_ins;
        if passing == 0u {
            return WALK_DONE;
        }
        let bit = 1u << firstTrailingBit(passing);
        let group = group_at((*walk).first_group + firstTrailingBit(passing));
        let walks_blockers = ((*walk).blockers & bit) != 0u;
        (*walk).blockers &= ~bit;
        (*walk).next = group.first;
        (*walk).end = select(group.first, group.first + group.count, walks_blockers);
        let share = stand_in_share(group, (*walk).receiver);
        (*walk).weight = (*walk).cluster_weight * (1.0 - share);
        (*walk).stand_in_pending = ((*walk).stand_ins & bit) != 0u;
        (*walk).stand_ins &= ~bit;
        (*walk).stand_in = vec4<f32>(group.center_extent.xyz, group.stand_in_radius_m);
        (*walk).stand_in_extent = group.center_extent.w;
        (*walk).stand_in_weight = (*walk).cluster_weight * share * group.stand_in_depth;
        if !walks_blockers {
            // Only the stand-in: it is this step.
            (*walk).stand_in_pending = false;
            return WALK_STAND_IN;
        }
    }
    (*walk).next += 1u;
    return (*walk).next - 1u;
}

// Groups per BlockerWalk (the bits of `passing`): the most groups in one cluster
// (blocker_groups::CLUSTER_GROUPS).
const WALK_GROUPS: u32 = 32u;

// The groups of cluster c that a receiver walks: all of them when `visit`, else none
// (first == end, so the walk's loops take one masked pass).
struct ClusterGroups {
    first: u32,
    end: u32,
};

fn cluster_groups(cluster: BlockerGroup, visit: bool) -> ClusterGroups {
    return ClusterGroups(cluster.first, select(cluster.first, cluster.first + cluster.count, visit));
}

// Whether a group's (or a cluster's) stand-in weighs anything at p: its share there times
// `weight` above 0, as large in the sky as min_cap_ratio, not wholly below the tangent
// plane (add_walked's tests before its cap).
fn stand_in_weighs(group: BlockerGroup, p: vec3<f32>, n: vec3<f32>, weight: f32) -> bool {
    let offset = group.center_extent.xyz - p;
    let ratio_reached = group.stand_in_radius_m * group.stand_in_radius_m
        >= shadow.min_cap_ratio * shadow.min_cap_ratio * dot(offset, offset);
    let above = dot(offset, n) > -group.center_extent.w;
    return stand_in_share(group, p) * weight > 0.0 && ratio_reached && above && group.count > 0u;
}

// Whether the SH walk takes a group's (or a cluster's) blockers at p: within its
// hand-over distance (beyond it the stand-in alone), not wholly below the tangent plane
// (every sphere there would be skipped by add_walked's tests), and not empty.
fn group_in_reach(group: BlockerGroup, p: vec3<f32>, n: vec3<f32>) -> bool {
    let to_group = group.center_extent.xyz - p;
    return dot(to_group, to_group) <= group.hand_over_m * group.hand_over_m
        && dot(to_group, n) + group.center_extent.w > 0.0 && group.count > 0u;
}

// Whether any sphere of a group (or a cluster) can count at p on the exact path, which
// has no stand-ins (conservative, as blocker_groups.rs's tests check): each sphere i lies
// within |cᵢ − c| + rᵢ ≤ extent of the centre and counts out to rᵢ / min_cap_ratio, and
// rᵢ ≤ stand_in_radius_m (at least the largest sphere's radius: src/shading/stand_in.rs);
// not wholly below the tangent plane, not empty.
fn group_in_influence(group: BlockerGroup, p: vec3<f32>, n: vec3<f32>) -> bool {
    let to_group = group.center_extent.xyz - p;
    let influence_m = group.center_extent.w + group.stand_in_radius_m / max(shadow.min_cap_ratio, 1e-30);
    return dot(to_group, to_group) <= influence_m * influence_m
        && dot(to_group, n) + group.center_extent.w > 0.0 && group.count > 0u;
}

// Where a stand-in starts taking over, as a share of the hand-over distance
// (blocker_groups::STAND_IN_BLEND_START).
const STAND_IN_BLEND_START: f32 = 0.75;

// How much of a group's (or a cluster's) shadow at p its stand-in carries
// (blocker_groups.rs): 0 within STAND_IN_BLEND_START of its hand-over distance, 1 beyond
// it, smoothly between, where its blockers are weighed 1 − share — so no ring shows
// where one takes over from the other.
fn stand_in_share(group: BlockerGroup, p: vec3<f32>) -> f32 {
    if group.stand_in_radius_m <= 0.0 {
        return 0.0;
    }
    return smoothstep(STAND_IN_BLEND_START * group.hand_over_m, group.hand_over_m, distance(group.center_extent.xyz, p));
}
