//! Zonal harmonics (ZH): functions symmetric about +z, stored as one value per band
//! (z_l = the m = 0 coefficient), and their rotation to any axis.

use std::f64::consts::PI;

use glam::DVec3;

use num_traits::Float;

use super::legendre::legendre;
use super::quadrature::gauss_legendre;

/// ZH of the indicator of a spherical cap of half-angle `half_angle_rad` around +z.
///
/// Stable form (design §4): with s = sin θ and c = cos θ,
/// z_0 = √π · s²/(1 + c) (= √π(1 − c) without the cancellation), and
/// z_l = √(π(2l+1)) / (l(l+1)) · s² · P_l′(c)   (l ≥ 1),
/// equal to the textbook √(π(2l+1))·(P_{l−1}(c) − P_{l+1}(c))/(2l+1) but without its
/// catastrophic cancellation for small caps. Angles are clamped to [0, π].
pub fn cap_zh(order: usize, half_angle_rad: f64) -> Vec<f64> {
    let theta = if half_angle_rad.is_nan() {
        0.0
    } else {
        half_angle_rad.clamp(0.0, PI)
    };
    let (s, c) = theta.sin_cos();
    cap_zh_from_sin_cos(order, s, c)
}

/// [`cap_zh`] for the cap a sphere of radius r subtends at distance d, from s = r/d
/// directly (no asin): the form the shaders use. s is clamped to [0, 1].
pub fn cap_zh_from_ratio(order: usize, s: f64) -> Vec<f64> {
    let s = if s.is_nan() { 0.0 } else { s.clamp(0.0, 1.0) };
    cap_zh_from_sin_cos(order, s, (1.0 - s * s).sqrt())
}

fn cap_zh_from_sin_cos(order: usize, s: f64, c: f64) -> Vec<f64> {
    cap_zh_generic(order, s, c)
}

/// The stable cap ZH in any float type, from s = sin θ and c = cos θ: what the f32 shader
/// computes. P_l′(c) by P_{l+1}′ = P_{l−1}′ + (2l+1)·P_l, with Bonnet's recurrence for P_l.
pub fn cap_zh_generic<T: Float>(order: usize, s: T, c: T) -> Vec<T> {
    let mut out = Vec::with_capacity(order);
    cap_zh_each(order, s, c, |_, value| out.push(value));
    out
}

/// The cap ZH of [`cap_zh_from_ratio`] handed to `each(l, z_l)` band by band, without
/// allocating (the CPU shading calls it per blocker and receiver).
pub fn cap_zh_ratio_each(order: usize, s: f64, each: impl FnMut(usize, f64)) {
    let s = if s.is_nan() { 0.0 } else { s.clamp(0.0, 1.0) };
    cap_zh_each(order, s, (1.0 - s * s).sqrt(), each);
}

fn cap_zh_each<T: Float>(order: usize, s: T, c: T, mut each: impl FnMut(usize, T)) {
    let k = |v: f64| T::from(v).expect("float constant");
    let s2 = s * s;
    // P_{l−1}, P_l and P_{l−1}′, P_l′ as l advances.
    let (mut p_prev, mut p) = (T::zero(), T::one());
    let (mut dp_prev, mut dp) = (T::zero(), T::zero());
    for l in 0..order {
        let lf = l as f64;
        let value = if l == 0 {
            // For c < 0 the direct form has no cancellation, and s²/(1 + c) is 0/0 at θ = π.
            if c >= T::zero() {
                k(PI.sqrt()) * s2 / (T::one() + c)
            } else {
                k(PI.sqrt()) * (T::one() - c)
            }
        } else {
            k((PI * (2.0 * lf + 1.0)).sqrt() / (lf * (lf + 1.0))) * s2 * dp
        };
        each(l, value);
        // Advance to l + 1.
        let dp_next = dp_prev + k(2.0 * lf + 1.0) * p;
        let p_next = if l == 0 {
            c
        } else {
            (k(2.0 * lf + 1.0) * c * p - k(lf) * p_prev) / k(lf + 1.0)
        };
        (p_prev, p) = (p, p_next);
        (dp_prev, dp) = (dp, dp_next);
    }
}

/// Rotates a ZH (axis +z) to axis `dir` by Funk–Hecke: f_l^m = √(4π/(2l+1)) · z_l · y_l^m(dir).
pub fn rotate_zh(zh: &[f64], dir: DVec3) -> Vec<f64> {
    let order = zh.len();
    let y = super::basis(order, dir);
    let mut out = vec![0.0; order * order];
    for (l, &z) in zh.iter().enumerate() {
        let scale = (4.0 * PI / (2 * l + 1) as f64).sqrt() * z;
        for i in l * l..(l + 1) * (l + 1) {
            out[i] = scale * y[i];
        }
    }
    out
}

