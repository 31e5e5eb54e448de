//! Solid voxelisation of a triangle mesh by winding numbers along columns: a line along +x
//! through the centre of each (y, z) column enters a closed, outward-wound surface (+1) as
//! often as it leaves it (−1), and cells where the running sum is positive are inside — so
//! overlapping closed parts merged into one mesh make their union. Columns whose crossings
//! do not balance (an open mesh, or a ray grazing an edge) are left empty, not guessed.

use glam::{IVec3, Vec3};

use crate::scene::Aabb;

/// Inside/outside flags on a regular grid of cubic cells.
#[derive(Debug, Clone)]
pub struct VoxelGrid {
    /// World position of the corner of cell (0, 0, 0).
    pub origin: Vec3,
    /// Edge length of a cell in metres.
    pub cell_m: f32,
    pub dims: IVec3,
    inside: Vec<bool>,
}

impl VoxelGrid {
    /// Voxelises the solid bounded by `indices` over `positions` with about `cell_budget`
    /// cubic cells over its bounds (at least 8 and at most 400 along the longest side),
    /// plus one empty cell of margin on every side.
    pub fn solid(positions: &[Vec3], indices: &[u32], cell_budget: usize) -> VoxelGrid {
        let bounds = Aabb::from_points(positions);
        let extent = if bounds.is_empty() {
            Vec3::ZERO
        } else {
            bounds.max - bounds.min
        };
        let longest = extent.max_element();
        let cell_m = if longest > 0.0 && longest.is_finite() {
            let by_volume = (extent.x * extent.y * extent.z / cell_budget.max(1) as f32).cbrt();
            by_volume.clamp(longest / 400.0, longest / 8.0)
        } else {
            1.0
        };
        let origin = if bounds.is_empty() {
            Vec3::ZERO
        } else {
            bounds.min - Vec3::splat(cell_m)
        };
        let dims = ((extent / cell_m).ceil().as_ivec3() + IVec3::splat(2)).max(IVec3::ONE);
        let mut grid = VoxelGrid {
            origin,
            cell_m,
            dims,
            inside: vec![false; (dims.x * dims.y * dims.z) as usize],
        };
        if !bounds.is_empty() && longest > 0.0 {
            grid.fill_by_parity(positions, indices);
        }
        grid
    }

    fn fill_by_parity(&mut self, positions: &[Vec3], indices: &[u32]) {
        let (ny, nz) = (self.dims.y as usize, self.dims.z as usize);
        // Column centres are nudged off the cell centres by an irrational fraction so that
        // rays through the regular vertices of generated meshes do not graze edges.
        let nudge = 0.5 + 1e-3 * std::f32::consts::PI;
        let (origin, cell_m) = (self.origin, self.cell_m);
        let column_yz = |j: usize, k: usize| {
            (
                origin.y + (j as f32 + nudge) * cell_m,
                origin.z + (k as f32 + nudge * 0.97) * cell_m,
            )
        };
        // Triangles binned by the columns their yz bounds overlap.
        let mut bins: Vec<Vec<usize>> = vec![Vec::new(); ny * nz];
        for (t, tri) in indices.chunks_exact(3).enumerate() {
            let [a, b, c] = [tri[0], tri[1], tri[2]].map(|i| positions.get(i as usize).copied());
            let (Some(a), Some(b), Some(c)) = (a, b, c) else {
                continue;
            };
            let lo = a.min(b).min(c);
            let hi = a.max(b).max(c);
            let j0 = ((lo.y - self.origin.y) / self.cell_m - nudge).ceil().max(0.0) as usize;
            let j1 = ((hi.y - self.origin.y) / self.cell_m - nudge)
                .floor()
                .min(ny as f32 - 1.0);
            let k0 = ((lo.z - self.origin.z) / self.cell_m - nudge * 0.97).ceil().max(0.0) as usize;
            let k1 = ((hi.z - self.origin.z) / self.cell_m - nudge * 0.97)
                .floor()
                .min(nz as f32 - 1.0);
            if j1 < 0.0 || k1 < 0.0 {
                continue;
            }
            for j in j0..=(j1 as usize) {
                for k in k0..=(k1 as usize) {
                    bins[j * nz + k].push(t);
                }
            }
        }
        let mut crossings: Vec<(f32, i32)> = Vec::new();
        for j in 0..ny {
            for k in 0..nz {
                let (y, z) = column_yz(j, k);
                crossings.clear();
                for &t in &bins[j * nz + k] {
                    let tri = &indices[3 * t..3 * t + 3];
                    let [a, b, c] = [tri[0], tri[1], tri[2]].map(|i| positions[i as usize]);
                    if let Some(crossing) = column_crossing(a, b, c, y, z) {
                        crossings.push(crossing);
                    }
                }
                // A closed surface (or a union of them) enters as often as it leaves.
                if crossings.iter().map(|c| c.1).sum::<i32>() != 0 {
                    continue;
                }
                crossings.sort_by(|a, b| a.0.total_cmp(&b.0));
                let mut winding = 0;
                for pair in crossings.windows(2) {
                    winding += pair[0].1;
                    if winding > 0 {
                        self.fill_x_span(j, k, pair[0].0, pair[1].0);
                    }
                }
            }
        }
    }

