//! Culling groups for the shading pass: nearby spheres gathered into groups of at most
//! [`group_size`] by recursive median splits, each with a bounding radius and an influence
//! radius, so a receiver skips a whole group at once; and the groups into clusters of at
//! most [`CLUSTER_GROUPS`] (a two-level sphere hierarchy), so a receiver far from a
//! cluster skips its groups too.
//!
//! The exact path's group tests are conservative: a group is skipped only when every one
//! of its spheres would be (beyond its influence distance r/min_cap_ratio, or wholly below
//! the tangent plane), so culling never changes a pixel there. On the SH path a group's
//! spheres are skipped beyond its hand-over distance too, where its stand-in has taken
//! over. Far from a group its spheres are not simply dropped: one sphere at their centre stands
//! in for them (`stand_in_radius_m`, the area their projections cover together:
//! `shading::stand_in`), taking over smoothly between [`STAND_IN_BLEND_START`] of its
//! hand-over distance and that distance (no ring shows where it does), for as long as it is large enough in the
//! sky: many small blockers (a lattice's, a helix's) keep the far reaches of their soft
//! shadows, each of them alone too small to count. The hand-over comes where each sphere
//! alone stops counting, or sooner, at [`GROUP_HAND_OVER_CUTS`] times the distance at
//! which the group's bounding cap narrows to the cut angle below, where the order can no
//! longer tell its spheres apart.
//!
//! A cluster does the same one level up (Ren et al. 2006 cut their sphere tree where a
//! node's cap is under about 80°/order, the finest angle the order tells apart): one
//! sphere of its groups' stand-ins' summed area takes over from its groups and their
//! stand-ins between [`STAND_IN_BLEND_START`] of its hand-over distance and that
//! distance, the larger of where
//! the last of its groups' spheres is walked or stand-ins stops counting and twice where its
//! bounding cap narrows to 80°/order (`BlockerCluster::hand_over_m`). So beyond that
//! distance a receiver adds one cap for hundreds of spheres, and the walk's cost grows
//! with the clusters near a receiver, not with every group of the scene.

use glam::Vec3;

use super::stand_in::{joined_stand_in_radius_m, stand_in_depth, stand_in_radius_m};
use crate::blockers::Sphere;

/// Most spheres in one group: 8 up to 1,024 spheres, 16 above. Measured at the walk of
/// 2c4ec7e (docs/performance.md): the blocker bench's frame (`cargo bench --bench frame
/// -- frame/sphere-count`) at 20,000 spheres took 365–380 ms with 16, 507 with 8 and 342
/// with 32, at 600 spheres 106–111, 117 and 130 ms; but the large sample's 576 spheres
/// shade faster in groups of 8 (`render --time-frames`: its low-resolution shading 52.9
/// against 57.0 ms, its pixels shaded in full 119 against 133 ms), as do the studio's 51.
pub fn group_size(sphere_count: usize) -> usize {
    if sphere_count <= 1024 { 8 } else { 16 }
}

/// Most groups in one cluster: the bits of one walk's mask (WGSL `WALK_GROUPS`). With
/// 16, twice the clusters cost more than the smaller clusters saved (20,000 spheres:
/// 437 against 365 ms).
pub const CLUSTER_GROUPS: usize = 32;

/// A group's stand-in has taken over wholly at this many times the distance at which
/// its bounding cap narrows to the cut angle (it starts at [`STAND_IN_BLEND_START`] of
/// it). Measured with [`STAND_IN_BLEND_START`] (docs/performance.md, "The stand-ins take
/// over nearer"): 2 with the blend from a half gave the blocker bench a penumbra RMS of
/// 0.330 against exact visibility and the large sample 193 blockers visited per point;
/// 1.5 and a half 0.338 and 158; 1.25 from three quarters 0.338 and 133, and the large
/// sample's frame 17 % faster, the same against the path tracer; 1 from three quarters
/// 0.346 and 112.
pub const GROUP_HAND_OVER_CUTS: f32 = 1.25;

/// Where a stand-in starts taking over from its spheres, as a share of its hand-over
/// distance (WGSL `STAND_IN_BLEND_START`): wide enough a blend that no ring shows.
pub const STAND_IN_BLEND_START: f32 = 0.75;

/// Ren et al. 2006's cut angle for order n: a node whose cap is narrower than
/// 80°/n stands in for its children.
pub fn cut_half_angle_rad(order: usize) -> f32 {
    80f32.to_radians() / order.max(1) as f32
}