/// Log-visibility of spherical blockers seen from one receiver (shading-model.md §4): the sum over
/// caps (unit direction to the blocker's centre, half-angle in radians) of ln ε times the
/// cap's indicator ZH rotated to that direction.
pub fn log_visibility(order: usize, caps: &[(DVec3, f64)], epsilon: f64) -> Vec<f64> {
    let ln_epsilon = epsilon.ln();
    let mut f = vec![0.0; order * order];
    for &(dir, half_angle_rad) in caps {
        for (fi, ci) in f.iter_mut().zip(rotate_zh(&cap_zh(order, half_angle_rad), dir)) {
            *fi += ln_epsilon * ci;
        }
    }
    f
}

/// ZH projection z_l = 2π ∫₋₁¹ f(t) y_l^0(t) dt of a function of t = cos θ, by composite
/// 128-point Gauss–Legendre on panels split at `breakpoints` (put kinks there: the rule is
/// then accurate to about machine precision for piecewise-smooth f).
pub fn zh_of_function(order: usize, f: impl Fn(f64) -> f64, breakpoints: &[f64]) -> Vec<f64> {
    let mut edges: Vec<f64> = vec![-1.0, 1.0];
    edges.extend(
        breakpoints
            .iter()
            .copied()
            .filter(|b| b.is_finite() && *b > -1.0 && *b < 1.0),
    );
    edges.sort_by(f64::total_cmp);
    let rule = gauss_legendre(128);
    let mut out = vec![0.0; order];
    for panel in edges.windows(2) {
        let (a, b) = (panel[0], panel[1]);
        let (mid, half) = (0.5 * (a + b), 0.5 * (b - a));
        for &(x, w) in &rule {
            let t = mid + half * x;
            let value = f(t) * w * half;
            for (l, p) in legendre(order, t).into_iter().enumerate() {
                out[l] += 2.0 * PI * ((2 * l + 1) as f64 / (4.0 * PI)).sqrt() * p * value;
            }
        }
    }
    out
}

/// ZH of the clamped cosine divided by π, max(cos θ, 0)/π (the diffuse transfer).
pub fn clamped_cosine_zh(order: usize) -> Vec<f64> {
    zh_of_function(order, |t| t.max(0.0) / PI, &[0.0])
}

/// ZH of the log diffuse lobe, ln max(cos θ/π, ε) (cos θ ≤ 0 gives ln ε).
pub fn log_diffuse_zh(order: usize, epsilon: f64) -> Vec<f64> {
    let ln_eps = epsilon.ln();
    let f = |t: f64| if t > 0.0 { (t / PI).ln().max(ln_eps) } else { ln_eps };
    zh_of_function(order, f, &[0.0, PI * epsilon])
}

/// ZH of the log normalised Phong lobe, ln max((r+1)/(2π) · cos^r θ, ε) on the upper
/// hemisphere and ln ε below, evaluated in log space so large exponents do not underflow.
pub fn log_phong_zh(order: usize, exponent: f64, epsilon: f64) -> Vec<f64> {
    let ln_eps = epsilon.ln();
    let ln_norm = ((exponent + 1.0) / (2.0 * PI)).ln();
    let f = |t: f64| {
        if t > 0.0 {
            (ln_norm + exponent * t.ln()).max(ln_eps)
        } else {
            ln_eps
        }
    };
    // The kink where the lobe meets ε: cos^r θ = 2πε/(r+1).
    let kink = if exponent > 0.0 {
        ((ln_eps - ln_norm) / exponent).exp()
    } else {
        2.0
    };
    zh_of_function(order, f, &[0.0, kink])
}

#[cfg(test)]
mod tests {
    use super::*;

    fn assert_close(actual: &[f64], expected: &[f64], tolerance: f64) {
        for (l, (a, e)) in actual.iter().zip(expected).enumerate() {
            assert!((a - e).abs() <= tolerance * e.abs().max(1.0), "band {l}: {a} vs {e}");
        }
    }

    #[test]
    fn cap_matches_design_values() {
        assert_close(
            &cap_zh(4, 30f64.to_radians()),
            &[0.237464, 0.383748, 0.429043, 0.403002],
            2e-6,
        );
        let sp = PI.sqrt();
        assert_close(
            &cap_zh(4, PI / 2.0),
            &[sp, (3.0 * PI).sqrt() / 2.0, 0.0, -(7.0 * PI).sqrt() / 8.0],
            1e-14,
        );
        assert_close(&cap_zh(4, PI), &[2.0 * sp, 0.0, 0.0, 0.0], 1e-14);
    }

