//! Per-band windows that damp high bands to reduce ringing (Gibbs oscillation) of a
//! truncated expansion, at the cost of blur.

/// A per-band window over n bands.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
pub enum Window {
    /// No damping.
    None,
    /// Hann: σ_l = (1 + cos(π l / n)) / 2.
    Hann,
    /// Lanczos σ-factors: σ_l = sinc(l / n) = sin(π l/n) / (π l/n).
    Lanczos,
}

/// σ_0 … σ_{n−1} for `order` n bands; σ_0 = 1 always, so the mean is kept.
pub fn window_factors(order: usize, window: Window) -> Vec<f64> {
    use std::f64::consts::PI;
    (0..order)
        .map(|l| {
            let x = l as f64 / order as f64;
            match window {
                Window::None => 1.0,
                Window::Hann => 0.5 * (1.0 + (PI * x).cos()),
                Window::Lanczos if l == 0 => 1.0,
                Window::Lanczos => (PI * x).sin() / (PI * x),
            }
        })
        .collect()
}

/// Multiplies each band of `f` by its window factor.
pub fn apply_window(f: &[f64], window: Window) -> Vec<f64> {
    let order = super::order_of(f.len()).expect("an SH vector has a square number of coefficients");
    let factors = window_factors(order, window);
    f.iter()
        .enumerate()
        .map(|(i, v)| v * factors[(i as f64).sqrt() as usize])
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn windows_keep_the_mean_and_decrease() {
        for window in [Window::Hann, Window::Lanczos] {
            let f = window_factors(8, window);
            assert_eq!(f[0], 1.0);
            assert!(f.windows(2).all(|w| w[1] < w[0]), "{window:?}: {f:?}");
            assert!(f.iter().all(|v| *v > 0.0));
        }
    }

    #[test]
    fn hann_reduces_the_negative_lobe_of_a_truncated_cap() {
        use crate::sh::{cap_zh, evaluate, rotate_zh};
        let cap = rotate_zh(&cap_zh(6, 0.3), glam::DVec3::Z);
        let ringing = |f: &[f64]| {
            (0..400)
                .map(|k| {
                    let theta = k as f64 / 400.0 * std::f64::consts::PI;
                    evaluate(f, glam::DVec3::new(theta.sin(), 0.0, theta.cos()))
                })
                .fold(0.0f64, |acc, v| acc.min(v))
        };
        assert!(ringing(&apply_window(&cap, Window::Hann)).abs() < ringing(&cap).abs());
    }
}
