//! Levels of detail of a mesh: simplified triangle lists over the mesh's own vertices, so
//! that everything stored per vertex (normals, uvs, the baked indirect light, per-vertex
//! visibility) stays valid at every level, and the level drawn for a view is chosen by
//! how far its surface may lie from the mesh's, in pixels.
//!
//! Each level is an edge-collapse simplification of the level before (Garland and Heckbert
//! 1997, "Surface simplification using quadric error metrics", with collapses onto an
//! edge's end so that no vertex moves: meshoptimizer's `meshopt_simplify`, asked for
//! evener triangles with `RegularizeLight`), with open borders locked (a card's outline,
//! a lattice's holes, a uv seam stay where they are). Its error is the largest distance
//! between the level's surface and the mesh's, in metres, measured at the mesh's
//! vertices and the level's face centres and edge midpoints (`level_deviation.rs`).
//! The simplifier's own estimate is no bound: on a 320 × 160 uv sphere the first level
//! left a sliver 1.9 mm off the mesh where twice the estimate said 0.49 mm, while deeper
//! levels lay two to three times nearer than their chained estimates said.
//!
//! Choosing a level ([`DetailLevels::level_for`]): the coarsest whose error, seen from
//! the camera at the nearest point of the object's bounds, is within
//! [`MAX_ERROR_PX`], and whose longest edge is no longer than the mesh's own or within
//! [`MAX_EDGE_PX`] — so a finely tessellated floor, flat and simplified to a few long
//! triangles without error, keeps vertices for its per-vertex light to be interpolated
//! between. Where the frame interpolates nothing across the mesh's triangles that varies
//! from vertex to vertex ([`VertexValues::Uniform`]: one normal over each connected
//! piece, no texture, no baked light), a level within the error bound draws the same
//! surface whatever its edges' length, and the edge rule is left out. The shadow maps
//! draw the meshes as they are; so do per-vertex shading and the heat map, whose values
//! live at the vertices.

use std::ops::Range;

use glam::Vec3;

use super::Aabb;
use super::level_deviation::{TriangleSet, level_deviation_m};

/// The farthest, in pixels, a drawn level's surface may lie from the mesh's (measured):
/// a fifth of a pixel. The large sample at 960 × 540 draws 333,956 of its 954,656
/// triangles (390,800 at a quarter of a pixel of the estimated errors before, 287,632 at a
/// quarter of the measured ones); against the path tracer (`render --reference --spp 64
/// --bounces 0` at 960 × 540, frames `--no-baked-indirect`) relative L1 0.0467 against
/// 0.0468 before. tests/detail_levels.rs holds a far sphere's silhouette and normals to
/// ray casts: at a fifth its normals lie within 2.5° of the true sphere's, at a quarter
/// of the measured errors 7.1° (a coarser level meets the rays past the rim elsewhere
/// than the sphere does). The interior draws 116,000 triangles instead of 164,384; the
/// lamp room, studio and sample as many as before (their shadow maps' texels bind
/// first). The shadow maps bound it too ([`MAX_SHADOW_TEXEL_SHARE`]); docs/performance.md.
pub const MAX_ERROR_PX: f32 = 0.2;

/// The longest edge, in pixels, a drawn level may have where it is longer than the mesh's
/// own longest edge. A flat floor tessellated for its per-vertex light (the baked indirect
/// light) simplifies without error to a few long triangles, which would interpolate that
/// light over metres; here its triangles stay within 64 pixels. The large sample's columns,
/// whose sides simplify to edges their height long, kept their finer levels at 8, 16 and
/// 32 pixels (708k, 668k and 585k of its 955k triangles drawn against 484k at 64, with
/// levels simplified from the whole mesh). Not applied where nothing varies at the
/// mesh's vertices ([`VertexValues::Uniform`]).
pub const MAX_EDGE_PX: f32 = 64.0;

/// The widest turn, in radians, between two vertex normals of one triangle of a mesh
/// whose normals count as one ([`VertexValues::of`]): 1 mrad (0.06°), a normal
/// written to a file in single precision and read back turns by far less.
pub const MAX_UNIFORM_NORMAL_TURN_RAD: f32 = 1e-3;

