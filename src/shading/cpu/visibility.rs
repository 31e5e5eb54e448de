//! The shadowed side of the f64 shading twin: the blockers' and the terrain's
//! log-visibility, its means over a light's cap and the clamped cosine, and the exact
//! path's visibility of a small light (`logsh.wgsl`, `exact_lights.wgsl`).

use std::f64::consts::PI;

use glam::DVec3;

use super::surface::{Incidence, SurfacePoint};
use super::windows::LightWindows;
use crate::blockers::Sphere;
use crate::sh::{self, ExpMethod};
use crate::shading::ShadowSettings;
use crate::shading::blocker_groups::{
    BlockerCluster, BlockerGroup, GroupedBlockers, STAND_IN_BLEND_START, group_blockers,
};
use crate::shading::gpu_types::{GpuLight, SHADOW_PATH_EXACT};
use crate::terrain::TerrainShadow;

/// Log-visibility of `blockers` at `p` with normal `n` (`log_visibility` in logsh.wgsl):
/// per cluster its stand-in sphere weighed by its share at p and, within its hand-over
/// distance, the blockers of its groups in reach one by one, weighed 1 − their group's
/// stand-in share, and each group's stand-in weighed by that share, all weighed 1 − the
/// cluster's share (`shading::blocker_groups`).
pub fn log_visibility(settings: &ShadowSettings, blockers: &[Sphere], p: DVec3, n: DVec3) -> Vec<f64> {
    log_visibility_within(settings, blockers, p, n, None)
}

/// [`log_visibility`] with each cap weighed and scaled by the SH-path lights' `windows`
/// (`LightWindows::cap_scale`, in place of the cap-mass scale k(s)), or as it is with
/// None.
pub fn log_visibility_within(
    settings: &ShadowSettings,
    blockers: &[Sphere],
    p: DVec3,
    n: DVec3,
    windows: Option<&LightWindows>,
) -> Vec<f64> {
    log_visibilities_within(settings, blockers, p, n, &[windows])
        .pop()
        .expect("one reader, one log-visibility")
}

/// [`log_visibility_within`] for each of `readers` from one walk over the blockers, as
/// the shaders' walk fills each window's sum beside its own (`add_cap` in logsh.wgsl):
/// each cap's basis and zonal harmonics are evaluated once and added to every reader's
/// sum at that reader's scale, in the order and arithmetic one reader alone would use
/// (each sum is bit for bit [`log_visibility_within`]'s).
pub fn log_visibilities_within(
    settings: &ShadowSettings,
    blockers: &[Sphere],
    p: DVec3,
    n: DVec3,
    readers: &[Option<&LightWindows>],
) -> Vec<Vec<f64>> {
    let order = settings.order;
    let ln_epsilon = (settings.epsilon as f64).ln();
    let mass_scales = settings.cap_mass_table();
    let mut sums = vec![vec![0.0; order * order]; readers.len()];
    let mut scales = vec![0.0; readers.len()];
    let mut add_cap = |direction: DVec3, ratio: f64, horizon: f64, disc: Option<(DVec3, DVec3)>| {
        let k = sh::interpolate_cap_mass_scale(&mass_scales, ratio);
        let disc = disc.map(|(center, normal)| (center, normal, p));
        for (scale, windows) in scales.iter_mut().zip(readers) {
            let (mass_scale, window) = match windows {
                Some(windows) => (1.0, windows.disc_cap_scale(direction, ratio, k, disc)),
                None => (k, 1.0),
            };
            let horizon = horizon * window;
            *scale = if window <= 0.0 {
                0.0
            } else if settings.ratio_attenuation {
                ln_epsilon * horizon * ratio * mass_scale
            } else {
                ln_epsilon * horizon * mass_scale
            };
        }
        if scales.iter().all(|&scale| scale == 0.0) {
            return;
        }
        // Funk–Hecke: f_lm += scale·√(4π/(2l+1))·z_l·y_lm(d), without building the
        // rotated vector.
        with_basis(order, direction, |y| {
            sh::cap_zh_ratio_each(order, ratio, |l, z| {
                let band = (4.0 * PI / (2 * l + 1) as f64).sqrt();
                for (f, &scale) in sums.iter_mut().zip(&scales) {
                    if scale == 0.0 {
                        continue;
                    }
                    let weight = scale * band * z;
                    for i in l * l..(l + 1) * (l + 1) {
                        f[i] += weight * y[i];
                    }
                }
            });
        });
    };
    for_each_cap(settings, blockers, p, n, |direction, ratio, horizon, disc| {
        add_cap(direction, ratio, horizon, disc)
    });
    sums
}

