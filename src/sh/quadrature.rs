//! Product quadrature on the sphere: Gauss–Legendre in z = cos θ times equispaced
//! azimuths. With N Gauss nodes and M azimuths it integrates exactly every spherical
//! polynomial of degree ≤ min(2N − 1, M − 1), in particular every product of SH functions
//! whose bands sum to at most that degree.

use std::f64::consts::PI;

use glam::DVec3;

use super::legendre::{legendre, legendre_derivative};

/// Nodes and weights of the `n`-point Gauss–Legendre rule on [−1, 1] (exact for
/// polynomials of degree ≤ 2n − 1). Nodes by Newton's method on P_n from Tricomi's
/// initial guesses; converges to machine precision for every n used here (tested to 200).
pub fn gauss_legendre(n: usize) -> Vec<(f64, f64)> {
    (0..n)
        .map(|i| {
            let mut x = (PI * (i as f64 + 0.75) / (n as f64 + 0.5)).cos();
            for _ in 0..100 {
                let p = legendre(n + 1, x)[n];
                let dp = legendre_derivative(n + 1, x)[n];
                let step = p / dp;
                x -= step;
                if step.abs() < 1e-16 {
                    break;
                }
            }
            let dp = legendre_derivative(n + 1, x)[n];
            (x, 2.0 / ((1.0 - x * x) * dp * dp))
        })
        .collect()
}

/// A product rule on the sphere.
#[derive(Debug, Clone)]
pub struct SphereQuadrature {
    z_rule: Vec<(f64, f64)>,
    azimuths: usize,
}

impl SphereQuadrature {
    /// The smallest product rule exact for spherical polynomials of degree ≤ `degree`:
    /// ⌊degree/2⌋ + 1 Gauss nodes and degree + 1 azimuths.
    pub fn exact_for_degree(degree: usize) -> SphereQuadrature {
        SphereQuadrature {
            z_rule: gauss_legendre(degree / 2 + 1),
            azimuths: degree + 1,
        }
    }

    pub fn len(&self) -> usize {
        self.z_rule.len() * self.azimuths
    }

    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// Every node as (unit direction, weight); the weights sum to 4π.
    pub fn points(&self) -> impl Iterator<Item = (DVec3, f64)> + '_ {
        let azimuth_weight = 2.0 * PI / self.azimuths as f64;
        self.z_rule.iter().flat_map(move |&(z, w)| {
            let r = (1.0 - z * z).max(0.0).sqrt();
            (0..self.azimuths).map(move |k| {
                let phi = 2.0 * PI * (k as f64 + 0.5) / self.azimuths as f64;
                (DVec3::new(r * phi.cos(), r * phi.sin(), z), w * azimuth_weight)
            })
        })
    }

    /// SH projection f_i = ∫ f y_i dω at `order`; exact when f is a spherical polynomial
    /// of degree ≤ (this rule's degree) − (order − 1).
    pub fn project(&self, order: usize, f: impl Fn(DVec3) -> f64) -> Vec<f64> {
        let mut out = vec![0.0; order * order];
        for (dir, weight) in self.points() {
            let value = f(dir) * weight;
            for (o, y) in out.iter_mut().zip(super::basis(order, dir)) {
                *o += value * y;
            }
        }
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn gauss_legendre_integrates_monomials_exactly_up_to_2n_minus_1() {
        for n in [1, 2, 5, 16, 64, 200] {
            let rule = gauss_legendre(n);
            for k in 0..(2 * n).min(40) {
                let exact = if k % 2 == 1 { 0.0 } else { 2.0 / (k as f64 + 1.0) };
                let sum: f64 = rule.iter().map(|(x, w)| w * x.powi(k as i32)).sum();
                assert!((sum - exact).abs() < 1e-13, "n = {n}, x^{k}: {sum} vs {exact}");
            }
        }
    }

    #[test]
    fn sphere_rule_weights_sum_to_4_pi_and_integrate_z_squared() {
        let q = SphereQuadrature::exact_for_degree(6);
        let total: f64 = q.points().map(|(_, w)| w).sum();
        assert!((total - 4.0 * PI).abs() < 1e-12);
        let z2: f64 = q.points().map(|(d, w)| w * d.z * d.z).sum();
        assert!((z2 - 4.0 * PI / 3.0).abs() < 1e-12);
        let x2y2: f64 = q.points().map(|(d, w)| w * d.x * d.x * d.y * d.y).sum();
        assert!((x2y2 - 4.0 * PI / 15.0).abs() < 1e-12);
    }

    #[test]
    fn projection_recovers_band_limited_functions_exactly() {
        let f: Vec<f64> = (0..25).map(|i| ((i * 7 % 11) as f64 - 5.0) / 3.0).collect();
        // f has degree 4; projecting onto order 5 needs degree 4 + 4 = 8.
        let q = SphereQuadrature::exact_for_degree(8);
        let projected = q.project(5, |d| crate::sh::evaluate(&f, d));
        for (a, b) in projected.iter().zip(&f) {
            assert!((a - b).abs() < 1e-13);
        }
    }

    #[test]
    fn one_node_fewer_is_not_exact() {
        // Degree-4 integrand z⁴ needs 3 Gauss nodes; the degree-3 rule has 2.
        let q = SphereQuadrature::exact_for_degree(3);
        let z4: f64 = q.points().map(|(d, w)| w * d.z.powi(4)).sum();
        assert!((z4 - 4.0 * PI / 5.0).abs() > 1e-3);
    }
}
