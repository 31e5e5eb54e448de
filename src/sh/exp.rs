//! SH exponentiation exp*(f): the SH of the function exp(f(ω)), approximated as Ren et
//! al. (2006) do by the reference exp(M_f)·1, where M_f is f's product matrix.
//!
//! Methods, all approximating [`exp_reference`]:
//! - `Ps(k)`: the power series 1 + f + f∗f/2! + … with k terms (no DC isolation).
//! - `Dc`: DC isolation, exp*(f) = e^{f₀/√(4π)} · exp*(f̂) with f̂ = f minus its DC, which is
//!   exact, followed by the first-order term exp*(f̂) ≈ 1 + f̂. The cheapest method.
//! - `Ol`: DC isolation, then optimal linear exp*(f̂) ≈ a(‖f̂‖)·1 + b(‖f̂‖)·f̂ with a, b
//!   tabulated per order by our least-squares fit (`cargo run --bin fit-ol-tables`).
//! - `Hyb`: DC isolation; scale f̂ by 2^−k so that ‖f̂‖/2^k ≤ [`hyb_threshold`]; OL;
//!   square k times (exp(x) = exp(x/2^k)^(2^k)).
//! - `Reference`: eigendecomposition of the symmetric M_f̂ (after DC isolation).

use nalgebra::{DMatrix, SymmetricEigen};

use super::gaunt::{product, product_matrix};
use super::{coefficient_count, constant, ol_tables, order_of};

const SQRT_4PI: f64 = 3.544_907_701_811_032;

/// Norm ‖f̂‖ up to which HYB applies OL directly at `order`: 1 at order 2 (where OL is
/// nearly exact), 0.25 up to order 4, 0.125 above. OL is first-order accurate in f̂ and the
/// higher bands amplify its error: a 11.5° cap under a point light (‖f̂‖ ≈ 0.3–0.6) erred 8
/// points at order 6 and 23 at order 8 with threshold 1, under 2 with these
/// (tests/shading_laws.rs checks it), for two or three more squarings; docs/sh-accuracy.md
/// has the random-configuration errors.
pub fn hyb_threshold(order: usize) -> f64 {
    match order {
        0..=2 => 1.0,
        3 | 4 => 0.25,
        _ => 0.125,
    }
}

/// How to exponentiate an SH vector; see the module documentation.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, serde::Serialize, serde::Deserialize)]
pub enum ExpMethod {
    Dc,
    Ol,
    Hyb,
    /// Power series with this many terms (1 = just the constant).
    Ps(usize),
    Reference,
}

/// exp*(f) by `method`. The order is that of `f` (its length must be a square).
pub fn exp(method: ExpMethod, f: &[f64]) -> Vec<f64> {
    match method {
        ExpMethod::Ps(terms) => exp_ps(f, terms),
        ExpMethod::Dc => exp_dc_isolated(f, |h| {
            let mut out = h.to_vec();
            out[0] = SQRT_4PI;
            out
        }),
        ExpMethod::Ol => exp_dc_isolated(f, exp_ol),
        ExpMethod::Hyb => exp_hyb(f, hyb_threshold(order(f))),
        ExpMethod::Reference => exp_reference(f),
    }
}

fn order(f: &[f64]) -> usize {
    order_of(f.len()).expect("an SH vector has a square number of coefficients")
}

fn norm(f: &[f64]) -> f64 {
    f.iter().map(|v| v * v).sum::<f64>().sqrt()
}

/// DC isolation: e^{f₀/√(4π)} · inner(f̂), f̂ = f with its DC coefficient set to zero.
pub fn exp_dc_isolated(f: &[f64], inner: impl Fn(&[f64]) -> Vec<f64>) -> Vec<f64> {
    if f.is_empty() {
        return Vec::new();
    }
    let scale = (f[0] / SQRT_4PI).exp();
    let mut hat = f.to_vec();
    hat[0] = 0.0;
    inner(&hat).into_iter().map(|v| v * scale).collect()
}