/// Calls `add_cap(direction, ratio, horizon weight, disc)` for each blocker cap that shadows `p`
/// with normal `n` as logsh.wgsl's walk takes them: per cluster, its stand-in weighed by
/// its share at p and, within its hand-over distance, its groups as [`add_group_caps`]
/// takes them, weighed 1 − the cluster's share; then the discs. Returns how many
/// blockers the walk visits (every sphere of a group in reach, every stand-in it weighs,
/// every disc): the per-pixel work. `disc` is a disc blocker's centre and unit normal
/// (None for the spheres and stand-ins), which the lights' windows test
/// (`LightWindows::disc_cap_scale`).
fn for_each_cap(
    settings: &ShadowSettings,
    blockers: &[Sphere],
    p: DVec3,
    n: DVec3,
    mut add_cap: impl FnMut(DVec3, f64, f64, Option<(DVec3, DVec3)>),
) -> usize {
    let min_ratio = settings.min_cap_ratio as f64;
    with_groups(blockers, settings, |grouped, discs| {
        let mut walked = discs.len();
        let mut add_sphere_cap = |direction, ratio, horizon| add_cap(direction, ratio, horizon, None);
        for cluster in &grouped.clusters {
            let bounds = Bounds::of_cluster(cluster);
            let share = bounds.stand_in_share(p);
            if bounds.in_reach(p, n) && share < 1.0 {
                let groups = &grouped.groups[cluster.first_group..cluster.first_group + cluster.group_count];
                for group in groups {
                    walked += add_group_caps(
                        group,
                        &grouped.spheres,
                        min_ratio,
                        1.0 - share,
                        p,
                        n,
                        &mut add_sphere_cap,
                    );
                }
            }
            walked += bounds.add_stand_in(min_ratio, 1.0, p, n, &mut add_sphere_cap);
        }
        // The discs, at every receiver (`add_discs`).
        for disc in discs {
            if let Some(cap) = disc.cap_from(p, n, min_ratio) {
                let plane = (disc.center.as_dvec3(), disc.disc_normal.as_dvec3());
                add_cap(cap.direction, cap.ratio, cap.horizon, Some(plane));
            }
        }
        walked
    })
}

/// A group's caps at p (logsh.wgsl's `groups_to_walk` and walk): in reach, its spheres
/// weighed 1 − its stand-in's share, then the stand-in weighed by that share, all times
/// `weight`. Returns the blockers visited.
fn add_group_caps(
    group: &BlockerGroup,
    spheres: &[Sphere],
    min_ratio: f64,
    weight: f64,
    p: DVec3,
    n: DVec3,
    add_cap: &mut impl FnMut(DVec3, f64, f64),
) -> usize {
    let bounds = Bounds::of_group(group);
    let share = bounds.stand_in_share(p);
    let mut walked = 0;
    if bounds.in_reach(p, n) && share < 1.0 {
        walked += group.count;
        for cap in spheres[group.first..group.first + group.count]
            .iter()
            .filter_map(|b| b.cap_from(p, n, min_ratio))
        {
            add_cap(cap.direction, cap.ratio, cap.horizon * (1.0 - share) * weight);
        }
    }
    walked + bounds.add_stand_in(min_ratio, weight, p, n, add_cap)
}

/// A group's or a cluster's bounds and stand-in (WGSL `BlockerGroup`).
struct Bounds {
    center: glam::Vec3,
    extent_m: f32,
    hand_over_m: f32,
    stand_in_radius_m: f32,
    stand_in_depth: f32,
}

impl Bounds {
    fn of_group(group: &BlockerGroup) -> Bounds {
        Bounds {
            center: group.center,
            extent_m: group.extent_m,
            hand_over_m: group.hand_over_m,
            stand_in_radius_m: group.stand_in_radius_m,
            stand_in_depth: group.stand_in_depth,
        }
    }

    /// A cluster read as a group (as the shader's `groups` array holds it,
    /// `GpuBlockerGroup::cluster`).
    fn of_cluster(cluster: &BlockerCluster) -> Bounds {
        Bounds {
            center: cluster.center,
            extent_m: cluster.extent_m,
            hand_over_m: cluster.hand_over_m,
            stand_in_radius_m: cluster.stand_in_radius_m,
            stand_in_depth: cluster.stand_in_depth,
        }
    }

    /// `stand_in_share` in blockers.wgsl: 0 within [`STAND_IN_BLEND_START`] of the
    /// hand-over distance, 1 beyond it, smoothstep between.
    fn stand_in_share(&self, p: DVec3) -> f64 {
        if self.stand_in_radius_m <= 0.0 {
            return 0.0;
        }
        let hand_over = self.hand_over_m as f64;
        smoothstep(
            STAND_IN_BLEND_START as f64 * hand_over,
            hand_over,
            self.center.as_dvec3().distance(p),
        )
    }

