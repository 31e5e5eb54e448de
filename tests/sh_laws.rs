//! Laws of the SH module that hold for all inputs, checked with proptest through the
//! public API of docs/shading-model.md §5.

use std::f64::consts::PI;

use glam::{DMat3, DQuat, DVec3};
use lightpaint::sh::{self, ExpMethod};
use proptest::prelude::*;

fn direction() -> impl Strategy<Value = DVec3> {
    (-1.0f64..=1.0, 0.0f64..std::f64::consts::TAU).prop_map(|(z, phi)| {
        let r = (1.0 - z * z).sqrt();
        DVec3::new(r * phi.cos(), r * phi.sin(), z)
    })
}

fn rotation() -> impl Strategy<Value = DMat3> {
    (direction(), 0.0f64..std::f64::consts::TAU)
        .prop_map(|(axis, angle)| DMat3::from_quat(DQuat::from_axis_angle(axis, angle)))
}

fn vector(order: usize) -> impl Strategy<Value = Vec<f64>> {
    prop::collection::vec(-2.0f64..2.0, order * order)
}

proptest! {
    /// Addition theorem: Σ_m y_lm(d)² = (2l+1)/(4π), so the whole vector has n²/(4π).
    #[test]
    fn basis_obeys_the_addition_theorem(d in direction(), order in 1usize..16) {
        let y = sh::basis(order, d);
        let total: f64 = y.iter().map(|v| v * v).sum();
        prop_assert!((total - (order * order) as f64 / (4.0 * PI)).abs() < 1e-11);
    }

    #[test]
    fn rotation_preserves_band_energy_and_inverts(f in vector(6), r in rotation()) {
        let g = sh::rotate(&f, r);
        for (a, b) in sh::band_energies(&f).iter().zip(sh::band_energies(&g)) {
            prop_assert!((a - b).abs() < 1e-10 * a.max(1.0));
        }
        let back = sh::rotate(&g, r.transpose());
        for (a, b) in back.iter().zip(&f) {
            prop_assert!((a - b).abs() < 1e-10);
        }
    }

    #[test]
    fn rotated_zonal_peaks_along_its_axis(d in direction(), zh in prop::collection::vec(-1.0f64..1.0, 1..8)) {
        let f = sh::rotate_zh(&zh, d);
        let on_axis: f64 = zh.iter().enumerate().map(|(l, z)| z * ((2 * l + 1) as f64 / (4.0 * PI)).sqrt()).sum();
        prop_assert!((sh::evaluate(&f, d) - on_axis).abs() < 1e-11);
    }

    #[test]
    fn product_is_commutative(f in vector(4), g in vector(4)) {
        let a = sh::product(4, &f, &g);
        let b = sh::product(4, &g, &f);
        for (x, y) in a.iter().zip(&b) {
            prop_assert!((x - y).abs() < 1e-12);
        }
    }

    #[test]
    fn cap_grows_with_its_half_angle(a in 0.0f64..PI, b in 0.0f64..PI) {
        let (small, large) = if a < b { (a, b) } else { (b, a) };
        let z_small = sh::cap_zh(4, small)[0];
        let z_large = sh::cap_zh(4, large)[0];
        prop_assert!(z_small <= z_large + 1e-15);
        prop_assert!((0.0..=2.0 * PI.sqrt() + 1e-12).contains(&z_large));
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(32))]

    #[test]
    fn every_method_exponentiates_constants_exactly(c in -20.0f64..5.0, order in 2usize..=8) {
        let f = sh::constant(order, c);
        let expected = c.exp() * (4.0 * PI).sqrt();
        for method in [ExpMethod::Dc, ExpMethod::Ol, ExpMethod::Hyb, ExpMethod::Reference] {
            let g = sh::exp(method, &f);
            prop_assert!((g[0] - expected).abs() <= 1e-12 * expected.max(1.0), "{:?}", method);
            prop_assert!(g[1..].iter().all(|v| v.abs() < 1e-12 * expected.max(1.0)));
        }
    }

    #[test]
    fn hyb_is_finite_for_any_stack_of_caps(count in 1usize..20_000, eps in 1e-6f64..0.99, half_angle in 1e-4f64..3.0, d in direction()) {
        let cap = sh::rotate_zh(&sh::cap_zh(4, half_angle), d);
        let f: Vec<f64> = cap.iter().map(|c| c * eps.ln() * count as f64).collect();
        for method in [ExpMethod::Dc, ExpMethod::Ol, ExpMethod::Hyb, ExpMethod::Reference] {
            prop_assert!(sh::exp(method, &f).iter().all(|v| v.is_finite()), "{:?}", method);
        }
    }
}