/// A group of consecutive spheres `first..first + count` of the reordered list.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BlockerGroup {
    pub center: Vec3,
    /// Every sphere lies within this distance of `center`: max |cᵢ − c| + rᵢ.
    pub extent_m: f32,
    /// A receiver farther than this from `center` is beyond every sphere's influence
    /// distance: max |cᵢ − c| + rᵢ / min_cap_ratio.
    pub influence_m: f32,
    /// The group's stand-in takes over from its spheres between [`STAND_IN_BLEND_START`]
    /// of this distance and
    /// this distance from `center`: the nearer of `influence_m` (where each sphere alone
    /// is too small to count) and [`GROUP_HAND_OVER_CUTS`] times the distance at which
    /// the group's bounding cap narrows to the cut angle.
    pub hand_over_m: f32,
    /// The radius of one sphere at `center` that stands in for the group's spheres far
    /// away: the area their projections cover together (`stand_in::stand_in_radius_m`;
    /// √Σ rᵢ² where none overlap). Groups hold spheres only: discs are shaded apart
    /// (`blockers::spheres_and_discs`).
    pub stand_in_radius_m: f32,
    /// Σ rᵢ² / R², R the stand-in's radius (≥ 1): how deep the spheres lie over each
    /// other on average, by which the stand-in's log-visibility is weighed, so that it
    /// keeps their summed log-visibility on the area they cover (`stand_in`).
    pub stand_in_depth: f32,
    pub first: usize,
    pub count: usize,
}

/// Consecutive groups `first_group..first_group + group_count`, at most
/// [`CLUSTER_GROUPS`], with one stand-in for all their spheres far away.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BlockerCluster {
    pub center: Vec3,
    /// Every sphere, and every group's stand-in sphere, lies within this distance of
    /// `center`.
    pub extent_m: f32,
    /// The cluster's stand-in takes over from its groups between [`STAND_IN_BLEND_START`]
    /// of this distance and
    /// this distance from `center`; a receiver farther away skips the groups. At least
    /// where every group's spheres and stand-in stop counting (so skipping them there
    /// changes nothing), and at least twice the distance at which the cluster's bounding
    /// cap narrows to the cut angle (so the stand-in starts where the order cannot tell
    /// it from its spheres).
    pub hand_over_m: f32,
    /// √Σ Rᵢ² over its groups' stand-in radii.
    pub stand_in_radius_m: f32,
    /// Σ rᵢ² / R² over its spheres, as a group's.
    pub stand_in_depth: f32,
    pub first_group: usize,
    pub group_count: usize,
}

/// The spheres reordered so that groups are contiguous, the groups (ordered so that
/// clusters are contiguous) and the clusters.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct GroupedBlockers {
    pub spheres: Vec<Sphere>,
    pub groups: Vec<BlockerGroup>,
    pub clusters: Vec<BlockerCluster>,
}

/// Groups and clusters `spheres` for a frame whose blockers under `min_cap_ratio` are
/// skipped and whose SH have `order` bands.
pub fn group_blockers(spheres: &[Sphere], min_cap_ratio: f32, order: usize) -> GroupedBlockers {
    let mut grouped = GroupedBlockers {
        spheres: spheres.to_vec(),
        ..GroupedBlockers::default()
    };
    let mut ordered = std::mem::take(&mut grouped.spheres);
    let grouping = Grouping {
        group_size: group_size(spheres.len()),
        min_cap_ratio,
        cut_sine: cut_half_angle_rad(order).sin(),
    };
    grouping.cluster(&mut ordered, 0, &mut grouped);
    grouped.spheres = ordered;
    grouped
}

/// How one set of spheres is split: the most spheres in a group, the influence cut-off
/// and the sine of the cut angle.
struct Grouping {
    group_size: usize,
    min_cap_ratio: f32,
    cut_sine: f32,
}

impl Grouping {
    /// How many groups `split` makes of `count` spheres.
    fn group_count(&self, count: usize) -> usize {
        if count <= self.group_size {
            1
        } else {
            self.group_count(count / 2) + self.group_count(count - count / 2)
        }
    }

    fn cluster(&self, spheres: &mut [Sphere], offset: usize, grouped: &mut GroupedBlockers) {
        if spheres.is_empty() {
            return;
        }
        if self.group_count(spheres.len()) <= CLUSTER_GROUPS {
            let first_group = grouped.groups.len();
            self.split(spheres, offset, &mut grouped.groups);
            let cluster = bound_cluster(spheres, &grouped.groups[first_group..], first_group, self);
            grouped.clusters.push(cluster);
            return;
        }
        let middle = split_at_median(spheres);
        let (left, right) = spheres.split_at_mut(middle);
        self.cluster(left, offset, grouped);
        self.cluster(right, offset + middle, grouped);
    }

    fn split(&self, spheres: &mut [Sphere], offset: usize, groups: &mut Vec<BlockerGroup>) {
        if spheres.is_empty() {
            return;
        }
        if spheres.len() <= self.group_size {
            groups.push(bound(spheres, offset, self.min_cap_ratio, self.cut_sine));
            return;
        }
        let middle = split_at_median(spheres);
        let (left, right) = spheres.split_at_mut(middle);
        self.split(left, offset, groups);
        self.split(right, offset + middle, groups);
    }
}

