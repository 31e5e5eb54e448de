//! Rotation of SH vectors. Convention: rotating f by R gives the SH of g(ω) = f(Rᵀω), the
//! function turned by R, so that g(Rω) = f(ω).
//!
//! General rotations use the band recurrence of Ivanic & Ruedenberg (J. Phys. Chem. 1996,
//! with the 1998 erratum): band l's matrix is built from band l − 1's and band 1's with
//! products and square roots of small integers only, which keeps it stable at any order.
//! The recurrence is stated for real SH without the Condon–Shortley phase; our basis has
//! it, which conjugates each band matrix by diag((−1)^m).

use glam::DMat3;

use super::order_of;

/// Rotates `f` by the angle `angle_rad` about +z: each (m, −m) pair turns by m·angle.
pub fn rotate_z(f: &[f64], angle_rad: f64) -> Vec<f64> {
    let order = order_of(f.len()).expect("an SH vector has a square number of coefficients");
    let mut out = f.to_vec();
    for l in 0..order {
        let centre = l * (l + 1);
        for m in 1..=l {
            let (sin, cos) = (m as f64 * angle_rad).sin_cos();
            let (a, b) = (f[centre + m], f[centre - m]);
            out[centre + m] = a * cos - b * sin;
            out[centre - m] = a * sin + b * cos;
        }
    }
    out
}

/// One square matrix per band, (2l+1)² values row-major, rows and columns indexed by
/// m + l. Band l of a rotated vector is `matrix[l] × band l of the original`.
pub fn rotation_matrices(order: usize, rotation: DMat3) -> Vec<Vec<f64>> {
    let mut bands: Vec<Vec<f64>> = Vec::with_capacity(order);
    if order == 0 {
        return bands;
    }
    bands.push(vec![1.0]);
    if order == 1 {
        return bands;
    }
    // Band 1 is (y, z, x) up to sign: permute R's rows and columns into that order.
    let axis = |m: i64| match m {
        -1 => 1,
        0 => 2,
        _ => 0,
    };
    let r = |i: usize, j: usize| rotation.col(j)[i];
    let band1: Vec<f64> = (-1..=1)
        .flat_map(|m| (-1..=1).map(move |n| (m, n)))
        .map(|(m, n)| r(axis(m), axis(n)))
        .collect();
    bands.push(band1);
    for l in 2..order {
        let next = next_band(l as i64, &bands[1], &bands[l - 1]);
        bands.push(next);
    }
    // Condon–Shortley: D_cs[m][n] = (−1)^(m+n) D[m][n].
    for (l, band) in bands.iter_mut().enumerate() {
        let width = 2 * l + 1;
        for (k, value) in band.iter_mut().enumerate() {
            let (row, col) = (k / width, k % width);
            if (row + col) % 2 == 1 {
                *value = -*value;
            }
        }
    }
    bands
}

/// Band `l` from band 1 and band l − 1 (both without the Condon–Shortley phase).
fn next_band(l: i64, band1: &[f64], previous: &[f64]) -> Vec<f64> {
    let r1 = |i: i64, j: i64| band1[((i + 1) * 3 + (j + 1)) as usize];
    let prev_width = 2 * l - 1;
    let prev = |a: i64, b: i64| previous[((a + l - 1) * prev_width + (b + l - 1)) as usize];
    let p = |i: i64, a: i64, b: i64| {
        if b == l {
            r1(i, 1) * prev(a, l - 1) - r1(i, -1) * prev(a, -l + 1)
        } else if b == -l {
            r1(i, 1) * prev(a, -l + 1) + r1(i, -1) * prev(a, l - 1)
        } else {
            r1(i, 0) * prev(a, b)
        }
    };
    let delta = |a: i64, b: i64| if a == b { 1.0 } else { 0.0 };
    let width = (2 * l + 1) as usize;
    let mut out = vec![0.0; width * width];
    for m in -l..=l {
        for n in -l..=l {
            let d = delta(m, 0);
            let denominator = if n.abs() < l {
                (l + n) * (l - n)
            } else {
                2 * l * (2 * l - 1)
            } as f64;
            let am = m.abs();
            let u = (((l + m) * (l - m)) as f64 / denominator).sqrt();
            let v = 0.5 * ((1.0 + d) * ((l + am - 1) * (l + am)) as f64 / denominator).sqrt() * (1.0 - 2.0 * d);
            let w = -0.5 * (((l - am - 1) * (l - am)) as f64 / denominator).sqrt() * (1.0 - d);
            let mut value = 0.0;
            if u != 0.0 {
                value += u * p(0, m, n);
            }
            if v != 0.0 {
                let big_v = if m == 0 {
                    p(1, 1, n) + p(-1, -1, n)
                } else if m > 0 {
                    p(1, m - 1, n) * (1.0 + delta(m, 1)).sqrt() - p(-1, -m + 1, n) * (1.0 - delta(m, 1))
                } else {
                    p(1, m + 1, n) * (1.0 - delta(m, -1)) + p(-1, -m - 1, n) * (1.0 + delta(m, -1)).sqrt()
                };
                value += v * big_v;
            }
            if w != 0.0 {
                let big_w = if m > 0 {
                    p(1, m + 1, n) + p(-1, -m - 1, n)
                } else {
                    p(1, m - 1, n) - p(-1, -m + 1, n)
                };
                value += w * big_w;
            }
            out[(m + l) as usize * width + (n + l) as usize] = value;
        }
    }
    out
}

