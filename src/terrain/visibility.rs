//! The terrain's log-visibility at a receiver, in world axes, and the visibility of a
//! small light above its horizon: the f64 twin of `shaders/terrain.wgsl`.
//!
//! F_terrain(p) = R · Σ_k Rot_z(M_lin·[ln ε·v̄(σ_k); ln ε·v̄(σ_{k+1})], ϕ_k), σ_k the
//! horizon along azimuth ϕ_k = 2πk/W from p and R the terrain-to-world SH rotation
//! (Giraud's thesis §4.4–4.5). It is added to the sphere blockers' log-visibility before
//! the one exponentiation.

use std::f64::consts::PI;

use glam::DVec3;

use super::height_field::HeightPyramid;
use super::horizon::{March, horizon_sin};
use super::slice::slice_vector;
use super::wedge::{WedgeOperator, terrain_to_world};

/// Everything shading needs of one terrain: its pyramid, the marching schedule and the
/// wedge operator for one order and azimuth count.
#[derive(Debug, Clone)]
pub struct TerrainShadow {
    pub pyramid: HeightPyramid,
    pub march: March,
    pub operator: WedgeOperator,
}

impl TerrainShadow {
    /// The shadow model of `pyramid` at SH `order` with `azimuths` (W ≥ 3) marching
    /// directions and `levels` pyramid levels.
    pub fn new(pyramid: HeightPyramid, order: usize, azimuths: usize, levels: usize) -> TerrainShadow {
        let march = March::for_pyramid(&pyramid, levels);
        TerrainShadow {
            operator: WedgeOperator::new(order, azimuths.max(3)),
            pyramid,
            march,
        }
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
    /// `ln_epsilon`.
    pub fn log_visibility(&self, p: DVec3, ln_epsilon: f64) -> Vec<f64> {
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