    /// `group_in_reach`: within the hand-over distance and not wholly below the
    /// tangent plane.
    fn in_reach(&self, p: DVec3, n: DVec3) -> bool {
        let offset = self.center.as_dvec3() - p;
        let hand_over = self.hand_over_m as f64;
        offset.length_squared() <= hand_over * hand_over && offset.dot(n) + self.extent_m as f64 > 0.0
    }

    /// A stand-in's step of logsh.wgsl's walk (`stand_in_weighs`, `add_walked`): the
    /// stand-in's cap weighed by its share times `weight`, faded
    /// below the tangent plane over the extent. Returns 1 if it was added.
    fn add_stand_in(
        &self,
        min_ratio: f64,
        weight: f64,
        p: DVec3,
        n: DVec3,
        add_cap: &mut impl FnMut(DVec3, f64, f64),
    ) -> usize {
        let share = self.stand_in_share(p) * weight;
        let offset = self.center.as_dvec3() - p;
        let distance = offset.length();
        let ratio = self.stand_in_radius_m as f64 / distance.max(1e-300);
        let horizon = smoothstep(-1.0, 1.0, offset.dot(n) / (self.extent_m as f64).max(1e-30));
        if share > 0.0 && ratio >= min_ratio && horizon > 0.0 {
            add_cap(offset / distance, ratio, horizon * share * self.stand_in_depth as f64);
            1
        } else {
            0
        }
    }
}

fn smoothstep(edge0: f64, edge1: f64, x: f64) -> f64 {
    let t = ((x - edge0) / (edge1 - edge0)).clamp(0.0, 1.0);
    t * t * (3.0 - 2.0 * t)
}

/// What the SH walk of `blockers` costs a receiver at `p` with normal `n`, and what it
/// finds there: the blockers (spheres, group stand-ins, discs) it visits, and how many of
/// those shadow p (a cap above its horizon, as large in its sky as
/// `ShadowSettings::min_cap_ratio`).
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct BlockersInReach {
    pub walked: usize,
    pub shadowing: usize,
}

pub fn blockers_in_reach(settings: &ShadowSettings, blockers: &[Sphere], p: DVec3, n: DVec3) -> BlockersInReach {
    let mut shadowing = 0;
    let walked = for_each_cap(settings, blockers, p, n, |_, _, _, _| shadowing += 1);
    BlockersInReach { walked, shadowing }
}

/// Calls `f` with the spheres of `blockers` grouped and clustered as the GPU groups them
/// (`group_blockers`, for the settings' influence cut-off and order) and the discs (at
/// most `MAX_DISCS`, shaded apart), the split of the last blocker list kept per thread:
/// the twin shades pixel after pixel with one list.
fn with_groups<R>(
    blockers: &[Sphere],
    settings: &ShadowSettings,
    f: impl FnOnce(&GroupedBlockers, &[Sphere]) -> R,
) -> R {
    type Key = (Vec<Sphere>, u32, usize);
    thread_local! {
        static LAST: std::cell::RefCell<Option<(Key, GroupedBlockers, Vec<Sphere>)>> = const { std::cell::RefCell::new(None) };
    }
    LAST.with(|last| {
        let mut last = last.borrow_mut();
        let (min_cap_ratio, order) = (settings.min_cap_ratio, settings.order);
        let fresh = !matches!(&*last, Some(((input, ratio, o), ..)) if input.as_slice() == blockers && *ratio == min_cap_ratio.to_bits() && *o == order);
        if fresh {
            let (spheres, discs) = crate::blockers::spheres_and_discs(blockers);
            let grouped = group_blockers(&spheres, min_cap_ratio, order);
            *last = Some(((blockers.to_vec(), min_cap_ratio.to_bits(), order), grouped, discs));
        }
        let (_, grouped, discs) = last.as_ref().expect("just grouped");
        f(grouped, discs)
    })
}

/// The blockers' log-visibility plus, with a terrain, the terrain's (`log_visibility` in
/// logsh.wgsl, which adds `terrain_log_visibility`), the blockers' weighed by `windows`
/// when given (the terrain's never: its horizon is not a blocker's cap).
pub fn scene_log_visibility(
    settings: &ShadowSettings,
    blockers: &[Sphere],
    terrain: Option<&TerrainShadow>,
    p: DVec3,
    n: DVec3,
    windows: Option<&LightWindows>,
) -> Vec<f64> {
    scene_log_visibilities(settings, blockers, terrain, p, n, &[windows])
        .pop()
        .expect("one reader, one log-visibility")
}

/// [`scene_log_visibility`] for each of `readers` from one walk over the blockers
/// ([`log_visibilities_within`]), the terrain's added to each.
pub fn scene_log_visibilities(
    settings: &ShadowSettings,
    blockers: &[Sphere],
    terrain: Option<&TerrainShadow>,
    p: DVec3,
    n: DVec3,
    readers: &[Option<&LightWindows>],
) -> Vec<Vec<f64>> {
    let mut sums = log_visibilities_within(settings, blockers, p, n, readers);
    if let Some(terrain) = terrain {
        let ln_epsilon = (settings.epsilon as f64).ln();
        let horizon = terrain.log_visibility(p, ln_epsilon);
        for f in &mut sums {
            for (a, b) in f.iter_mut().zip(&horizon) {
                *a += b;
            }
        }
    }
    sums
}

