//! Bounded least squares, min ‖A x − b‖² + μ‖x − x₀‖² subject to lo ≤ x ≤ hi (x ≥ 0 for
//! [`solve`]), by cyclic (projected) coordinate descent on the normal equations (Q = AᵀA + μI is positive definite for
//! μ > 0, so every sweep lowers the objective and the iteration converges to the unique
//! minimiser). Deterministic: a fixed sweep order and no parallel sums. The problems here
//! are small (one unknown per light, one row per stroke or constrained vertex), so a dense
//! Q is cheapest; a crate such as `nnls` would bring ndarray for the same few lines.

/// Solves the regularised problem with x ≥ 0; `rows` are the rows of A with their
/// targets b. Returns x ≥ 0, finite.
pub fn solve(rows: &[(Vec<f64>, f64)], mu: f64, x0: &[f64]) -> Vec<f64> {
    let bounds = vec![(0.0, f64::INFINITY); x0.len()];
    solve_bounded(rows, mu, x0, &bounds)
}

/// Solves the regularised problem with each x_i within `bounds[i]` = (lo_i, hi_i),
/// 0 ≤ lo_i ≤ hi_i (a bound that is not finite or not ordered counts as [0, ∞)). Each
/// coordinate step is the exact minimiser along it, clamped to its interval, so every
/// sweep still lowers the convex objective. Returns x within its bounds, finite.
pub fn solve_bounded(rows: &[(Vec<f64>, f64)], mu: f64, x0: &[f64], bounds: &[(f64, f64)]) -> Vec<f64> {
    let n = x0.len();
    let interval = |i: usize| match bounds.get(i) {
        Some(&(lo, hi)) if lo.is_finite() && lo >= 0.0 && hi >= lo => (lo, hi),
        _ => (0.0, f64::INFINITY),
    };
    let mut q = vec![0.0; n * n];
    let mut rhs: Vec<f64> = x0.iter().map(|x| mu * x).collect();
    for (a, b) in rows {
        for i in 0..n {
            if a[i] == 0.0 {
                continue;
            }
            rhs[i] += a[i] * b;
            for j in 0..n {
                q[i * n + j] += a[i] * a[j];
            }
        }
    }
    for i in 0..n {
        q[i * n + i] += mu;
    }
    let mut x: Vec<f64> = x0
        .iter()
        .enumerate()
        .map(|(i, v)| {
            let (lo, hi) = interval(i);
            if v.is_finite() { v.clamp(lo, hi) } else { lo }
        })
        .collect();
    // Gradient Qx − rhs kept up to date as coordinates move.
    let mut gradient: Vec<f64> = (0..n)
        .map(|i| (0..n).map(|j| q[i * n + j] * x[j]).sum::<f64>() - rhs[i])
        .collect();
    let scale = x.iter().fold(1e-300f64, |m, v| m.max(v.abs()));
    for _sweep in 0..20_000 {
        let mut largest_move = 0.0f64;
        for i in 0..n {
            let diagonal = q[i * n + i];
            if diagonal.is_nan() || diagonal <= 0.0 {
                continue;
            }
            let (lo, hi) = interval(i);
            let updated = (x[i] - gradient[i] / diagonal).clamp(lo, hi);
            let step = updated - x[i];
            if step != 0.0 {
                x[i] = updated;
                for (j, g) in gradient.iter_mut().enumerate() {
                    *g += q[j * n + i] * step;
                }
                largest_move = largest_move.max(step.abs());
            }
        }
        if largest_move <= 1e-13 * scale.max(x.iter().fold(0.0f64, |m, v| m.max(*v))) {
            break;
        }
    }
    x.into_iter()
        .enumerate()
        .map(|(i, v)| {
            if v.is_finite() {
                v.max(interval(i).0)
            } else {
                interval(i).0
            }
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn an_exactly_solvable_system_is_solved() {
        // x = (1, 2): rows x₀ + x₁ = 3 and x₀ − x₁ = −1.
        let rows = vec![(vec![1.0, 1.0], 3.0), (vec![1.0, -1.0], -1.0)];
        let x = solve(&rows, 1e-12, &[0.0, 0.0]);
        assert!((x[0] - 1.0).abs() < 1e-9 && (x[1] - 2.0).abs() < 1e-9, "{x:?}");
    }

    #[test]
    fn a_negative_optimum_is_clamped_to_the_best_non_negative_point() {
        // Unconstrained optimum x = −1; with x ≥ 0 the answer is 0.
        let x = solve(&[(vec![1.0], -1.0)], 1e-9, &[5.0]);
        assert_eq!(x, vec![0.0]);
        // Rows x₀ + x₁ = 1 and x₀ = 2: the exact solution (2, −1) is infeasible; with
        // x₁ = 0, x₀ minimises (x₀ − 1)² + (x₀ − 2)², so x₀ = 1.5 (and ∂/∂x₁ = 1 > 0 there).
        let rows = vec![(vec![1.0, 1.0], 1.0), (vec![1.0, 0.0], 2.0)];
        let x = solve(&rows, 1e-12, &[0.0, 0.0]);
        assert!((x[0] - 1.5).abs() < 1e-9 && x[1] == 0.0, "{x:?}");
    }

    /// With bounds the answer is the constrained optimum: rows x₀ = 3 and x₁ = −2 with
    /// 0.5 ≤ x₀ ≤ 2 and 1 ≤ x₁ ≤ 4 give (2, 1), each at the bound nearest its row's
    /// value; a row satisfiable within its bounds is met.
    #[test]
    fn bounded_unknowns_stop_at_their_bounds() {
        let rows = vec![(vec![1.0, 0.0], 3.0), (vec![0.0, 1.0], -2.0)];
        let x = solve_bounded(&rows, 1e-12, &[1.0, 2.0], &[(0.5, 2.0), (1.0, 4.0)]);
        assert!((x[0] - 2.0).abs() < 1e-9 && (x[1] - 1.0).abs() < 1e-9, "{x:?}");
        let x = solve_bounded(&[(vec![1.0, 1.0], 3.0)], 1e-12, &[1.0, 1.0], &[(0.0, 1.0), (0.0, 5.0)]);
        assert!((x[0] + x[1] - 3.0).abs() < 1e-6 && x[0] <= 1.0, "{x:?}");
    }

    #[test]
    fn unconstrained_unknowns_stay_at_the_regularisation_point() {
        let x = solve(&[(vec![1.0, 0.0], 4.0)], 1e-6, &[1.0, 7.0]);
        assert!((x[0] - 4.0).abs() < 1e-5 && (x[1] - 7.0).abs() < 1e-12, "{x:?}");
    }
}