/// exp(M_f)·1 by eigendecomposition of the symmetric product matrix M_f̂ of the DC-free
/// part, with the DC folded into the eigenvalues (M_f = M_f̂ + f₀/√(4π)·I), so a large
/// negative DC damps the ringing modes instead of multiplying an overflowed value by zero.
/// Exponents are capped at `MAX_EXPONENT`: beyond it the value (over 1e43, where a
/// visibility is at most 1) can only come from the ringing of a truncated log-visibility,
/// and saturating keeps everything downstream finite.
pub fn exp_reference(f: &[f64]) -> Vec<f64> {
    if f.is_empty() {
        return Vec::new();
    }
    let order = order(f);
    let n = coefficient_count(order);
    let dc = f[0] / SQRT_4PI;
    let mut hat = f.to_vec();
    hat[0] = 0.0;
    let matrix = DMatrix::from_row_slice(n, n, &product_matrix(order, &hat));
    let eigen = SymmetricEigen::new(matrix);
    // exp(M)·1 = V e^Λ Vᵀ 1, and 1 = √(4π)·e₀, so Vᵀ1 = √(4π)·(row 0 of V).
    let v = &eigen.eigenvectors;
    let weights: Vec<f64> = (0..n)
        .map(|k| (eigen.eigenvalues[k] + dc).min(MAX_EXPONENT).exp() * v[(0, k)] * SQRT_4PI)
        .collect();
    (0..n).map(|i| (0..n).map(|k| v[(i, k)] * weights[k]).sum()).collect()
}

/// Largest exponent [`exp_reference`] and [`exp_hyb`] evaluate (e^100 ≈ 2.7e43).
pub const MAX_EXPONENT: f64 = 100.0;

/// The power series Σ_{k<terms} f^{∗k}/k!.
pub fn exp_ps(f: &[f64], terms: usize) -> Vec<f64> {
    let order = order(f);
    let mut term = constant(order, 1.0);
    let mut sum = vec![0.0; f.len()];
    for k in 0..terms {
        if k > 0 {
            term = product(order, &term, f).into_iter().map(|v| v / k as f64).collect();
        }
        for (s, t) in sum.iter_mut().zip(&term) {
            *s += t;
        }
    }
    sum
}

/// The tabulated OL coefficients (a, b) at `order` for ‖f̂‖ = `norm`, interpolated
/// linearly; beyond the table the last entry is used (OL is not meant for such norms).
pub fn ol_coefficients(order: usize, norm: f64) -> (f64, f64) {
    let Some(table) = ol_tables::table(order) else {
        return (1.0, 1.0);
    };
    let position = (norm / ol_tables::NORM_STEP).max(0.0);
    let i = (position.floor() as usize).min(table.len() - 1);
    let j = (i + 1).min(table.len() - 1);
    let t = (position - i as f64).clamp(0.0, 1.0);
    let (a0, b0) = table[i];
    let (a1, b1) = table[j];
    (a0 + t * (a1 - a0), b0 + t * (b1 - b0))
}

/// Optimal linear exp*(f̂) ≈ a·1 + b·f̂ for a DC-free f̂.
pub fn exp_ol(hat: &[f64]) -> Vec<f64> {
    let (a, b) = ol_coefficients(order(hat), norm(hat));
    let mut out: Vec<f64> = hat.iter().map(|v| b * v).collect();
    out[0] += a * SQRT_4PI;
    out
}

