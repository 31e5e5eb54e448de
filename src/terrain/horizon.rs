//! Horizon elevation by marching a height field (Snyder & Nowrouzezahrai 2008).
//!
//! From a receiver at (x, y, z) the horizon along azimuth φ is the largest elevation
//! angle σ of the terrain seen in the horizontal direction (sin φ, 0, cos φ):
//! tan σ = max_t (h(x + t sin φ, z + t cos φ) − y)/t. The result is returned as
//! sin σ ∈ [−1, 1] (−1 when nothing is sampled), what the slice vectors take.
//!
//! The pyramid marcher samples distances t_0·g^i (g = 2^{1/4}, four samples per octave,
//! t_0 one finest spacing) out to `max_distance_m`, reading each sample from the level
//! whose spacing matches the gap between samples (capped at the coarsest level it has):
//! the prefiltered levels stand in for the terrain a far sample skips. A receiver above
//! the ground (an object, or the cast-shadow offset of the thesis §4.5.1) marches with
//! its height above the terrain kept at every level, so each level compares like with like.

use super::height_field::HeightPyramid;
use super::wedge::azimuth_direction;

/// Growth of the sample distance from one step to the next (four samples per octave).
pub const STEP_GROWTH: f64 = 1.189_207_115_002_721; // 2^(1/4)

/// The marching schedule shared by the CPU twin and the shaders.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct March {
    /// First sample distance, metres (one finest spacing).
    pub first_step_m: f64,
    /// Samples stop beyond this distance, metres.
    pub max_distance_m: f64,
    /// Levels of the pyramid used (1: the finest only).
    pub levels: usize,
}

impl March {
    /// The schedule for `pyramid` using its first `levels` levels: from one finest spacing
    /// out to the footprint's diagonal.
    pub fn for_pyramid(pyramid: &HeightPyramid, levels: usize) -> March {
        let finest = pyramid.finest();
        let [ex, ez] = finest.extent_m();
        March {
            first_step_m: finest.spacing_m[0].min(finest.spacing_m[1]),
            max_distance_m: (ex * ex + ez * ez).sqrt().max(finest.spacing_m[0]),
            levels: levels.clamp(1, pyramid.levels.len()),
        }
    }

    /// Number of samples per azimuth.
    pub fn sample_count(&self) -> usize {
        if self.first_step_m <= 0.0 || self.max_distance_m < self.first_step_m {
            return 0;
        }
        ((self.max_distance_m / self.first_step_m).ln() / STEP_GROWTH.ln()).floor() as usize + 1
    }

    /// Distance of sample `i`: t_i = t_0·2^{i/4}.
    pub fn distance_m(&self, i: usize) -> f64 {
        self.first_step_m * (i as f64 / 4.0).exp2()
    }

    /// The level sample `i` is read from: the one whose spacing is closest to the gap to
    /// the next sample, t_i·(g − 1) = t_0·2^{i/4 − 2.402}, i.e. level round(i/4 − 2.402)
    /// within the levels used. It depends on i alone, so the shaders agree exactly.
    pub fn level_of_sample(&self, i: usize) -> usize {
        let level = (i as f64 / 4.0 + (STEP_GROWTH - 1.0).log2()).round().max(0.0) as usize;
        level.min(self.levels - 1)
    }
}

/// The receiver's height above the terrain at its footprint point (0 on the surface).
fn height_above_ground(pyramid: &HeightPyramid, x: f64, y: f64, z: f64) -> f64 {
    (y - pyramid.finest().height_at(x, z)).max(0.0)
}

/// sin σ along `azimuth_rad` from (x, y, z) by the pyramid schedule `march`.
pub fn horizon_sin(pyramid: &HeightPyramid, march: &March, x: f64, y: f64, z: f64, azimuth_rad: f64) -> f64 {
    let (dx, dz) = azimuth_direction(azimuth_rad);
    let offset = height_above_ground(pyramid, x, y, z);
    let mut best_slope = f64::NEG_INFINITY;
    let mut current = (usize::MAX, 0.0);
    for i in 0..march.sample_count() {
        let level = march.level_of_sample(i);
        let field = &pyramid.levels[level];
        if current.0 != level {
            current = (level, field.height_at(x, z) + offset);
        }
        let t = march.distance_m(i);
        let h = field.height_at(x + t * dx, z + t * dz);
        best_slope = best_slope.max((h - current.1) / t);
    }
    slope_to_sin(best_slope)
}

