//! Log-visibility scales that keep a blocker's shadow mass through the band limit.
//!
//! A blocker's log-visibility is ln ε on its cap, truncated to order n before it is
//! exponentiated. Truncation spreads a small cap's −|ln ε| over a wide, shallow lobe, and
//! 1 − e^{−x} ≈ x there: the light it takes, ∫(1 − exp F_n) dω, tends to |ln ε|·Ω
//! instead of the (1 − ε)·Ω the cap truly blocks — 2.5× too much at ε = 0.1 (the sky's
//! soft shadows came out that much too dark). Scaling the cap's log-visibility by the
//! k(s) for which the truncated cap blocks exactly (1 − ε)·Ω restores the mass:
//!
//!   ∫_{S²} 1 − exp(k · ln ε · f_n(ω)) dω = (1 − ε) · 2π(1 − √(1 − s²)),
//!
//! f_n the order-n truncation of the cap's indicator, s the sine of its half-angle. k is
//! (1 − ε)/|ln ε| for caps far below the band limit and rises toward 1 for caps the order
//! resolves; it is tabulated over s for the frame's order and ε (the GPU interpolates the
//! same table, `ShadowParams.cap_mass_scale`).

use super::{cap_zh_ratio_each, gauss_legendre, legendre};

/// Entries of a table, at s = i / (CAP_MASS_ENTRIES − 1).
pub const CAP_MASS_ENTRIES: usize = 32;

/// k(s) at s = i / (CAP_MASS_ENTRIES − 1) for caps of log-visibility ln `epsilon` at
/// `order` (see the module's documentation).
pub fn cap_mass_scales(order: usize, epsilon: f64) -> [f64; CAP_MASS_ENTRIES] {
    let nodes = gauss_legendre(256);
    let ln_epsilon = epsilon.clamp(1e-6, 1.0 - 1e-6).ln();
    let mut table = [1.0; CAP_MASS_ENTRIES];
    for (i, entry) in table.iter_mut().enumerate() {
        // A vanishing cap's limit is that of a tiny one.
        let s = (i as f64 / (CAP_MASS_ENTRIES - 1) as f64).max(1e-3);
        let mut zh = vec![0.0; order];
        cap_zh_ratio_each(order, s, |l, z| zh[l] = z);
        // The truncated indicator along the cap's axis, f_n(x), x = cos θ.
        let profile: Vec<(f64, f64)> = nodes
            .iter()
            .map(|&(x, w)| {
                let p = legendre(order, x);
                let f: f64 = (0..order)
                    .map(|l| zh[l] * ((2 * l + 1) as f64 / (4.0 * std::f64::consts::PI)).sqrt() * p[l])
                    .sum();
                (f, w)
            })
            .collect();
        let blocked = |k: f64| -> f64 {
            2.0 * std::f64::consts::PI
                * profile
                    .iter()
                    .map(|&(f, w)| w * (1.0 - (k * ln_epsilon * f).exp()))
                    .sum::<f64>()
        };
        let target = (1.0 - epsilon) * 2.0 * std::f64::consts::PI * (1.0 - (1.0 - s * s).sqrt());
        // The first k in (0, 1] at which the truncated cap blocks the target: scanned,
        // then bisected (ringing makes the blocked light non-monotonic for large k).
        let mut lo = 0.0;
        let mut found = None;
        for step in 1..=100 {
            let k = step as f64 / 100.0;
            if blocked(k) >= target {
                found = Some(k);
                break;
            }
            lo = k;
        }
        if let Some(mut hi) = found {
            for _ in 0..40 {
                let mid = 0.5 * (lo + hi);
                if blocked(mid) >= target {
                    hi = mid;
                } else {
                    lo = mid;
                }
            }
            *entry = 0.5 * (lo + hi);
        }
    }
    table
}

/// k at sine `s`, linearly interpolated in `table` (as logsh.wgsl's `cap_mass_scale`).
pub fn interpolate_cap_mass_scale(table: &[f64; CAP_MASS_ENTRIES], s: f64) -> f64 {
    let t = s.clamp(0.0, 1.0) * (CAP_MASS_ENTRIES - 1) as f64;
    let i = (t.floor() as usize).min(CAP_MASS_ENTRIES - 2);
    let a = t - i as f64;
    table[i] * (1.0 - a) + table[i + 1] * a
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn tiny_caps_take_the_linear_limit_and_large_ones_nearly_all() {
        for epsilon in [0.05, 0.1, 0.3] {
            let table = cap_mass_scales(4, epsilon);
            let limit = (1.0 - epsilon) / -epsilon.ln();
            assert!(
                (table[0] - limit).abs() < 0.01 * limit,
                "{epsilon}: {} against {limit}",
                table[0]
            );
            assert!(table[CAP_MASS_ENTRIES - 1] > 0.7, "{table:?}");
            assert!(table.iter().all(|&k| k > 0.0 && k <= 1.0));
        }
    }

    #[test]
    fn a_higher_order_needs_less_correction() {
        let (four, eight) = (cap_mass_scales(4, 0.1), cap_mass_scales(8, 0.1));
        // s = 0.3: order 8 resolves the cap better than order 4.
        let i = (0.3 * (CAP_MASS_ENTRIES - 1) as f64).round() as usize;
        assert!(eight[i] > four[i] + 0.1, "{} {}", four[i], eight[i]);
    }

    #[test]
    fn the_scaled_cap_blocks_what_the_cap_blocks() {
        // Checked independently on a sphere quadrature: the order-4 projection of the
        // scaled log-visibility, exponentiated pointwise, integrated over the sphere.
        let (order, epsilon, s) = (4, 0.1f64, 0.4f64);
        let table = cap_mass_scales(order, epsilon);
        let k = interpolate_cap_mass_scale(&table, s);
        let zh = super::super::cap_zh_from_ratio(order, s);
        let quadrature = super::super::SphereQuadrature::exact_for_degree(40);
        let blocked: f64 = quadrature
            .points()
            .map(|(d, w)| {
                let p = legendre(order, d.z);
                let f: f64 = (0..order)
                    .map(|l| zh[l] * ((2 * l + 1) as f64 / (4.0 * std::f64::consts::PI)).sqrt() * p[l])
                    .sum();
                w * (1.0 - (k * epsilon.ln() * f).exp())
            })
            .sum();
        let truth = (1.0 - epsilon) * 2.0 * std::f64::consts::PI * (1.0 - (1.0 - s * s).sqrt());
        // Interpolation between entries costs a little.
        assert!((blocked / truth - 1.0).abs() < 0.02, "{blocked} against {truth}");
    }
}
