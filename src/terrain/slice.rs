//! Slice occlusion vectors of a height-field horizon in the normalised Legendre basis
//! (Nowrouzezahrai & Snyder 2009; Giraud's thesis eq. 3.26–3.27).
//!
//! Along one azimuth, the directions from zenith angle π/2 − σ down to the nadir are
//! blocked by a horizon of elevation σ. In z = cos θ that is the interval [−1, sin σ], and
//! its coefficients in the orthonormal basis P̂_l(z) = √((2l+1)/2)·P_l(z) of [−1, 1] are
//! v̄_l(σ) = ∫_{−1}^{sin σ} P̂_l(z) dz. For order 4 (shading-model.md §4):
//! v̄(σ) = [(sin σ + 1)/√2, −3cos²σ/(2√6), −5 sin σ cos²σ/(2√10), 7cos²σ(5cos²σ − 4)/(8√14)].

use crate::sh::legendre_derivative;

/// v̄_0 … v̄_{order−1} for a horizon of elevation σ given as `sin_elevation` = sin σ
/// (clamped to [−1, 1]; −1: nothing above the nadir blocks, 1: the whole slice).
///
/// Stable form: ∫_{−1}^{s} P_l = (P_{l+1}(s) − P_{l−1}(s))/(2l+1) = −(1 − s²)·P_l′(s)/(l(l+1))
/// for l ≥ 1 (Legendre's (1 − x²)P_l′ = l(l+1)/(2l+1)·(P_{l−1} − P_{l+1})), so no
/// difference of nearly equal polynomials is formed near the poles.
pub fn slice_vector(order: usize, sin_elevation: f64) -> Vec<f64> {
    let s = if sin_elevation.is_nan() {
        -1.0
    } else {
        sin_elevation.clamp(-1.0, 1.0)
    };
    let derivative = legendre_derivative(order, s);
    (0..order)
        .map(|l| {
            let normalisation = ((2 * l + 1) as f64 / 2.0).sqrt();
            if l == 0 {
                normalisation * (1.0 + s)
            } else {
                -normalisation * (1.0 - s * s) * derivative[l] / (l * (l + 1)) as f64
            }
        })
        .collect()
}

/// The normalised Legendre polynomials P̂_0(z) … P̂_{order−1}(z), the slice basis.
pub fn slice_basis(order: usize, z: f64) -> Vec<f64> {
    crate::sh::legendre(order, z)
        .into_iter()
        .enumerate()
        .map(|(l, p)| ((2 * l + 1) as f64 / 2.0).sqrt() * p)
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sh::gauss_legendre;

    /// The order-4 closed form printed in shading-model.md §4, written out independently.
    fn printed_closed_form(sigma: f64) -> [f64; 4] {
        let (s, c) = sigma.sin_cos();
        let c2 = c * c;
        [
            (s + 1.0) / 2f64.sqrt(),
            -3.0 * c2 / (2.0 * 6f64.sqrt()),
            -5.0 * s * c2 / (2.0 * 10f64.sqrt()),
            7.0 * c2 * (5.0 * c2 - 4.0) / (8.0 * 14f64.sqrt()),
        ]
    }

    #[test]
    fn matches_the_printed_order_4_closed_form() {
        for k in 0..=40 {
            let sigma = -std::f64::consts::FRAC_PI_2 + k as f64 * std::f64::consts::PI / 40.0;
            let v = slice_vector(4, sigma.sin());
            for (a, b) in v.iter().zip(printed_closed_form(sigma)) {
                assert!((a - b).abs() < 1e-14, "σ = {sigma}: {v:?}");
            }
        }
    }

    #[test]
    fn matches_quadrature_of_the_blocked_interval_at_order_8() {
        let rule = gauss_legendre(40);
        for sigma_deg in [-80.0, -30.0, -1.0, 0.0, 0.5, 20.0, 60.0, 89.0] {
            let s = f64::to_radians(sigma_deg).sin();
            // ∫_{−1}^{s} P̂_l(z) dz with Gauss–Legendre mapped onto [−1, s].
            let half = (s + 1.0) / 2.0;
            let mut quadrature = vec![0.0; 8];
            for &(x, w) in &rule {
                let z = -1.0 + half * (x + 1.0);
                for (q, p) in quadrature.iter_mut().zip(slice_basis(8, z)) {
                    *q += half * w * p;
                }
            }
            for (a, b) in slice_vector(8, s).iter().zip(&quadrature) {
                assert!((a - b).abs() < 1e-13, "σ = {sigma_deg}°");
            }
        }
    }

    #[test]
    fn ends_are_the_whole_slice_and_nothing() {
        let full = slice_vector(6, 1.0);
        assert!((full[0] - 2f64.sqrt()).abs() < 1e-15);
        assert!(full[1..].iter().all(|v| v.abs() < 1e-15));
        assert!(slice_vector(6, -1.0).iter().all(|v| v.abs() < 1e-15));
        assert!(slice_vector(6, f64::NAN).iter().all(|v| v.abs() < 1e-15));
    }
}
