//! Blockers for meshes the solid fit cannot serve — open surfaces and meshes thinner than
//! a voxel (walls, floors, shelves, cards, lattices, thin tubes) — fitted to the surface
//! instead of the solid.
//!
//! The surface is sampled by area ([`SurfaceSamples`]) and clustered by k-means. A cluster
//! whose triangles face one way (the dominant eigenvalue of Σ a·n nᵀ holds
//! `PLANAR_SHARE` of the area) becomes a disc in its mean plane, of the radius of a
//! uniform disc with the same in-plane second moment (r² = 2(λ₁ + λ₂) of the points'
//! covariance), so a quad's disc covers about the quad and both faces of a thin shelf
//! count once. Any other cluster (a piece of a tube, of a lattice) becomes a sphere of its
//! mean projected area: by Cauchy's formula a closed convex surface of area A shows A/4
//! on average over directions, so πr² = A/4, bounded by the cluster's own spread
//! r² ≤ tr(covariance).
//!
//! How well a set fits is measured on what shadows need: the silhouettes of the mesh and
//! of the blockers in [`SILHOUETTE_DIRECTIONS`] directions ([`Silhouettes`]), the error
//! being |mesh △ blockers| / |mesh| summed over them. The number of blockers climbs the
//! same ladder as the solid fit's until that error is within budget or stops improving.

use std::collections::HashMap;
use std::sync::{Mutex, OnceLock};

use glam::{Vec2, Vec3};

use super::{BlockerSettings, K_LADDER, Sphere, SphereBudget, SphereSet};
use crate::random::SplitMix64;
use crate::scene::MeshObject;

/// Points sampled on a mesh's surface for clustering.
pub const SURFACE_SAMPLES: usize = 8192;
/// Share of a cluster's area that must face one way (up to sign) for a disc.
const PLANAR_SHARE: f32 = 0.75;
/// Directions the silhouettes are compared in (spread over a hemisphere: a silhouette
/// seen from −d is the mirror of the one from d).
pub const SILHOUETTE_DIRECTIONS: usize = 16;
/// Pixels along each side of a silhouette raster.
const SILHOUETTE_PIXELS: usize = 64;

/// The surface fit of `object`, cached like the solid fits; None when the
/// mesh has no area.
pub(super) fn fit_mesh(object: &MeshObject, settings: &BlockerSettings) -> Option<SphereSet> {
    let cache_key = {
        let mut hasher = blake3::Hasher::new();
        hasher.update(b"surface");
        hasher.update(bytemuck::cast_slice(&object.positions));
        hasher.update(bytemuck::cast_slice(&object.indices));
        hasher.update(format!("{:?} {}", settings.budget, settings.max_spheres_per_mesh).as_bytes());
        hasher.finalize()
    };
    static CACHE: OnceLock<Mutex<HashMap<blake3::Hash, Option<SphereSet>>>> = OnceLock::new();
    let cache = CACHE.get_or_init(Default::default);
    if let Some(hit) = cache.lock().unwrap_or_else(|e| e.into_inner()).get(&cache_key) {
        return hit.clone();
    }
    let set = fit_mesh_uncached(object, settings);
    cache
        .lock()
        .unwrap_or_else(|e| e.into_inner())
        .insert(cache_key, set.clone());
    set
}

fn fit_mesh_uncached(object: &MeshObject, settings: &BlockerSettings) -> Option<SphereSet> {
    let samples = SurfaceSamples::of_mesh(&object.positions, &object.indices, SURFACE_SAMPLES);
    if samples.points.is_empty() {
        return None;
    }
    let silhouettes = Silhouettes::of_mesh(&object.positions, &object.indices);
    let budget = match settings.budget {
        SphereBudget::FitError(budget) => budget,
        SphereBudget::Total(_) => match BlockerSettings::default().budget {
            SphereBudget::FitError(budget) => budget,
            SphereBudget::Total(_) => 0.35,
        },
    };
    let mut best: Option<(Vec<Sphere>, f32)> = None;
    let mut steps_without_gain = 0;
    for k in K_LADDER
        .into_iter()
        .filter(|&k| k <= settings.max_spheres_per_mesh.max(1))
    {
        let blockers = fit_k(&samples, k);
        let error = silhouettes.error(&blockers);
        let best_error = best.as_ref().map_or(f32::INFINITY, |(_, e)| *e);
        steps_without_gain = if error < best_error { 0 } else { steps_without_gain + 1 };
        if error < best_error && !blockers.is_empty() {
            best = Some((blockers, error));
        }
        if error <= budget || steps_without_gain >= 3 {
            break;
        }
    }
    let (spheres, fit_error) = best?;
    Some(SphereSet {
        spheres,
        fit_error,
        skipped: None,
        on_surface: true,
    })
}

