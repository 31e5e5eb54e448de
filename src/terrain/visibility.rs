//! The terrain's log-visibility at a receiver, in world axes, and the visibility of a
//! small light above its horizon: the f64 twin of `shaders/terrain.wgsl`.
//!
//! F_terrain(p) = R · Σ_k Rot_z(M_lin·[ln ε·v̄(σ_k); ln ε·v̄(σ_{k+1})], ϕ_k), σ_k the
//! horizon along azimuth ϕ_k = 2πk/W from p and R the terrain-to-world SH rotation
//! (Giraud's thesis §4.4–4.5). It is added to the sphere blockers' log-visibility before
//! the one exponentiation.
//!
//! The terrain does not move while lights and camera do, so the sum (without ln ε) is
//! marched once at every finest sample ([`TerrainShadow::surface`]); a receiver on the
//! terrain's surface inside its footprint reads it, interpolated on the mesh triangle it
//! lies in, instead of marching W directions per pixel. Receivers above the surface
//! (objects, by more than [`SURFACE_TOLERANCE`] of a spacing) march.

use std::f64::consts::PI;

use glam::DVec3;

use super::height_field::HeightPyramid;
use super::horizon::{March, horizon_sin};
use super::slice::slice_vector;
use super::wedge::{WedgeOperator, terrain_to_world};

/// Receivers less than this share of the finest spacing above the terrain read the
/// surface cache (the rasterised mesh and the height field agree to f32 rounding).
pub const SURFACE_TOLERANCE: f64 = 0.01;

/// Terrains with more samples than this (257²) get no surface cache: marching every
/// sample would take seconds each time the terrain or a knob changes (about 48 µs per
/// sample at W 16 on one core), so their receivers all march.
pub const MAX_SURFACE_CACHE_SAMPLES: usize = 257 * 257;

/// Everything shading needs of one terrain: its pyramid, the marching schedule, the
/// wedge operator for one order and azimuth count, and the marched sums at every sample.
#[derive(Debug, Clone)]
pub struct TerrainShadow {
    pub pyramid: HeightPyramid,
    pub march: March,
    pub operator: WedgeOperator,
    /// R·Σ_k Rot_z(M_lin·[v̄(σ_k); v̄(σ_{k+1})], ϕ_k) (no ln ε) at every finest sample,
    /// n² values per sample, samples row-major; empty above [`MAX_SURFACE_CACHE_SAMPLES`].
    pub surface: Vec<f64>,
}

impl TerrainShadow {
    /// The shadow model of `pyramid` at SH `order` with `azimuths` (W ≥ 3) marching
    /// directions and `levels` pyramid levels, its surface cache filled (a march per
    /// finest sample, on all cores).
    pub fn new(pyramid: HeightPyramid, order: usize, azimuths: usize, levels: usize) -> TerrainShadow {
        let mut shadow = TerrainShadow::marching_only(pyramid, order, azimuths, levels);
        shadow.fill_surface_cache();
        shadow
    }

    /// [`Self::new`] without the surface cache: every receiver marches. For callers that
    /// shade a few points (the painting estimate at painted vertices, which sit on the
    /// samples where cache and march agree), not whole frames.
    pub fn marching_only(pyramid: HeightPyramid, order: usize, azimuths: usize, levels: usize) -> TerrainShadow {
        let march = March::for_pyramid(&pyramid, levels);
        TerrainShadow {
            operator: WedgeOperator::new(order, azimuths.max(3)),
            pyramid,
            march,
            surface: Vec::new(),
        }
    }

    /// Marches every finest sample into [`Self::surface`] (not above
    /// [`MAX_SURFACE_CACHE_SAMPLES`]).
    fn fill_surface_cache(&mut self) {
        use rayon::prelude::*;
        let field = self.pyramid.finest();
        if field.columns * field.rows > MAX_SURFACE_CACHE_SAMPLES {
            return;
        }
        let samples: Vec<DVec3> = (0..field.rows as i64)
            .flat_map(|j| (0..field.columns as i64).map(move |i| (i, j)))
            .map(|(i, j)| {
                DVec3::new(
                    field.min_xz[0] + i as f64 * field.spacing_m[0],
                    field.sample(i, j),
                    field.min_xz[1] + j as f64 * field.spacing_m[1],
                )
            })
            .collect();
        let surface = samples.par_iter().flat_map_iter(|p| self.marched(*p, 1.0)).collect();
        self.surface = surface;
    }

    pub fn azimuths(&self) -> usize {
        self.operator.azimuths
    }

    /// sin σ of the horizon along each of the W azimuths from `p`.
    pub fn horizons(&self, p: DVec3) -> Vec<f64> {
        let w = self.azimuths();
        (0..w)
            .map(|k| {
                horizon_sin(
                    &self.pyramid,
                    &self.march,
                    p.x,
                    p.y,
                    p.z,
                    2.0 * PI * k as f64 / w as f64,
                )
            })
            .collect()
    }

