//! Modification strategies (Rozon 2009, §8, with the formulas the thesis leaves open):
//! how a stroke changes the intensities P_i of the lights it selected. Everything here is
//! linear algebra on the stroke's mean transfer T_i (luminance of the painted vertices per
//! unit intensity of light i), so the painted mean luminance is ȳ = Σ_i P_i·T_i exactly.

use super::brush::BrushKind;

/// How a stroke changes the selected lights.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
#[serde(tag = "type", rename_all = "snake_case", deny_unknown_fields)]
pub enum ModificationStrategy {
    /// P ± `amount`, in each light's own unit (cd, lx or nits), floored at 0.
    Constant { amount: f64 },
    /// P × `factor` (positive brush) or P ÷ `factor` (negative); Rozon's "double" is 2.
    Double { factor: f64 },
    /// Intensities solved so the painted mean luminance equals the brush target.
    Direct,
    /// P + `fraction`·(P_direct − P): approaches the target over repeated strokes.
    FractionOfDirect { fraction: f64 },
}

impl Default for ModificationStrategy {
    fn default() -> Self {
        ModificationStrategy::Double { factor: 2.0 }
    }
}

impl ModificationStrategy {
    pub fn label(&self) -> &'static str {
        match self {
            ModificationStrategy::Constant { .. } => "constant",
            ModificationStrategy::Double { .. } => "double",
            ModificationStrategy::Direct => "direct",
            ModificationStrategy::FractionOfDirect { .. } => "fraction of direct",
        }
    }

    pub fn problems(&self) -> Vec<String> {
        match *self {
            ModificationStrategy::Constant { amount } if !(amount.is_finite() && amount > 0.0) => {
                vec![format!("constant amount must be finite and > 0, not {amount}")]
            }
            ModificationStrategy::Double { factor } if !(factor.is_finite() && factor > 1.0) => {
                vec![format!("double factor must be finite and > 1, not {factor}")]
            }
            ModificationStrategy::FractionOfDirect { fraction } if !(fraction > 0.0 && fraction <= 1.0) => {
                vec![format!("fraction of direct must be in (0, 1], not {fraction}")]
            }
            _ => Vec::new(),
        }
    }

    /// Whether the strategy aims at the brush's target luminance.
    pub fn uses_target(&self) -> bool {
        matches!(
            self,
            ModificationStrategy::Direct | ModificationStrategy::FractionOfDirect { .. }
        )
    }
}

/// The inputs of one modification.
#[derive(Debug, Clone, Copy)]
pub struct Step<'a> {
    pub kind: BrushKind,
    pub strategy: ModificationStrategy,
    /// Fraction of the strategy's step applied, (0, 1].
    pub strength: f64,
    pub target_luminance: f64,
    /// Current intensities of all lights.
    pub intensities: &'a [f64],
    /// The painted mean transfer of every light.
    pub transfer: &'a [f64],
    pub selected: &'a [usize],
}

/// Painted mean luminance ȳ = Σ P_i T_i.
pub fn mean_luminance(intensities: &[f64], transfer: &[f64]) -> f64 {
    intensities.iter().zip(transfer).map(|(p, t)| p * t).sum()
}

/// The new intensities of all lights (only selected ones differ), always finite and ≥ 0.
/// A positive brush never lowers ȳ, a negative one never raises it.
pub fn modify(step: &Step) -> Vec<f64> {
    let sign = match step.kind {
        BrushKind::Positive => 1.0,
        BrushKind::Negative => -1.0,
        BrushKind::Constraint | BrushKind::Release => return step.intensities.to_vec(),
    };
    let full = match step.strategy {
        ModificationStrategy::Constant { amount } => map_selected(step, |p| p + sign * amount),
        ModificationStrategy::Double { factor } => {
            map_selected(step, |p| if sign > 0.0 { p * factor } else { p / factor })
        }
        ModificationStrategy::Direct => direct(step, sign),
        ModificationStrategy::FractionOfDirect { fraction } => {
            let target = direct(step, sign);
            blend(step.intensities, &target, fraction.clamp(0.0, 1.0))
        }
    };
    blend(step.intensities, &full, step.strength.clamp(0.0, 1.0))
        .into_iter()
        .map(|p| if p.is_finite() { p.max(0.0) } else { 0.0 })
        .collect()
}

fn map_selected(step: &Step, f: impl Fn(f64) -> f64) -> Vec<f64> {
    let mut out = step.intensities.to_vec();
    for &i in step.selected {
        out[i] = f(out[i]).max(0.0);
    }
    out
}

/// `from + t·(to − from)`, element-wise.
fn blend(from: &[f64], to: &[f64], t: f64) -> Vec<f64> {
    from.iter().zip(to).map(|(a, b)| a + t * (b - a)).collect()
}