/// What a level's triangles interpolate across the mesh besides its positions: what
/// decides whether [`MAX_EDGE_PX`] bounds the level drawn ([`DetailLevels::level_for`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum VertexValues {
    /// Values that change from vertex to vertex: baked light, uvs a texture reads,
    /// normals that turn. A long edge would interpolate them over metres.
    Varying,
    /// Nothing that changes within a connected piece of the mesh: its vertices' normals
    /// are one (a vertex shared by two triangles has one normal, so a triangle whose
    /// corners' normals agree passes it on to its neighbours), no texture is read, no
    /// baked light. Any triangle over the mesh's vertices within the error bound
    /// interpolates what the mesh's own triangles do.
    Uniform,
}

impl VertexValues {
    /// For a mesh whose triangles' corner normals turn by at most
    /// `widest_normal_turn_rad` (`shading::vertex_lighting::MeshFineness`), `textured`
    /// (its material reads a base colour texture through its uvs), with `baked_light`
    /// (the frame reads baked indirect light at its vertices).
    pub fn of(widest_normal_turn_rad: f32, textured: bool, baked_light: bool) -> VertexValues {
        // NaN turns (a normal of no length) count as varying.
        let one_normal = widest_normal_turn_rad <= MAX_UNIFORM_NORMAL_TURN_RAD;
        if one_normal && !textured && !baked_light {
            VertexValues::Uniform
        } else {
            VertexValues::Varying
        }
    }
}

/// The share of the finest shadow-map texel on an object its level may lie from the
/// mesh. The maps are drawn from the meshes as they are, so a level lying inside its
/// mesh by ε would shadow itself were the receiver not pushed out: shadow_lookup.wgsl
/// pushes it a quarter of a texel t along its normal and (1 + 2 tan θ) t toward the light
/// (θ the light's incidence), whose part along the normal is (cos θ + 2 sin θ) t ≥ t:
/// 1.25 t in all, against which ε ≤ t leaves a quarter of a texel to spare. (Measured
/// on tests/detail_levels.rs' sphere with no bound at all and a lamp 1.6 m from its
/// centre: 4 pixels more than 8/255 from the whole mesh's frame.)
pub const MAX_SHADOW_TEXEL_SHARE: f32 = 1.0;

/// The simplifier's error is an estimate from its quadrics, which a level's measured
/// deviation (level_deviation) replaces: twice it, chained from level to level, seeds
/// the search for that.
const ERROR_ESTIMATE_SCALE: f32 = 2.0;

/// The least reach of that search, as a share of the mesh's extent (a level simplified
/// without error, such as a flat floor's, is measured to within rounding).
const MIN_REACH_SHARE: f32 = 1e-4;

/// Meshes with fewer triangles are drawn as they are.
pub const MIN_SIMPLIFIED_TRIANGLES: usize = 512;

/// Levels stop when one would keep more than this share of the previous level's triangles
/// (the locked borders, or the error, left little to collapse) or fewer than
/// [`MIN_LEVEL_TRIANGLES`].
const MIN_REDUCTION: f32 = 0.8;
const MIN_LEVEL_TRIANGLES: usize = 32;

/// One level: its triangles' indices in [`DetailLevels::indices`], the largest distance
/// of its surface from the mesh's, and its longest edge.
#[derive(Debug, Clone, PartialEq)]
pub struct DetailLevel {
    pub indices: Range<u32>,
    pub error_m: f32,
    pub longest_edge_m: f32,
}

/// The levels of one mesh, finest (the mesh itself, error 0) first; their triangle lists
/// one after another in `indices`.
#[derive(Debug, Clone, PartialEq)]
pub struct DetailLevels {
    pub indices: Vec<u32>,
    pub levels: Vec<DetailLevel>,
}