/// Rotates the SH vector `f` by the rotation matrix `rotation` (see the module convention).
pub fn rotate(f: &[f64], rotation: DMat3) -> Vec<f64> {
    let order = order_of(f.len()).expect("an SH vector has a square number of coefficients");
    let matrices = rotation_matrices(order, rotation);
    let mut out = vec![0.0; f.len()];
    for (l, matrix) in matrices.iter().enumerate() {
        let width = 2 * l + 1;
        let start = l * l;
        for row in 0..width {
            out[start + row] = (0..width).map(|col| matrix[row * width + col] * f[start + col]).sum();
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use glam::DVec3;

    use super::*;
    use crate::sh::{band_energies, evaluate, rotate_zh};

    fn test_vector(order: usize, seed: f64) -> Vec<f64> {
        (0..order * order).map(|i| ((i as f64 + 1.0) * seed).sin()).collect()
    }

    fn test_rotation(seed: f64) -> DMat3 {
        DMat3::from_quat(glam::DQuat::from_euler(
            glam::EulerRot::ZYZ,
            seed,
            0.7 * seed + 0.3,
            1.9 - seed,
        ))
    }

    #[test]
    fn rotated_function_is_the_original_turned() {
        for order in [2, 4, 8, 12] {
            let f = test_vector(order, 0.37);
            let r = test_rotation(0.8);
            let g = rotate(&f, r);
            for k in 0..20 {
                let t = k as f64 * 0.9;
                let w = DVec3::new(t.cos() * (2.0 * t).sin(), t.sin(), t.cos() * (2.0 * t).cos()).normalize();
                let expected = evaluate(&f, w);
                let actual = evaluate(&g, r * w);
                assert!(
                    (expected - actual).abs() < 1e-10,
                    "order {order}: {expected} vs {actual}"
                );
            }
        }
    }

    #[test]
    fn rotation_preserves_band_energy_composes_and_inverts() {
        let order = 10;
        let f = test_vector(order, 1.3);
        let (r1, r2) = (test_rotation(0.4), test_rotation(2.1));
        let energy = band_energies(&f);
        let g = rotate(&f, r1);
        for (a, b) in energy.iter().zip(band_energies(&g)) {
            assert!((a - b).abs() < 1e-11 * a.max(1.0));
        }
        let composed = rotate(&rotate(&f, r1), r2);
        let at_once = rotate(&f, r2 * r1);
        let back = rotate(&g, r1.transpose());
        for i in 0..f.len() {
            assert!((composed[i] - at_once[i]).abs() < 1e-11);
            assert!((back[i] - f[i]).abs() < 1e-11);
        }
    }

    #[test]
    fn rotation_about_z_agrees_with_the_general_rotation() {
        let f = test_vector(6, 0.9);
        let a = rotate_z(&f, 0.77);
        let b = rotate(&f, DMat3::from_rotation_z(0.77));
        for i in 0..f.len() {
            assert!((a[i] - b[i]).abs() < 1e-12, "coefficient {i}");
        }
    }

    #[test]
    fn funk_hecke_agrees_with_direct_projection() {
        // The zonal function g(ω) = Σ_l z_l √((2l+1)/(4π)) P_l(d·ω) is band-limited, so an
        // exact quadrature projects it without error.
        let zh = [0.7, 0.4, -0.25, 0.1, 0.05, -0.02];
        let d = DVec3::new(-0.4, 0.3, 0.2).normalize();
        let g = |w: DVec3| -> f64 {
            let p = crate::sh::legendre(zh.len(), d.dot(w));
            zh.iter()
                .enumerate()
                .map(|(l, z)| z * ((2 * l + 1) as f64 / (4.0 * std::f64::consts::PI)).sqrt() * p[l])
                .sum()
        };
        let order = zh.len();
        let projected = crate::sh::SphereQuadrature::exact_for_degree(2 * (order - 1)).project(order, g);
        let rotated = rotate_zh(&zh, d);
        for i in 0..order * order {
            assert!((projected[i] - rotated[i]).abs() < 1e-13, "coefficient {i}");
        }
    }

    #[test]
    fn funk_hecke_agrees_with_rotating_the_zonal_vector() {
        let zh = [0.8, -0.3, 0.5, 0.2, -0.1];
        let dir = DVec3::new(0.2, -0.9, 0.4).normalize();
        let mut zonal = vec![0.0; 25];
        for (l, z) in zh.iter().enumerate() {
            zonal[l * (l + 1)] = *z;
        }
        // Any rotation taking +z to dir.
        let r = DMat3::from_quat(glam::DQuat::from_rotation_arc(DVec3::Z, dir));
        let a = rotate(&zonal, r);
        let b = rotate_zh(&zh, dir);
        for i in 0..25 {
            assert!((a[i] - b[i]).abs() < 1e-12, "coefficient {i}");
        }
    }
}
