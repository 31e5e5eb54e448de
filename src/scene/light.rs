use glam::Vec3;

/// A light source. `intensity` is in the light kind's unit ([`LightKind::intensity_unit`]):
/// candela (lm/sr) for point, spot and sphere lights, lux (lm/m²) for directional lights
/// (as KHR_lights_punctual), and luminance in nits (cd/m²) for area lights.
#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Light {
    pub name: String,
    pub kind: LightKind,
    /// Linear RGB colour, multiplied by `intensity` (absent in a project file: white).
    #[serde(default = "white")]
    pub color: Vec3,
    /// Candela (point, spot, sphere), lux (directional) or nits (rect and disk area lights).
    pub intensity: f32,
    /// World position (unused by directional lights; absent in a project file: the
    /// origin).
    #[serde(default)]
    pub position: Vec3,
    /// Unit direction the light travels (spot and directional lights; for area lights the
    /// normal of the emitting side): the node's −z (absent in a project file: straight
    /// down).
    #[serde(default = "straight_down")]
    pub direction: Vec3,
    /// Distance beyond which a point or spot light has no effect (glTF `range`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub range: Option<f32>,
    /// Locked by the artist: painting leaves its intensity as it is (strokes rank it out,
    /// the global solve holds it). The project's, not glTF's (a scene's lights open
    /// unlocked); absent in a project file: unlocked.
    #[serde(default, skip_serializing_if = "std::ops::Not::not")]
    pub locked: bool,
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
    /// A uniformly emitting sphere; `intensity` is its radiant intensity in candela.
    Sphere {
        radius_m: f32,
    },
    /// A one-sided Lambertian rectangle facing `direction`, its width along
    /// [`Light::area_width_axis`]; `intensity` is its luminance in nits.
    Rect {
        width_m: f32,
        height_m: f32,
        /// Turn about `direction` (radians, right-handed about the way the light travels)
        /// from the default width axis, perpendicular to the normal and world +y (+z when
        /// the light faces straight up or down). Format 9; absent: 0.
        #[serde(default, skip_serializing_if = "is_zero")]
        turn_rad: f32,
    },
    /// A one-sided Lambertian disk facing `direction`; `intensity` is its luminance in nits.
    Disk {
        radius_m: f32,
    },
}

impl LightKind {
    pub fn label(&self) -> &'static str {
        match self {
            LightKind::Point => "point",
            LightKind::Spot { .. } => "spot",
            LightKind::Directional => "directional",
            LightKind::Sphere { .. } => "sphere",
            LightKind::Rect { .. } => "rect",
            LightKind::Disk { .. } => "disk",
        }
    }

    /// The unit of [`Light::intensity`] for this kind, as shown to users.
    pub fn intensity_unit(&self) -> &'static str {
        match self {
            LightKind::Directional => "lx",
            LightKind::Rect { .. } | LightKind::Disk { .. } => "nt",
            _ => "cd",
        }
    }

    /// A spot's cone as (cos outer half-angle, 1 / (cos inner − cos outer)), the
    /// parameters of KHR_lights_punctual's smooth falloff (None for other kinds). The
    /// transition is kept at least 1e-4 wide so a zero-width one does not divide by zero.
    pub fn spot_cone(&self) -> Option<(f32, f32)> {
        match *self {
            LightKind::Spot {
                inner_cone_rad,
                outer_cone_rad,
            } => {
                let cos_outer = outer_cone_rad.cos();
                let transition = (inner_cone_rad.cos() - cos_outer).max(1e-4);
                Some((cos_outer, 1.0 / transition))
            }
            _ => None,
        }
    }

    /// Emitting area in m² of area lights (None for the others).
    pub fn emitting_area_m2(&self) -> Option<f32> {
        match *self {
            LightKind::Rect { width_m, height_m, .. } => Some(width_m * height_m),
            LightKind::Disk { radius_m } => Some(std::f32::consts::PI * radius_m * radius_m),
            _ => None,
        }
    }
}

/// What a point source of a light delivers at a receiver, per unit intensity.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct UnitIncidence {
    /// Irradiance on a plane facing the source, per unit of [`Light::intensity`] (lux per
    /// candela, per lux, or per nit).
    pub irradiance: f32,
    /// Unit direction from the receiver to the source.
    pub to_light: Vec3,
    /// Distance to the source in metres (∞ for directional lights).
    pub distance_m: f32,
}