/// sin σ along `azimuth_rad` from (x, y, z) by stepping the finest level every quarter
/// spacing out to `max_distance_m`: the slow reference the pyramid marcher is tested against.
pub fn horizon_sin_dense(
    pyramid: &HeightPyramid,
    max_distance_m: f64,
    x: f64,
    y: f64,
    z: f64,
    azimuth_rad: f64,
) -> f64 {
    let field = pyramid.finest();
    let (dx, dz) = azimuth_direction(azimuth_rad);
    let base = field.height_at(x, z).max(y);
    let step = 0.25 * field.spacing_m[0].min(field.spacing_m[1]);
    let mut best_slope = f64::NEG_INFINITY;
    let mut t = step;
    while t <= max_distance_m {
        best_slope = best_slope.max((field.height_at(x + t * dx, z + t * dz) - base) / t);
        t += step;
    }
    slope_to_sin(best_slope)
}

/// sin(atan(slope)), −1 for −∞ (no sample).
pub fn slope_to_sin(slope: f64) -> f64 {
    if slope == f64::NEG_INFINITY || slope.is_nan() {
        -1.0
    } else {
        slope / (1.0 + slope * slope).sqrt()
    }
}

#[cfg(test)]
mod tests {
    use super::super::height_field::HeightField;
    use super::*;
    use std::f64::consts::PI;

    /// A `size`² grid over [−half, half]² with heights from `f(x, z)`.
    fn terrain(size: usize, half_m: f64, f: impl Fn(f64, f64) -> f64) -> HeightPyramid {
        let spacing = 2.0 * half_m / (size - 1) as f64;
        let heights_m = (0..size)
            .flat_map(|j| (0..size).map(move |i| (i, j)))
            .map(|(i, j)| f(-half_m + i as f64 * spacing, -half_m + j as f64 * spacing) as f32)
            .collect();
        HeightPyramid::new(
            HeightField {
                columns: size,
                rows: size,
                min_xz: [-half_m, -half_m],
                spacing_m: [spacing, spacing],
                heights_m,
            },
            6,
        )
    }

    #[test]
    fn levels_start_where_the_shaders_start_them() {
        // terrain.wgsl reads level 0 for samples 0–11 and level l ≥ 1 from 4l + 8 on.
        let march = March {
            first_step_m: 1.0,
            max_distance_m: 1e6,
            levels: 12,
        };
        let start = |l: usize| if l == 0 { 0 } else { 4 * l + 8 };
        for i in 0..80 {
            let level = march.level_of_sample(i);
            assert!(
                start(level) <= i && (level == 11 || i < start(level + 1)),
                "sample {i}: level {level}"
            );
        }
    }

    #[test]
    fn flat_ground_is_level_from_the_surface_and_below_level_from_above() {
        let pyramid = terrain(65, 8.0, |_, _| 1.0);
        let march = March::for_pyramid(&pyramid, 6);
        for k in 0..8 {
            let phi = k as f64 * PI / 4.0;
            assert_eq!(horizon_sin(&pyramid, &march, 0.3, 1.0, -0.2, phi), 0.0);
            // 1 m above the ground the horizon dips: the ground seen farthest (the border
            // extends to the march's end) sets it.
            let raised = horizon_sin(&pyramid, &march, 0.3, 2.0, -0.2, phi);
            let farthest = march.distance_m(march.sample_count() - 1);
            assert!((raised - slope_to_sin(-1.0 / farthest)).abs() < 1e-9, "{raised}");
        }
    }

    #[test]
    fn a_wall_sets_the_horizon_by_its_height_over_its_distance() {
        // A 3 m wall from x = 2 m on: toward +x (φ = 90°) the horizon is atan(3/2) at the
        // wall's nearest sample, backwards nothing rises.
        let pyramid = terrain(129, 8.0, |x, _| if x >= 2.0 { 3.0 } else { 0.0 });
        let dense = horizon_sin_dense(&pyramid, 20.0, 0.0, 0.0, 0.0, PI / 2.0);
        let analytic = (3.0f64).atan2(2.0).sin();
        // The bilinear ramp spans one spacing (0.125 m) before the wall.
        assert!((dense - analytic).abs() < 0.03, "{dense} vs {analytic}");
        assert_eq!(horizon_sin_dense(&pyramid, 20.0, 0.0, 0.0, 0.0, -PI / 2.0), 0.0);
        let march = March::for_pyramid(&pyramid, 1);
        let sampled = horizon_sin(&pyramid, &march, 0.0, 0.0, 0.0, PI / 2.0);
        assert!((sampled - analytic).abs() < 0.06, "{sampled}");
    }