impl DetailLevels {
    /// The levels of the triangle list `indices` over `positions`: the mesh alone when it
    /// has fewer than [`MIN_SIMPLIFIED_TRIANGLES`] triangles, a position that is not
    /// finite or an index past `positions` (which the simplifier must never see).
    pub fn of_mesh(positions: &[Vec3], indices: &[u32]) -> DetailLevels {
        let mut levels = DetailLevels {
            indices: indices.to_vec(),
            levels: vec![DetailLevel {
                indices: 0..indices.len() as u32,
                error_m: 0.0,
                longest_edge_m: longest_edge_m(positions, indices),
            }],
        };
        let triangles = indices.len() / 3;
        let valid = indices.len().is_multiple_of(3)
            && indices.iter().all(|&i| (i as usize) < positions.len())
            && positions.iter().all(|p| p.is_finite());
        if triangles < MIN_SIMPLIFIED_TRIANGLES || !valid {
            return levels;
        }
        let Ok(vertices) = meshopt::VertexDataAdapter::new(bytemuck::cast_slice(positions), 12, 0) else {
            return levels;
        };
        // Each level simplifies the last one, so the work shrinks by half a level (about
        // twice the mesh's own in all, however many levels). Its deviation from the mesh
        // is measured (level_deviation), each point's search seeded with the
        // simplifier's estimate chained from level to level (the last one's plus its own).
        let mesh = TriangleSet::new(positions, indices);
        let mesh_extent_m = extent_m(positions, indices);
        let least_reach_m = MIN_REACH_SHARE * mesh_extent_m;
        let mut chained_error_m = 0.0f32;
        let mut current = indices.to_vec();
        let mut options = meshopt::SimplifyOptions::LockBorder
            | meshopt::SimplifyOptions::ErrorAbsolute
            | meshopt::SimplifyOptions::RegularizeLight;
        loop {
            let previous = current.len() / 3;
            let mut error_m = 0.0f32;
            let simplified = meshopt::simplify(
                &current,
                &vertices,
                3 * (previous / 2),
                f32::MAX,
                options,
                Some(&mut error_m),
            );
            let kept = simplified.len() / 3;
            if kept < MIN_LEVEL_TRIANGLES || kept as f32 > MIN_REDUCTION * previous as f32 || !error_m.is_finite() {
                break;
            }
            chained_error_m += ERROR_ESTIMATE_SCALE * error_m;
            // Unmeasured within the mesh's extent: never drawn.
            let reach_m = [chained_error_m.max(least_reach_m), mesh_extent_m.max(least_reach_m)];
            let measured_m =
                level_deviation_m(&mesh, positions, [indices, &simplified], reach_m).unwrap_or(f32::INFINITY);
            let first = levels.indices.len() as u32;
            levels.indices.extend_from_slice(&simplified);
            let last_error_m = levels.levels.last().map_or(0.0, |l| l.error_m);
            levels.levels.push(DetailLevel {
                indices: first..levels.indices.len() as u32,
                // Kept non-decreasing: a coarser level never counts as nearer the mesh.
                error_m: measured_m.max(last_error_m),
                longest_edge_m: longest_edge_m(positions, &simplified),
            });
            current = simplified;
            // Later levels use a shrinking subset of the vertices.
            options |= meshopt::SimplifyOptions::Sparse;
        }
        levels
    }

    /// The index of the level to draw for an object whose nearest point lies
    /// `distance_m` from the eye, where one pixel spans `pixel_m_per_m` metres per metre
    /// of distance (2 tan(yfov/2) / height in pixels): the coarsest within
    /// [`MAX_ERROR_PX`], within `max_error_m` (what the shadow maps drawn from the meshes
    /// allow: [`MAX_SHADOW_TEXEL_SHARE`]) and, where the mesh's `values` vary, the edge
    /// rule above; the mesh itself at or behind the eye.
    pub fn level_for(&self, distance_m: f32, pixel_m_per_m: f32, max_error_m: f32, values: VertexValues) -> usize {
        let pixel_m = distance_m * pixel_m_per_m;
        if pixel_m.is_nan() || pixel_m <= 0.0 {
            return 0;
        }
        let own_edge_m = self.levels[0].longest_edge_m;
        let error_m = (MAX_ERROR_PX * pixel_m).min(max_error_m);
        self.levels
            .iter()
            .rposition(|level| {
                level.error_m <= error_m
                    && (values == VertexValues::Uniform
                        || level.longest_edge_m <= own_edge_m
                        || level.longest_edge_m <= MAX_EDGE_PX * pixel_m)
            })
            .unwrap_or(0)
    }
}

/// The diagonal of the bounding box of the vertices the triangle list `indices` over
/// `positions` uses, in metres (0 for none).
fn extent_m(positions: &[Vec3], indices: &[u32]) -> f32 {
    let bounds = indices
        .iter()
        .fold(Aabb::EMPTY, |bounds, &i| bounds.including(positions[i as usize]));
    2.0 * bounds.radius()
}