fn bound_cluster(
    spheres: &[Sphere],
    groups: &[BlockerGroup],
    first_group: usize,
    grouping: &Grouping,
) -> BlockerCluster {
    let Grouping {
        min_cap_ratio,
        cut_sine,
        ..
    } = *grouping;
    let center = spheres.iter().map(|s| s.center).sum::<Vec3>() / spheres.len() as f32;
    // Every sphere and every group's stand-in lies within it: the shader's window test
    // of a cluster stands for its groups' stand-ins too.
    let extent_m = spheres
        .iter()
        .map(|s| s.center.distance(center) + s.radius_m)
        .chain(groups.iter().map(|g| g.center.distance(center) + g.stand_in_radius_m))
        .fold(0.0, f32::max);
    // Where the last group's spheres or stand-in stops counting.
    let groups_reach_m = groups
        .iter()
        .map(|g| {
            let stand_in_reach = if min_cap_ratio > 0.0 {
                g.stand_in_radius_m / min_cap_ratio
            } else {
                f32::INFINITY
            };
            g.center.distance(center) + g.hand_over_m.max(stand_in_reach)
        })
        .fold(0.0, f32::max);
    let stand_in_radius_m = joined_stand_in_radius_m(groups.iter().map(|g| g.stand_in_radius_m));
    BlockerCluster {
        center,
        extent_m,
        hand_over_m: groups_reach_m.max(2.0 * extent_m / cut_sine.max(1e-6)),
        stand_in_radius_m,
        stand_in_depth: stand_in_depth(spheres, stand_in_radius_m),
        first_group,
        group_count: groups.len(),
    }
}

/// Reorders `spheres` about the median of their centres along the axis of widest
/// spread; returns the split index.
fn split_at_median(spheres: &mut [Sphere]) -> usize {
    let (lo, hi) = spheres
        .iter()
        .fold((Vec3::INFINITY, Vec3::NEG_INFINITY), |(lo, hi), s| {
            (lo.min(s.center), hi.max(s.center))
        });
    let extent = hi - lo;
    let axis = if extent.x >= extent.y && extent.x >= extent.z {
        0
    } else if extent.y >= extent.z {
        1
    } else {
        2
    };
    let middle = spheres.len() / 2;
    spheres.select_nth_unstable_by(middle, |a, b| a.center[axis].total_cmp(&b.center[axis]));
    middle
}

