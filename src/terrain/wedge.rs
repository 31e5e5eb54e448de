//! Combining per-azimuth slices into one SH vector: the wedge interpolation operator
//! M_lin and z-rotations (Nowrouzezahrai & Snyder 2009; Giraud's thesis eq. 4.17–4.21).
//!
//! W azimuths ϕ_k = k·Δϕ, Δϕ = 2π/W, split the sphere into wedges [ϕ_k, ϕ_{k+1}] (wrapping
//! round). Within a wedge the slice *functions* are interpolated linearly in azimuth,
//! V(θ, φ) = ((1 − α)·v_k + α·v_{k+1})·P̂(cos θ) with α = (φ − ϕ_k)/Δϕ, and are 0 outside
//! it. For the canonical wedge [0, Δϕ] the SH of that function is M_lin·[v_k; v_{k+1}]:
//! [M_lin]_{i,j} = ∫_0^{Δϕ} ∫_0^π I_j(φ)·P̂_{j mod n}(cos θ)·y_i(θ, φ) sin θ dθ dφ with
//! I = [1 − α (n times), α (n times)]. Each wedge's vector is turned to ϕ_k about the polar
//! axis and the W vectors are summed. Because the wedges partition the sphere and every
//! step is linear, the same operator serves occlusion and log-visibility slices.
//!
//! These formulas take the terrain's up axis (world +y) as the SH polar axis; the result
//! is turned into world axes (polar axis +z) once per receiver by [`TERRAIN_TO_WORLD`].

use std::f64::consts::PI;

use glam::{DMat3, DVec3};

use super::slice::slice_basis;
use crate::sh::{self, gauss_legendre};

/// The terrain frame in world axes: its x axis is world +z, its y axis world +x and its
/// polar axis world +y (a cyclic permutation of the axes, so a proper rotation). A
/// marching azimuth φ is the world direction (sin φ, 0, cos φ).
pub const TERRAIN_TO_WORLD: DMat3 = DMat3::from_cols(DVec3::Z, DVec3::X, DVec3::Y);

/// The world-space horizontal direction of terrain azimuth `azimuth_rad`.
pub fn azimuth_direction(azimuth_rad: f64) -> (f64, f64) {
    let (sin, cos) = azimuth_rad.sin_cos();
    (sin, cos)
}

/// M_lin for one order and wedge count: n² rows, 2n columns, row-major.
#[derive(Debug, Clone, PartialEq)]
pub struct WedgeOperator {
    pub order: usize,
    pub azimuths: usize,
    pub matrix: Vec<f64>,
}

impl WedgeOperator {
    /// M_lin by Gauss–Legendre quadrature in θ and φ. The integrand is a polynomial in
    /// cos θ times sin^|m| θ (analytic in θ) times a linear function times cos/sin(mφ):
    /// 48 × 32 nodes reach f64 precision for every supported order.
    pub fn new(order: usize, azimuths: usize) -> WedgeOperator {
        let n2 = order * order;
        let width = 2 * order;
        let wedge = 2.0 * PI / azimuths.max(1) as f64;
        let mut matrix = vec![0.0; n2 * width];
        let theta_rule = gauss_legendre(48);
        let phi_rule = gauss_legendre(32);
        for &(u, wu) in &theta_rule {
            let theta = (u + 1.0) * PI / 2.0;
            let (sin_t, cos_t) = theta.sin_cos();
            let slice = slice_basis(order, cos_t);
            for &(v, wv) in &phi_rule {
                let alpha = (v + 1.0) / 2.0;
                let phi = alpha * wedge;
                let weight = wu * (PI / 2.0) * wv * (wedge / 2.0) * sin_t;
                let (sin_p, cos_p) = phi.sin_cos();
                let y = sh::basis(order, DVec3::new(sin_t * cos_p, sin_t * sin_p, cos_t));
                for (i, yi) in y.iter().enumerate() {
                    let row = &mut matrix[i * width..(i + 1) * width];
                    for (j, p) in slice.iter().enumerate() {
                        row[j] += weight * (1.0 - alpha) * p * yi;
                        row[order + j] += weight * alpha * p * yi;
                    }
                }
            }
        }
        WedgeOperator {
            order,
            azimuths,
            matrix,
        }
    }

    /// The SH (terrain frame) of the canonical wedge between slices `left` (at φ = 0) and
    /// `right` (at φ = Δϕ): M_lin·[left; right].
    pub fn apply(&self, left: &[f64], right: &[f64]) -> Vec<f64> {
        let width = 2 * self.order;
        self.matrix
            .chunks_exact(width)
            .map(|row| {
                let (a, b) = row.split_at(self.order);
                a.iter().zip(left).map(|(m, v)| m * v).sum::<f64>()
                    + b.iter().zip(right).map(|(m, v)| m * v).sum::<f64>()
            })
            .collect()
    }

    /// Σ_k Rot_z(M_lin·[v_k; v_{k+1}], ϕ_k) over the W slices `slices` (one per azimuth,
    /// in azimuth order, wrapping round): the SH in the terrain frame of the interpolated
    /// slice function.
    pub fn sum_wedges(&self, slices: &[Vec<f64>]) -> Vec<f64> {
        let w = slices.len();
        let mut total = vec![0.0; self.order * self.order];
        for k in 0..w {
            let wedge = self.apply(&slices[k], &slices[(k + 1) % w]);
            let turned = sh::rotate_z(&wedge, 2.0 * PI * k as f64 / w as f64);
            for (t, v) in total.iter_mut().zip(turned) {
                *t += v;
            }
        }
        total
    }
}