/// HYB with an explicit threshold on ‖f̂‖ (must be > 0): with k = ⌈log₂(‖f̂‖/threshold)⌉,
/// exp*(f) = (e^{f₀/(√(4π)·2^k)} · OL(f̂/2^k))^(∗2^k).
///
/// The squarings keep the vector at unit norm and carry its magnitude as a logarithm, so
/// thousands of stacked blockers (whose truncated log-visibility rings to huge values)
/// neither overflow nor turn into NaN; the magnitude saturates like [`exp_reference`]'s.
pub fn exp_hyb(f: &[f64], threshold: f64) -> Vec<f64> {
    if f.is_empty() {
        return Vec::new();
    }
    let order = order(f);
    let mut hat = f.to_vec();
    hat[0] = 0.0;
    let n = norm(&hat);
    let squarings = if n > threshold {
        (n / threshold).log2().ceil() as i32
    } else {
        0
    };
    let scale = 0.5f64.powi(squarings);
    let scaled: Vec<f64> = hat.iter().map(|v| v * scale).collect();
    let mut g = exp_ol(&scaled);
    // g = e^{ln_magnitude} · unit vector.
    let mut ln_magnitude = f[0] / SQRT_4PI * scale;
    for _ in 0..squarings {
        let g_norm = norm(&g);
        if g_norm == 0.0 || !g_norm.is_finite() {
            break;
        }
        let unit: Vec<f64> = g.iter().map(|v| v / g_norm).collect();
        ln_magnitude = 2.0 * (ln_magnitude + g_norm.ln());
        g = product(order, &unit, &unit);
    }
    let factor = ln_magnitude.min(MAX_EXPONENT).exp();
    g.into_iter().map(|v| v * factor).collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sh::log_visibility;

    /// exp*(0) is the constant 1 exactly, whatever the method: the OL tables start at
    /// a(0) = 1, and every method keeps the zero vector zero. The shaders skip a light's
    /// exponentiation where its log-visibility is zero (`harmonic_radiance`), relying on it.
    #[test]
    fn the_exponential_of_zero_is_exactly_one_for_every_method() {
        for order in 2..=8 {
            assert_eq!(crate::sh::ol_tables::table(order).expect("a table")[0].0, 1.0);
            let zero = vec![0.0; order * order];
            let mut one = zero.clone();
            one[0] = SQRT_4PI;
            for method in [ExpMethod::Dc, ExpMethod::Ol, ExpMethod::Hyb, ExpMethod::Ps(6)] {
                // The constant 1 as each method writes it (√(4π) computed two ways).
                assert!(
                    max_abs_diff(&exp(method, &zero), &one) <= 1e-15,
                    "order {order}, {method:?}"
                );
            }
        }
    }

    fn max_abs_diff(a: &[f64], b: &[f64]) -> f64 {
        a.iter().zip(b).map(|(x, y)| (x - y).abs()).fold(0.0, f64::max)
    }

    fn caps(order: usize, count: usize, epsilon: f64) -> Vec<f64> {
        let caps: Vec<(glam::DVec3, f64)> = (0..count)
            .map(|k| {
                let t = k as f64 * 2.3 + 0.4;
                let dir = glam::DVec3::new(t.cos(), (1.7 * t).sin(), (0.9 * t).cos() + 0.5).normalize();
                (dir, 0.2 + 0.1 * (k % 5) as f64)
            })
            .collect();
        log_visibility(order, &caps, epsilon)
    }

    #[test]
    fn exp_of_zero_is_one_for_every_method() {
        for method in [
            ExpMethod::Dc,
            ExpMethod::Ol,
            ExpMethod::Hyb,
            ExpMethod::Ps(5),
            ExpMethod::Reference,
        ] {
            let g = exp(method, &[0.0; 16]);
            assert!(max_abs_diff(&g, &constant(4, 1.0)) < 1e-13, "{method:?}");
        }
    }

    #[test]
    fn exp_of_a_constant_is_e_to_the_constant() {
        for c in [-3.0, 0.5, 2.0] {
            let f = constant(4, c);
            let expected = constant(4, f64::exp(c));
            for method in [ExpMethod::Dc, ExpMethod::Ol, ExpMethod::Hyb, ExpMethod::Reference] {
                assert!(max_abs_diff(&exp(method, &f), &expected) < 1e-12, "{method:?} c = {c}");
            }
            assert!(max_abs_diff(&exp(ExpMethod::Ps(40), &f), &expected) < 1e-10);
        }
    }

    #[test]
    fn power_series_converges_to_the_reference() {
        let f = caps(4, 3, 0.1);
        let reference = exp_reference(&f);
        let errors: Vec<f64> = [4, 8, 16, 32, 64]
            .iter()
            .map(|&k| max_abs_diff(&exp_ps(&f, k), &reference))
            .collect();
        assert!(errors[4] < 1e-9, "{errors:?}");
        assert!(errors.windows(2).all(|w| w[1] <= w[0] + 1e-12), "{errors:?}");
    }

    #[test]
    fn dc_isolation_is_exact() {
        let f = caps(4, 2, 0.2);
        let isolated = exp_dc_isolated(&f, |hat| exp_ps(hat, 60));
        assert!(max_abs_diff(&isolated, &exp_ps(&f, 80)) < 1e-9);
    }

    #[test]
    fn reference_is_the_exponential_of_the_function_for_band_limited_inputs() {
        // For f = c·y₁₀ (a linear function of z), exp(f) is not band-limited, but its
        // projection's low coefficients follow from the series and the reference agrees
        // with a long power series.
        let mut f = vec![0.0; 25];
        f[2] = 1.5;
        assert!(max_abs_diff(&exp_reference(&f), &exp_ps(&f, 60)) < 1e-10);
    }

    #[test]
    fn no_nan_for_thousands_of_coincident_caps() {
        let single = caps(4, 1, 0.1);
        let many: Vec<f64> = single.iter().map(|v| v * 10_000.0).collect();
        for method in [ExpMethod::Dc, ExpMethod::Ol, ExpMethod::Hyb, ExpMethod::Reference] {
            let g = exp(method, &many);
            assert!(g.iter().all(|v| v.is_finite()), "{method:?}: {g:?}");
        }
    }
}

