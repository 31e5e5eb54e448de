//! Constraint-brushed vertices: "keep this as it is". Each keeps the luminance it had
//! when it was brushed, with its transfer from that view. Later strokes
//! - rank lights that reach constrained vertices lower (Rozon's eq. 5.11 penalty, applied
//!   as importance ÷ (1 + λ·c_i), c_i the light's share of the constrained light), and
//! - never move a constrained vertex's luminance by more than the tolerance: a step that
//!   would is shortened along its direction to the largest fraction that keeps every
//!   constrained vertex inside its band (a guard the thesis did not have).

use super::pick::VertexRef;

/// One constrained vertex.
#[derive(Debug, Clone, PartialEq)]
pub struct ConstrainedVertex {
    pub vertex: VertexRef,
    /// Brush weight; Rozon's object factor (1 − S^c/S) is applied in [`penalty_shares`].
    pub weight: f64,
    /// Luminance when constrained (cd/m²).
    pub luminance: f64,
    /// Luminance no light changes.
    pub fixed: f64,
    /// (light, transfer) toward the view it was constrained from.
    pub transfer: Vec<(u32, f64)>,
}

impl ConstrainedVertex {
    /// Luminance under `intensities`.
    pub fn luminance_at(&self, intensities: &[f64]) -> f64 {
        self.fixed
            + self
                .transfer
                .iter()
                .map(|&(i, t)| intensities[i as usize] * t)
                .sum::<f64>()
    }
}

/// Each light's share c_i ∈ [0, 1] of the light the constrained vertices receive,
/// weighted per Rozon's eq. 5.11 by (1 − S^c_o/S_o) for a vertex on object o (S^c_o of its
/// S_o vertices constrained: the fewer constrained, the more each one weighs).
/// `received` scales each light's transfer by its intensity (1 for transfer ranking).
pub fn penalty_shares<'a>(
    constrained: impl Iterator<Item = &'a ConstrainedVertex> + Clone,
    vertices_per_object: &[usize],
    light_scale: &[f64],
) -> Vec<f64> {
    let mut constrained_per_object = vec![0usize; vertices_per_object.len()];
    for c in constrained.clone() {
        if let Some(n) = constrained_per_object.get_mut(c.vertex.object as usize) {
            *n += 1;
        }
    }
    let mut sums = vec![0.0; light_scale.len()];
    for c in constrained {
        let o = c.vertex.object as usize;
        let all = vertices_per_object.get(o).copied().unwrap_or(1).max(1);
        let factor = 1.0 - constrained_per_object.get(o).copied().unwrap_or(0) as f64 / all as f64;
        for &(i, t) in &c.transfer {
            if let Some(sum) = sums.get_mut(i as usize) {
                *sum += c.weight * factor.max(0.0) * light_scale[i as usize] * t;
            }
        }
    }
    let total: f64 = sums.iter().sum();
    if total > 0.0 {
        sums.iter_mut().for_each(|s| *s /= total);
    }
    sums
}

/// Largest s ∈ [0, 1] such that `from + s·(to − from)` keeps every constrained vertex's
/// luminance within `tolerance` (relative) of what it was constrained at; a vertex already
/// outside its band may move toward it but not away.
pub fn allowed_fraction<'a>(
    constrained: impl Iterator<Item = &'a ConstrainedVertex>,
    from: &[f64],
    to: &[f64],
    tolerance: f64,
) -> f64 {
    let mut allowed = 1.0f64;
    for c in constrained {
        let now = c.luminance_at(from);
        let change = c.luminance_at(to) - now;
        // The band never shrinks to nothing, so a vertex constrained in the dark may still
        // get a hair of light.
        let slack = tolerance * c.luminance.abs() + 1e-9 * (1.0 + c.luminance.abs());
        let (low, high) = (c.luminance - slack, c.luminance + slack);
        let limit = if change > 0.0 {
            (high - now).max(0.0) / change
        } else if change < 0.0 {
            (now - low).max(0.0) / -change
        } else {
            1.0
        };
        allowed = allowed.min(limit);
    }
    allowed.clamp(0.0, 1.0)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn vertex(object: u32, transfer: Vec<(u32, f64)>, luminance: f64) -> ConstrainedVertex {
        ConstrainedVertex {
            vertex: VertexRef { object, vertex: 0 },
            weight: 1.0,
            luminance,
            fixed: 0.0,
            transfer,
        }
    }

    #[test]
    fn no_constraint_no_penalty_and_shares_follow_the_transfer() {
        let none: Vec<ConstrainedVertex> = Vec::new();
        assert_eq!(penalty_shares(none.iter(), &[10], &[1.0, 1.0]), vec![0.0, 0.0]);
        let some = [vertex(0, vec![(0, 3.0), (1, 1.0)], 4.0)];
        let shares = penalty_shares(some.iter(), &[10], &[1.0, 1.0]);
        assert!((shares[0] - 0.75).abs() < 1e-12 && (shares[1] - 0.25).abs() < 1e-12);
    }

    #[test]
    fn a_fully_constrained_object_weighs_nothing() {
        // Rozon's quirk: (1 − S^c/S) = 0 when every vertex of the object is constrained.
        let all = [vertex(0, vec![(0, 1.0)], 1.0)];
        assert_eq!(penalty_shares(all.iter(), &[1], &[1.0]), vec![0.0]);
    }

    #[test]
    fn the_guard_stops_a_step_at_the_edge_of_the_band() {
        let constrained = [vertex(0, vec![(0, 1.0)], 10.0)];
        // From P = 10 (luminance 10) toward P = 20: only +2 % is allowed, s = 0.02.
        let s = allowed_fraction(constrained.iter(), &[10.0], &[20.0], 0.02);
        assert!((s - 0.02).abs() < 1e-6, "{s}");
        // A step that does not touch the vertex is free.
        let other = [vertex(0, vec![(0, 1.0)], 10.0)];
        assert_eq!(allowed_fraction(other.iter(), &[10.0, 0.0], &[10.0, 5.0], 0.02), 1.0);
    }
}