/// Points on a mesh's surface, uniform by area, each with its triangle's unit normal.
#[derive(Debug, Clone, Default)]
pub struct SurfaceSamples {
    pub points: Vec<Vec3>,
    pub normals: Vec<Vec3>,
    /// Surface area each point stands for, m².
    pub area_each_m2: f32,
}

impl SurfaceSamples {
    /// About `count` points placed by systematic sampling of the cumulative area (a fixed
    /// seed places them within their triangles). Degenerate and non-finite triangles are
    /// left out.
    pub fn of_mesh(positions: &[Vec3], indices: &[u32], count: usize) -> SurfaceSamples {
        let triangles: Vec<[Vec3; 3]> = indices
            .chunks_exact(3)
            .filter_map(|t| {
                let [a, b, c] = [t[0], t[1], t[2]].map(|i| positions.get(i as usize).copied());
                let tri = [a?, b?, c?];
                tri.iter().all(|v| v.is_finite()).then_some(tri)
            })
            .collect();
        let areas: Vec<f64> = triangles
            .iter()
            .map(|[a, b, c]| 0.5 * (*b - *a).cross(*c - *a).length() as f64)
            .collect();
        let total: f64 = areas.iter().sum();
        if !(total > 0.0 && total.is_finite()) || count == 0 {
            return SurfaceSamples::default();
        }
        let step = total / count as f64;
        let mut random = SplitMix64(0x005e_ed0f_5a3f_ace5 ^ triangles.len() as u64);
        let mut samples = SurfaceSamples {
            area_each_m2: step as f32,
            ..Default::default()
        };
        // The next sample sits at `next` along the cumulative area.
        let (mut before, mut next) = (0.0f64, 0.5 * step);
        for (tri, &area) in triangles.iter().zip(&areas) {
            if area <= 0.0 {
                continue;
            }
            let [a, b, c] = *tri;
            let normal = (b - a).cross(c - a).normalize_or_zero();
            while next < before + area {
                let (mut u, mut v) = (random.next_f64() as f32, random.next_f64() as f32);
                if u + v > 1.0 {
                    (u, v) = (1.0 - u, 1.0 - v);
                }
                samples.points.push(a + u * (b - a) + v * (c - a));
                samples.normals.push(normal);
                next += step;
            }
            before += area;
        }
        samples
    }
}

/// The blockers of `k` clusters of `samples` (fewer if there are fewer points).
pub fn fit_k(samples: &SurfaceSamples, k: usize) -> Vec<Sphere> {
    let centres = super::fit::k_means(&samples.points, k.min(samples.points.len()));
    let mut members: Vec<Vec<usize>> = vec![Vec::new(); centres.len()];
    for (i, p) in samples.points.iter().enumerate() {
        members[super::fit::nearest(&centres, *p)].push(i);
    }
    members
        .iter()
        .filter(|m| !m.is_empty())
        .filter_map(|m| cluster_blocker(samples, m))
        .collect()
}

