use glam::Vec3;

/// A light source. Units follow KHR_lights_punctual: point and spot intensity in candela
/// (lm/sr), directional in lux (lm/m²).
#[derive(Debug, Clone, PartialEq)]
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
    pub range: Option<f32>,
}

#[derive(Debug, Clone, Copy, PartialEq)]
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
