//! The unshadowed light of rect and disk lights, exactly: the vector irradiance of the
//! emitting polygon (Lambert's formula; Arvo 1994, "The irradiance Jacobian for partially
//! occluded polyhedral sources"). For a Lambertian polygon of radiance L seen from p,
//!
//!   Φ = ½ Σ_edges γ_e · n̂_e,
//!
//! γ_e the angle the edge subtends at p and n̂_e the unit normal of the plane through p
//! and the edge (oriented toward the polygon's side), and the irradiance of a receiver
//! with normal n is E = L · Φ·n wherever the polygon lies wholly above its horizon
//! (`area_vector_irradiance` in scene.wgsl). A disk is taken as the regular polygon of
//! [`DISK_LIGHT_SIDES`] sides and the disk's area (within 0.3 % of the disk on its axis
//! at any height; tests below).
//!
//! Conventions: a rect's corners are the centre ± the half-width vector ± the half-height
//! vector, the latter direction × width axis (`scene::Light::area_axes`); a disk's polygon
//! is laid on the same axes ([`area_frame`] when the light carries no width axis).

use std::f64::consts::{PI, TAU};

use glam::DVec3;

use crate::blockers::disc::edge_form_factor;
use crate::shading::gpu_types::{GpuLight, LIGHT_AREA, LIGHT_DIRECTIONAL, LIGHT_POINT};

/// The xyz of a GPU vector in f64.
fn v3(a: [f32; 4]) -> DVec3 {
    glam::Vec4::from_array(a).truncate().as_dvec3()
}

/// Sides of the regular polygon a disk light is taken as (`DISK_LIGHT_SIDES` in
/// scene.wgsl).
pub const DISK_LIGHT_SIDES: usize = 8;

/// The emitting plane's unit (width, height) axes for an emitting `normal`: width as an
/// unturned rect's ([`crate::scene::Light::unturned_width_axis`]), height = normal × width
/// (`Light::area_axes`; `area_width_axis` in scene.wgsl).
pub fn area_frame(normal: DVec3) -> (DVec3, DVec3) {
    let width = crate::scene::Light::unturned_width_axis(normal.as_vec3()).as_dvec3();
    (width, normal.cross(width))
}

/// The corners of an area light's emitting polygon (world space) and how many there are:
/// a rect's 4 (its `area_half_width_m` non-zero), or a disk's [`DISK_LIGHT_SIDES`], each
/// on an ellipse through them: centre + cos θ_k·U + sin θ_k·V.
pub fn area_light_corners(light: &GpuLight) -> ([DVec3; DISK_LIGHT_SIDES], usize) {
    let centre = v3(light.position);
    let (u, v, sides, first_angle) = match emitter(light) {
        // Rect: corners at θ = 45° + k·90° on the ellipse of semi-axes √2·(half extents).
        crate::penumbra::Emitter::Rect {
            half_width_m,
            half_height_m,
        } => (half_width_m * 2f64.sqrt(), half_height_m * 2f64.sqrt(), 4, 0.25 * PI),
        // Disk: the regular polygon of equal area, on the circle of its circumradius.
        crate::penumbra::Emitter::Disk { radius_m, normal } => {
            let (width, height) = area_frame(normal);
            (width * radius_m, height * radius_m, DISK_LIGHT_SIDES, 0.0)
        }
        // Not an area light: no polygon.
        _ => (DVec3::ZERO, DVec3::ZERO, 0, 0.0),
    };
    let mut corners = [centre; DISK_LIGHT_SIDES];
    for (k, corner) in corners.iter_mut().enumerate().take(sides) {
        let angle = first_angle + TAU * k as f64 / sides as f64;
        *corner = centre + u * angle.cos() + v * angle.sin();
    }
    (corners, sides)
}

/// A light's emitter about its centre (`penumbra::Emitter`): a rect's half extents, a
/// disk's circle of its polygon's circumradius (its polygon's support is within it), a
/// sphere light's radius, a point for point-like lights, none at infinity for the sun.
/// scene.wgsl's `emitter_support_m` measures the same shapes.
pub fn emitter(light: &GpuLight) -> crate::penumbra::Emitter {
    use crate::penumbra::Emitter;
    match light.kind {
        LIGHT_AREA => {
            let normal = v3(light.direction_range);
            let half_width = DVec3::new(
                light.area_half_width_m[0] as f64,
                light.area_half_width_m[1] as f64,
                light.area_half_width_m[2] as f64,
            );
            let area = light.source_size as f64;
            if half_width.length_squared() > 0.0 {
                let half_height = area / (4.0 * half_width.length());
                Emitter::Rect {
                    half_width_m: half_width,
                    half_height_m: normal.cross(half_width).normalize_or_zero() * half_height,
                }
            } else {
                // The regular polygon of equal area, A = ½·N·ρ²·sin(2π/N).
                let n = DISK_LIGHT_SIDES as f64;
                Emitter::Disk {
                    radius_m: (area / (0.5 * n * (TAU / n).sin())).sqrt(),
                    normal,
                }
            }
        }
        LIGHT_DIRECTIONAL => Emitter::AtInfinity,
        LIGHT_POINT => Emitter::Sphere {
            radius_m: light.source_size as f64,
        },
        _ => Emitter::Sphere { radius_m: 0.0 },
    }
}