/// An SH vector of the terrain frame in world axes.
pub fn terrain_to_world(f: &[f64]) -> Vec<f64> {
    sh::rotate(f, TERRAIN_TO_WORLD)
}

#[cfg(test)]
mod tests {
    use super::super::slice::slice_vector;
    use super::*;

    #[test]
    fn constant_horizon_gives_the_zonal_slice_times_root_two_pi() {
        // Every azimuth at the same σ: the wedge sum is zonal with m = 0 entries
        // √(2π)·v̄_l(σ), for W = 8 and 16 (shading-model.md §4).
        for azimuths in [8, 16] {
            let op = WedgeOperator::new(4, azimuths);
            for sigma in [-0.7f64, 0.0, 0.3, 1.2] {
                let v = slice_vector(4, sigma.sin());
                let sum = op.sum_wedges(&vec![v.clone(); azimuths]);
                for (l, v_l) in v.iter().enumerate() {
                    for m in -(l as i64)..=l as i64 {
                        let i = (l as i64 * (l as i64 + 1) + m) as usize;
                        let expected = if m == 0 { (2.0 * PI).sqrt() * v_l } else { 0.0 };
                        assert!(
                            (sum[i] - expected).abs() < 1e-12,
                            "W {azimuths} σ {sigma} i {i}: {}",
                            sum[i]
                        );
                    }
                }
            }
        }
    }

    #[test]
    fn flat_ground_log_zh_matches_the_printed_values() {
        // ε = 0.1, all horizons at 0: [−4.0812, 3.5344, 0, −1.3497] (shading-model.md §4).
        let op = WedgeOperator::new(4, 8);
        let log_slice: Vec<f64> = slice_vector(4, 0.0).iter().map(|v| 0.1f64.ln() * v).collect();
        let sum = op.sum_wedges(&vec![log_slice; 8]);
        let printed = [-4.0812, 3.5344, 0.0, -1.3497];
        for (l, want) in printed.iter().enumerate() {
            assert!((sum[l * (l + 1)] - want).abs() < 1e-4, "band {l}: {}", sum[l * (l + 1)]);
        }
    }

    #[test]
    fn wedge_sum_is_the_projection_of_the_interpolated_slice_function() {
        // Brute force: project the piecewise-linear-in-azimuth slice function directly.
        let (order, w) = (4, 6);
        let sigmas = [0.1, 0.5, -0.2, 0.9, 0.0, 0.3];
        let slices: Vec<Vec<f64>> = sigmas.iter().map(|s: &f64| slice_vector(order, s.sin())).collect();
        let wedge = 2.0 * PI / w as f64;
        let function = |d: DVec3| {
            let phi = d.y.atan2(d.x).rem_euclid(2.0 * PI);
            let k = ((phi / wedge) as usize).min(w - 1);
            let alpha = (phi - k as f64 * wedge) / wedge;
            let p = slice_basis(order, d.z);
            (0..order)
                .map(|j| ((1.0 - alpha) * slices[k][j] + alpha * slices[(k + 1) % w][j]) * p[j])
                .sum::<f64>()
        };
        // The midpoint rule in θ and in azimuth (cells ending on the wedge borders), fine
        // enough for 1e-5.
        let mut brute = vec![0.0; order * order];
        let azimuth_cells = 400 * w;
        let polar_cells = 1000;
        for t in 0..polar_cells {
            let theta = PI * (t as f64 + 0.5) / polar_cells as f64;
            let (r, z) = theta.sin_cos();
            let wz = r * PI / polar_cells as f64;
            for c in 0..azimuth_cells {
                let phi = 2.0 * PI * (c as f64 + 0.5) / azimuth_cells as f64;
                let d = DVec3::new(r * phi.cos(), r * phi.sin(), z);
                let value = function(d) * wz * 2.0 * PI / azimuth_cells as f64;
                for (b, y) in brute.iter_mut().zip(sh::basis(order, d)) {
                    *b += value * y;
                }
            }
        }
        let sum = WedgeOperator::new(order, w).sum_wedges(&slices);
        for (a, b) in sum.iter().zip(&brute) {
            assert!((a - b).abs() < 1e-5, "{sum:?}\n{brute:?}");
        }
    }

    #[test]
    fn terrain_frame_puts_the_polar_axis_on_world_up() {
        // A zonal function about the terrain's up axis becomes one about world +y.
        let zh = crate::sh::cap_zh(4, 0.6);
        let local = crate::sh::rotate_zh(&zh, DVec3::Z);
        let world = terrain_to_world(&local);
        let expected = crate::sh::rotate_zh(&zh, DVec3::Y);
        for (a, b) in world.iter().zip(&expected) {
            assert!((a - b).abs() < 1e-12);
        }
        // And the marching azimuth φ = 0 is the terrain's x axis, world +z.
        assert_eq!(TERRAIN_TO_WORLD * DVec3::X, DVec3::Z);
        assert_eq!(azimuth_direction(0.0), (0.0, 1.0));
    }
}