#[cfg(test)]
mod accuracy_tests {
    use super::*;
    use crate::sh::accuracy::{measure, relative_error};
    use crate::sh::ol_fit::{OL_TRAINING_SEED, OL_TRAINING_SHAPES, fit_ol_at, training_shapes};
    use crate::sh::{log_visibility, ol_tables, rotate_zh};

    #[test]
    fn committed_ol_table_matches_a_fresh_fit() {
        let order = 3;
        let shapes = training_shapes(order, OL_TRAINING_SHAPES, OL_TRAINING_SEED);
        let table = ol_tables::table(order).expect("order 3 is tabulated");
        for k in [1, 8, 19] {
            assert_eq!(
                fit_ol_at(&shapes, k as f64 * ol_tables::NORM_STEP),
                table[k],
                "entry {k}"
            );
        }
        for order in 2..=8 {
            assert_eq!(ol_tables::table(order).expect("tabulated")[0], (1.0, 1.0));
        }
    }

    /// Order 4, mean relative error per ‖f̂‖ bucket (0–1, 1–4.8, 4.8–10, 10–20); the bounds
    /// sit above the values docs/sh-accuracy.md reports (HYB 0.011, 0.050, 0.14, 0.19).
    #[test]
    fn hyb_stays_accurate_up_to_norm_20_and_beats_ol_and_dc() {
        let hyb = measure(4, ExpMethod::Hyb, 8);
        let ol = measure(4, ExpMethod::Ol, 8);
        let dc = measure(4, ExpMethod::Dc, 8);
        let bounds = [0.02, 0.08, 0.25, 0.35];
        for (bucket, bound) in bounds.into_iter().enumerate() {
            assert!(
                hyb.mean_relative_error[bucket] < bound,
                "bucket {bucket}: {:?}",
                hyb.mean_relative_error
            );
            assert!(hyb.mean_relative_error[bucket] <= ol.mean_relative_error[bucket] + 1e-12);
            assert!(hyb.mean_relative_error[bucket] < dc.mean_relative_error[bucket]);
        }
        assert!(
            ol.mean_relative_error[1] < 0.25,
            "OL within its published range: {:?}",
            ol.mean_relative_error
        );
    }

    /// `count` caps on one spot: one cap's log-visibility times `count`.
    fn coincident_caps(order: usize, count: usize, epsilon: f64, half_angle: f64) -> Vec<f64> {
        let dir = glam::DVec3::new(0.3, 0.5, 0.8).normalize();
        log_visibility(order, &[(dir, half_angle)], epsilon)
            .into_iter()
            .map(|c| c * count as f64)
            .collect()
    }

    /// Stacked caps ring: the truncated log-visibility grows positive lobes that the
    /// reference exponentiates too, so beyond ‖f̂‖ ≈ 20 no method is meaningful (the sphere
    /// fit must merge coincident blockers). Up to 16 caps HYB tracks the reference (measured
    /// 0.015, 0.030, 0.10 relative for 1, 4, 16); beyond, everything must stay finite.
    #[test]
    fn coincident_caps_from_1_to_1000_stay_finite_and_bounded() {
        for count in [1, 4, 16, 64, 256, 1000] {
            let f = coincident_caps(4, count, 0.1, 0.3);
            let reference = exp_reference(&f);
            let hyb = exp(ExpMethod::Hyb, &f);
            let ol = exp(ExpMethod::Ol, &f);
            assert!(
                hyb.iter().chain(&reference).chain(&ol).all(|v| v.is_finite()),
                "{count} caps"
            );
            let error = relative_error(&hyb, &reference);
            assert!(error.is_finite());
            if count <= 16 {
                assert!(error < 0.2, "{count} coincident caps: HYB relative error {error}");
            }
        }
    }

    #[test]
    fn no_nan_or_inf_at_the_extremes() {
        let light = rotate_zh(&crate::sh::clamped_cosine_zh(4), glam::DVec3::Y);
        for epsilon in [1e-6, 1e-3, 0.1, 0.5, 0.99] {
            for count in [1, 10_000] {
                let f = coincident_caps(4, count, epsilon, 0.3);
                for method in [
                    ExpMethod::Dc,
                    ExpMethod::Ol,
                    ExpMethod::Hyb,
                    ExpMethod::Ps(8),
                    ExpMethod::Reference,
                ] {
                    let g = exp(method, &f);
                    for intensity in [0.0, 1.0, 1e6] {
                        let shaded: f64 = g.iter().zip(&light).map(|(a, b)| a * b * intensity).sum();
                        assert!(
                            shaded.is_finite(),
                            "{method:?} ε = {epsilon}, {count} caps, I = {intensity}"
                        );
                    }
                }
            }
        }
    }
}
