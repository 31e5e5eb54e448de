//! Whether a mesh encloses volume with its faces turned outward, so that no back face of
//! it can be seen from outside: the passes drawn from the camera may then cull its back
//! faces, which lavapipe would otherwise rasterise and, without a depth pre-pass, shade
//! before the front faces hide them (docs/performance.md, "Back faces of closed meshes").
//!
//! The test, with vertices nearer each other than a millionth of the mesh's extent
//! welded (a uv seam or a sharp crease duplicates vertices, not edges):
//! - closed and consistently wound: every edge of a triangle is run once in each
//!   direction, by exactly two triangles (no border, no fold of three faces onto an edge,
//!   no flipped neighbour);
//! - outward: each connected part has a positive signed volume (the divergence theorem,
//!   Σ p₀ · (p₁ × p₂) / 6 over its triangles, counter-clockwise seen from outside).
//!
//! Then a ray from a point outside every part first crosses a surface going in, through a
//! front face, however the parts overlap (a lattice of merged tori, tubes whose segments
//! overlap at the bends). A surface that passes through itself with parts of it wound
//! inward is not told apart by the volumes; such meshes do not come from modelling tools.
//! Triangles whose corners weld into fewer than three vertices (a uv sphere's poles) have
//! no area and are left out.

use std::collections::HashMap;

use glam::Vec3;

/// Whether the triangles `indices` lists over `positions` enclose volume with their faces
/// turned outward (see the module comment). False for an empty mesh, indices past the
/// positions, or positions that are not finite.
pub fn encloses_outward(positions: &[Vec3], indices: &[u32]) -> bool {
    if indices.is_empty() || !indices.len().is_multiple_of(3) || !positions.iter().all(|p| p.is_finite()) {
        return false;
    }
    let Some(welded) = welded_ids(positions, indices) else {
        return false;
    };
    let triangles: Vec<[u32; 3]> = indices
        .chunks_exact(3)
        .map(|t| [welded[t[0] as usize], welded[t[1] as usize], welded[t[2] as usize]])
        .filter(|[a, b, c]| a != b && b != c && c != a)
        .collect();
    if triangles.is_empty() {
        return false;
    }
    let mut edges: Vec<u64> = triangles
        .iter()
        .flat_map(|&[a, b, c]| [(a, b), (b, c), (c, a)])
        .map(|(from, to)| (u64::from(from) << 32) | u64::from(to))
        .collect();
    edges.sort_unstable();
    let each_once = edges.windows(2).all(|pair| pair[0] != pair[1]);
    let each_reversed = || {
        edges.iter().all(|&edge| {
            let reversed = edge.rotate_right(32);
            edges.binary_search(&reversed).is_ok()
        })
    };
    each_once && each_reversed() && every_part_has_positive_volume(positions, &triangles)
}

/// How near two vertices weld, as a share of the mesh's largest extent: procedural seams
/// (a sphere's meridian at 0 and 2π) land within a few units in the last place, far
/// closer than any gap that could show.
const WELD_SHARE: f32 = 1e-6;

/// Each vertex's weld: the index of the first vertex within the weld distance of it (found
/// in the 27 cells of a grid of that side around it). None when an index lies past the
/// positions.
fn welded_ids(positions: &[Vec3], indices: &[u32]) -> Option<Vec<u32>> {
    if indices.iter().any(|&i| i as usize >= positions.len()) {
        return None;
    }
    let (low, high) = positions
        .iter()
        .fold((Vec3::INFINITY, Vec3::NEG_INFINITY), |(low, high), &p| {
            (low.min(p), high.max(p))
        });
    let weld_m = WELD_SHARE * (high - low).max_element().max(f32::MIN_POSITIVE);
    let cell_of = |p: Vec3| ((p - low) / weld_m).floor().as_i64vec3();
    // Each cell's first vertex, and each vertex's next in its cell (u32::MAX: none).
    let mut first_in: HashMap<glam::I64Vec3, u32, CellHasher> =
        HashMap::with_capacity_and_hasher(positions.len(), CellHasher);
    let mut next_in_cell = vec![u32::MAX; positions.len()];
    let mut welded = Vec::with_capacity(positions.len());
    for (k, &p) in positions.iter().enumerate() {
        let cell = cell_of(p);
        let mut near = None;
        'cells: for offset in NEIGHBOUR_CELLS {
            let mut other = first_in.get(&(cell + offset)).copied().unwrap_or(u32::MAX);
            while other != u32::MAX {
                if positions[other as usize].distance(p) <= weld_m {
                    near = Some(other);
                    break 'cells;
                }
                other = next_in_cell[other as usize];
            }
        }
        match near {
            Some(other) => welded.push(other),
            None => {
                let k = k as u32;
                if let Some(first) = first_in.insert(cell, k) {
                    next_in_cell[k as usize] = first;
                }
                welded.push(k);
            }
        }
    }
    Some(welded)
}

/// The 27 cells around a cell (itself first: most welds are found there).
const NEIGHBOUR_CELLS: [glam::I64Vec3; 27] = {
    let mut cells = [glam::I64Vec3::ZERO; 27];
    let mut k = 1;
    let mut i = 0;
    while i < 27 {
        let offset = glam::I64Vec3::new(i % 3 - 1, (i / 3) % 3 - 1, i / 9 - 1);
        if i != 13 {
            cells[k] = offset;
            k += 1;
        }
        i += 1;
    }
    cells
};

/// A multiplicative hash of a grid cell (std's SipHash took most of the weld's time on
/// the large sample's half a million vertices).
#[derive(Default, Clone, Copy)]
struct CellHasher;

impl std::hash::BuildHasher for CellHasher {
    type Hasher = CellHash;
    fn build_hasher(&self) -> CellHash {
        CellHash(0)
    }
}

