//! How far a level of detail lies from its mesh, measured rather than estimated.
//!
//! A level is a subset of the mesh's triangles re-joined over a subset of its vertices
//! (`detail_levels`): no vertex moves, so the two surfaces part only between the level's
//! vertices. The deviation kept for a level is the larger of two one-sided distances,
//! each taken as the largest over sample points of the distance to the nearest triangle
//! of the other surface (a sampled two-sided Hausdorff distance):
//! - the mesh's vertices (those the level dropped stand where the mesh bulges out of, or
//!   dips into, the level's faces) to the level's triangles;
//! - each level triangle's centroid and edge midpoints (where a flat face spanning a
//!   curved stretch of the mesh lies deepest inside or farthest outside it) to the
//!   mesh's triangles.
//!
//! The simplifier's own estimate (meshoptimizer's quadric error, chained from level to
//! level) is no bound: on a 128 × 64 uv sphere and a 96 × 48 torus its deeper levels
//! lay two to three times nearer than it said, so far objects were drawn a level finer
//! than their pixels needed, and a 320 × 160 sphere's first level four times farther (a
//! sliver). Nearest triangles are found in a bounding volume hierarchy of each surface
//! (obvhs) with a box around the point that grows until it holds a triangle nearer than
//! the box's half-width; a point that a triangle within the running largest distance
//! already serves ends its search at the first such triangle.

use glam::{Vec3, Vec3A};
use obvhs::aabb::Aabb;
use obvhs::bvh2::Bvh2;
use obvhs::triangle::Triangle;

/// The triangles of one surface, for nearest-triangle queries.
pub(crate) struct TriangleSet {
    triangles: Vec<[Vec3; 3]>,
    bvh: Bvh2,
}

impl TriangleSet {
    /// The triangles of the list `indices` over `positions` (indices checked by the caller).
    pub(crate) fn new(positions: &[Vec3], indices: &[u32]) -> TriangleSet {
        let triangles: Vec<[Vec3; 3]> = indices
            .chunks_exact(3)
            .map(|t| [t[0], t[1], t[2]].map(|i| positions[i as usize]))
            .collect();
        let for_bvh: Vec<Triangle> = triangles
            .iter()
            .map(|[a, b, c]| Triangle {
                v0: Vec3A::from(*a),
                v1: Vec3A::from(*b),
                v2: Vec3A::from(*c),
            })
            .collect();
        // The builder reports its time here; it is not read.
        let mut build_time = std::time::Duration::ZERO;
        let bvh = obvhs::bvh2::builder::build_bvh2_from_tris(
            &for_bvh,
            obvhs::BvhBuildParams::very_fast_build(),
            &mut build_time,
        );
        TriangleSet { triangles, bvh }
    }

    /// Visits the triangles whose bounds meet the cube of half-width `reach` around p
    /// until `visit` returns false.
    fn visit_near(&self, p: Vec3, reach: f32, mut visit: impl FnMut(&[Vec3; 3]) -> bool) {
        let around = Aabb::new(
            Vec3A::from(p) - Vec3A::splat(reach),
            Vec3A::from(p) + Vec3A::splat(reach),
        );
        self.bvh.aabb_traverse(around, |bvh, node_index| {
            let node = &bvh.nodes[node_index as usize];
            let first = node.first_index as usize;
            (first..first + node.prim_count as usize)
                .all(|slot| visit(&self.triangles[bvh.primitive_indices[slot] as usize]))
        });
    }

    /// Whether some triangle lies within `distance` of p.
    fn has_within(&self, p: Vec3, distance: f32) -> bool {
        let mut found = false;
        self.visit_near(p, distance, |[a, b, c]| {
            found = point_triangle_distance(p, *a, *b, *c) <= distance;
            !found
        });
        found
    }

    /// The distance from p to the nearest triangle, searching boxes from half-width
    /// `first_reach` up, doubling, to `max_reach`; None when none lies within it.
    fn nearest_distance(&self, p: Vec3, first_reach: f32, max_reach: f32) -> Option<f32> {
        let mut reach = first_reach;
        loop {
            let mut nearest = f32::INFINITY;
            self.visit_near(p, reach, |[a, b, c]| {
                nearest = nearest.min(point_triangle_distance(p, *a, *b, *c));
                true
            });
            // A triangle beyond the box may be nearer than one found in it but outside
            // the ball of radius `reach`: only one within that ball is surely the nearest.
            if nearest <= reach {
                return Some(nearest);
            }
            if reach >= max_reach {
                return None;
            }
            reach = (2.0 * reach).min(max_reach);
        }
    }