    /// The terrain's log-visibility at `p`, world axes, for blocked directions worth
    /// `ln_epsilon`: from the surface cache on the terrain, marched above it.
    pub fn log_visibility(&self, p: DVec3, ln_epsilon: f64) -> Vec<f64> {
        match self.on_surface(p) {
            Some(corners) => {
                let n2 = self.operator.order * self.operator.order;
                let mut f = vec![0.0; n2];
                for (index, weight) in corners {
                    for (a, b) in f.iter_mut().zip(&self.surface[index * n2..(index + 1) * n2]) {
                        *a += ln_epsilon * weight * b;
                    }
                }
                f
            }
            None => self.marched(p, ln_epsilon),
        }
    }

    /// The three samples (index, weight) of the mesh triangle under `p` when `p` lies on
    /// the terrain's surface inside its footprint; None otherwise (the weights are those
    /// of `HeightField::height_at`).
    fn on_surface(&self, p: DVec3) -> Option<[(usize, f64); 3]> {
        let field = self.pyramid.finest();
        let u = (p.x - field.min_xz[0]) / field.spacing_m[0];
        let v = (p.z - field.min_xz[1]) / field.spacing_m[1];
        let tolerance = SURFACE_TOLERANCE * field.spacing_m[0].min(field.spacing_m[1]);
        let inside = (0.0..=(field.columns - 1) as f64).contains(&u) && (0.0..=(field.rows - 1) as f64).contains(&v);
        if self.surface.is_empty() || !inside || p.y - field.height_at(p.x, p.z) > tolerance {
            return None;
        }
        let (i, j) = (
            u.floor().min((field.columns - 2) as f64),
            v.floor().min((field.rows - 2) as f64),
        );
        let (fu, fv) = (u - i, v - j);
        let at = |di: usize, dj: usize| (j as usize + dj) * field.columns + i as usize + di;
        Some(if fu + fv <= 1.0 {
            [(at(0, 0), 1.0 - fu - fv), (at(1, 0), fu), (at(0, 1), fv)]
        } else {
            [(at(1, 1), fu + fv - 1.0), (at(0, 1), 1.0 - fu), (at(1, 0), 1.0 - fv)]
        })
    }

    /// The log-visibility at `p` by marching W azimuths.
    pub fn marched(&self, p: DVec3, ln_epsilon: f64) -> Vec<f64> {
        let order = self.operator.order;
        let slices: Vec<Vec<f64>> = self
            .horizons(p)
            .into_iter()
            .map(|s| slice_vector(order, s).into_iter().map(|v| ln_epsilon * v).collect())
            .collect();
        terrain_to_world(&self.operator.sum_wedges(&slices))
    }

    /// The share of a light's disc above the horizon along the light's own azimuth, seen
    /// from `p`: the disc of angular radius asin(`cap_ratio`) centred at elevation e above a
    /// horizon line at elevation σ shows 1/2 + (h√(1 − h²) + asin h)/π with
    /// h = (e − σ)/radius clamped to [−1, 1] (a circle cut by a chord, the curvature of
    /// lines of equal elevation neglected for small lights); a light of no size is 0 or 1.
    pub fn light_visibility(&self, p: DVec3, to_light: DVec3, cap_ratio: f64) -> f64 {
        let horizontal = (to_light.x * to_light.x + to_light.z * to_light.z).sqrt();
        let elevation = to_light.y.clamp(-1.0, 1.0).asin();
        let azimuth = if horizontal > 0.0 {
            to_light.x.atan2(to_light.z)
        } else {
            0.0
        };
        let horizon = horizon_sin(&self.pyramid, &self.march, p.x, p.y, p.z, azimuth).asin();
        disc_share_above(elevation - horizon, cap_ratio.clamp(0.0, 1.0).asin())
    }
}

/// The share of a disc of angular radius `radius_rad` whose centre is `height_rad` above a
/// straight edge (negative: below it).
pub fn disc_share_above(height_rad: f64, radius_rad: f64) -> f64 {
    if radius_rad <= 0.0 {
        return if height_rad > 0.0 { 1.0 } else { 0.0 };
    }
    let h = (height_rad / radius_rad).clamp(-1.0, 1.0);
    0.5 + (h * (1.0 - h * h).sqrt() + h.asin()) / PI
}

#[cfg(test)]
mod tests {
    use super::super::height_field::HeightField;
    use super::*;
    use crate::sh;

    fn flat(size: usize) -> HeightPyramid {
        HeightPyramid::new(
            HeightField {
                columns: size,
                rows: size,
                min_xz: [-5.0, -5.0],
                spacing_m: [10.0 / (size - 1) as f64, 10.0 / (size - 1) as f64],
                heights_m: vec![0.0; size * size],
            },
            4,
        )
    }

