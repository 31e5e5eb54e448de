//! Editing a light the way an artist thinks of it: turning it into another kind while it
//! stays about as bright, and aiming it by azimuth and elevation.

use glam::Vec3;

use super::{Light, LightKind};

/// Every kind of light, with the shape a newly chosen kind starts with: a 35°/45° spot
/// cone, a 10 cm sphere, a 1 m × 1 m rect, a 25 cm disk.
pub const LIGHT_KINDS: [LightKind; 6] = [
    LightKind::Point,
    LightKind::Spot {
        inner_cone_rad: 35.0 * std::f32::consts::PI / 180.0,
        outer_cone_rad: 45.0 * std::f32::consts::PI / 180.0,
    },
    LightKind::Directional,
    LightKind::Sphere { radius_m: 0.1 },
    LightKind::Rect {
        width_m: 1.0,
        height_m: 1.0,
        turn_rad: 0.0,
    },
    LightKind::Disk { radius_m: 0.25 },
];

impl Light {
    /// The light's on-axis luminous intensity in candela as seen from `distance_m` along
    /// its direction: the intensity itself for point, spot and sphere lights; luminance ×
    /// area for area lights (a Lambertian emitter's on-axis intensity); illuminance × d²
    /// for directional lights (the point source giving the same lux at that distance).
    pub fn on_axis_intensity_cd(&self, distance_m: f32) -> f32 {
        match self.kind {
            LightKind::Directional => self.intensity * distance_m * distance_m,
            kind => self.intensity * kind.emitting_area_m2().unwrap_or(1.0),
        }
    }

    /// This light as `kind`, its intensity converted so that a receiver `distance_m` away
    /// along the light's direction gets the same irradiance (see
    /// [`Light::on_axis_intensity_cd`]); everything else is kept.
    pub fn converted_to(&self, kind: LightKind, distance_m: f32) -> Light {
        let candela = self.on_axis_intensity_cd(distance_m);
        let intensity = match kind {
            LightKind::Directional => candela / (distance_m * distance_m).max(1e-12),
            kind => candela / kind.emitting_area_m2().unwrap_or(1.0),
        };
        Light {
            kind,
            intensity: if intensity.is_finite() { intensity } else { 0.0 },
            ..self.clone()
        }
    }
}

impl LightKind {
    /// Whether the kind's light has a position (all but directional lights).
    pub fn has_position(&self) -> bool {
        *self != LightKind::Directional
    }

    /// Whether the kind's light points somewhere (spot, directional and area lights).
    pub fn has_direction(&self) -> bool {
        !matches!(self, LightKind::Point | LightKind::Sphere { .. })
    }

    /// Whether `self` and `other` are the same kind, whatever their shape.
    pub fn same_kind(&self, other: &LightKind) -> bool {
        std::mem::discriminant(self) == std::mem::discriminant(other)
    }
}

/// Azimuth and elevation in degrees of unit `direction`: elevation above the horizontal
/// plane (−90° straight down), azimuth about +y from +z towards +x.
pub fn direction_angles_deg(direction: Vec3) -> (f32, f32) {
    let elevation = direction.y.clamp(-1.0, 1.0).asin().to_degrees();
    let azimuth = direction.x.atan2(direction.z).to_degrees();
    (azimuth, elevation)
}

/// The unit direction of [`direction_angles_deg`]'s azimuth and elevation.
pub fn direction_from_angles_deg(azimuth_deg: f32, elevation_deg: f32) -> Vec3 {
    let (azimuth, elevation) = (azimuth_deg.to_radians(), elevation_deg.to_radians());
    Vec3::new(
        elevation.cos() * azimuth.sin(),
        elevation.sin(),
        elevation.cos() * azimuth.cos(),
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    fn light(kind: LightKind, intensity: f32) -> Light {
        Light {
            name: "key".into(),
            kind,
            color: Vec3::ONE,
            intensity,
            position: Vec3::new(0.0, 3.0, 0.0),
            direction: Vec3::NEG_Y,
            range: None,
            locked: false,
        }
    }

    /// Irradiance `distance_m` below the light, facing it, from the renderer's incidence.
    fn irradiance_below(light: &Light, distance_m: f32) -> f32 {
        let p = light.position + light.direction * distance_m;
        light.intensity * light.unit_incidence(light.position, p).irradiance
    }

    #[test]
    fn a_converted_light_lights_the_reference_distance_alike() {
        let distance = 2.5;
        for from in LIGHT_KINDS {
            let original = light(from, 40.0);
            for to in LIGHT_KINDS {
                let converted = original.converted_to(to, distance);
                let (a, b) = (
                    irradiance_below(&original, distance),
                    irradiance_below(&converted, distance),
                );
                assert!(
                    (a - b).abs() <= 1e-4 * a,
                    "{} → {}: {a} lx became {b} lx",
                    from.label(),
                    to.label()
                );
                assert!(converted.problems().is_empty(), "{:?}", converted.problems());
            }
        }
    }

    #[test]
    fn converting_there_and_back_keeps_the_intensity() {
        let original = light(LightKind::Disk { radius_m: 0.4 }, 123.0);
        let back = original
            .converted_to(LightKind::Directional, 3.0)
            .converted_to(
                LightKind::Rect {
                    width_m: 2.0,
                    height_m: 0.5,
                    turn_rad: 0.0,
                },
                3.0,
            )
            .converted_to(original.kind, 3.0);
        assert!((back.intensity - 123.0).abs() < 1e-3, "{}", back.intensity);
    }

    #[test]
    fn angles_round_trip_and_name_the_axes() {
        let cases = [
            (Vec3::Z, (0.0, 0.0)),
            (Vec3::X, (90.0, 0.0)),
            (Vec3::NEG_Y, (0.0, -90.0)),
            (Vec3::new(-1.0, 1.0, 0.0).normalize(), (-90.0, 45.0)),
        ];
        for (direction, (azimuth, elevation)) in cases {
            let (a, e) = direction_angles_deg(direction);
            assert!(
                (a - azimuth).abs() < 1e-4 && (e - elevation).abs() < 1e-4,
                "{direction}: {a}, {e}"
            );
            assert!(direction_from_angles_deg(a, e).distance(direction) < 1e-6);
        }
    }
}
