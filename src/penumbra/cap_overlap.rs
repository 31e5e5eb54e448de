//! The share of a light's disc that a blocker hides, in closed form: both are spherical
//! caps on the receiver's sphere of directions — the light of angular radius α, the
//! blocker sphere of angular radius β (sin β = r/d) — whose centres are γ apart. The
//! hidden solid angle is the lens where the caps intersect:
//!
//!   Ω = 2θ_L(1 − cos α) + 2θ_B(1 − cos β) − 2E,
//!
//! two cap sectors (θ_L, θ_B the angles at the centres, in the spherical triangle of the
//! two centres and one point where the circles cross, with sides α, β, γ) minus the two
//! triangles (E their spherical excess). The angles come from the half-angle formulas and
//! E from L'Huilier's theorem, all in terms of the sides, so nothing cancels for tiny caps
//! (the law-of-cosines form loses every digit in f32 below a fraction of a degree).
//! `shaders/exact_lights.wgsl` computes the same lens by another route, cheaper in f32:
//! the law of cosines and the triangle's volume written in versines 1 − cos x, with
//! three arctangents and no angle.
//! The share is Ω / (2π(1 − cos α)), with 1 − cos x written 2 sin²(x/2).

use std::f64::consts::PI;

/// The share (0–1) of a cap of angular radius `light_rad` hidden by a cap of angular
/// radius `blocker_rad` whose centre is `separation_rad` away. Caps up to a hemisphere
/// (π/2). A light of radius 0 is a point: hidden (1) when strictly inside the blocker.
pub fn hidden_fraction(light_rad: f64, blocker_rad: f64, separation_rad: f64) -> f64 {
    let (a, b, g) = (light_rad.max(0.0), blocker_rad.max(0.0), separation_rad.abs());
    if g >= a + b || b == 0.0 {
        return 0.0;
    }
    if g + a <= b {
        return 1.0; // the light lies inside the blocker
    }
    let light_area = cap_area(a);
    if g + b <= a {
        return (cap_area(b) / light_area).min(1.0); // the blocker lies inside the light
    }
    let s = 0.5 * (a + b + g);
    let (sin_s, sin_sa, sin_sb, sin_sg) = (s.sin(), (s - a).sin(), (s - b).sin(), (s - g).sin());
    // Half-angle formulas: the angle at a vertex from the three sides.
    let theta_light = 2.0 * (sin_sa * sin_sg / (sin_s * sin_sb)).max(0.0).sqrt().atan();
    let theta_blocker = 2.0 * (sin_sb * sin_sg / (sin_s * sin_sa)).max(0.0).sqrt().atan();
    // L'Huilier: tan(E/4) = √(tan(s/2)·tan((s − a)/2)·tan((s − b)/2)·tan((s − γ)/2)).
    let excess = 4.0
        * ((0.5 * s).tan() * (0.5 * (s - a)).tan() * (0.5 * (s - b)).tan() * (0.5 * (s - g)).tan())
            .max(0.0)
            .sqrt()
            .atan();
    let lens = 2.0 * theta_light * one_minus_cos(a) + 2.0 * theta_blocker * one_minus_cos(b) - 2.0 * excess;
    (lens / light_area).clamp(0.0, 1.0)
}

/// 1 − cos x without cancellation.
fn one_minus_cos(x: f64) -> f64 {
    let h = (0.5 * x).sin();
    2.0 * h * h
}