    /// The largest distance from any of `points` to its nearest triangle (0 for no
    /// points), or None where some point has none within `max_reach`. `first_reach`
    /// seeds each search (a small share of the expected distance).
    fn farthest_of(&self, points: impl Iterator<Item = Vec3>, first_reach: f32, max_reach: f32) -> Option<f32> {
        let mut farthest = 0.0f32;
        for p in points {
            if farthest > 0.0 && self.has_within(p, farthest) {
                continue;
            }
            farthest = farthest.max(self.nearest_distance(p, first_reach.max(farthest), max_reach)?);
        }
        Some(farthest)
    }
}

/// The sampled two-sided distance (module comment) between `mesh` — the triangle list
/// `mesh_indices` over `positions` — and the level `level_indices` over the same
/// positions, each point's search starting at `first_reach` (metres; about the distance
/// expected); None where a point has no triangle of the other surface within
/// `max_reach`. Of the mesh's vertices only those the level dropped are looked up: the
/// ones it keeps lie on it.
pub(crate) fn level_deviation_m(
    mesh: &TriangleSet,
    positions: &[Vec3],
    [mesh_indices, level_indices]: [&[u32]; 2],
    [first_reach, max_reach]: [f32; 2],
) -> Option<f32> {
    let level = TriangleSet::new(positions, level_indices);
    let dropped = dropped_vertices(positions.len(), mesh_indices, level_indices);
    let outward = level.farthest_of(dropped.iter().map(|&i| positions[i]), first_reach, max_reach)?;
    let face_points = level
        .triangles
        .iter()
        .flat_map(|[a, b, c]| [(*a + *b + *c) / 3.0, 0.5 * (*a + *b), 0.5 * (*b + *c), 0.5 * (*c + *a)]);
    let inward = mesh.farthest_of(face_points, first_reach, max_reach)?;
    Some(outward.max(inward))
}

/// The vertices (of `vertex_count`) that `mesh_indices` uses and `level_indices` does not.
fn dropped_vertices(vertex_count: usize, mesh_indices: &[u32], level_indices: &[u32]) -> Vec<usize> {
    let mut in_mesh = vec![false; vertex_count];
    for &i in mesh_indices {
        in_mesh[i as usize] = true;
    }
    for &i in level_indices {
        in_mesh[i as usize] = false;
    }
    (0..vertex_count).filter(|&i| in_mesh[i]).collect()
}

/// The distance from p to the triangle (a, b, c): to its nearest point, found by the
/// Voronoi region of the triangle's vertices, edges or face that p projects into
/// (Ericson 2005, "Real-Time Collision Detection", §5.1.5).
pub(crate) fn point_triangle_distance(p: Vec3, a: Vec3, b: Vec3, c: Vec3) -> f32 {
    let (ab, ac, ap) = (b - a, c - a, p - a);
    let (d1, d2) = (ab.dot(ap), ac.dot(ap));
    if d1 <= 0.0 && d2 <= 0.0 {
        return p.distance(a);
    }
    let bp = p - b;
    let (d3, d4) = (ab.dot(bp), ac.dot(bp));
    if d3 >= 0.0 && d4 <= d3 {
        return p.distance(b);
    }
    let vc = d1 * d4 - d3 * d2;
    if vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0 {
        return p.distance(a + ab * (d1 / (d1 - d3)));
    }
    let cp = p - c;
    let (d5, d6) = (ab.dot(cp), ac.dot(cp));
    if d6 >= 0.0 && d5 <= d6 {
        return p.distance(c);
    }
    let vb = d5 * d2 - d1 * d6;
    if vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0 {
        return p.distance(a + ac * (d2 / (d2 - d6)));
    }
    let va = d3 * d6 - d5 * d4;
    if va <= 0.0 && d4 - d3 >= 0.0 && d5 - d6 >= 0.0 {
        return p.distance(b + (c - b) * ((d4 - d3) / ((d4 - d3) + (d5 - d6))));
    }
    let sum = va + vb + vc;
    if sum == 0.0 || !sum.is_finite() {
        // A degenerate triangle: its nearest point lies on one of its edges.
        return segment_distance(p, a, b)
            .min(segment_distance(p, b, c))
            .min(segment_distance(p, c, a));
    }
    p.distance(a + ab * (vb / sum) + ac * (vc / sum))
}