/// The SH basis at unit `d`: the unrolled polynomials up to order 4 (as the shaders
/// evaluate it), the general recurrence above.
fn basis(order: usize, d: DVec3) -> Vec<f64> {
    with_basis(order, d, <[f64]>::to_vec)
}

/// Calls `f` with the n² basis values at unit `d`, on the stack up to order 4 (the shading
/// loops call this per blocker and per light).
fn with_basis<R>(order: usize, d: DVec3, f: impl FnOnce(&[f64]) -> R) -> R {
    if order <= 4 {
        f(&sh::basis16(d.normalize_or(DVec3::Z))[..order * order])
    } else {
        f(&sh::basis(order, d))
    }
}

/// Mean of the visibility SH `g` over a cap of sin(half-angle) `cap_ratio` around `d`.
pub fn visibility_toward(g: &[f64], d: DVec3, cap_ratio: f64) -> f64 {
    let order = sh::order_of(g.len()).unwrap_or(0);
    let s = cap_ratio.clamp(0.0, 1.0);
    if s == 0.0 {
        // A point: every band's weight is 1, V̄ = G(d).
        return with_basis(order, d, |y| g.iter().zip(y).map(|(a, b)| a * b).sum());
    }
    let y = basis(order, d);
    let c = (1.0 - s * s).max(0.0).sqrt();
    let dp = sh::legendre_derivative(order, c);
    (0..order)
        .map(|l| {
            let w = if l == 0 {
                1.0
            } else {
                (1.0 + c) * dp[l] / (l * (l + 1)) as f64
            };
            w * (l * l..(l + 1) * (l + 1)).map(|i| g[i] * y[i]).sum::<f64>()
        })
        .sum()
}

/// Clamped-cosine average of `g` about `n`: ⟨G, max(n·ω, 0)/π⟩ (1 when unoccluded).
pub fn visibility_cosine(g: &[f64], n: DVec3) -> f64 {
    let order = sh::order_of(g.len()).unwrap_or(0);
    let cosine = sh::rotate_zh(&sh::phong_lobe_zh(order, 1.0), n);
    g.iter().zip(cosine).map(|(a, b)| a * b).sum()
}

/// The visibility of `light`, seen as `inc` from `s`, when it is on the exact path
/// (`GpuLight::shadow_path`, which `shading::shading_lights` sets): `crate::penumbra` times
/// the share of its disc above the terrain's horizon. None when it takes the SH path.
/// `pixel_footprint_m` anti-aliases hard blocker edges (`penumbra::light_visibility`; 0:
/// none).
pub fn exact_visibility(
    s: &SurfacePoint,
    light: &GpuLight,
    inc: &Incidence,
    settings: &ShadowSettings,
    blockers: &[Sphere],
    terrain: Option<&TerrainShadow>,
    pixel_footprint_m: f64,
) -> Option<f64> {
    (light.shadow_path == SHADOW_PATH_EXACT).then(|| {
        let above_terrain = terrain.map_or(1.0, |t| t.light_visibility(s.position, inc.to_light, inc.cap_ratio));
        let light = crate::penumbra::LightDisc {
            to_light: inc.to_light,
            distance_m: inc.distance_m,
            cap_ratio: inc.cap_ratio,
            emitter: super::area::emitter(light),
        };
        let min_cap_ratio = settings.min_cap_ratio as f64;
        // The spheres in the GPU's order: their union is taken in order (penumbra::union).
        with_groups(blockers, settings, |grouped, discs| {
            above_terrain
                * crate::penumbra::light_visibility(
                    s.position,
                    s.normal,
                    &light,
                    &grouped.spheres,
                    discs,
                    min_cap_ratio,
                    pixel_footprint_m,
                )
        })
    })
}

/// exp* as the GPU evaluates it: HYB's carried magnitude capped where f32 stops (see
/// `wgsl_sh::F32_MAX_EXPONENT`); every other method as in `sh::exp`.
pub(super) fn exp_for_shading(method: ExpMethod, f: &[f64]) -> Vec<f64> {
    let g = sh::exp(method, f);
    if method != ExpMethod::Hyb {
        return g;
    }
    let cap = crate::shading::wgsl::sh::F32_MAX_EXPONENT.exp();
    let norm = g.iter().map(|v| v * v).sum::<f64>().sqrt();
    if norm > cap {
        g.into_iter().map(|v| v * cap / norm).collect()
    } else {
        g
    }
}