fn bound(spheres: &[Sphere], first: usize, min_cap_ratio: f32, cut_sine: f32) -> BlockerGroup {
    let center = spheres.iter().map(|s| s.center).sum::<Vec3>() / spheres.len() as f32;
    let reach = |s: &Sphere, radius: f32| s.center.distance(center) + radius;
    let extent_m = spheres.iter().map(|s| reach(s, s.radius_m)).fold(0.0, f32::max);
    let influence_m = if min_cap_ratio > 0.0 {
        spheres
            .iter()
            .map(|s| reach(s, s.radius_m / min_cap_ratio))
            .fold(0.0, f32::max)
    } else {
        f32::INFINITY
    };
    let stand_in_radius_m = stand_in_radius_m(spheres);
    BlockerGroup {
        center,
        extent_m,
        influence_m,
        hand_over_m: if spheres.len() > 1 {
            influence_m.min(GROUP_HAND_OVER_CUTS * extent_m / cut_sine.max(1e-6))
        } else {
            // One sphere is its own stand-in: nothing to hand over.
            influence_m
        },
        stand_in_radius_m,
        stand_in_depth: stand_in_depth(spheres, stand_in_radius_m),
        first,
        count: spheres.len(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn spheres(count: usize) -> Vec<Sphere> {
        (0..count)
            .map(|i| {
                let t = i as f32 * 0.37;
                Sphere {
                    center: Vec3::new(t.cos() * t, (1.3 * t).sin(), t * 0.2),
                    radius_m: 0.05 + 0.01 * (i % 7) as f32,
                    disc_normal: glam::Vec3::ZERO,
                }
            })
            .collect()
    }

    #[test]
    fn groups_cover_every_sphere_once_and_bound_them() {
        let input = spheres(203);
        let GroupedBlockers {
            spheres: ordered,
            groups,
            ..
        } = group_blockers(&input, 0.03, 4);
        assert_eq!(ordered.len(), input.len());
        assert_eq!(groups.iter().map(|g| g.count).sum::<usize>(), input.len());
        let mut next = 0;
        for g in &groups {
            assert_eq!(g.first, next);
            assert!(g.count <= group_size(input.len()) && g.count > 0);
            next += g.count;
            for s in &ordered[g.first..g.first + g.count] {
                assert!(s.center.distance(g.center) + s.radius_m <= g.extent_m + 1e-5);
                assert!(s.center.distance(g.center) + s.radius_m / 0.03 <= g.influence_m + 1e-3);
                assert!(s.radius_m <= g.stand_in_radius_m);
            }
            // The stand-in keeps the spheres' summed log-visibility: R² · depth = Σ r².
            let summed: f32 = ordered[g.first..g.first + g.count]
                .iter()
                .map(|s| s.radius_m * s.radius_m)
                .sum();
            let kept = g.stand_in_radius_m * g.stand_in_radius_m * g.stand_in_depth;
            assert!((kept - summed).abs() <= 1e-5 * summed, "{kept} against {summed}");
            // The stand-in has taken over where the spheres stop counting, or where the
            // group's cap is GROUP_HAND_OVER_CUTS times narrower than at the cut angle.
            let cut_sine = cut_half_angle_rad(4).sin();
            assert!(g.hand_over_m <= g.influence_m);
            assert!(g.hand_over_m <= GROUP_HAND_OVER_CUTS * g.extent_m / cut_sine * (1.0 + 1e-5));
        }
        let mut a: Vec<String> = input.iter().map(|s| format!("{s:?}")).collect();
        let mut b: Vec<String> = ordered.iter().map(|s| format!("{s:?}")).collect();
        a.sort();
        b.sort();
        assert_eq!(a, b);
    }

    #[test]
    fn clusters_cover_every_group_once_and_bound_their_spheres() {
        let input = spheres(5000);
        let grouped = group_blockers(&input, 0.03, 4);
        assert!(grouped.clusters.len() > 1);
        let cut_sine = cut_half_angle_rad(4).sin();
        let mut next = 0;
        for c in &grouped.clusters {
            assert_eq!(c.first_group, next);
            assert!(c.group_count <= CLUSTER_GROUPS && c.group_count > 0);
            next += c.group_count;
            let mut area = 0.0;
            for g in &grouped.groups[c.first_group..c.first_group + c.group_count] {
                // Beyond the hand-over distance no group's spheres are walked (its own
                // stand-in has taken over) and no group stand-in is large enough in the
                // sky to count.
                assert!(c.center.distance(g.center) + g.stand_in_radius_m / 0.03 <= c.hand_over_m * (1.0 + 1e-5));
                assert!(c.center.distance(g.center) + g.hand_over_m <= c.hand_over_m * (1.0 + 1e-5));
                assert!(c.center.distance(g.center) + g.stand_in_radius_m <= c.extent_m * (1.0 + 1e-5));
                for s in &grouped.spheres[g.first..g.first + g.count] {
                    assert!(s.center.distance(c.center) + s.radius_m <= c.extent_m * (1.0 + 1e-5));
                }
                area += g.stand_in_radius_m * g.stand_in_radius_m;
            }
            assert!((c.stand_in_radius_m - area.sqrt()).abs() <= 1e-4 * area.sqrt());
            // Where the stand-in starts, the cluster's cap is within the cut angle.
            assert!(c.extent_m / (STAND_IN_BLEND_START * c.hand_over_m) <= cut_sine * (1.0 + 1e-5));
        }
        assert_eq!(next, grouped.groups.len());
    }

    #[test]
    fn a_higher_order_hands_over_farther() {
        let input = spheres(3000);
        let (low, high) = (group_blockers(&input, 0.03, 2), group_blockers(&input, 0.03, 8));
        // The same spheres in the same groups, each handed over no nearer.
        assert_eq!(low.spheres, high.spheres);
        for (l, h) in low.groups.iter().zip(&high.groups) {
            assert_eq!((l.first, l.count, l.center), (h.first, h.count, h.center));
            assert!(h.hand_over_m >= l.hand_over_m);
        }
        for (l, h) in low.clusters.iter().zip(&high.clusters) {
            assert!(h.hand_over_m >= l.hand_over_m);
        }
        assert!(
            low.clusters
                .iter()
                .zip(&high.clusters)
                .any(|(l, h)| h.hand_over_m > l.hand_over_m)
        );
    }

    #[test]
    fn group_count_is_what_split_makes() {
        for count in [1, 7, 8, 9, 16, 17, 100, 255, 256, 257, 600, 20_000] {
            for group_size in [8, 16] {
                let grouping = Grouping {
                    group_size,
                    min_cap_ratio: 0.03,
                    cut_sine: 0.3,
                };
                let mut groups = Vec::new();
                grouping.split(&mut spheres(count), 0, &mut groups);
                assert_eq!(groups.len(), grouping.group_count(count), "{count} spheres");
                assert!(groups.iter().all(|g| g.count <= group_size));
            }
        }
    }

    #[test]
    fn no_spheres_no_groups() {
        let grouped = group_blockers(&[], 0.03, 4);
        assert!(grouped.groups.is_empty() && grouped.clusters.is_empty());
    }
}
