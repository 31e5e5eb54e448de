//! A height field on a regular grid over the terrain's footprint, and its prefiltered
//! multi-resolution pyramid.
//!
//! Sample (i, j) sits at world x = x_min + i·spacing_x, z = z_min + j·spacing_z with height
//! `heights_m[j·columns + i]` (world y, metres). Between samples heights are linear on the
//! render mesh's triangles;
//! outside the footprint the border heights extend outward (clamp to edge): the ground
//! does not end where the map does.

/// One level of heights on a regular grid.
#[derive(Debug, Clone, PartialEq)]
pub struct HeightField {
    /// Samples along x.
    pub columns: usize,
    /// Samples along z.
    pub rows: usize,
    /// World x and z of sample (0, 0), metres.
    pub min_xz: [f64; 2],
    /// Distance between neighbouring samples along x and z, metres.
    pub spacing_m: [f64; 2],
    /// World y of every sample, row-major (x fastest), metres.
    pub heights_m: Vec<f32>,
}

impl HeightField {
    /// The height at sample (i, j), indices clamped to the grid.
    pub fn sample(&self, i: i64, j: i64) -> f64 {
        let i = i.clamp(0, self.columns as i64 - 1) as usize;
        let j = j.clamp(0, self.rows as i64 - 1) as usize;
        self.heights_m[j * self.columns + i] as f64
    }

    /// The height at world (x, z), linear on the two triangles of each grid cell split
    /// along the diagonal from sample (i + 1, j) to (i, j + 1) — the triangles of the
    /// terrain's render mesh, so a receiver on the mesh sits exactly on this surface —
    /// and clamped to the border outside the footprint. The shaders' `terrain_height`
    /// reads the same samples with the same weights.
    pub fn height_at(&self, x: f64, z: f64) -> f64 {
        let u = ((x - self.min_xz[0]) / self.spacing_m[0]).clamp(0.0, (self.columns - 1) as f64);
        let v = ((z - self.min_xz[1]) / self.spacing_m[1]).clamp(0.0, (self.rows - 1) as f64);
        let (i, j) = (u.floor(), v.floor());
        let (fu, fv) = (u - i, v - j);
        let (i, j) = (i as i64, j as i64);
        let (h10, h01) = (self.sample(i + 1, j), self.sample(i, j + 1));
        if fu + fv <= 1.0 {
            let h00 = self.sample(i, j);
            h00 + fu * (h10 - h00) + fv * (h01 - h00)
        } else {
            let h11 = self.sample(i + 1, j + 1);
            h11 + (1.0 - fu) * (h01 - h11) + (1.0 - fv) * (h10 - h11)
        }
    }

    /// The world extent of the footprint along x and z, metres.
    pub fn extent_m(&self) -> [f64; 2] {
        [
            (self.columns - 1) as f64 * self.spacing_m[0],
            (self.rows - 1) as f64 * self.spacing_m[1],
        ]
    }

    /// The lowest and highest sample, metres.
    pub fn height_range_m(&self) -> (f64, f64) {
        self.heights_m
            .iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), &h| {
                (lo.min(h as f64), hi.max(h as f64))
            })
    }

    /// The next coarser level: every other sample of this one after the separable
    /// [1 2 1]/4 filter (the linear B-spline prefilter), so level k's samples keep the
    /// positions of level 0's samples 2^k apart and the footprint is unchanged (the last
    /// row or column may reach one fine spacing beyond it, clamped).
    pub fn coarser(&self) -> HeightField {
        let columns = (self.columns - 1).div_ceil(2) + 1;
        let rows = (self.rows - 1).div_ceil(2) + 1;
        let weights = [(-1, 0.25), (0, 0.5), (1, 0.25)];
        let mut heights_m = Vec::with_capacity(columns * rows);
        for j in 0..rows as i64 {
            for i in 0..columns as i64 {
                let mut h = 0.0;
                for (dj, wj) in weights {
                    for (di, wi) in weights {
                        h += wi * wj * self.sample(2 * i + di, 2 * j + dj);
                    }
                }
                heights_m.push(h as f32);
            }
        }
        HeightField {
            columns,
            rows,
            min_xz: self.min_xz,
            spacing_m: [2.0 * self.spacing_m[0], 2.0 * self.spacing_m[1]],
            heights_m,
        }
    }
}