impl Light {
    /// The incidence at `p` of a point source of this light at `source` (a point of its
    /// emitter): inverse square falloff, the glTF range window, the spot cone and, for
    /// area lights, the emitter's cos θ times its whole area, so that an area sample drawn
    /// with density 1/A is an unbiased estimate (the path tracer, the bake) and, far away,
    /// a source at the centre stands for the whole emitter (the renderers take its exact
    /// polygon: `shading::cpu::area`).
    pub fn unit_incidence(&self, source: Vec3, p: Vec3) -> UnitIncidence {
        if self.kind == LightKind::Directional {
            return UnitIncidence {
                irradiance: 1.0,
                to_light: -self.direction,
                distance_m: f32::INFINITY,
            };
        }
        let offset = source - p;
        let distance2 = offset.length_squared().max(1e-8);
        let distance = distance2.sqrt();
        let to_light = offset / distance;
        let mut falloff = self.range_window(distance) / distance2;
        if let Some((cos_outer, inverse_transition)) = self.kind.spot_cone() {
            let t = (((-to_light).dot(self.direction) - cos_outer) * inverse_transition).clamp(0.0, 1.0);
            falloff *= t * t;
        }
        if let Some(area_m2) = self.kind.emitting_area_m2() {
            falloff *= (-to_light).dot(self.direction).max(0.0) * area_m2;
        }
        UnitIncidence {
            irradiance: falloff,
            to_light,
            distance_m: distance,
        }
    }

    /// glTF's smooth range window at `distance_m`: (clamp(1 − (d/range)⁴, 0, 1))², 1
    /// without a range (KHR_lights_punctual's recommended falloff).
    pub fn range_window(&self, distance_m: f32) -> f32 {
        let Some(range) = self.range else { return 1.0 };
        let ratio2 = (distance_m / range).powi(2);
        let window = (1.0 - ratio2 * ratio2).clamp(0.0, 1.0);
        window * window
    }

    /// The width axis of a rect light: perpendicular to its normal and to world +y (world +z
    /// when the light faces straight up or down), turned about the normal by the rect's
    /// `turn_rad`.
    pub fn area_width_axis(&self) -> Vec3 {
        let untouched = Light::unturned_width_axis(self.direction);
        match self.kind {
            LightKind::Rect { turn_rad, .. } if turn_rad != 0.0 && self.direction.is_normalized() => {
                (glam::Quat::from_axis_angle(self.direction, turn_rad) * untouched).normalize_or_zero()
            }
            _ => untouched,
        }
    }

    /// The width axis of an area light facing `direction` before any turn: perpendicular to
    /// it and to world +y (world +z within 8° of straight up or down). Disks lie on it too
    /// (`shading::cpu::area::area_frame`; WGSL `area_width_axis`).
    pub fn unturned_width_axis(direction: Vec3) -> Vec3 {
        let reference = if direction.y.abs() > 0.99 { Vec3::Z } else { Vec3::Y };
        reference.cross(direction).normalize_or_zero()
    }

    /// The emitting plane's (width, height) unit axes of an area light: the width axis and
    /// direction × width, so (width, height, direction) is right-handed.
    pub fn area_axes(&self) -> (Vec3, Vec3) {
        let width = self.area_width_axis();
        (width, self.direction.cross(width).normalize_or_zero())
    }

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
        let sizes: &[(&str, f32)] = match &self.kind {
            LightKind::Sphere { radius_m } | LightKind::Disk { radius_m } => &[("radius_m", *radius_m)],
            LightKind::Rect { width_m, height_m, .. } => &[("width_m", *width_m), ("height_m", *height_m)],
            _ => &[],
        };
        for (name, size) in sizes {
            if !(size.is_finite() && *size > 0.0) {
                problems.push(("kind", format!("{name} {size} must be a positive size in metres")));
            }
        }
        if let LightKind::Rect { turn_rad, .. } = self.kind
            && !turn_rad.is_finite()
        {
            problems.push(("kind", format!("turn_rad {turn_rad} must be finite")));
        }
        if let Some(range) = self.range
            && !(range.is_finite() && range > 0.0)
        {
            problems.push(("range", format!("{range} must be a positive distance")));
        }
        problems
    }
}

fn is_zero(value: &f32) -> bool {
    *value == 0.0
}

fn white() -> Vec3 {
    Vec3::ONE
}

fn straight_down() -> Vec3 {
    Vec3::NEG_Y
}
