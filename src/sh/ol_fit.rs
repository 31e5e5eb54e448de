//! The least-squares fit behind the OL tables (Ren et al. 2006, "optimal linear"):
//! for each norm ν, the (a, b) minimising Σ_s ‖a·1 + b·f̂_s − exp*(f̂_s)‖² over a training
//! set of DC-free log-visibility vectors f̂_s of norm ν, with exp* the reference.
//!
//! Training vectors are shapes of random blocker configurations — 1 to 8 caps of half-angle
//! 5°–60° in uniformly random directions, ln ε = ln 0.1 — with the DC removed and rescaled
//! to norm ν. Because f̂·1 = 0, the normal equations decouple:
//! a = mean(exp*(f̂)₀)/√(4π), b = mean(f̂·exp*(f̂))/ν².
//! `cargo run --bin fit-ol-tables` writes `src/sh/ol_tables.rs` from this.

use glam::DVec3;

use super::{exp_reference, log_visibility};
use crate::random::SplitMix64;

/// Settings of the committed tables.
pub const OL_TABLE_ORDERS: std::ops::RangeInclusive<usize> = 2..=8;
pub const OL_TABLE_ENTRIES: usize = 65;
pub const OL_TRAINING_SHAPES: usize = 48;
pub const OL_TRAINING_SEED: u64 = 0x5eed_0f01;

/// A uniformly distributed unit direction.
fn random_direction(rng: &mut SplitMix64) -> DVec3 {
    let z = 2.0 * rng.next_f64() - 1.0;
    let phi = std::f64::consts::TAU * rng.next_f64();
    let r = (1.0 - z * z).sqrt();
    DVec3::new(r * phi.cos(), r * phi.sin(), z)
}

/// Unit-norm, DC-free training shapes at `order`.
pub fn training_shapes(order: usize, count: usize, seed: u64) -> Vec<Vec<f64>> {
    let mut rng = SplitMix64(seed ^ order as u64);
    let mut shapes = Vec::with_capacity(count);
    while shapes.len() < count {
        let count = 1 + (rng.next_u64() % 8) as usize;
        let caps: Vec<(DVec3, f64)> = (0..count)
            .map(|_| {
                let half_angle = (5.0 + 55.0 * rng.next_f64()).to_radians();
                (random_direction(&mut rng), half_angle)
            })
            .collect();
        let mut f = log_visibility(order, &caps, 0.1);
        f[0] = 0.0;
        let norm = f.iter().map(|v| v * v).sum::<f64>().sqrt();
        if norm > 1e-9 {
            shapes.push(f.into_iter().map(|v| v / norm).collect());
        }
    }
    shapes
}

/// The OL (a, b) at norm `norm` for the given unit training shapes.
pub fn fit_ol_at(shapes: &[Vec<f64>], norm: f64) -> (f64, f64) {
    if norm == 0.0 {
        return (1.0, 1.0);
    }
    let sqrt_4pi = (4.0 * std::f64::consts::PI).sqrt();
    let (mut a_sum, mut b_sum) = (0.0, 0.0);
    for shape in shapes {
        let hat: Vec<f64> = shape.iter().map(|v| v * norm).collect();
        let e = exp_reference(&hat);
        a_sum += e[0] / sqrt_4pi;
        b_sum += hat.iter().zip(&e).map(|(h, v)| h * v).sum::<f64>() / (norm * norm);
    }
    (a_sum / shapes.len() as f64, b_sum / shapes.len() as f64)
}

/// The whole table of one order: entries at ‖f̂‖ = k · `norm_step`, k < `entries`.
pub fn fit_ol_table(order: usize, entries: usize, norm_step: f64) -> Vec<(f64, f64)> {
    let shapes = training_shapes(order, OL_TRAINING_SHAPES, OL_TRAINING_SEED);
    (0..entries).map(|k| fit_ol_at(&shapes, k as f64 * norm_step)).collect()
}