    fn fill_x_span(&mut self, j: usize, k: usize, x0: f32, x1: f32) {
        let first = ((x0 - self.origin.x) / self.cell_m - 0.5).ceil().max(0.0) as i32;
        let last = ((x1 - self.origin.x) / self.cell_m - 0.5).floor() as i32;
        for i in first..=last.min(self.dims.x - 1) {
            let index = self.flat(IVec3::new(i, j as i32, k as i32));
            self.inside[index] = true;
        }
    }

    /// Number of cells in the grid.
    pub fn cell_count(&self) -> usize {
        self.inside.len()
    }

    /// Flat index of a cell inside the grid.
    pub fn flat(&self, cell: IVec3) -> usize {
        ((cell.x * self.dims.y + cell.y) * self.dims.z + cell.z) as usize
    }

    /// Whether `cell` is inside the solid (cells outside the grid are outside).
    pub fn is_inside(&self, cell: IVec3) -> bool {
        cell.cmpge(IVec3::ZERO).all() && cell.cmplt(self.dims).all() && self.inside[self.flat(cell)]
    }

    /// The cell containing world point `p`.
    pub fn cell_of(&self, p: Vec3) -> IVec3 {
        ((p - self.origin) / self.cell_m).floor().as_ivec3()
    }

    pub fn center(&self, cell: IVec3) -> Vec3 {
        self.origin + (cell.as_vec3() + Vec3::splat(0.5)) * self.cell_m
    }

    /// Every cell of the grid.
    pub fn cells(&self) -> impl Iterator<Item = IVec3> + '_ {
        let d = self.dims;
        (0..d.x).flat_map(move |i| (0..d.y).flat_map(move |j| (0..d.z).map(move |k| IVec3::new(i, j, k))))
    }

    pub fn inside_cells(&self) -> Vec<IVec3> {
        self.cells().filter(|&c| self.is_inside(c)).collect()
    }

    pub fn cell_volume_m3(&self) -> f32 {
        self.cell_m.powi(3)
    }
}

/// Where the line {(x, y, z)} crosses triangle abc, if it does: x, and +1 where the line
/// enters the solid (the counter-clockwise face looks toward −x) or −1 where it leaves.
/// A half-open rule on the barycentric signs makes a line through a shared edge count once.
fn column_crossing(a: Vec3, b: Vec3, c: Vec3, y: f32, z: f32) -> Option<(f32, i32)> {
    let edge = |p: Vec3, q: Vec3| (q.y - p.y) * (z - p.z) - (q.z - p.z) * (y - p.y);
    let (wa, wb, wc) = (edge(b, c), edge(c, a), edge(a, b));
    let all_positive = wa >= 0.0 && wb >= 0.0 && wc >= 0.0;
    let all_negative = wa <= 0.0 && wb <= 0.0 && wc <= 0.0;
    let sum = wa + wb + wc;
    if !(all_positive || all_negative) || sum == 0.0 {
        return None;
    }
    let normal_x = (b - a).cross(c - a).x;
    let direction = if normal_x < 0.0 { 1 } else { -1 };
    Some(((wa * a.x + wb * b.x + wc * c.x) / sum, direction))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::shapes;

    #[test]
    fn a_cube_fills_its_interior_and_nothing_else() {
        let mesh = shapes::cuboid(Vec3::splat(0.5));
        let grid = VoxelGrid::solid(&mesh.positions, &mesh.indices, 8000);
        let inside = grid.inside_cells();
        // 20³ cells of 5 cm fill the 1 m cube (centres strictly inside).
        assert_eq!(inside.len(), 20 * 20 * 20);
        assert!(!grid.is_inside(grid.cell_of(Vec3::splat(0.55))));
        assert!(grid.is_inside(grid.cell_of(Vec3::ZERO)));
    }

    #[test]
    fn a_sphere_fills_its_volume_to_a_few_percent() {
        let mesh = shapes::uv_sphere(1.0, 48, 24);
        let grid = VoxelGrid::solid(&mesh.positions, &mesh.indices, 64000);
        let volume = grid.inside_cells().len() as f32 * grid.cell_volume_m3();
        let exact = 4.0 / 3.0 * std::f32::consts::PI;
        assert!((volume / exact - 1.0).abs() < 0.04, "{volume} vs {exact}");
    }

    #[test]
    fn overlapping_closed_parts_make_their_union() {
        let a = shapes::cuboid(Vec3::splat(0.5));
        let b = shapes::cuboid(Vec3::splat(0.5)).transformed(glam::Affine3A::from_translation(Vec3::X * 0.5));
        let merged = a.merged(b);
        let grid = VoxelGrid::solid(&merged.positions, &merged.indices, 27000);
        let volume = grid.inside_cells().len() as f32 * grid.cell_volume_m3();
        // Cells of 3.8 cm over a 1.5 m span: a few percent of quantisation.
        assert!((volume - 1.5).abs() < 0.06, "{volume}");
    }

    #[test]
    fn an_open_plane_has_no_inside() {
        let positions = [Vec3::ZERO, Vec3::X, Vec3::new(1.0, 0.0, 1.0), Vec3::Z];
        let grid = VoxelGrid::solid(&positions, &[0, 1, 2, 0, 2, 3], 1000);
        assert!(grid.inside_cells().is_empty());
    }
}