struct CellHash(u64);

impl std::hash::Hasher for CellHash {
    fn finish(&self) -> u64 {
        self.0
    }
    fn write(&mut self, bytes: &[u8]) {
        for &b in bytes {
            self.write_u64(u64::from(b));
        }
    }
    fn write_i64(&mut self, value: i64) {
        self.write_u64(value as u64);
    }
    fn write_u64(&mut self, value: u64) {
        // Fibonacci hashing, mixed with what came before (rustc's FxHasher's scheme).
        self.0 = (self.0.rotate_left(5) ^ value).wrapping_mul(0x9e37_79b9_7f4a_7c15);
    }
}

/// Whether every connected part of `triangles` (welded corners: each the index of the
/// vertex its weld keeps, `welded_ids`) has a positive signed volume, measured about the
/// first triangle's first corner for precision.
fn every_part_has_positive_volume(positions: &[Vec3], triangles: &[[u32; 3]]) -> bool {
    let mut parts = Parts::new(positions.len());
    for &[a, b, c] in triangles {
        parts.join(a, b);
        parts.join(b, c);
    }
    let origin = positions[triangles[0][0] as usize].as_dvec3();
    let mut volumes = vec![0.0f64; positions.len()];
    for &[a, b, c] in triangles {
        let [p, q, r] = [a, b, c].map(|k| positions[k as usize].as_dvec3() - origin);
        volumes[parts.root(a) as usize] += p.dot(q.cross(r)) / 6.0;
    }
    triangles.iter().all(|&[a, _, _]| volumes[parts.root(a) as usize] > 0.0)
}

/// Union–find over vertex ids: which vertices the triangles connect.
struct Parts {
    parent: Vec<u32>,
}

impl Parts {
    fn new(count: usize) -> Parts {
        Parts {
            parent: (0..count as u32).collect(),
        }
    }

    fn root(&mut self, mut k: u32) -> u32 {
        while self.parent[k as usize] != k {
            // Path halving: each step also points k at its grandparent.
            let grandparent = self.parent[self.parent[k as usize] as usize];
            self.parent[k as usize] = grandparent;
            k = grandparent;
        }
        k
    }

    fn join(&mut self, a: u32, b: u32) {
        let (ra, rb) = (self.root(a), self.root(b));
        if ra != rb {
            self.parent[ra.max(rb) as usize] = ra.min(rb);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::shapes::{self, ShapeMesh};

    fn encloses(mesh: &ShapeMesh) -> bool {
        encloses_outward(&mesh.positions, &mesh.indices)
    }

    fn reversed(mut mesh: ShapeMesh) -> ShapeMesh {
        for triangle in mesh.indices.chunks_exact_mut(3) {
            triangle.swap(1, 2);
        }
        mesh
    }

    #[test]
    fn closed_shapes_wound_outward_enclose() {
        let tube = shapes::tube_along(|t| Vec3::new(t, t * t, 0.0), 5, 0.02, 6);
        let lattice = shapes::torus(0.6, 0.012, 96, 6).merged(
            shapes::torus(0.6, 0.012, 96, 6).transformed(glam::Affine3A::from_rotation_x(std::f32::consts::FRAC_PI_2)),
        );
        for (name, mesh) in [
            ("cuboid", shapes::cuboid(Vec3::new(1.0, 0.5, 0.25))),
            ("sphere with welded poles", shapes::uv_sphere(1.0, 16, 8)),
            ("torus with seams", shapes::torus(1.0, 0.25, 32, 12)),
            ("cylinder", shapes::cylinder(0.5, 2.0, 12)),
            ("tube of overlapping segments", tube),
            ("two crossing tori", lattice),
        ] {
            assert!(encloses(&mesh), "{name}");
        }
    }

    #[test]
    fn open_or_inward_meshes_do_not() {
        let cuboid = shapes::cuboid(Vec3::ONE);
        let mut open_box = cuboid.clone();
        open_box.indices.truncate(open_box.indices.len() - 6);
        let mut flipped_face = cuboid.clone();
        flipped_face.indices[..3].swap(1, 2);
        let mut doubled_face = cuboid.clone();
        let face: Vec<u32> = doubled_face.indices[..3].to_vec();
        doubled_face.indices.extend(face);
        // An outward box holding an inward one: the total volume is positive, the inner
        // part's is not.
        let nested = cuboid.clone().merged(reversed(shapes::cuboid(Vec3::splat(0.5))));
        for (name, mesh) in [
            ("a quad", shapes::plane(2.0, 1, 1.0)),
            ("a box without a face", open_box),
            ("a box wound inward", reversed(cuboid.clone())),
            ("a box with one face flipped", flipped_face),
            ("a box with a face doubled", doubled_face),
            ("a box around an inward box", nested),
        ] {
            assert!(!encloses(&mesh), "{name}");
        }
    }

    #[test]
    fn bad_input_does_not_enclose() {
        let cuboid = shapes::cuboid(Vec3::ONE);
        assert!(!encloses_outward(&[], &[]));
        assert!(!encloses_outward(&cuboid.positions, &[]));
        let mut past_the_end = cuboid.indices.clone();
        past_the_end[0] = cuboid.positions.len() as u32;
        assert!(!encloses_outward(&cuboid.positions, &past_the_end));
        let mut not_finite = cuboid.positions.clone();
        not_finite[0].x = f32::NAN;
        assert!(!encloses_outward(&not_finite, &cuboid.indices));
        let mut ragged = cuboid.indices.clone();
        ragged.pop();
        assert!(!encloses_outward(&cuboid.positions, &ragged));
        // Every triangle collapsed onto one point.
        assert!(!encloses_outward(&[Vec3::ZERO; 3], &[0, 1, 2]));
    }
}