/// Solid angle of a cap of angular radius `x`.
pub(super) fn cap_area(x: f64) -> f64 {
    2.0 * PI * one_minus_cos(x)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The hidden share by brute force: a fine polar grid over the light cap (cells of
    /// equal solid angle: uniform in cos θ and φ), counting the cell centres within the
    /// blocker cap. Error about the cells along the blocker's edge.
    fn hidden_by_integration(a: f64, b: f64, g: f64) -> f64 {
        let (rings, sectors) = (1500, 1500);
        let blocker_axis = [g.sin(), 0.0, g.cos()];
        let cos_b = b.cos();
        let mut hidden = 0usize;
        for i in 0..rings {
            let cos_t = 1.0 - (i as f64 + 0.5) / rings as f64 * (1.0 - a.cos());
            let sin_t = (1.0 - cos_t * cos_t).max(0.0).sqrt();
            for j in 0..sectors {
                let phi = (j as f64 + 0.5) / sectors as f64 * 2.0 * PI;
                let d = [sin_t * phi.cos(), sin_t * phi.sin(), cos_t];
                let dot = d[0] * blocker_axis[0] + d[1] * blocker_axis[1] + d[2] * blocker_axis[2];
                hidden += usize::from(dot > cos_b);
            }
        }
        hidden as f64 / (rings * sectors) as f64
    }

    #[test]
    fn the_closed_form_matches_numerical_integration() {
        let deg = |x: f64| x.to_radians();
        // (light, blocker, separation) in degrees: partial overlaps of every size.
        let cases = [
            (10.0, 10.0, 10.0),
            (10.0, 5.0, 12.0),
            (5.0, 20.0, 18.0),
            (40.0, 15.0, 35.0),
            (60.0, 60.0, 70.0),
            (30.0, 45.0, 40.0),
            (1.0, 1.5, 1.2),
            (89.0, 85.0, 120.0),
            (80.0, 30.0, 75.0),
            (15.0, 14.0, 2.0),
        ];
        for (a, b, g) in cases {
            let exact = hidden_fraction(deg(a), deg(b), deg(g));
            let numeric = hidden_by_integration(deg(a), deg(b), deg(g));
            assert!(
                (exact - numeric).abs() < 2e-3,
                "light {a}°, blocker {b}°, {g}° apart: closed form {exact}, integration {numeric}"
            );
            assert!(exact > 0.0 && exact < 1.0, "{a} {b} {g}: {exact}");
        }
    }

    #[test]
    fn disjoint_touching_nested_identical_and_antipodal_caps() {
        let deg = |x: f64| x.to_radians();
        // Disjoint and touching: nothing hidden.
        assert_eq!(hidden_fraction(deg(10.0), deg(10.0), deg(25.0)), 0.0);
        assert_eq!(hidden_fraction(deg(10.0), deg(10.0), deg(20.0)), 0.0);
        // Just overlapping: a sliver, continuous with touching.
        let sliver = hidden_fraction(deg(10.0), deg(10.0), deg(19.999));
        assert!(sliver > 0.0 && sliver < 1e-5, "{sliver}");
        // The light inside the blocker, identical caps: all hidden.
        assert_eq!(hidden_fraction(deg(5.0), deg(20.0), deg(3.0)), 1.0);
        assert_eq!(hidden_fraction(deg(7.0), deg(7.0), 0.0), 1.0);
        // A blocker inside the light hides its own area: (1 − cos β)/(1 − cos α).
        let nested = hidden_fraction(deg(30.0), deg(10.0), deg(5.0));
        let expected = (1.0 - deg(10.0).cos()) / (1.0 - deg(30.0).cos());
        assert!((nested - expected).abs() < 1e-12, "{nested} vs {expected}");
        // Antipodal caps never meet.
        assert_eq!(hidden_fraction(deg(60.0), deg(60.0), PI), 0.0);
        // A point light: hidden exactly when inside the blocker.
        assert_eq!(hidden_fraction(0.0, deg(10.0), deg(9.0)), 1.0);
        assert_eq!(hidden_fraction(0.0, deg(10.0), deg(11.0)), 0.0);
    }

    /// Continuity across the regime boundaries (partial ↔ nested ↔ contained), and a
    /// monotone fall as the caps separate.
    #[test]
    fn the_share_is_continuous_and_falls_as_the_caps_separate() {
        let deg = |x: f64| x.to_radians();
        for (a, b) in [(10.0, 4.0), (4.0, 10.0), (30.0, 30.0), (1.0, 0.3), (85.0, 60.0)] {
            let mut last = hidden_fraction(deg(a), deg(b), 0.0);
            let steps = 4000;
            for k in 0..=steps {
                let g = deg(a + b) * k as f64 / steps as f64;
                let f = hidden_fraction(deg(a), deg(b), g);
                assert!(f.is_finite() && (0.0..=1.0).contains(&f), "{a} {b} {g}: {f}");
                assert!(f <= last + 1e-9, "{a}° {b}° at {g}: {f} rose from {last}");
                assert!(last - f < 0.01, "{a}° {b}° at {g}: jump from {last} to {f}");
                last = f;
            }
        }
    }

    /// Tiny caps keep their digits: the hidden share of a 0.01° light by an equal blocker
    /// half a radius away matches the planar lens of two unit circles a half apart.
    #[test]
    fn tiny_caps_match_the_planar_lens() {
        let r = 0.01f64.to_radians();
        let f = hidden_fraction(r, r, 0.5 * r);
        // Two unit circles, centres d apart: lens = 2acos(d/2) − (d/2)√(4 − d²), over π.
        let d = 0.5f64;
        let lens = 2.0 * (d / 2.0).acos() - d / 2.0 * (4.0 - d * d).sqrt();
        let planar = lens / PI;
        assert!((f - planar).abs() < 1e-7, "{f} vs {planar}");
    }
}