    #[test]
    fn cap_matches_closed_forms_from_tiny_to_full() {
        let mut theta = 1e-8;
        while theta < PI {
            let c = theta.cos();
            let s2 = theta.sin().powi(2);
            let z = cap_zh(4, theta);
            // Order-4 closed forms, written without cancellation: 1 − c = 2 sin²(θ/2), 1 − c² = s².
            let expected = [
                PI.sqrt() * 2.0 * (theta / 2.0).sin().powi(2),
                (3.0 * PI).sqrt() * s2 / 2.0,
                (5.0 * PI).sqrt() * c * s2 / 2.0,
                (7.0 * PI).sqrt() * s2 * (5.0 * c * c - 1.0) / 8.0,
            ];
            for l in 0..4 {
                // Relative to the band's natural size s², so zeros of P_l′ do not demand
                // absolute precision below round-off.
                let scale = expected[l].abs() + s2;
                assert!((z[l] - expected[l]).abs() <= 1e-12 * scale, "θ = {theta}, l = {l}");
            }
            theta *= 1.7;
        }
    }

    #[test]
    fn small_caps_behave_like_their_limit() {
        // For θ → 0, z_l → √(π(2l+1)) · θ²/2 (the cap area ≈ πθ² times y_l^0(pole)).
        let theta = 1e-4f64;
        for (l, z) in cap_zh(8, theta).into_iter().enumerate() {
            let limit = (PI * (2 * l + 1) as f64).sqrt() * theta * theta / 2.0;
            assert!((z / limit - 1.0).abs() < 1e-6, "l = {l}");
        }
    }

    #[test]
    fn f32_stable_form_holds_down_to_a_hundredth_of_a_degree() {
        for degrees in [0.01f64, 0.1, 1.0, 10.0, 45.0, 89.0] {
            let theta = degrees.to_radians();
            let exact = cap_zh(8, theta);
            let single = cap_zh_generic::<f32>(8, theta.sin() as f32, theta.cos() as f32);
            for (l, (a, b)) in single.iter().zip(&exact).enumerate() {
                let scale = b.abs() + theta.sin().powi(2);
                assert!(
                    ((*a as f64) - b).abs() <= 1e-6 * scale,
                    "{degrees}°, l = {l}: {a} vs {b}"
                );
            }
        }
    }

    #[test]
    fn ratio_form_agrees_with_angle_form() {
        for theta in [1e-6, 0.01, 0.3, 1.0, 1.5] {
            let a = cap_zh(8, theta);
            let b = cap_zh_from_ratio(8, theta.sin());
            assert_close(&a, &b, 1e-12);
        }
    }

    #[test]
    fn zh_projection_of_a_cap_indicator_matches_cap_zh() {
        let theta: f64 = 0.7;
        let by_quadrature = zh_of_function(6, |t| if t > theta.cos() { 1.0 } else { 0.0 }, &[theta.cos()]);
        assert_close(&by_quadrature, &cap_zh(6, theta), 1e-12);
    }

    #[test]
    fn blockers_covering_the_sky_give_a_constant_ln_epsilon_each() {
        // A cap of half-angle π is the whole sphere: each such blocker adds ln ε everywhere.
        let dir = DVec3::new(0.2, -0.5, 0.7).normalize();
        let f = log_visibility(4, &[(dir, PI), (dir, PI)], 0.1);
        assert!((f[0] - 2.0 * 0.1f64.ln() * (4.0 * PI).sqrt()).abs() < 1e-12);
        assert!(f[1..].iter().all(|v| v.abs() < 1e-12));
    }

    #[test]
    fn clamped_cosine_matches_design_values() {
        assert_close(&clamped_cosine_zh(4), &[0.282095, 0.325735, 0.157696, 0.0], 2e-6);
    }

    #[test]
    fn log_lobes_are_finite_for_extreme_parameters() {
        for eps in [1e-6, 0.02, 0.1, 0.5, 0.99] {
            for order in [2, 4, 8] {
                assert!(log_diffuse_zh(order, eps).iter().all(|v| v.is_finite()));
                for exponent in [0.0, 1.0, 16.0, 1e4] {
                    assert!(log_phong_zh(order, exponent, eps).iter().all(|v| v.is_finite()));
                }
            }
        }
    }

    #[test]
    fn log_diffuse_dc_is_the_mean_log() {
        // z_0 = 2π·(1/√(4π))·∫ f dt; with ε = 0.5/π the lobe is ln(max(t, 0.5)/π) for t > 0.
        let eps = 0.5 / PI;
        // Direct: ∫₋₁¹ f dt = ∫₋₁^0.5 ln(0.5/π) dt + ∫_0.5^1 ln(t/π) dt.
        let direct = 1.5 * (0.5 / PI).ln() + ((1.0f64.ln() - 1.0) - 0.5 * (0.5f64.ln() - 1.0)) - 0.5 * PI.ln();
        let z0 = log_diffuse_zh(1, eps)[0];
        assert!((z0 - 2.0 * PI / (4.0 * PI).sqrt() * direct).abs() < 1e-12, "{z0}");
    }
}