/// One cluster's disc or sphere (see the module's documentation).
fn cluster_blocker(samples: &SurfaceSamples, members: &[usize]) -> Option<Sphere> {
    let count = members.len() as f32;
    let center = members.iter().map(|&i| samples.points[i]).sum::<Vec3>() / count;
    let covariance = members.iter().fold(glam::Mat3::ZERO, |m, &i| {
        let d = samples.points[i] - center;
        m + outer(d, d)
    }) * (1.0 / count);
    let normals = members.iter().fold(glam::Mat3::ZERO, |m, &i| {
        m + outer(samples.normals[i], samples.normals[i])
    }) * (1.0 / count);
    let (facing, share) = dominant_eigen(normals);
    let spread2 = covariance.x_axis.x + covariance.y_axis.y + covariance.z_axis.z;
    if share >= PLANAR_SHARE {
        // In-plane second moment: the trace less the part along the normal.
        let in_plane2 = (spread2 - facing.dot(covariance * facing)).max(0.0);
        let radius = (2.0 * in_plane2).sqrt();
        return (radius > 0.0 && radius.is_finite()).then(|| Sphere::disc(center, radius, facing));
    }
    let area = count * samples.area_each_m2;
    let radius = (area / (4.0 * std::f32::consts::PI)).min(spread2).sqrt();
    (radius > 0.0 && radius.is_finite()).then(|| Sphere::ball(center, radius))
}

fn outer(a: Vec3, b: Vec3) -> glam::Mat3 {
    glam::Mat3::from_cols(a * b.x, a * b.y, a * b.z)
}

/// The unit eigenvector of the largest eigenvalue of symmetric positive semi-definite
/// `m` (by power iteration), and that eigenvalue's share of the trace.
fn dominant_eigen(m: glam::Mat3) -> (Vec3, f32) {
    let trace = m.x_axis.x + m.y_axis.y + m.z_axis.z;
    if trace <= 0.0 {
        return (Vec3::Y, 0.0);
    }
    // Start from the column of largest norm, which is never orthogonal to the dominant
    // eigenvector of a PSD matrix.
    let mut v = [m.x_axis, m.y_axis, m.z_axis]
        .into_iter()
        .max_by(|a, b| a.length_squared().total_cmp(&b.length_squared()))
        .unwrap_or(Vec3::Y)
        .normalize_or(Vec3::Y);
    for _ in 0..64 {
        v = (m * v).normalize_or(v);
    }
    (v, v.dot(m * v) / trace)
}

/// Silhouettes of a mesh seen along [`SILHOUETTE_DIRECTIONS`] directions, rasterised over
/// its bounding sphere, against which blocker sets are compared.
pub struct Silhouettes {
    center: Vec3,
    half_extent_m: f32,
    /// Per direction: (u, v, d) orthonormal, d the direction of view.
    frames: Vec<[Vec3; 3]>,
    /// Per direction, covered pixels of the mesh, row-major.
    mesh: Vec<Vec<bool>>,
    mesh_pixels: usize,
}

impl Silhouettes {
    pub fn of_mesh(positions: &[Vec3], indices: &[u32]) -> Silhouettes {
        let bounds = crate::scene::Aabb::from_points(positions);
        let (center, half_extent_m) = if bounds.is_empty() {
            (Vec3::ZERO, 1.0)
        } else {
            (bounds.center(), bounds.radius().max(1e-6))
        };
        let frames = hemisphere_frames(SILHOUETTE_DIRECTIONS);
        let mut silhouettes = Silhouettes {
            center,
            half_extent_m,
            frames,
            mesh: Vec::new(),
            mesh_pixels: 0,
        };
        let mesh: Vec<Vec<bool>> = (0..silhouettes.frames.len())
            .map(|f| silhouettes.rasterise_mesh(f, positions, indices))
            .collect();
        silhouettes.mesh_pixels = mesh.iter().map(|m| m.iter().filter(|&&c| c).count()).sum();
        silhouettes.mesh = mesh;
        silhouettes
    }

    /// Pixel coordinates (continuous, pixel centres at +0.5) of world point `p` in frame f.
    fn project(&self, f: usize, p: Vec3) -> Vec2 {
        let [u, v, _] = self.frames[f];
        let scale = SILHOUETTE_PIXELS as f32 / (2.0 * self.half_extent_m);
        let q = p - self.center;
        Vec2::new(q.dot(u), q.dot(v)) * scale + Vec2::splat(SILHOUETTE_PIXELS as f32 / 2.0)
    }

