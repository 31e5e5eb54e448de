//! SH logarithms: Ren et al.'s log* by eigendecomposition with an eigenvalue clamp, and the
//! naive projection of the clamped pointwise logarithm. Natural logarithm throughout.

use nalgebra::{DMatrix, SymmetricEigen};

use super::gaunt::product_matrix;
use super::quadrature::SphereQuadrature;
use super::{coefficient_count, constant, evaluate, order_of};

/// Eigenvalues below this fraction of the largest are clamped to it (Ren et al. 2006).
pub const LOG_STAR_EIGEN_CLAMP: f64 = 0.02;

/// log*(g) = R q(D) Rᵀ (g − 1), M_g = R D Rᵀ, q(x) = ln x/(x − 1) (q(1) = 1), with the
/// eigenvalues of M_g clamped to ≥ 0.02·λ_max.
pub fn log_star(g: &[f64]) -> Vec<f64> {
    let order = order_of(g.len()).expect("an SH vector has a square number of coefficients");
    let n = coefficient_count(order);
    let eigen = SymmetricEigen::new(DMatrix::from_row_slice(n, n, &product_matrix(order, g)));
    let max = eigen.eigenvalues.iter().copied().fold(f64::MIN, f64::max);
    let floor = LOG_STAR_EIGEN_CLAMP * max.max(f64::MIN_POSITIVE);
    let q = |x: f64| {
        let x = x.max(floor);
        if (x - 1.0).abs() < 1e-8 {
            1.0 - (x - 1.0) / 2.0
        } else {
            x.ln() / (x - 1.0)
        }
    };
    let one = constant(order, 1.0);
    let g_minus_one: Vec<f64> = g.iter().zip(&one).map(|(a, b)| a - b).collect();
    let v = &eigen.eigenvectors;
    let projected: Vec<f64> = (0..n)
        .map(|k| (0..n).map(|i| v[(i, k)] * g_minus_one[i]).sum())
        .collect();
    (0..n)
        .map(|i| (0..n).map(|k| v[(i, k)] * q(eigen.eigenvalues[k]) * projected[k]).sum())
        .collect()
}

/// Projection of ln max(g(ω), ε) by a quadrature of degree 4n (the integrand is not
/// band-limited, so this is an approximation that converges with the rule's degree).
pub fn log_naive(g: &[f64], epsilon: f64) -> Vec<f64> {
    let order = order_of(g.len()).expect("an SH vector has a square number of coefficients");
    let quadrature = SphereQuadrature::exact_for_degree(4 * order.max(4));
    quadrature.project(order, |dir| evaluate(g, dir).max(epsilon).ln())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sh::{cap_zh, exp_reference, rotate_zh};

    /// log* inverts exp* only approximately: M_{exp*(f)} is not exp(M_f) once products
    /// are truncated to the order. For this vector (‖f‖ ≈ 0.3) the gap measured 2e-5 of
    /// the largest coefficient.
    #[test]
    fn log_star_inverts_exp_for_moderate_vectors() {
        let mut f = vec![0.0; 16];
        let cap = rotate_zh(&cap_zh(4, 0.5), glam::DVec3::new(0.3, 0.2, 0.9));
        for (fi, ci) in f.iter_mut().zip(cap) {
            *fi = 0.1f64.ln() * ci * 0.3;
        }
        let round_trip = log_star(&exp_reference(&f));
        let largest = f.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        for (a, b) in round_trip.iter().zip(&f) {
            assert!((a - b).abs() < 1e-4 * largest, "{a} vs {b}");
        }
    }

    #[test]
    fn natural_log_is_used() {
        // log*(e·1) = 1·1: with log10 it would be 0.434.
        let g = constant(3, std::f64::consts::E);
        let l = log_star(&g);
        assert!((l[0] - constant(3, 1.0)[0]).abs() < 1e-12, "{l:?}");
        let naive = log_naive(&g, 1e-3);
        assert!((naive[0] - constant(3, 1.0)[0]).abs() < 1e-12, "{naive:?}");
    }
}
