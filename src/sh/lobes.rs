//! Zonal harmonics of the BRDF lobes in closed form, for carrying a BRDF inside the SH
//! (Ren et al. 2006: the log-BRDF added to the log-visibility, or the BRDF multiplied in
//! by the SH product).
//!
//! The lobe of normalised Phong exponent r about its axis is f(t) = (r+1)/(2π) · t^r for
//! t = cos θ > 0 and 0 below; r = 1 is the diffuse lobe cos θ/π. Its log lobe follows
//! shading-model.md §4: ln max(f(t), ε), so ln ε where the lobe is below ε (the whole lower
//! hemisphere). Both are projected through the monomial moments m_k = ∫₋₁¹ g(t) t^k dt,
//! which have closed forms for any real r, and the monomial coefficients a_lk of the
//! Legendre polynomials: z_l = 2π √((2l+1)/(4π)) Σ_k a_lk m_k. The shaders evaluate the
//! same sums per pixel (the exponent is a material's); `zonal::zh_of_function` checks them
//! by quadrature.

use std::f64::consts::PI;

/// Monomial coefficients of the Legendre polynomials P_0 … P_{order−1}: row l holds a_l0 …
/// a_ll with P_l(t) = Σ_k a_lk t^k, by (l+1) P_{l+1} = (2l+1) t P_l − l P_{l−1}.
pub fn legendre_monomials(order: usize) -> Vec<Vec<f64>> {
    let mut rows: Vec<Vec<f64>> = Vec::with_capacity(order);
    for l in 0..order {
        let row = match l {
            0 => vec![1.0],
            1 => vec![0.0, 1.0],
            _ => {
                let lf = (l - 1) as f64;
                let (previous, before) = (&rows[l - 1], &rows[l - 2]);
                (0..=l)
                    .map(|k| {
                        let shifted = if k >= 1 {
                            previous.get(k - 1).copied().unwrap_or(0.0)
                        } else {
                            0.0
                        };
                        let lower = before.get(k).copied().unwrap_or(0.0);
                        ((2.0 * lf + 1.0) * shifted - lf * lower) / (lf + 1.0)
                    })
                    .collect()
            }
        };
        rows.push(row);
    }
    rows
}

/// z_l = 2π √((2l+1)/(4π)) Σ_k a_lk m_k for the moments `moments` (m_k = ∫₋₁¹ g t^k dt).
fn zh_from_moments(order: usize, moments: &[f64]) -> Vec<f64> {
    legendre_monomials(order)
        .iter()
        .enumerate()
        .map(|(l, row)| {
            let sum: f64 = row.iter().zip(moments).map(|(a, m)| a * m).sum();
            2.0 * PI * ((2 * l + 1) as f64 / (4.0 * PI)).sqrt() * sum
        })
        .collect()
}

/// ZH of the normalised Phong lobe (r+1)/(2π) · max(cos θ, 0)^r (r = `exponent` ≥ 0; 1 is
/// the diffuse cos θ/π): m_k = (r+1) / (2π (r+k+1)).
pub fn phong_lobe_zh(order: usize, exponent: f64) -> Vec<f64> {
    let r = exponent.max(0.0);
    let moments: Vec<f64> = (0..order)
        .map(|k| (r + 1.0) / (2.0 * PI * (r + k as f64 + 1.0)))
        .collect();
    zh_from_moments(order, &moments)
}

/// Â_l = √(4π/(2l+1)) · π · (ZH of cos θ/π)_l: how the clamped cosine scales band l of a
/// radiance SH into irradiance (E_lm = Â_l L_lm, Funk–Hecke), the factor the environment's
/// radiance is recovered from its irradiance SH by.
pub fn irradiance_band_scale(l: usize) -> f64 {
    (4.0 * PI / (2 * l + 1) as f64).sqrt() * phong_lobe_zh(l + 1, 1.0)[l] * PI
}