/// Level 0 (the field itself) and successively coarser prefiltered levels.
#[derive(Debug, Clone, PartialEq)]
pub struct HeightPyramid {
    pub levels: Vec<HeightField>,
}

impl HeightPyramid {
    /// `level_count` levels (at least 1), stopping early once a level is 2 × 2.
    pub fn new(field: HeightField, level_count: usize) -> HeightPyramid {
        let mut levels = vec![field];
        while levels.len() < level_count.max(1) {
            let last = &levels[levels.len() - 1];
            if last.columns <= 2 && last.rows <= 2 {
                break;
            }
            let next = last.coarser();
            levels.push(next);
        }
        HeightPyramid { levels }
    }

    pub fn finest(&self) -> &HeightField {
        &self.levels[0]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn plane(columns: usize, rows: usize, f: impl Fn(f64, f64) -> f64) -> HeightField {
        let heights_m = (0..rows)
            .flat_map(|j| (0..columns).map(move |i| (i, j)))
            .map(|(i, j)| f(i as f64 * 0.5 - 1.0, j as f64 * 0.25) as f32)
            .collect();
        HeightField {
            columns,
            rows,
            min_xz: [-1.0, 0.0],
            spacing_m: [0.5, 0.25],
            heights_m,
        }
    }

    #[test]
    fn heights_reproduce_a_plane_and_clamp_outside() {
        let field = plane(9, 7, |x, z| 1.0 + 0.5 * x - 2.0 * z);
        for (x, z) in [(-1.0, 0.0), (0.3, 0.7), (2.9, 1.4), (3.0, 1.5)] {
            assert!((field.height_at(x, z) - (1.0 + 0.5 * x - 2.0 * z)).abs() < 1e-6);
        }
        // Beyond the footprint the border height extends outward.
        assert!((field.height_at(10.0, 0.7) - field.height_at(3.0, 0.7)).abs() < 1e-12);
        assert!((field.height_at(0.3, -5.0) - field.height_at(0.3, 0.0)).abs() < 1e-12);
    }

    #[test]
    fn prefiltering_keeps_planes_and_the_footprint_and_smooths_spikes() {
        let field = plane(65, 65, |x, z| 2.0 + x + z);
        let pyramid = HeightPyramid::new(field.clone(), 4);
        assert_eq!(pyramid.levels.len(), 4);
        for level in &pyramid.levels[1..] {
            assert_eq!(level.extent_m(), field.extent_m(), "odd sample counts halve exactly");
            // Away from the border (where the filter sees the clamped extension) a plane
            // is unchanged by the symmetric filter.
            for (x, z) in [(14.3, 7.7), (10.0, 5.0)] {
                assert!((level.height_at(x, z) - (2.0 + x + z)).abs() < 1e-5, "{x} {z}");
            }
        }
        let mut spike = plane(9, 9, |_, _| 0.0);
        spike.heights_m[4 * 9 + 4] = 16.0;
        let coarse = spike.coarser();
        assert_eq!(coarse.sample(2, 2), 4.0);
        let total: f64 = coarse.heights_m.iter().map(|h| *h as f64).sum();
        assert!(
            (total - 4.0).abs() < 1e-12,
            "the spike's mass lands on one coarse sample"
        );
    }

    #[test]
    fn pyramid_stops_at_two_by_two() {
        let pyramid = HeightPyramid::new(plane(5, 5, |_, _| 0.0), 10);
        let sizes: Vec<usize> = pyramid.levels.iter().map(|l| l.columns).collect();
        assert_eq!(sizes, vec![5, 3, 2]);
    }
}
