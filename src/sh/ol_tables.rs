//! Placeholder, replaced by `cargo run --bin fit-ol-tables`.

/// Spacing of the table in ‖f̂‖.
pub const NORM_STEP: f64 = 0.25;

/// (a, b) at ‖f̂‖ = k · NORM_STEP, for orders 2..=8.
pub fn table(_order: usize) -> Option<&'static [(f64, f64)]> {
    None
}
