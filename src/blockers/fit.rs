//! Fitting a set of spheres to a voxelised solid: Lloyd's k-means on the inside cell
//! centres (deterministic k-means++ seeding), one sphere per cluster centred at the
//! cluster's mean, its radius the one that covers the most cells of its own cluster for
//! the fewest cells outside the solid (weighed double; cells of other clusters are neutral, so spheres do
//! not stack). The fit error is the volume where the solid and the union of
//! spheres disagree, relative to the solid's volume (0 = perfect; measured on the grid).

use glam::{IVec3, Vec3};

use super::Sphere;
use super::voxel::VoxelGrid;
use crate::random::SplitMix64;

/// Lloyd iterations per fit; the cell centres of a solid converge well before this.
const LLOYD_ITERATIONS: usize = 24;
/// Most cell centres k-means clusters (a regular subsample of the inside cells).
const KMEANS_SAMPLE_LIMIT: usize = 20_000;

/// Spheres fitted to `grid` with `k` clusters of its `inside` cells (fewer if the solid has
/// fewer cells, or a cluster's sphere would cover more outside than inside), and their
/// fit error.
pub fn fit_k(grid: &VoxelGrid, inside: &[IVec3], k: usize) -> (Vec<Sphere>, f32) {
    let points: Vec<Vec3> = inside.iter().map(|&c| grid.center(c)).collect();
    // Clustering a regular subsample gives the same centres at a fraction of the cost.
    let stride = points.len().div_ceil(KMEANS_SAMPLE_LIMIT).max(1);
    let sample: Vec<Vec3> = points.iter().step_by(stride).copied().collect();
    let centres = k_means(&sample, k.min(sample.len()));
    // Cluster of every cell: -1 outside the solid.
    let mut cluster = vec![-1i32; grid.cell_count()];
    let mut counts = vec![0usize; centres.len()];
    for (&cell, &p) in inside.iter().zip(&points) {
        let q = nearest(&centres, p);
        cluster[grid.flat(cell)] = q as i32;
        counts[q] += 1;
    }
    let spheres: Vec<Sphere> = centres
        .iter()
        .enumerate()
        .filter_map(|(q, &center)| {
            let volume_radius = (3.0 * counts[q] as f32 * grid.cell_volume_m3() / (4.0 * std::f32::consts::PI)).cbrt();
            // Beyond the grid (the mesh's bounds plus a cell) every cell would be outside.
            let to_grid_edge = (center - grid.origin)
                .min(grid.origin + grid.dims.as_vec3() * grid.cell_m - center)
                .min_element();
            let max_radius = (3.0 * volume_radius).min(to_grid_edge);
            best_radius(grid, &cluster, q as i32, center, max_radius).map(|radius_m| Sphere {
                center,
                radius_m,
                disc_normal: glam::Vec3::ZERO,
            })
        })
        .collect();
    let error = fit_error(grid, inside.len(), &spheres);
    (spheres, error)
}

/// The radius up to `max_radius` that best trades the cells a sphere at `center` covers:
/// +1 for each cell of its own cluster, 0 for cells of other clusters (already served; no
/// stacking), −2 for each cell outside the solid. None if no radius gains anything.
fn best_radius(grid: &VoxelGrid, cluster: &[i32], own: i32, center: Vec3, max_radius: f32) -> Option<f32> {
    let lo = grid.cell_of(center - Vec3::splat(max_radius)).max(IVec3::ZERO);
    let hi = grid
        .cell_of(center + Vec3::splat(max_radius))
        .min(grid.dims - IVec3::ONE);
    let mut scored: Vec<(f32, i32)> = Vec::new();
    for i in lo.x..=hi.x {
        for j in lo.y..=hi.y {
            for k in lo.z..=hi.z {
                let cell = IVec3::new(i, j, k);
                let distance = grid.center(cell).distance(center);
                if distance > max_radius {
                    continue;
                }
                let label = cluster[grid.flat(cell)];
                // Outside cells weigh double: a sphere poking out of its mesh shadows the
                // mesh's own surface where nothing is.
                let score = if label == own {
                    1
                } else if label < 0 {
                    -2
                } else {
                    0
                };
                scored.push((distance, score));
            }
        }
    }
    scored.sort_by(|a, b| a.0.total_cmp(&b.0));
    let (mut sum, mut best) = (0, (0, 0.0f32));
    for (distance, score) in scored {
        sum += score;
        if sum > best.0 {
            best = (sum, distance);
        }
    }
    // Cover the last counted cell centre, not just touch it.
    (best.0 > 0).then_some(best.1 + 1e-3 * grid.cell_m)
}

/// |solid △ union of spheres| / |solid|, counted in grid cells.
pub fn fit_error(grid: &VoxelGrid, inside_count: usize, spheres: &[Sphere]) -> f32 {
    if inside_count == 0 {
        return if spheres.is_empty() { 0.0 } else { f32::INFINITY };
    }
    let covered = |p: Vec3| {
        spheres
            .iter()
            .any(|s| s.center.distance_squared(p) <= s.radius_m * s.radius_m)
    };
    let mismatched = grid
        .cells()
        .filter(|&cell: &IVec3| grid.is_inside(cell) != covered(grid.center(cell)))
        .count();
    mismatched as f32 / inside_count as f32
}

pub(super) fn nearest(centres: &[Vec3], p: Vec3) -> usize {
    let mut best = (0, f32::INFINITY);
    for (i, c) in centres.iter().enumerate() {
        let d = c.distance_squared(p);
        if d < best.1 {
            best = (i, d);
        }
    }
    best.0
}

/// k-means++ seeding with a fixed-seed generator, then Lloyd iterations.
pub(super) fn k_means(points: &[Vec3], k: usize) -> Vec<Vec3> {
    if k == 0 || points.is_empty() {
        return Vec::new();
    }
    let mut random = SplitMix64(0x9e37_79b9_7f4a_7c15 ^ points.len() as u64 ^ ((k as u64) << 32));
    let mut centres = vec![points[random.below(points.len())]];
    let mut distance2: Vec<f32> = points.iter().map(|p| p.distance_squared(centres[0])).collect();
    while centres.len() < k {
        let total: f64 = distance2.iter().map(|&d| d as f64).sum();
        if total <= 0.0 {
            break;
        }
        let mut target = random.next_f64() * total;
        let mut chosen = points.len() - 1;
        for (i, &d) in distance2.iter().enumerate() {
            target -= d as f64;
            if target <= 0.0 {
                chosen = i;
                break;
            }
        }
        let c = points[chosen];
        centres.push(c);
        for (d, p) in distance2.iter_mut().zip(points) {
            *d = d.min(p.distance_squared(c));
        }
    }
    for _ in 0..LLOYD_ITERATIONS {
        let mut sums = vec![(Vec3::ZERO, 0usize); centres.len()];
        for p in points {
            let slot = &mut sums[nearest(&centres, *p)];
            slot.0 += *p;
            slot.1 += 1;
        }
        let mut moved = false;
        for (c, (sum, count)) in centres.iter_mut().zip(sums) {
            if count > 0 {
                let mean = sum / count as f32;
                moved |= mean.distance_squared(*c) > 1e-12;
                *c = mean;
            }
        }
        if !moved {
            break;
        }
    }
    centres
}
