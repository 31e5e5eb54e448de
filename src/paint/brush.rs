//! Brushes: what a dab does (more light, less light, keep this) and how its weight falls
//! off across the screen-space disc it covers.

/// What a stroke asks for (Rozon's three brushes).
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum BrushKind {
    /// More light on the painted vertices.
    Positive,
    /// Less light on the painted vertices.
    Negative,
    /// "Keep this as it is": marks the vertices; later strokes spare the lights that reach
    /// them and never move their luminance beyond the tolerance.
    Constraint,
    /// Releases the Keep areas under the brush: the vertices it paints are no longer
    /// kept for the strokes after it (earlier strokes stand; undo brings the Keep back).
    Release,
}

/// How a dab's weight falls from its centre (1) to its rim.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Falloff {
    /// Weight 1 everywhere inside the disc.
    Hard,
    /// Weight (1 − (d/r)²)²: smooth at the rim, flat at the centre.
    #[default]
    Smooth,
}

/// A brush: kind, screen-space size and falloff, how much of a strategy's step it applies,
/// and the luminance the "direct" strategies aim for.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Brush {
    pub kind: BrushKind,
    /// Radius of the dab's disc on screen, pixels (Rozon used an 11-pixel diameter).
    #[serde(default = "default_radius_px")]
    pub radius_px: f32,
    #[serde(default)]
    pub falloff: Falloff,
    /// Fraction in (0, 1] of the modification strategy's step that a stroke applies.
    #[serde(default = "default_strength")]
    pub strength: f32,
    /// Mean luminance (cd/m², linear, before exposure) the direct strategies aim for.
    #[serde(default = "default_target_nits")]
    pub target_luminance_nits: f32,
}

fn default_radius_px() -> f32 {
    12.0
}

fn default_strength() -> f32 {
    1.0
}

fn default_target_nits() -> f32 {
    1.0
}

impl Brush {
    pub fn new(kind: BrushKind) -> Brush {
        Brush {
            kind,
            radius_px: default_radius_px(),
            falloff: Falloff::default(),
            strength: default_strength(),
            target_luminance_nits: default_target_nits(),
        }
    }

    /// Weight of a vertex `distance_px` from the dab centre: in (0, 1] inside the disc,
    /// None outside it.
    pub fn weight(&self, distance_px: f32) -> Option<f32> {
        let radius = self.radius_px.max(0.5);
        if distance_px.is_nan() || distance_px > radius {
            return None;
        }
        let weight = match self.falloff {
            Falloff::Hard => 1.0,
            Falloff::Smooth => {
                let x = distance_px / radius;
                (1.0 - x * x).powi(2)
            }
        };
        // The rim of a smooth dab still counts a little, so no hit has weight zero.
        Some(weight.max(1e-3))
    }

    /// What is wrong with the brush's numbers, if anything.
    pub fn problems(&self) -> Vec<String> {
        let mut problems = Vec::new();
        if !(self.radius_px.is_finite() && self.radius_px > 0.0) {
            problems.push(format!("radius_px must be positive, not {}", self.radius_px));
        }
        if !(self.strength.is_finite() && self.strength > 0.0 && self.strength <= 1.0) {
            problems.push(format!("strength must be in (0, 1], not {}", self.strength));
        }
        if !(self.target_luminance_nits.is_finite() && self.target_luminance_nits >= 0.0) {
            problems.push(format!(
                "target_luminance_nits must be finite and ≥ 0, not {}",
                self.target_luminance_nits
            ));
        }
        problems
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn weights_are_one_at_the_centre_and_none_outside() {
        for falloff in [Falloff::Hard, Falloff::Smooth] {
            let brush = Brush {
                falloff,
                radius_px: 10.0,
                ..Brush::new(BrushKind::Positive)
            };
            assert_eq!(brush.weight(0.0), Some(1.0));
            assert!(brush.weight(10.0).is_some());
            assert_eq!(brush.weight(10.01), None);
            assert_eq!(brush.weight(f32::NAN), None);
        }
        let smooth = Brush::new(BrushKind::Positive);
        let inner = smooth.weight(3.0).unwrap();
        let outer = smooth.weight(9.0).unwrap();
        assert!(inner > outer && outer > 0.0);
    }

    #[test]
    fn bad_numbers_are_named() {
        let brush = Brush {
            strength: 0.0,
            radius_px: f32::INFINITY,
            ..Brush::new(BrushKind::Negative)
        };
        assert_eq!(brush.problems().len(), 2);
        assert!(Brush::new(BrushKind::Constraint).problems().is_empty());
    }
}