/// ZH of ln max((r+1)/(2π) · cos^r θ, ε) on the upper hemisphere and ln ε below (shading-model.md
/// §4's log-BRDF; r = 1 is its diffuse ln max(cos θ/π, ε)). With the peak P = (r+1)/(2π),
/// q = min(ln(ε/P), 0) and the kink t₀ = e^{q/r} where the lobe meets ε:
/// m_k = ln ε ∫₋₁^{t₀} t^k + ln P ∫_{t₀}^1 t^k + r ∫_{t₀}^1 t^k ln t
///     = ln ε (t₀^{k+1} − (−1)^{k+1})/(k+1) + ln P (1 − t₀^{k+1})/(k+1)
///       − r/(k+1)² − t₀^{k+1} q/(k+1) + r t₀^{k+1}/(k+1)²,
/// where r ln t₀ = q is used so that r → 0 (t₀ → 0) stays finite.
pub fn log_phong_lobe_zh(order: usize, exponent: f64, epsilon: f64) -> Vec<f64> {
    zh_from_moments(order, &log_lobe_moments(order, exponent, epsilon))
}

fn log_lobe_moments(order: usize, exponent: f64, epsilon: f64) -> Vec<f64> {
    let r = exponent.max(0.0);
    let ln_epsilon = epsilon.ln();
    let ln_peak = ((r + 1.0) / (2.0 * PI)).ln();
    let q = (ln_epsilon - ln_peak).min(0.0);
    let t0 = (q / r.max(LOG_LOBE_MIN_EXPONENT)).exp();
    (0..order)
        .map(|k| {
            let k1 = (k + 1) as f64;
            let t0_k1 = t0.powi(k as i32 + 1);
            let below = (t0_k1 - (-1f64).powi(k as i32 + 1)) / k1;
            let above = (1.0 - t0_k1) / k1;
            let log_cosine = -r / (k1 * k1) - t0_k1 * q / k1 + r * t0_k1 / (k1 * k1);
            ln_epsilon * below + ln_peak * above + log_cosine
        })
        .collect()
}

/// Exponents below this take it for the kink t₀ = e^{q/r}, which is then 0 to the last
/// digit for any ε under the peak, so the lobe is its constant upper hemisphere.
pub const LOG_LOBE_MIN_EXPONENT: f64 = 1e-6;

/// The sharpest Phong exponent an order's SH carry without visibly blurring the highlight:
/// (order/2)², which matches Ren et al. 2006's observation that low orders carry only broad lobes (order 4 resolves
/// exponents up to about 4, order 8 up to about 16). Sharper lobes keep their exact
/// per-light specular, through the visibility averaged over the light.
pub fn max_carried_phong_exponent(order: usize) -> f64 {
    let half = order as f64 / 2.0;
    half * half
}

#[cfg(test)]
mod tests {

    #[test]
    fn irradiance_band_scales_are_ramamoorthi_and_hanrahans() {
        // Ramamoorthi and Hanrahan 2001: Â_0 = π, Â_1 = 2π/3, Â_2 = π/4.
        for (l, expected) in [(0, PI), (1, 2.0 * PI / 3.0), (2, PI / 4.0)] {
            assert!((irradiance_band_scale(l) - expected).abs() < 1e-12, "band {l}");
        }
    }

    use super::*;
    use crate::sh::{clamped_cosine_zh, log_diffuse_zh, log_phong_zh, zh_of_function};

    fn assert_close(actual: &[f64], expected: &[f64], tolerance: f64) {
        assert_eq!(actual.len(), expected.len());
        for (l, (a, e)) in actual.iter().zip(expected).enumerate() {
            assert!(
                (a - e).abs() <= tolerance * e.abs().max(1.0),
                "band {l}: {a} vs {e} ({actual:?} vs {expected:?})"
            );
        }
    }