/// The longest edge of the triangle list `indices` over `positions` (triangles with an
/// index past `positions` left out).
fn longest_edge_m(positions: &[Vec3], indices: &[u32]) -> f32 {
    indices
        .chunks_exact(3)
        .filter_map(|t| {
            let [a, b, c] = [t[0], t[1], t[2]].map(|i| positions.get(i as usize).copied());
            let (a, b, c) = (a?, b?, c?);
            Some(a.distance(b).max(b.distance(c)).max(c.distance(a)))
        })
        .fold(0.0, f32::max)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::shapes;

    /// A unit sphere's mesh of `segments` around and `segments / 2` rings.
    fn sphere(segments: u32) -> (Vec<Vec3>, Vec<u32>) {
        let mesh = shapes::uv_sphere(1.0, segments, segments / 2);
        (mesh.positions, mesh.indices)
    }

    #[test]
    fn a_fine_sphere_gets_coarser_levels_whose_faces_stay_within_their_error() {
        let (positions, indices) = sphere(128);
        let levels = DetailLevels::of_mesh(&positions, &indices);
        assert!(levels.levels.len() >= 4, "{} levels", levels.levels.len());
        assert_eq!(levels.levels[0].error_m, 0.0);
        for pair in levels.levels.windows(2) {
            assert!(pair[1].indices.len() < pair[0].indices.len());
            assert!(pair[1].error_m >= pair[0].error_m);
        }
        // Every vertex lies on the unit sphere, so a face's deepest point below it is
        // where the plane through its corners comes nearest the centre (when the foot lies
        // within the face; its centroid's depth 1 − |centroid| is a lower bound checked
        // here): a level's faces lie no deeper than the mesh's own by more than its error
        // (measured at its faces' centroids among other points: level_deviation.rs).
        let deepest = |list: &[u32]| {
            list.chunks_exact(3)
                .map(|t| {
                    let [a, b, c] = [t[0], t[1], t[2]].map(|i| positions[i as usize]);
                    1.0 - ((a + b + c) / 3.0).length()
                })
                .fold(0.0f32, f32::max)
        };
        let own = deepest(&indices);
        for level in &levels.levels {
            let list = &levels.indices[level.indices.start as usize..level.indices.end as usize];
            assert!(list.iter().all(|&i| (i as usize) < positions.len()));
            let deepest = deepest(list);
            assert!(
                deepest <= own + level.error_m,
                "level with {} triangles: a face {deepest} m deep against an error of {} m",
                list.len() / 3,
                level.error_m
            );
        }
    }

    #[test]
    fn small_meshes_and_meshes_with_bad_positions_are_kept_as_they_are() {
        let (positions, indices) = sphere(16);
        assert!(indices.len() / 3 < MIN_SIMPLIFIED_TRIANGLES);
        assert_eq!(DetailLevels::of_mesh(&positions, &indices).levels.len(), 1);
        let (mut positions, mut indices) = sphere(128);
        indices[7] = positions.len() as u32;
        assert_eq!(DetailLevels::of_mesh(&positions, &indices).levels.len(), 1);
        indices[7] = 0;
        positions[5] = Vec3::NAN;
        assert_eq!(DetailLevels::of_mesh(&positions, &indices).levels.len(), 1);
    }

    #[test]
    fn the_level_drawn_gets_coarser_with_distance_and_stays_within_its_pixel_bound() {
        let (positions, indices) = sphere(128);
        let levels = DetailLevels::of_mesh(&positions, &indices);
        // 60° over 540 pixels.
        let pixel_m_per_m = 2.0 * (30f32).to_radians().tan() / 540.0;
        assert_eq!(
            levels.level_for(0.0, pixel_m_per_m, f32::INFINITY, VertexValues::Varying),
            0
        );
        assert_eq!(
            levels.level_for(-1.0, pixel_m_per_m, f32::INFINITY, VertexValues::Varying),
            0
        );
        let mut previous = 0;
        for distance_m in [0.5f32, 2.0, 8.0, 32.0, 128.0, 512.0] {
            let chosen = levels.level_for(distance_m, pixel_m_per_m, f32::INFINITY, VertexValues::Varying);
            assert!(chosen >= previous);
            let level = &levels.levels[chosen];
            assert!(level.error_m <= MAX_ERROR_PX * distance_m * pixel_m_per_m);
            previous = chosen;
        }
        assert!(previous > 0, "far away a coarser level is drawn");
        assert_eq!(
            levels.level_for(1e-3, pixel_m_per_m, f32::INFINITY, VertexValues::Varying),
            0,
            "close up the mesh itself"
        );
        // However far, no coarser than the shadow maps' texels allow.
        let limited = levels.level_for(512.0, pixel_m_per_m, 1e-3, VertexValues::Varying);
        assert!(levels.levels[limited].error_m <= 1e-3 && limited < previous);
    }

    #[test]
    fn a_fine_flat_floor_keeps_short_edges_until_they_are_a_few_pixels_long() {
        let floor = shapes::plane(10.0, 64, 1.0);
        let levels = DetailLevels::of_mesh(&floor.positions, &floor.indices);
        let pixel_m_per_m = 2.0 * (30f32).to_radians().tan() / 540.0;
        let own_edge_m = levels.levels[0].longest_edge_m;
        for distance_m in [1.0f32, 5.0, 20.0, 100.0, 1000.0] {
            let level =
                &levels.levels[levels.level_for(distance_m, pixel_m_per_m, f32::INFINITY, VertexValues::Varying)];
            assert!(
                level.longest_edge_m <= own_edge_m || level.longest_edge_m <= MAX_EDGE_PX * distance_m * pixel_m_per_m,
                "at {distance_m} m an edge of {} m",
                level.longest_edge_m
            );
        }
        // The border is locked: every level keeps the floor's corners.
        for level in &levels.levels {
            let list = &levels.indices[level.indices.start as usize..level.indices.end as usize];
            for corner in [Vec3::new(-5.0, 0.0, -5.0), Vec3::new(5.0, 0.0, 5.0)] {
                assert!(
                    list.iter()
                        .any(|&i| floor.positions[i as usize].distance(corner) < 1e-5)
                );
            }
        }
    }

    #[test]
    fn a_fine_flat_floor_with_nothing_varying_at_its_vertices_is_drawn_from_long_edges() {
        let floor = shapes::plane(10.0, 64, 1.0);
        let levels = DetailLevels::of_mesh(&floor.positions, &floor.indices);
        let pixel_m_per_m = 2.0 * (30f32).to_radians().tan() / 540.0;
        let fineness =
            crate::shading::vertex_lighting::MeshFineness::of(&floor.positions, &floor.normals, &floor.indices);
        assert_eq!(fineness.widest_normal_turn_rad, 0.0);
        let values = VertexValues::of(fineness.widest_normal_turn_rad, false, false);
        assert_eq!(values, VertexValues::Uniform);
        // The flat floor simplifies without error (measured: within rounding), so even a
        // metre away, where a fifth of a pixel spans 0.4 mm, a level of long edges lies
        // within it: a sixteenth of the floor's triangles or fewer.
        let triangles = |level: usize| levels.levels[level].indices.len() / 3;
        for distance_m in [1.0f32, 5.0, 100.0] {
            let chosen = levels.level_for(distance_m, pixel_m_per_m, f32::INFINITY, values);
            assert!(
                16 * triangles(chosen) <= triangles(0),
                "at {distance_m} m {} of {} triangles",
                triangles(chosen),
                triangles(0)
            );
            assert!(levels.levels[chosen].error_m <= MAX_ERROR_PX * distance_m * pixel_m_per_m);
        }
        // A metre away the edge rule would keep the floor's own edges (22 cm, past 64
        // pixels' 14 cm): it is what is left out.
        let varying = levels.level_for(1.0, pixel_m_per_m, f32::INFINITY, VertexValues::Varying);
        let uniform = levels.level_for(1.0, pixel_m_per_m, f32::INFINITY, values);
        assert_eq!(varying, 0);
        assert!(levels.levels[uniform].longest_edge_m > MAX_EDGE_PX * pixel_m_per_m);
        // Still no level past the shadow maps' bound.
        let bounded = levels.level_for(1.0, pixel_m_per_m, -1.0, values);
        assert_eq!(bounded, 0);
    }

    #[test]
    fn a_texture_baked_light_or_turning_normals_make_a_meshs_values_vary() {
        assert_eq!(VertexValues::of(0.0, false, false), VertexValues::Uniform);
        assert_eq!(
            VertexValues::of(MAX_UNIFORM_NORMAL_TURN_RAD, false, false),
            VertexValues::Uniform
        );
        assert_eq!(VertexValues::of(0.0, true, false), VertexValues::Varying);
        assert_eq!(VertexValues::of(0.0, false, true), VertexValues::Varying);
        assert_eq!(VertexValues::of(0.01, false, false), VertexValues::Varying);
        assert_eq!(VertexValues::of(f32::NAN, false, false), VertexValues::Varying);
        // A curved mesh's normals turn: a sphere keeps the edge rule.
        let (positions, indices) = sphere(64);
        let normals: Vec<Vec3> = positions.iter().map(|p| p.normalize()).collect();
        let fineness = crate::shading::vertex_lighting::MeshFineness::of(&positions, &normals, &indices);
        assert_eq!(
            VertexValues::of(fineness.widest_normal_turn_rad, false, false),
            VertexValues::Varying
        );
    }
}