fn segment_distance(p: Vec3, a: Vec3, b: Vec3) -> f32 {
    let ab = b - a;
    let t = if ab.length_squared() > 0.0 {
        ((p - a).dot(ab) / ab.length_squared()).clamp(0.0, 1.0)
    } else {
        0.0
    };
    p.distance(a + ab * t)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::detail_levels::DetailLevels;
    use crate::scene::shapes;

    /// The distance to a triangle's nearest point by brute force over a fine grid of its
    /// barycentric points (an upper bound that approaches the distance).
    fn sampled_distance(p: Vec3, a: Vec3, b: Vec3, c: Vec3) -> f32 {
        const STEPS: u32 = 200;
        let mut nearest = f32::INFINITY;
        for i in 0..=STEPS {
            for j in 0..=STEPS - i {
                let (u, v) = (i as f32 / STEPS as f32, j as f32 / STEPS as f32);
                nearest = nearest.min(p.distance(a + (b - a) * u + (c - a) * v));
            }
        }
        nearest
    }

    #[test]
    fn a_points_distance_to_a_triangle_is_that_of_its_nearest_point() {
        let (a, b, c) = (Vec3::ZERO, Vec3::new(2.0, 0.0, 0.0), Vec3::new(0.5, 1.5, 0.0));
        // Above the face, beside each edge, past each corner, in the plane and off it.
        let points = [
            Vec3::new(0.6, 0.4, 0.7),
            Vec3::new(1.0, -0.8, 0.3),
            Vec3::new(1.6, 1.0, -0.2),
            Vec3::new(-0.5, 0.7, 0.0),
            Vec3::new(-1.0, -1.0, 1.0),
            Vec3::new(3.0, -0.2, 0.4),
            Vec3::new(0.4, 2.5, -1.0),
            Vec3::new(0.9, 0.3, 0.0),
        ];
        for p in points {
            let exact = point_triangle_distance(p, a, b, c);
            let sampled = sampled_distance(p, a, b, c);
            // The grid's spacing (2 m / 200) bounds how far its nearest point lies from
            // the true one.
            assert!(
                exact <= sampled + 1e-6 && sampled - exact < 0.011,
                "{p}: {exact} against {sampled}"
            );
        }
        // Degenerate triangles: a segment and a point.
        let p = Vec3::new(1.0, 1.0, 0.0);
        assert!((point_triangle_distance(p, a, b, b) - 1.0).abs() < 1e-6);
        assert!((point_triangle_distance(p, a, a, a) - 2f32.sqrt()).abs() < 1e-6);
    }

    #[test]
    fn the_nearest_triangle_found_in_the_hierarchy_is_the_nearest_of_all() {
        let mesh = shapes::torus(1.0, 0.3, 48, 24);
        let set = TriangleSet::new(&mesh.positions, &mesh.indices);
        // Points on a lattice through and around the torus.
        for i in 0..400 {
            let p = Vec3::new(
                (i % 7) as f32 * 0.5 - 1.5,
                (i / 7 % 5) as f32 * 0.3 - 0.6,
                (i / 35) as f32 * 0.3 - 1.6,
            );
            let brute = set
                .triangles
                .iter()
                .map(|[a, b, c]| point_triangle_distance(p, *a, *b, *c))
                .fold(f32::INFINITY, f32::min);
            let found = set.nearest_distance(p, 1e-3, 10.0).expect("within 10 m");
            assert_eq!(found, brute, "{p}");
            assert!(set.has_within(p, brute + 1e-6) && (brute < 1e-6 || !set.has_within(p, 0.999 * brute)));
        }
    }

    /// A level's faces sampled at 28 points each (a barycentric grid of step 1/6) and the
    /// mesh's vertices, against the level's measured deviation from its centroids and
    /// edge midpoints: the sparse points find the dense ones' largest distance to within
    /// a tenth, on a sphere and a torus.
    #[test]
    fn a_levels_centroids_and_midpoints_find_its_faces_farthest_points() {
        for mesh in [shapes::uv_sphere(1.0, 96, 48), shapes::torus(1.0, 0.3, 96, 48)] {
            let levels = DetailLevels::of_mesh(&mesh.positions, &mesh.indices);
            assert!(levels.levels.len() >= 4);
            let set = TriangleSet::new(&mesh.positions, &mesh.indices);
            for level in &levels.levels[1..4] {
                let list = &levels.indices[level.indices.start as usize..level.indices.end as usize];
                let measured =
                    level_deviation_m(&set, &mesh.positions, [&mesh.indices, list], [1e-4, 1.0]).expect("measured");
                let level_set = TriangleSet::new(&mesh.positions, list);
                // Every vertex of the mesh, kept by the level or not.
                let outward = level_set
                    .farthest_of(mesh.positions.iter().copied(), 1e-4, 1.0)
                    .expect("outward");
                let dense_points = list.chunks_exact(3).flat_map(|t| {
                    let [a, b, c] = [t[0], t[1], t[2]].map(|i| mesh.positions[i as usize]);
                    (0..=6u32).flat_map(move |i| {
                        (0..=6 - i).map(move |j| a + (b - a) * (i as f32 / 6.0) + (c - a) * (j as f32 / 6.0))
                    })
                });
                let dense = set.farthest_of(dense_points, 1e-4, 1.0).expect("inward").max(outward);
                assert!(
                    measured <= dense * 1.0001 && measured >= 0.9 * dense,
                    "{} triangles: {measured} m against {dense} m sampled densely",
                    list.len() / 3
                );
                assert!(measured <= level.error_m);
            }
        }
    }
}