    #[test]
    fn legendre_monomials_evaluate_to_the_recurrence() {
        let rows = legendre_monomials(9);
        for &t in &[-0.9, -0.3, 0.0, 0.41, 1.0] {
            let reference = crate::sh::legendre(9, t);
            for (row, p) in rows.iter().zip(reference) {
                let value: f64 = row.iter().enumerate().map(|(k, a)| a * t.powi(k as i32)).sum();
                assert!((value - p).abs() < 1e-12, "{value} vs {p} at {t}");
            }
        }
        assert_eq!(rows[2], vec![-0.5, 0.0, 1.5]);
    }

    #[test]
    fn the_diffuse_lobe_is_the_clamped_cosine_of_the_design() {
        assert_close(&phong_lobe_zh(4, 1.0), &[0.282095, 0.325735, 0.157696, 0.0], 2e-6);
        for order in 2..=8 {
            assert_close(&phong_lobe_zh(order, 1.0), &clamped_cosine_zh(order), 1e-12);
        }
    }

    #[test]
    fn phong_lobes_match_quadrature_for_real_exponents() {
        for &r in &[0.0, 0.5, 3.0, 7.25, 40.0] {
            let lobe = |t: f64| {
                if t > 0.0 {
                    (r + 1.0) / (2.0 * PI) * t.powf(r)
                } else {
                    0.0
                }
            };
            let quadrature = zh_of_function(8, lobe, &[0.0]);
            // t^r with r < 1 has an unbounded slope at 0, where the quadrature loses digits.
            assert_close(&phong_lobe_zh(8, r), &quadrature, 1e-7);
            // Every lobe is normalised: ∫ f dω = 1, so z_0 = 1/√(4π) exactly.
            assert!((phong_lobe_zh(8, r)[0] - 1.0 / (4.0 * PI).sqrt()).abs() < 1e-15);
        }
    }

    #[test]
    fn log_lobes_match_quadrature() {
        for &epsilon in &[0.02, 0.1, 0.2] {
            for order in [2, 4, 8] {
                assert_close(
                    &log_phong_lobe_zh(order, 1.0, epsilon),
                    &log_diffuse_zh(order, epsilon),
                    1e-10,
                );
                for &r in &[0.0, 0.3, 2.0, 9.0, 64.0, 1e4] {
                    // Small r puts the kink near t = 0, where r ln t is steep: the
                    // quadrature is then the less accurate side (~1e-8, see below).
                    assert_close(
                        &log_phong_lobe_zh(order, r, epsilon),
                        &log_phong_zh(order, r, epsilon),
                        1e-7,
                    );
                }
            }
        }
    }

    #[test]
    fn a_steep_log_lobe_matches_high_precision_quadrature() {
        // r = 0.3, ε = 0.02, order 4, by mpmath's tanh-sinh quadrature at 30 digits on the
        // panels [−1, 0], [0, t₀], [t₀, 1] (a scratch script, not the crate).
        let expected = [
            -10.257919708908743,
            3.356271472202162,
            0.3960862925912338,
            -1.0618784103807741,
        ];
        assert_close(&log_phong_lobe_zh(4, 0.3, 0.02), &expected, 1e-13);
    }

    #[test]
    fn a_lobe_below_epsilon_everywhere_is_the_constant_ln_epsilon() {
        // r = 0: peak 1/(2π) ≈ 0.159 < ε = 0.2, so ln max(f, ε) = ln ε on the whole sphere.
        let zh = log_phong_lobe_zh(4, 0.0, 0.2);
        assert_close(&zh, &[0.2f64.ln() * (4.0 * PI).sqrt(), 0.0, 0.0, 0.0], 1e-12);
        assert!(log_phong_lobe_zh(8, 0.0, 1e-30).iter().all(|z| z.is_finite()));
    }

    #[test]
    fn carried_exponents_follow_the_measured_captures() {
        assert_eq!(max_carried_phong_exponent(4), 4.0);
        assert_eq!(max_carried_phong_exponent(8), 16.0);
        assert!(
            max_carried_phong_exponent(2) >= 1.0,
            "the diffuse lobe is always carried"
        );
    }
}