/// Direct: P_i ← P_i + δ·w_i over the selected lights, with δ such that Σ P_i T_i =
/// target. The weights are unit-free: w_i = P_i, so each light's share of the change is
/// its share of the light it already puts on the stroke (P_i·T_i) and every selected light
/// is scaled by the same factor 1 + δ, whatever its unit (cd, lx or nits). Where the
/// selected lights give nothing yet (all off), w_i = T_i: a light adds in proportion to
/// how much it reaches the stroke (Rozon's share-out), so a stroke still turns them on.
/// Lights driven below zero are fixed at zero and δ is solved again for the rest, so the
/// result is the reachable intensities closest to the target. A target on the wrong side
/// (brighter than now for a negative brush) changes nothing.
fn direct(step: &Step, sign: f64) -> Vec<f64> {
    let mut out = step.intensities.to_vec();
    let current = mean_luminance(step.intensities, step.transfer);
    let wanted = step.target_luminance;
    let gap = (wanted - current) * sign;
    if gap.is_nan() || gap <= 0.0 {
        return out;
    }
    let mut active: Vec<usize> = step
        .selected
        .iter()
        .copied()
        .filter(|&i| step.transfer[i] > 0.0)
        .collect();
    let lit = active.iter().any(|&i| step.intensities[i] * step.transfer[i] > 0.0);
    let weight = |i: usize| if lit { step.intensities[i] } else { step.transfer[i] };
    while !active.is_empty() {
        let now = mean_luminance(&out, step.transfer);
        let gain: f64 = active.iter().map(|&i| weight(i) * step.transfer[i]).sum();
        if gain <= 0.0 {
            break;
        }
        let delta = (wanted - now) / gain;
        let trial: Vec<(usize, f64)> = active.iter().map(|&i| (i, out[i] + delta * weight(i))).collect();
        let negative: Vec<usize> = trial.iter().filter(|(_, p)| *p < 0.0).map(|(i, _)| *i).collect();
        if negative.is_empty() {
            trial.into_iter().for_each(|(i, p)| out[i] = p);
            break;
        }
        for i in negative {
            out[i] = 0.0;
            active.retain(|&j| j != i);
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    fn step<'a>(
        kind: BrushKind,
        strategy: ModificationStrategy,
        intensities: &'a [f64],
        transfer: &'a [f64],
        selected: &'a [usize],
    ) -> Step<'a> {
        Step {
            kind,
            strategy,
            strength: 1.0,
            target_luminance: 10.0,
            intensities,
            transfer,
            selected,
        }
    }

    #[test]
    fn constant_adds_and_subtracts_with_a_floor_at_zero() {
        let strategy = ModificationStrategy::Constant { amount: 3.0 };
        let p = [5.0, 1.0];
        let up = modify(&step(BrushKind::Positive, strategy, &p, &[1.0, 1.0], &[0, 1]));
        assert_eq!(up, vec![8.0, 4.0]);
        let down = modify(&step(BrushKind::Negative, strategy, &p, &[1.0, 1.0], &[0, 1]));
        assert_eq!(down, vec![2.0, 0.0]);
    }

    #[test]
    fn double_then_halve_is_the_identity_and_zero_stays_zero() {
        let strategy = ModificationStrategy::Double { factor: 2.0 };
        let p = [3.0, 0.0, 7.0];
        let up = modify(&step(BrushKind::Positive, strategy, &p, &[1.0; 3], &[0, 1]));
        assert_eq!(up, vec![6.0, 0.0, 7.0]);
        let back = modify(&step(BrushKind::Negative, strategy, &up, &[1.0; 3], &[0, 1]));
        assert_eq!(back, p.to_vec());
    }

    #[test]
    fn direct_reaches_the_target_exactly_from_zero_and_when_dimming() {
        let transfer = [0.5, 0.25, 0.125];
        let off = [0.0, 0.0, 4.0];
        let up = modify(&step(
            BrushKind::Positive,
            ModificationStrategy::Direct,
            &off,
            &transfer,
            &[0, 1],
        ));
        assert!((mean_luminance(&up, &transfer) - 10.0).abs() < 1e-12);
        assert_eq!(up[2], 4.0, "unselected lights keep their intensity");
        // Dimming to a target that one light alone cannot reach clamps it at 0 and asks
        // the other for the rest.
        let bright = [100.0, 1.0, 0.0];
        let mut s = step(
            BrushKind::Negative,
            ModificationStrategy::Direct,
            &bright,
            &transfer,
            &[0, 1],
        );
        s.target_luminance = 1.0;
        let down = modify(&s);
        assert!((mean_luminance(&down, &transfer) - 1.0).abs() < 1e-12, "{down:?}");
        assert!(down.iter().all(|p| *p >= 0.0));
    }

    /// Two lights each giving the stroke 1 cd/m², one in candela reaching it weakly (a
    /// spot: T = 0.01 per cd, at 100 cd), one in lux reaching it strongly (a sun: T = 1 per
    /// lx, at 1 lx): doubling the stroke's light doubles both, whatever their units. A
    /// share-out by transfer per unit would have put 99 % of the change on the sun.
    #[test]
    fn direct_scales_lights_of_different_units_alike() {
        let transfer = [0.01, 1.0];
        let p = [100.0, 1.0];
        let mut s = step(
            BrushKind::Positive,
            ModificationStrategy::Direct,
            &p,
            &transfer,
            &[0, 1],
        );
        s.target_luminance = 4.0;
        let up = modify(&s);
        assert!((up[0] - 200.0).abs() < 1e-9 && (up[1] - 2.0).abs() < 1e-9, "{up:?}");
    }

    #[test]
    fn direct_on_the_wrong_side_of_the_target_changes_nothing() {
        let p = [100.0];
        let up = modify(&step(
            BrushKind::Positive,
            ModificationStrategy::Direct,
            &p,
            &[1.0],
            &[0],
        ));
        assert_eq!(up, p.to_vec(), "a positive brush does not dim to a lower target");
    }

    #[test]
    fn fraction_of_direct_closes_the_gap_geometrically() {
        let transfer = [0.5];
        let mut p = vec![2.0];
        let strategy = ModificationStrategy::FractionOfDirect { fraction: 0.25 };
        let mut gap = 10.0 - mean_luminance(&p, &transfer);
        for _ in 0..5 {
            p = modify(&step(BrushKind::Positive, strategy, &p, &transfer, &[0]));
            let new_gap = 10.0 - mean_luminance(&p, &transfer);
            assert!((new_gap - 0.75 * gap).abs() < 1e-12);
            gap = new_gap;
        }
    }
}