    #[test]
    fn a_thin_wall_is_seen_from_both_sides_and_not_along_it() {
        // A wall 3 m high and 0.5 m thick over x ∈ [2, 2.5]: from x = 0 toward +x the
        // horizon is atan(3/2), from x = 4 toward −x atan(3/1.5), along it (±z) nothing.
        let pyramid = terrain(257, 8.0, |x, _| if (2.0..=2.5).contains(&x) { 3.0 } else { 0.0 });
        let from_front = horizon_sin_dense(&pyramid, 20.0, 0.0, 0.0, 0.0, PI / 2.0);
        let from_back = horizon_sin_dense(&pyramid, 20.0, 4.0, 0.0, 0.0, -PI / 2.0);
        assert!((from_front - 3f64.atan2(2.0).sin()).abs() < 0.02, "{from_front}");
        assert!((from_back - 3f64.atan2(1.5).sin()).abs() < 0.02, "{from_back}");
        assert_eq!(horizon_sin_dense(&pyramid, 20.0, 0.0, 0.0, 0.0, 0.0), 0.0);
        // The pyramid marcher at one level finds it too (its samples land on the wall).
        let march = March::for_pyramid(&pyramid, 1);
        let sampled = horizon_sin(&pyramid, &march, 0.0, 0.0, 0.0, PI / 2.0);
        assert!((sampled - from_front).abs() < 0.05, "{sampled}");
    }

    #[test]
    fn a_cone_peak_seen_from_its_foot_and_a_step_up_close() {
        // Cone of height 4 m and base radius 4 m at the origin, seen from (6, 0, 0) looking
        // toward −x (φ = −90°): the apex at elevation atan(4/6) sets the horizon.
        let pyramid = terrain(257, 8.0, |x, z| (4.0 - (x * x + z * z).sqrt()).max(0.0));
        let analytic = (4.0f64).atan2(6.0).sin();
        let dense = horizon_sin_dense(&pyramid, 20.0, 6.0, 0.0, 0.0, -PI / 2.0);
        assert!((dense - analytic).abs() < 0.01, "{dense} vs {analytic}");
        for levels in [1, 3, 6] {
            let march = March::for_pyramid(&pyramid, levels);
            let sampled = horizon_sin(&pyramid, &march, 6.0, 0.0, 0.0, -PI / 2.0);
            // Prefiltering rounds the apex off: the marcher may only see it lower, and
            // not by much.
            assert!(
                sampled <= analytic + 0.01 && sampled > analytic - 0.12,
                "{levels} levels: {sampled}"
            );
        }
    }

    #[test]
    fn raising_the_receiver_lowers_the_horizon() {
        let pyramid = terrain(129, 8.0, |x, z| (0.7 * x).sin() + (0.4 * z).cos());
        let march = March::for_pyramid(&pyramid, 4);
        let ground = pyramid.finest().height_at(1.0, 2.0);
        let mut previous = 2.0;
        for lift in [0.0, 0.1, 0.5, 1.0, 3.0, 10.0] {
            let s = horizon_sin(&pyramid, &march, 1.0, ground + lift, 2.0, 0.7);
            assert!(s <= previous, "lift {lift}: {s} > {previous}");
            previous = s;
        }
    }

    #[test]
    fn no_nan_at_cliffs_the_border_or_outside() {
        let pyramid = terrain(33, 4.0, |x, _| if x > 0.0 { 50.0 } else { 0.0 });
        let march = March::for_pyramid(&pyramid, 5);
        for (x, y, z) in [
            (0.0, 0.0, 0.0),
            (0.01, 50.0, 0.0),
            (4.0, 50.0, 4.0),
            (-30.0, 0.0, 9.0),
            (0.0, 1e6, 0.0),
        ] {
            for k in 0..16 {
                let s = horizon_sin(&pyramid, &march, x, y, z, k as f64 * PI / 8.0);
                assert!(s.is_finite() && (-1.0..=1.0).contains(&s), "{s}");
            }
        }
    }
}