    /// World point of pixel centre (i, j) in frame f, on the plane through the centre.
    fn unproject(&self, f: usize, i: usize, j: usize) -> Vec3 {
        let [u, v, _] = self.frames[f];
        let scale = 2.0 * self.half_extent_m / SILHOUETTE_PIXELS as f32;
        let half = SILHOUETTE_PIXELS as f32 / 2.0;
        self.center + u * ((i as f32 + 0.5 - half) * scale) + v * ((j as f32 + 0.5 - half) * scale)
    }

    fn rasterise_mesh(&self, f: usize, positions: &[Vec3], indices: &[u32]) -> Vec<bool> {
        let mut covered = vec![false; SILHOUETTE_PIXELS * SILHOUETTE_PIXELS];
        for t in indices.chunks_exact(3) {
            let [a, b, c] = [t[0], t[1], t[2]].map(|i| positions.get(i as usize).copied());
            let (Some(a), Some(b), Some(c)) = (a, b, c) else {
                continue;
            };
            let [a, b, c] = [a, b, c].map(|p| self.project(f, p));
            if !(a.is_finite() && b.is_finite() && c.is_finite()) {
                continue;
            }
            let edge = |p: Vec2, q: Vec2, x: Vec2| (q - p).perp_dot(x - p);
            let area = edge(a, b, c);
            if area == 0.0 {
                continue;
            }
            let (lo, hi) = (a.min(b).min(c), a.max(b).max(c));
            let (i0, j0) = (
                (lo.x - 0.5).ceil().max(0.0) as usize,
                (lo.y - 0.5).ceil().max(0.0) as usize,
            );
            let last = SILHOUETTE_PIXELS as f32 - 1.0;
            let (i1, j1) = ((hi.x - 0.5).floor().min(last), (hi.y - 0.5).floor().min(last));
            if i1 < 0.0 || j1 < 0.0 {
                continue;
            }
            for j in j0..=(j1 as usize) {
                for i in i0..=(i1 as usize) {
                    let x = Vec2::new(i as f32 + 0.5, j as f32 + 0.5);
                    let w = [edge(b, c, x), edge(c, a, x), edge(a, b, x)].map(|e| e * area.signum());
                    if w.iter().all(|&e| e >= 0.0) {
                        covered[j * SILHOUETTE_PIXELS + i] = true;
                    }
                }
            }
        }
        covered
    }

    /// Σ over directions of |mesh △ blockers| / Σ |mesh|, in pixels of the rasters.
    pub fn error(&self, blockers: &[Sphere]) -> f32 {
        if self.mesh_pixels == 0 {
            return if blockers.is_empty() { 0.0 } else { f32::INFINITY };
        }
        let mut mismatched = 0usize;
        for (f, mesh) in self.mesh.iter().enumerate() {
            let covered = self.rasterise_blockers(f, blockers);
            mismatched += mesh.iter().zip(&covered).filter(|(a, b)| a != b).count();
        }
        mismatched as f32 / self.mesh_pixels as f32
    }

    fn rasterise_blockers(&self, f: usize, blockers: &[Sphere]) -> Vec<bool> {
        let mut covered = vec![false; SILHOUETTE_PIXELS * SILHOUETTE_PIXELS];
        let scale = SILHOUETTE_PIXELS as f32 / (2.0 * self.half_extent_m);
        let view = self.frames[f][2];
        for b in blockers {
            let c = self.project(f, b.center);
            let reach = b.radius_m * scale;
            let last = SILHOUETTE_PIXELS as f32 - 1.0;
            let (i0, j0) = ((c.x - reach - 0.5).ceil().max(0.0), (c.y - reach - 0.5).ceil().max(0.0));
            let (i1, j1) = (
                (c.x + reach - 0.5).floor().min(last),
                (c.y + reach - 0.5).floor().min(last),
            );
            if i1 < i0 || j1 < j0 || !(i0.is_finite() && j1.is_finite()) {
                continue;
            }
            let facing = b.disc_normal.dot(view);
            for j in (j0 as usize)..=(j1 as usize) {
                for i in (i0 as usize)..=(i1 as usize) {
                    let inside = if b.is_disc() {
                        // Where the line of sight through the pixel meets the disc's plane.
                        let q = self.unproject(f, i, j);
                        facing.abs() > 1e-6 && {
                            let hit = q + view * ((b.center - q).dot(b.disc_normal) / facing);
                            hit.distance_squared(b.center) <= b.radius_m * b.radius_m
                        }
                    } else {
                        let x = Vec2::new(i as f32 + 0.5, j as f32 + 0.5);
                        x.distance_squared(c) <= reach * reach
                    };
                    covered[j * SILHOUETTE_PIXELS + i] |= inside;
                }
            }
        }
        covered
    }
}