/// The radius (metres) of the smallest sphere about a light's centre that holds its
/// emitter: a rect's half diagonal, a disk's polygon's circumradius, a sphere light's
/// radius, 0 for point-like lights.
pub fn bounding_radius_m(light: &GpuLight) -> f64 {
    match light.kind {
        LIGHT_AREA => {
            let (corners, sides) = area_light_corners(light);
            let centre = v3(light.position);
            corners[..sides]
                .iter()
                .map(|c| (*c - centre).length())
                .fold(0.0, f64::max)
        }
        LIGHT_POINT => light.source_size as f64,
        _ => 0.0,
    }
}

/// The vector irradiance Φ at p of a polygon of unit radiance (corners in order around
/// it, either way round), oriented toward the polygon: E = Φ·n for a receiver normal n
/// with the polygon above its horizon; |Φ| is the projected solid angle on the plane
/// facing Φ. Zero where p lies in the polygon's plane.
pub fn polygon_vector_irradiance(corners: &[DVec3], p: DVec3) -> DVec3 {
    let sum: DVec3 = (0..corners.len())
        .map(|k| edge_form_factor(corners[k] - p, corners[(k + 1) % corners.len()] - p))
        .sum();
    let phi = 0.5 * sum;
    // The polygon's side: toward its centroid.
    let centroid = corners.iter().copied().sum::<DVec3>() / corners.len().max(1) as f64;
    if phi.dot(centroid - p) < 0.0 { -phi } else { phi }
}

