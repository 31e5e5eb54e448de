//! The Gaunt tensor Γ_ijk = ∫ y_i y_j y_k dω, the SH product built on it, and the product
//! matrix. Γ is computed once per order by a quadrature exact for the triple products
//! (degree 3(n − 1)), stored sparse and cached for the life of the process.

use std::collections::HashMap;
use std::sync::{Arc, Mutex, OnceLock};

use super::quadrature::SphereQuadrature;
use super::{basis, coefficient_count};

/// Entries with |Γ| below this are quadrature round-off of exact zeros.
const ZERO_THRESHOLD: f64 = 1e-12;

/// The non-zero entries of Γ at one order, all index triples (i, j, k) < n².
#[derive(Debug)]
pub struct Gaunt {
    pub order: usize,
    pub entries: Vec<(u16, u16, u16, f64)>,
}

impl Gaunt {
    fn compute(order: usize) -> Gaunt {
        let n = coefficient_count(order);
        let quadrature = SphereQuadrature::exact_for_degree(3 * order.saturating_sub(1));
        let mut dense = vec![0.0f64; n * n * n];
        for (dir, weight) in quadrature.points() {
            let y = basis(order, dir);
            for i in 0..n {
                let wi = weight * y[i];
                for j in i..n {
                    let wij = wi * y[j];
                    for k in j..n {
                        dense[(i * n + j) * n + k] += wij * y[k];
                    }
                }
            }
        }
        let mut entries = Vec::new();
        for i in 0..n {
            for j in 0..n {
                for k in 0..n {
                    let mut sorted = [i, j, k];
                    sorted.sort_unstable();
                    let value = dense[(sorted[0] * n + sorted[1]) * n + sorted[2]];
                    if value.abs() > ZERO_THRESHOLD {
                        entries.push((i as u16, j as u16, k as u16, value));
                    }
                }
            }
        }
        Gaunt { order, entries }
    }
}

/// The cached Gaunt tensor of `order`.
pub fn gaunt(order: usize) -> Arc<Gaunt> {
    static CACHE: OnceLock<Mutex<HashMap<usize, Arc<Gaunt>>>> = OnceLock::new();
    let cache = CACHE.get_or_init(Default::default);
    // A poisoned lock only means another thread panicked mid-insert; the map is still valid.
    let mut map = cache.lock().unwrap_or_else(|e| e.into_inner());
    map.entry(order)
        .or_insert_with(|| Arc::new(Gaunt::compute(order)))
        .clone()
}

fn padded(order: usize, f: &[f64]) -> Vec<f64> {
    let mut v = f.to_vec();
    v.resize(coefficient_count(order), 0.0);
    v
}

/// Truncated SH product (f ∗ g)_i = Σ_jk Γ_ijk f_j g_k at `order` (inputs are truncated or
/// zero-padded to that order).
pub fn product(order: usize, f: &[f64], g: &[f64]) -> Vec<f64> {
    let (f, g) = (padded(order, f), padded(order, g));
    let mut out = vec![0.0; coefficient_count(order)];
    for &(i, j, k, value) in &gaunt(order).entries {
        out[i as usize] += value * f[j as usize] * g[k as usize];
    }
    out
}

/// The product matrix (M_f)_ij = Σ_k Γ_ijk f_k (n² × n², row-major, symmetric), so that
/// f ∗ g = M_f g.
pub fn product_matrix(order: usize, f: &[f64]) -> Vec<f64> {
    let f = padded(order, f);
    let n = coefficient_count(order);
    let mut out = vec![0.0; n * n];
    for &(i, j, k, value) in &gaunt(order).entries {
        out[i as usize * n + j as usize] += value * f[k as usize];
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sh::constant;

    #[test]
    fn order_4_has_353_non_zeros() {
        assert_eq!(gaunt(4).entries.len(), 353);
    }

    #[test]
    fn gaunt_is_symmetric_in_all_indices() {
        let g = gaunt(5);
        let map: HashMap<(u16, u16, u16), f64> = g.entries.iter().map(|&(i, j, k, v)| ((i, j, k), v)).collect();
        for (&(i, j, k), &v) in &map {
            for perm in [(i, k, j), (j, i, k), (j, k, i), (k, i, j), (k, j, i)] {
                assert_eq!(map.get(&perm), Some(&v));
            }
        }
    }

    #[test]
    fn product_with_one_is_the_identity() {
        let f: Vec<f64> = (0..36).map(|i| (i as f64 * 0.7).cos()).collect();
        let one = constant(6, 1.0);
        let p = product(6, &f, &one);
        for i in 0..36 {
            assert!((p[i] - f[i]).abs() < 1e-13);
        }
    }

    #[test]
    fn product_projects_the_pointwise_product_of_low_bands() {
        // Two order-2 functions multiply to a degree-2 function: order 3 holds it exactly.
        let f = [0.5, 0.2, -0.4, 0.1];
        let g = [1.0, -0.3, 0.25, 0.6];
        let p = product(3, &f, &g);
        let dir = glam::DVec3::new(0.3, 0.4, -0.8).normalize();
        let pointwise = crate::sh::evaluate(&f, dir) * crate::sh::evaluate(&g, dir);
        assert!((crate::sh::evaluate(&p, dir) - pointwise).abs() < 1e-13);
    }
}