    #[test]
    fn flat_ground_blocks_the_lower_hemisphere_about_world_up() {
        let shadow = TerrainShadow::new(flat(33), 4, 8, 4);
        let ln_e = 0.1f64.ln();
        let f = shadow.log_visibility(DVec3::new(0.5, 0.0, -1.0), ln_e);
        // The printed flat-ground log-ZH [−4.0812, 3.5344, 0, −1.3497] about +y.
        let expected = sh::rotate_zh(&[-4.0812, 3.5344, 0.0, -1.3497], DVec3::Y);
        for (a, b) in f.iter().zip(&expected) {
            assert!((a - b).abs() < 1e-4, "{f:?}");
        }
        // Reconstructed, it is near ln ε straight down and near 0 straight up.
        assert!(sh::evaluate(&f, DVec3::NEG_Y) < 0.8 * ln_e);
        assert!(sh::evaluate(&f, DVec3::Y).abs() < 0.35 * -ln_e);
    }

    #[test]
    fn the_surface_cache_is_the_march_at_samples_and_close_between_them() {
        // Smooth hills, 2 m of relief over 10 m.
        let mut field = flat(41).finest().clone();
        for j in 0..41 {
            for i in 0..41 {
                let (x, z) = (i as f64 * 0.25 - 5.0, j as f64 * 0.25 - 5.0);
                field.heights_m[j * 41 + i] = ((0.6 * x).sin() * (0.5 * z).cos() + 1.0) as f32;
            }
        }
        let shadow = TerrainShadow::new(HeightPyramid::new(field.clone(), 3), 4, 12, 3);
        let ln_e = 0.1f64.ln();
        let at = |x: f64, z: f64| DVec3::new(x, field.height_at(x, z), z);
        for p in [at(0.0, 0.0), at(-2.5, 1.75), at(5.0, 5.0)] {
            let (cached, marched) = (shadow.log_visibility(p, ln_e), shadow.marched(p, ln_e));
            for (a, b) in cached.iter().zip(&marched) {
                assert!((a - b).abs() < 1e-9, "{p}: {a} vs {b}");
            }
        }
        for p in [at(0.1, 0.07), at(-2.4, 1.9), at(3.33, -4.1)] {
            let (cached, marched) = (shadow.log_visibility(p, ln_e), shadow.marched(p, ln_e));
            let error: f64 = cached
                .iter()
                .zip(&marched)
                .map(|(a, b)| (a - b).powi(2))
                .sum::<f64>()
                .sqrt();
            let norm: f64 = marched.iter().map(|v| v * v).sum::<f64>().sqrt();
            assert!(error < 0.05 * norm, "{p}: {error} of {norm}");
        }
        // Above the surface, or outside the footprint, the receiver marches.
        let above = at(0.1, 0.07) + DVec3::new(0.0, 0.5, 0.0);
        assert_eq!(shadow.log_visibility(above, ln_e), shadow.marched(above, ln_e));
        let outside = DVec3::new(7.0, 1.0, 0.0);
        assert_eq!(shadow.log_visibility(outside, ln_e), shadow.marched(outside, ln_e));
    }

    #[test]
    fn large_terrains_march_every_receiver() {
        let shadow = TerrainShadow::new(flat(300), 4, 8, 2);
        assert!(
            shadow.surface.is_empty(),
            "no cache above {MAX_SURFACE_CACHE_SAMPLES} samples"
        );
        let p = DVec3::new(0.3, 0.0, 0.2);
        assert_eq!(shadow.log_visibility(p, -2.0), shadow.marched(p, -2.0));
    }

    #[test]
    fn disc_share_is_a_half_on_the_edge_and_monotone() {
        assert!((disc_share_above(0.0, 0.1) - 0.5).abs() < 1e-15);
        assert_eq!(disc_share_above(0.2, 0.1), 1.0);
        assert_eq!(disc_share_above(-0.2, 0.1), 0.0);
        assert_eq!(disc_share_above(0.01, 0.0), 1.0);
        // Against the area of a circular segment measured on a grid.
        let h = 0.4;
        let mut inside = 0;
        let mut above = 0;
        let n = 1000;
        for i in 0..n {
            for j in 0..n {
                let (x, y) = (
                    2.0 * (i as f64 + 0.5) / n as f64 - 1.0,
                    2.0 * (j as f64 + 0.5) / n as f64 - 1.0,
                );
                if x * x + y * y <= 1.0 {
                    inside += 1;
                    if y > -h {
                        above += 1;
                    }
                }
            }
        }
        assert!((disc_share_above(h, 1.0) - above as f64 / inside as f64).abs() < 1e-3);
    }

    #[test]
    fn a_light_below_the_horizon_of_flat_ground_is_hidden() {
        let shadow = TerrainShadow::new(flat(33), 4, 8, 4);
        let p = DVec3::new(0.0, 0.0, 0.0);
        assert_eq!(shadow.light_visibility(p, DVec3::new(0.0, 1.0, 0.0), 0.1), 1.0);
        assert_eq!(
            shadow.light_visibility(p, DVec3::new(1.0, -0.3, 0.0).normalize(), 0.1),
            0.0
        );
        let grazing = shadow.light_visibility(p, DVec3::X, 0.1);
        assert!((grazing - 0.5).abs() < 1e-9, "{grazing}");
    }
}