/// An area light's vector irradiance at p per unit radiance (zero behind its emitting
/// side).
pub fn area_vector_irradiance(light: &GpuLight, p: DVec3) -> DVec3 {
    if (p - v3(light.position)).dot(v3(light.direction_range)) <= 0.0 {
        return DVec3::ZERO;
    }
    let (corners, sides) = area_light_corners(light);
    polygon_vector_irradiance(&corners[..sides], p)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::{Light, LightKind};
    use glam::Vec3;

    fn area_light(kind: LightKind, direction: Vec3) -> GpuLight {
        GpuLight::new(&Light {
            name: "area".into(),
            kind,
            color: Vec3::ONE,
            intensity: 1.0,
            position: Vec3::new(0.3, 2.0, -0.2),
            direction,
            range: None,
            locked: false,
        })
    }

    /// Irradiance at a point below the corner of a parallel a × b rectangle at height c,
    /// per unit radiance: π·F with the closed-form corner form factor (Howell's catalogue,
    /// C-11): F = (1/2π)[A/√(1+A²)·atan(B/√(1+A²)) + B/√(1+B²)·atan(A/√(1+B²))],
    /// A = a/c, B = b/c.
    fn corner_irradiance(a: f64, b: f64, c: f64) -> f64 {
        let (x, y) = (a / c, b / c);
        let f = (x / (1.0 + x * x).sqrt() * (y / (1.0 + x * x).sqrt()).atan()
            + y / (1.0 + y * y).sqrt() * (x / (1.0 + y * y).sqrt()).atan())
            / TAU;
        PI * f
    }

    /// Irradiance under a parallel rectangle [x0, x1] × [z0, z1] at height c, by adding
    /// and subtracting corner rectangles (signed extents).
    fn parallel_rect_irradiance(x0: f64, x1: f64, z0: f64, z1: f64, c: f64) -> f64 {
        let signed = |a: f64, b: f64| a.signum() * b.signum() * corner_irradiance(a.abs(), b.abs(), c);
        signed(x1, z1) - signed(x0, z1) - signed(x1, z0) + signed(x0, z0)
    }

    #[test]
    fn a_rect_gives_the_closed_form_under_it_near_and_far() {
        // 0.6 m × 0.4 m facing down at 2 m; receivers on planes 0.2 to 1.9 m below it.
        let light = area_light(
            LightKind::Rect {
                width_m: 0.6,
                height_m: 0.4,
                turn_rad: 0.0,
            },
            Vec3::NEG_Y,
        );
        let (corners, sides) = area_light_corners(&light);
        assert_eq!(sides, 4);
        // The light's centre as stored (f32), and its half extents along x and z (the
        // width axis of a light facing down is ±x: area_frame).
        let centre = v3(light.position);
        let extent = |axis: fn(DVec3) -> f64| corners[..4].iter().map(|c| axis(*c)).fold(f64::MIN, f64::max);
        let (x_half, z_half) = (extent(|c| c.x) - centre.x, extent(|c| c.z) - centre.z);
        assert!(
            (x_half - 0.3).abs() < 1e-6 && (z_half - 0.2).abs() < 1e-6,
            "{x_half} {z_half}"
        );
        for depth in [0.1, 0.2, 0.5, 1.0, 1.9] {
            for (dx, dz) in [(0.0, 0.0), (0.2, 0.1), (0.7, -0.5), (-1.5, 0.3)] {
                let p = centre + DVec3::new(dx, -depth, dz);
                let expected = parallel_rect_irradiance(-x_half - dx, x_half - dx, -z_half - dz, z_half - dz, depth);
                let got = area_vector_irradiance(&light, p).dot(DVec3::Y);
                assert!(
                    (got - expected).abs() <= 1e-9 + 1e-9 * expected,
                    "depth {depth}, offset ({dx}, {dz}): {got} vs {expected}"
                );
            }
        }
    }

    #[test]
    fn a_quarter_turn_swaps_a_rects_width_and_height() {
        let turned = area_light(
            LightKind::Rect {
                width_m: 0.6,
                height_m: 0.4,
                turn_rad: std::f32::consts::FRAC_PI_2,
            },
            Vec3::new(0.3, -1.0, 0.2).normalize(),
        );
        let swapped = area_light(
            LightKind::Rect {
                width_m: 0.4,
                height_m: 0.6,
                turn_rad: 0.0,
            },
            Vec3::new(0.3, -1.0, 0.2).normalize(),
        );
        for p in [
            DVec3::new(0.0, 1.0, 0.0),
            DVec3::new(1.0, 0.5, -0.7),
            DVec3::new(0.4, 1.8, -0.2),
        ] {
            let (a, b) = (area_vector_irradiance(&turned, p), area_vector_irradiance(&swapped, p));
            assert!((a - b).length() < 1e-6 * b.length().max(1e-3), "{a} vs {b}");
        }
        let untouched = area_light(
            LightKind::Rect {
                width_m: 0.6,
                height_m: 0.4,
                turn_rad: 0.0,
            },
            Vec3::new(0.3, -1.0, 0.2).normalize(),
        );
        let p = DVec3::new(0.9, 1.7, 0.1);
        assert!((area_vector_irradiance(&untouched, p) - area_vector_irradiance(&turned, p)).length() > 1e-3);
    }

    #[test]
    fn a_disk_gives_its_closed_form_on_its_axis() {
        // E = π·R²/(h² + R²) per unit radiance, facing the disk.
        let radius = 0.5;
        let light = area_light(
            LightKind::Disk {
                radius_m: radius as f32,
            },
            Vec3::NEG_Y,
        );
        for height in [0.05, 0.2, 0.5, 1.0, 3.0] {
            let p = DVec3::new(0.3, 2.0 - height, -0.2);
            let expected = PI * radius * radius / (height * height + radius * radius);
            let got = area_vector_irradiance(&light, p).dot(DVec3::Y);
            assert!(
                (got / expected - 1.0).abs() < 3e-3,
                "height {height}: {got} vs {expected}"
            );
        }
    }

    #[test]
    fn far_away_an_area_light_is_a_point_of_intensity_l_a_cos() {
        // E → L·A·cos θ_e·cos θ_r / d² (the point model the renderer had used).
        let light = area_light(
            LightKind::Rect {
                width_m: 0.2,
                height_m: 0.1,
                turn_rad: 0.0,
            },
            Vec3::new(0.0, -1.0, 1.0).normalize(),
        );
        let p = DVec3::new(5.0, -30.0, 20.0);
        let offset = v3(light.position) - p;
        let d = offset.length();
        let normal = DVec3::new(0.3, 1.0, -0.2).normalize();
        let cos_emitter = (-offset / d).dot(v3(light.direction_range));
        let expected = 0.02 * cos_emitter * (offset / d).dot(normal) / (d * d);
        let got = area_vector_irradiance(&light, p).dot(normal);
        assert!((got / expected - 1.0).abs() < 1e-4, "{got} vs {expected}");
    }

    #[test]
    fn nothing_behind_the_emitter_or_in_its_plane() {
        let light = area_light(LightKind::Disk { radius_m: 0.3 }, Vec3::NEG_Y);
        assert_eq!(area_vector_irradiance(&light, DVec3::new(0.0, 2.5, 0.0)), DVec3::ZERO);
        let in_plane = area_vector_irradiance(&light, DVec3::new(1.0, 2.0, 0.0));
        assert!(in_plane.length() < 1e-12, "{in_plane}");
    }

    #[test]
    fn the_disks_polygon_has_the_disks_area_and_lies_on_its_axes() {
        let light = area_light(LightKind::Disk { radius_m: 0.4 }, Vec3::new(1.0, -1.0, 0.5).normalize());
        let (corners, sides) = area_light_corners(&light);
        let centre = v3(light.position);
        let area: f64 = (0..sides)
            .map(|k| 0.5 * (corners[k] - centre).cross(corners[(k + 1) % sides] - centre).length())
            .sum();
        assert!((area / (PI * 0.16) - 1.0).abs() < 1e-6, "{area}");
        for corner in &corners[..sides] {
            assert!((corner - centre).dot(v3(light.direction_range)).abs() < 1e-6);
        }
    }
}
