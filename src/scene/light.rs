use glam::Vec3;

/// A light source. Units follow KHR_lights_punctual: point and spot intensity in candela
/// (lm/sr), directional in lux (lm/m²).
#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Light {
    pub name: String,
    pub kind: LightKind,
    /// Linear RGB colour, multiplied by `intensity`.
    pub color: Vec3,
    /// Candela for point and spot lights, lux for directional lights.
    pub intensity: f32,
    /// World position (unused by directional lights).
    pub position: Vec3,
    /// Unit direction the light travels (spot and directional lights): the node's −z.
    pub direction: Vec3,
    /// Distance beyond which a point or spot light has no effect (glTF `range`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub range: Option<f32>,
}

#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
#[serde(tag = "type", rename_all = "snake_case", deny_unknown_fields)]
pub enum LightKind {
    Point,
    /// Smooth falloff between the inner and outer cone half-angles (KHR_lights_punctual).
    Spot {
        inner_cone_rad: f32,
        outer_cone_rad: f32,
    },
    Directional,
}

impl LightKind {
    pub fn label(&self) -> &'static str {
        match self {
            LightKind::Point => "point",
            LightKind::Spot { .. } => "spot",
            LightKind::Directional => "directional",
        }
    }
}

impl Light {
    /// Every problem with this light's values, as (field, message) pairs: non-finite or
    /// negative colour and intensity, non-finite position, a direction that is not a unit
    /// vector, spot cones outside 0 ≤ inner < outer ≤ π/2, a non-positive range.
    pub fn problems(&self) -> Vec<(&'static str, String)> {
        let mut problems = Vec::new();
        if !self.color.is_finite() || self.color.min_element() < 0.0 {
            problems.push(("color", format!("{} must be finite and non-negative", self.color)));
        }
        if !self.intensity.is_finite() || self.intensity < 0.0 {
            problems.push((
                "intensity",
                format!("{} must be finite and non-negative", self.intensity),
            ));
        }
        if !self.position.is_finite() {
            problems.push(("position", format!("{} is not finite", self.position)));
        }
        if !self.direction.is_finite() || (self.direction.length() - 1.0).abs() > 1e-3 {
            problems.push(("direction", format!("{} is not a unit vector", self.direction)));
        }
        if let LightKind::Spot {
            inner_cone_rad,
            outer_cone_rad,
        } = self.kind
        {
            let valid = (0.0..=std::f32::consts::FRAC_PI_2).contains(&outer_cone_rad)
                && (0.0..outer_cone_rad).contains(&inner_cone_rad);
            if !valid {
                problems.push((
                    "kind",
                    format!(
                        "spot cone angles must satisfy 0 ≤ inner < outer ≤ π/2 \
                         (inner {inner_cone_rad}, outer {outer_cone_rad})"
                    ),
                ));
            }
        }
        if let Some(range) = self.range
            && !(range.is_finite() && range > 0.0)
        {
            problems.push(("range", format!("{range} must be a positive distance")));
        }
        problems
    }
}
