//! The global solve (docs/strokes.md, step 7): every applied stroke's equation and every
//! kept vertex as rows of one bounded, regularised least-squares problem over the
//! intensities (`nnls`), so that a later stroke does not undo an earlier one.

use super::constraint::ConstrainedVertex;
use super::nnls;

/// How far the global solve may move a light in one stroke, as a factor either way of its
/// intensity before the stroke (beyond what the stroke's own additive step asked).
pub const MAX_GLOBAL_CHANGE: f64 = 4.0;

/// A stroke's mean luminance as a linear function of the intensities, and the value the
/// stroke settled on: one row of the global solve.
#[derive(Debug, Clone, PartialEq)]
pub(super) struct Equation {
    pub transfer: Vec<f64>,
    pub fixed: f64,
    pub target: f64,
}

/// `equations` (every recorded stroke's and the new one's) and every `constrained`
/// vertex, solved together: min Σ rows² + μ Σ ((P_i − P̂_i)/s_i)², each row relative to its target,
/// unknowns scaled by s_i so lights of different units weigh alike; P̂ is the additive
/// result, the point the solve stays near where the equations say nothing. Each light
/// stays within [`MAX_GLOBAL_CHANGE`] times its intensity `before` the stroke either
/// way (and within reach of the additive result): conflicting strokes then move many
/// lights a little rather than switch most off and one up twentyfold. A `locked` light
/// stays at its intensity `before`. Returns the intensities and how many lights ended
/// at such a bound.
pub(super) fn solve_globally<'a>(
    equations: impl Iterator<Item = &'a Equation>,
    constrained: &[&ConstrainedVertex],
    [before, additive]: [&[f64]; 2],
    locked: &[bool],
) -> (Vec<f64>, usize) {
    let n = additive.len();
    let mean = additive.iter().sum::<f64>() / n.max(1) as f64;
    let scale: Vec<f64> = additive.iter().map(|&p| p.max(mean).max(1e-9)).collect();
    let mut rows: Vec<(Vec<f64>, f64)> = Vec::new();
    let mut add = |coefficients: Vec<(usize, f64)>, fixed: f64, target: f64, weight: f64| {
        let norm = target.abs().max(1e-12);
        let mut a = vec![0.0; n];
        for (i, t) in coefficients {
            a[i] += weight * t * scale[i] / norm;
        }
        rows.push((a, weight * (target - fixed) / norm));
    };
    for e in equations {
        add(e.transfer.iter().copied().enumerate().collect(), e.fixed, e.target, 1.0);
    }
    // A constrained set counts like ten strokes, however many vertices it has.
    let weight = (10.0 / constrained.len().max(1) as f64).sqrt();
    for c in constrained {
        let coefficients = c.transfer.iter().map(|&(i, t)| (i as usize, t)).collect();
        add(coefficients, c.fixed, c.luminance, weight);
    }
    let x0: Vec<f64> = additive.iter().zip(&scale).map(|(p, s)| p / s).collect();
    let bounds: Vec<(f64, f64)> = (0..n)
        .map(|i| {
            let (p, a) = (before.get(i).copied().unwrap_or(0.0), additive[i]);
            if locked.get(i).copied().unwrap_or(false) {
                return (p / scale[i], p / scale[i]);
            }
            let lo = (p / MAX_GLOBAL_CHANGE).min(a);
            let hi = (p * MAX_GLOBAL_CHANGE).max(a);
            (lo / scale[i], hi / scale[i])
        })
        .collect();
    let solved = nnls::solve_bounded(&rows, 1e-4, &x0, &bounds);
    let held = solved
        .iter()
        .zip(&bounds)
        .filter(|(x, (lo, hi))| lo < hi && (**x <= *lo * (1.0 + 1e-9) && *lo > 0.0 || **x >= *hi * (1.0 - 1e-9)))
        .count();
    (solved.into_iter().zip(&scale).map(|(x, s)| x * s).collect(), held)
}
