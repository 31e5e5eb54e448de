//! Real spherical harmonics in f64: the reference math every other part of lightpaint
//! (WGSL shaders, bake, study) is checked against. Pure; no GPU code.
//!
//! Conventions (docs/architecture.md, "SH"): real, orthonormal over the sphere,
//! Condon–Shortley phase included (y₁₋₁ = −0.488603·y, y₁₀ = 0.488603·z, y₁₁ = −0.488603·x);
//! polar axis +z of the frame the vector lives in. **Order** n = number of bands; a vector
//! has n² coefficients at flat index i = l(l+1) + m. Projection f_i = ∫ f y_i dω, so the
//! constant function 1 is (√(4π), 0, …) and ∫ f g dω = Σ f_i g_i.

pub mod accuracy;
mod basis;
mod cap_mass;
mod exp;
mod gaunt;
mod legendre;
mod lobes;
mod log;
pub mod ol_fit;
pub mod ol_tables;
mod quadrature;
mod rotation;
mod window;
mod zonal;

pub use basis::{basis, basis_generic, basis_unrolled4, basis16};
pub use cap_mass::{CAP_MASS_ENTRIES, cap_mass_scales, interpolate_cap_mass_scale};
pub use exp::{
    ExpMethod, exp, exp_dc_isolated, exp_hyb, exp_ol, exp_ps, exp_reference, hyb_threshold, ol_coefficients,
};
pub use gaunt::{Gaunt, gaunt, product, product_matrix};
pub use legendre::{legendre, legendre_derivative};
pub use lobes::{
    LOG_LOBE_MIN_EXPONENT, irradiance_band_scale, legendre_monomials, log_phong_lobe_zh, max_carried_phong_exponent,
    phong_lobe_zh,
};
pub use log::{LOG_STAR_EIGEN_CLAMP, log_naive, log_star};
pub use quadrature::{SphereQuadrature, gauss_legendre};
pub use rotation::{rotate, rotate_z, rotation_matrices};
pub use window::{Window, apply_window, window_factors};
pub use zonal::{
    cap_zh, cap_zh_from_ratio, cap_zh_generic, cap_zh_ratio_each, clamped_cosine_zh, log_diffuse_zh, log_phong_zh,
    log_visibility, rotate_zh, zh_of_function,
};

use std::f64::consts::PI;

/// Highest order the real-time renderer supports (coefficients up to band 7).
pub const MAX_REALTIME_ORDER: usize = 8;

/// Number of coefficients of an order-`order` vector: `order²`.
pub const fn coefficient_count(order: usize) -> usize {
    order * order
}

/// Flat index of band `l`, index `m` (−l ≤ m ≤ l).
pub const fn index(l: usize, m: i64) -> usize {
    ((l * (l + 1)) as i64 + m) as usize
}

/// The order of a vector with `len` coefficients, if `len` is a perfect square.
pub fn order_of(len: usize) -> Option<usize> {
    let order = (len as f64).sqrt().round() as usize;
    (order * order == len).then_some(order)
}

/// The SH vector of the constant function `value` at `order`: (value·√(4π), 0, …).
pub fn constant(order: usize, value: f64) -> Vec<f64> {
    let mut v = vec![0.0; coefficient_count(order)];
    if order > 0 {
        v[0] = value * (4.0 * PI).sqrt();
    }
    v
}

/// Value of the expansion `coefficients` in direction `dir` (unit vector).
pub fn evaluate(coefficients: &[f64], dir: glam::DVec3) -> f64 {
    let order = order_of(coefficients.len()).expect("an SH vector has a square number of coefficients");
    basis(order, dir).iter().zip(coefficients).map(|(y, c)| y * c).sum()
}

/// Energy (sum of squares) of each band.
pub fn band_energies(coefficients: &[f64]) -> Vec<f64> {
    let order = order_of(coefficients.len()).expect("an SH vector has a square number of coefficients");
    (0..order)
        .map(|l| coefficients[l * l..(l + 1) * (l + 1)].iter().map(|c| c * c).sum())
        .collect()
}
