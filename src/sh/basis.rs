//! Evaluation of the real SH basis.
//!
//! The general path is a recurrence on normalised associated Legendre functions with the
//! sin^m θ factor removed, q_l^m(z) = N_l^m P_l^m(z) / sin^m θ (polynomials in z), combined
//! with (x + iy)^m = sin^m θ · e^{imφ} computed from the Cartesian direction. No factorial
//! is ever formed (no overflow at high order) and there is no division by sin θ (finite and
//! continuous at the poles):
//!
//! - q_0^0 = 1/√(4π),  q_m^m = −√((2m+1)/(2m)) · q_{m−1}^{m−1}   (Condon–Shortley sign)
//! - q_{m+1}^m = √(2m+3) · z · q_m^m
//! - q_l^m = a_l^m (z q_{l−1}^m − b_l^m q_{l−2}^m),
//!   a = √((4l²−1)/(l²−m²)),  b = √(((l−1)²−m²)/(4(l−1)²−1))
//! - y_l^0 = q_l^0,  y_l^{±m} = √2 · q_l^m · (Re | Im)(x + iy)^m.

use glam::DVec3;
use num_traits::Float;

use super::coefficient_count;

/// The n² basis values y_i(dir) at `order` n. `dir` need not be normalised; the zero
/// vector evaluates as +z.
pub fn basis(order: usize, dir: DVec3) -> Vec<f64> {
    let d = dir.try_normalize().unwrap_or(DVec3::Z);
    basis_generic::<f64>(order, [d.x, d.y, d.z])
}

/// [`basis`] in any float type (f32 shows what the GPU's precision allows); `dir` must be
/// a unit vector.
pub fn basis_generic<T: Float>(order: usize, dir: [T; 3]) -> Vec<T> {
    let [x, y, z] = dir;
    let c = |v: f64| T::from(v).expect("float constant");
    let mut out = vec![T::zero(); coefficient_count(order)];
    // Re and Im of (x + iy)^m, updated in the m loop.
    let (mut cos_m, mut sin_m) = (T::one(), T::zero());
    let mut q_mm = c(1.0 / (4.0 * std::f64::consts::PI).sqrt());
    for m in 0..order {
        if m > 0 {
            let (re, im) = (cos_m * x - sin_m * y, cos_m * y + sin_m * x);
            cos_m = re;
            sin_m = im;
            let mf = m as f64;
            q_mm = -c(((2.0 * mf + 1.0) / (2.0 * mf)).sqrt()) * q_mm;
        }
        let mut q_prev = T::zero();
        let mut q = q_mm;
        for l in m..order {
            if l == m + 1 {
                q_prev = q;
                q = c((2.0 * m as f64 + 3.0).sqrt()) * z * q_mm;
            } else if l > m + 1 {
                let (lf, mf) = (l as f64, m as f64);
                let a = ((4.0 * lf * lf - 1.0) / (lf * lf - mf * mf)).sqrt();
                let b = (((lf - 1.0) * (lf - 1.0) - mf * mf) / (4.0 * (lf - 1.0) * (lf - 1.0) - 1.0)).sqrt();
                let next = c(a) * (z * q - c(b) * q_prev);
                q_prev = q;
                q = next;
            }
            let centre = l * (l + 1);
            if m == 0 {
                out[centre] = q;
            } else {
                let scaled = c(std::f64::consts::SQRT_2) * q;
                out[centre + m] = scaled * cos_m;
                out[centre - m] = scaled * sin_m;
            }
        }
    }
    out
}

/// Unrolled Cartesian polynomials for order ≤ 4 (the first n² of 16 values): the fast
/// path that the WGSL evaluator mirrors. `dir` must be a unit vector.
pub fn basis_unrolled4(order: usize, dir: DVec3) -> Vec<f64> {
    assert!(order <= 4, "basis_unrolled4 covers orders 0..=4");
    basis16(dir)[..coefficient_count(order)].to_vec()
}

/// The 16 basis values of order 4 at unit `dir`, on the stack (no allocation).
pub fn basis16(dir: DVec3) -> [f64; 16] {
    let (x, y, z) = (dir.x, dir.y, dir.z);
    let (x2, y2, z2) = (x * x, y * y, z * z);
    [
        0.282_094_791_773_878_14,
        -0.488_602_511_902_919_9 * y,
        0.488_602_511_902_919_9 * z,
        -0.488_602_511_902_919_9 * x,
        1.092_548_430_592_079_2 * x * y,
        -1.092_548_430_592_079_2 * y * z,
        0.315_391_565_252_520_05 * (3.0 * z2 - 1.0),
        -1.092_548_430_592_079_2 * x * z,
        0.546_274_215_296_039_6 * (x2 - y2),
        -0.590_043_589_926_643_5 * y * (3.0 * x2 - y2),
        2.890_611_442_640_554 * x * y * z,
        -0.457_045_799_464_465_8 * y * (5.0 * z2 - 1.0),
        0.373_176_332_590_115_4 * z * (5.0 * z2 - 3.0),
        -0.457_045_799_464_465_8 * x * (5.0 * z2 - 1.0),
        1.445_305_721_320_277 * z * (x2 - y2),
        -0.590_043_589_926_643_5 * x * (x2 - 3.0 * y2),
    ]
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sh::accuracy::orthonormality_error;

    #[test]
    fn f64_basis_is_orthonormal_to_1e_10_up_to_order_32() {
        for order in [1, 2, 4, 8, 16, 24, 32] {
            let error = orthonormality_error::<f64>(order);
            assert!(error < 1e-10, "order {order}: {error:e}");
        }
    }

    #[test]
    fn f32_basis_is_orthonormal_to_1e_5_up_to_order_16() {
        for order in (1..=8).chain([12, 16]) {
            let error = orthonormality_error::<f32>(order);
            assert!(error < 1e-5, "order {order}: {error:e}");
        }
    }

    #[test]
    fn first_bands_match_the_convention() {
        let d = DVec3::new(0.3, -0.5, 0.7).normalize();
        let y = basis(2, d);
        let k = (3.0 / (4.0 * std::f64::consts::PI)).sqrt();
        assert!((y[1] + k * d.y).abs() < 1e-15);
        assert!((y[2] - k * d.z).abs() < 1e-15);
        assert!((y[3] + k * d.x).abs() < 1e-15);
    }

    #[test]
    fn unrolled_path_matches_the_recurrence() {
        for i in 0..200 {
            let t = i as f64 * 0.731;
            let d = DVec3::new(t.sin() * (3.0 * t).cos(), t.sin() * (3.0 * t).sin(), t.cos()).normalize();
            let a = basis(4, d);
            let b = basis_unrolled4(4, d);
            for (u, v) in a.iter().zip(&b) {
                assert!((u - v).abs() < 1e-14, "{d}: {u} vs {v}");
            }
        }
    }

    #[test]
    fn finite_and_continuous_at_the_poles() {
        for order in [4, 8, 30] {
            for (theta, pole) in [(1e-12, DVec3::Z), (std::f64::consts::PI - 1e-12, DVec3::NEG_Z)] {
                let near = DVec3::new(theta.sin(), 0.0, theta.cos());
                let a = basis(order, near);
                let b = basis(order, pole);
                assert!(a.iter().all(|v| v.is_finite()));
                let gap = a.iter().zip(&b).map(|(u, v)| (u - v).abs()).fold(0.0, f64::max);
                assert!(gap < 1e-9, "order {order} θ = {theta}: gap {gap:e}");
            }
        }
    }
}