/// `count` orthonormal frames whose third axes spread over the upper (+y) hemisphere by a
/// Fibonacci spiral.
fn hemisphere_frames(count: usize) -> Vec<[Vec3; 3]> {
    let golden = std::f32::consts::PI * (3.0 - 5f32.sqrt());
    (0..count)
        .map(|k| {
            let z = 1.0 - (k as f32 + 0.5) / count as f32;
            let r = (1.0 - z * z).max(0.0).sqrt();
            let phi = golden * k as f32;
            let d = Vec3::new(r * phi.cos(), z, r * phi.sin());
            let (u, v) = d.any_orthonormal_pair();
            [u, v, d]
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::shapes;
    use glam::{Affine3A, DVec3, Quat};

    fn fit(mesh: &shapes::ShapeMesh, k: usize) -> (Vec<Sphere>, f32) {
        let samples = SurfaceSamples::of_mesh(&mesh.positions, &mesh.indices, SURFACE_SAMPLES);
        let blockers = fit_k(&samples, k);
        let error = Silhouettes::of_mesh(&mesh.positions, &mesh.indices).error(&blockers);
        (blockers, error)
    }

    #[test]
    fn samples_cover_the_surface_uniformly_by_area() {
        // A 2 m × 1 m quad beside a 1 m × 1 m one: two thirds of the points on the first.
        let wide = shapes::plane(1.0, 1, 1.0).transformed(Affine3A::from_scale(Vec3::new(2.0, 1.0, 1.0)));
        let small = shapes::plane(1.0, 1, 1.0).transformed(Affine3A::from_translation(Vec3::new(5.0, 0.0, 0.0)));
        let mesh = wide.merged(small);
        let samples = SurfaceSamples::of_mesh(&mesh.positions, &mesh.indices, 3000);
        let on_wide = samples.points.iter().filter(|p| p.x < 2.5).count();
        assert!(
            (samples.points.len() as i64 - 3000).abs() <= 1,
            "{}",
            samples.points.len()
        );
        assert!((on_wide as f32 / 3000.0 - 2.0 / 3.0).abs() < 0.01, "{on_wide}");
        assert!((samples.area_each_m2 * samples.points.len() as f32 - 3.0).abs() < 0.01);
    }

    #[test]
    fn a_tilted_card_is_a_disc_of_its_area_in_its_plane() {
        let tilt = Quat::from_rotation_x(0.5);
        let card = shapes::plane(0.8, 1, 1.0).transformed(Affine3A::from_rotation_translation(tilt, Vec3::Y));
        let (blockers, error) = fit(&card, 1);
        assert_eq!(blockers.len(), 1);
        let disc = blockers[0];
        assert!(disc.is_disc(), "{disc:?}");
        assert!(disc.center.distance(Vec3::Y) < 0.02, "{disc:?}");
        assert!(disc.disc_normal.dot(tilt * Vec3::Y).abs() > 0.999, "{disc:?}");
        // A uniform square of side a has the in-plane second moment of a disc of radius
        // a/√3, whose area is within 5 % of the square's.
        assert!((disc.radius_m - 0.8 / 3f32.sqrt()).abs() < 0.01, "{disc:?}");
        // The disc misses the corners and overhangs the sides: about 0.1 of the silhouette.
        assert!(error < 0.2, "{error}");
    }

    #[test]
    fn both_faces_of_a_thin_shelf_make_one_disc_of_the_shelf_not_two() {
        let shelf = shapes::cuboid(Vec3::new(0.5, 0.01, 0.5));
        let (blockers, _) = fit(&shelf, 1);
        let disc = blockers[0];
        assert!(disc.is_disc() && disc.disc_normal.y.abs() > 0.99, "{disc:?}");
        assert!((disc.radius_m - 1.0 / 3f32.sqrt()).abs() < 0.02, "{disc:?}");
    }

    #[test]
    fn a_thin_tube_becomes_spheres_of_its_mean_projected_area() {
        // A 1 m tube of radius 1 cm: its side shows 2ρL = 0.02 m² face on and, by Cauchy's
        // formula, a quarter of its area, πρL/2 ≈ 0.0157 m², on average.
        let tube = shapes::cylinder(0.01, 1.0, 12);
        let (blockers, _) = fit(&tube, 8);
        assert_eq!(blockers.len(), 8);
        assert!(blockers.iter().all(|b| !b.is_disc()), "{blockers:?}");
        let projected: f32 = blockers
            .iter()
            .map(|b| std::f32::consts::PI * b.radius_m * b.radius_m)
            .sum();
        let mean_projected = std::f32::consts::PI * 0.01 * 1.0 / 2.0;
        assert!(
            (projected / mean_projected - 1.0).abs() < 0.15,
            "{projected} against {mean_projected}"
        );
        for b in &blockers {
            assert!(
                b.center.x.hypot(b.center.z) < 0.011 && (0.0..=1.0).contains(&b.center.y),
                "{b:?}"
            );
        }
    }

    #[test]
    fn more_blockers_follow_a_long_wall_better() {
        let wall = shapes::plane(1.0, 1, 1.0).transformed(Affine3A::from_scale(Vec3::new(6.0, 1.0, 1.0)));
        let (_, one) = fit(&wall, 1);
        let (six, many) = fit(&wall, 6);
        assert!(many < 0.5 * one, "{one} → {many}");
        assert!(six.iter().all(|b| b.is_disc() && b.disc_normal.y.abs() > 0.999));
    }

    #[test]
    fn a_disc_is_seen_as_the_cap_of_its_solid_angle() {
        let disc = Sphere::disc(Vec3::new(0.0, 2.0, 0.0), 0.5, Vec3::Y);
        let up = DVec3::Y;
        // On its axis at height h the disc subtends 2π(1 − h/√(h² + r²)), a cap of that sine.
        let cap = disc.cap_from(DVec3::ZERO, up, 0.0).expect("seen");
        let expected_sine = 0.5 / (2.0f64 * 2.0 + 0.25).sqrt();
        // The square of the disc's area stands for it near by: within 1 %.
        assert!((cap.ratio / expected_sine - 1.0).abs() < 0.01, "{cap:?}");
        assert!((cap.direction - up).length() < 1e-9, "{cap:?}");
        assert!((cap.horizon - 1.0).abs() < 1e-12);
        // Far away and seen at 60° from its normal, its solid angle πr²·cos θ/d².
        let from = DVec3::new(0.0, 2.0, 0.0) - DVec3::new(0.0, 0.5, 3f64.sqrt() / 2.0) * 200.0;
        let cap = disc.cap_from(from, DVec3::Z, 0.0).expect("seen");
        let solid_angle = 2.0 * std::f64::consts::PI * (1.0 - (1.0 - cap.ratio * cap.ratio).sqrt());
        let expected = std::f64::consts::PI * 0.25 * 0.5 / (200.0f64 * 200.0);
        assert!((solid_angle / expected - 1.0).abs() < 1e-3, "{solid_angle} {expected}");
        // A receiver in the disc's plane (its own patch of a floor) sees nothing of it.
        assert!(disc.cap_from(DVec3::new(3.0, 2.0, 0.0), up, 1e-4).is_none());
    }

    #[test]
    fn eigen_of_a_diagonal_matrix() {
        let (v, share) = dominant_eigen(glam::Mat3::from_diagonal(Vec3::new(0.1, 0.7, 0.2)));
        assert!(v.y.abs() > 0.9999 && (share - 0.7).abs() < 1e-5, "{v} {share}");
    }
}
