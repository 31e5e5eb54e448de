//! What the selection looks like over the viewport, as world-space line segments: the
//! selected light's shape — a spot's outer cone out to what it lights (and its inner
//! cone's rim, where the falloff starts), a rect's or a disk's emitting outline at its
//! true size (turned as the renderer turns it: `Light::area_axes`), a sphere's three great
//! circles; points and the sun have none — and the selected object's bounding box. Pure
//! geometry, and [`draw_outline`], which projects and draws it.

use std::f32::consts::TAU;

use glam::Vec3;

use crate::scene::{Aabb, Light, LightKind};

/// Segments per full circle.
const CIRCLE_SEGMENTS: usize = 32;

/// What an outline is made of: its segments, and those drawn fainter (a spot's inner rim).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Outline {
    pub solid: Vec<[Vec3; 2]>,
    pub faint: Vec<[Vec3; 2]>,
}

/// `light`'s outline; a spot's cone reaches `reach_m` along its axis.
pub fn light_outline(light: &Light, reach_m: f32) -> Outline {
    let mut outline = Outline::default();
    let (u, v) = light.direction.any_orthonormal_pair();
    match light.kind {
        LightKind::Spot {
            inner_cone_rad,
            outer_cone_rad,
        } => {
            let axis_end = light.position + light.direction * reach_m;
            let rim = |half_angle: f32| reach_m * half_angle.min(1.5).tan();
            outline.solid = circle(axis_end, u * rim(outer_cone_rad), v * rim(outer_cone_rad));
            for k in 0..4 {
                let angle = TAU * k as f32 / 4.0;
                let edge = axis_end + (u * angle.cos() + v * angle.sin()) * rim(outer_cone_rad);
                outline.solid.push([light.position, edge]);
            }
            outline.faint = circle(axis_end, u * rim(inner_cone_rad), v * rim(inner_cone_rad));
        }
        LightKind::Rect { width_m, height_m, .. } => {
            let (width, height) = light.area_axes();
            let (a, b) = (width * (0.5 * width_m), height * (0.5 * height_m));
            let corners = [a + b, -a + b, -a - b, a - b].map(|c| light.position + c);
            outline.solid = (0..4).map(|k| [corners[k], corners[(k + 1) % 4]]).collect();
        }
        LightKind::Disk { radius_m } => {
            let (width, height) = light.area_axes();
            outline.solid = circle(light.position, width * radius_m, height * radius_m);
        }
        LightKind::Sphere { radius_m } => {
            for (a, b) in [(Vec3::X, Vec3::Y), (Vec3::Y, Vec3::Z), (Vec3::Z, Vec3::X)] {
                outline.solid.extend(circle(light.position, a * radius_m, b * radius_m));
            }
        }
        LightKind::Point | LightKind::Directional => {}
    }
    outline
}

/// The twelve edges of `bounds` (none when it is empty).
pub fn box_outline(bounds: &Aabb) -> Outline {
    if bounds.is_empty() {
        return Outline::default();
    }
    // Aabb::corners numbers corner k by its bits (x, y, z: max where set): corners whose
    // numbers differ in one bit share an edge.
    let corners = bounds.corners();
    let solid = (0..8)
        .flat_map(|k| {
            [1, 2, 4]
                .into_iter()
                .filter(move |bit| k & bit == 0)
                .map(move |bit| [corners[k], corners[k | bit]])
        })
        .collect();
    Outline {
        solid,
        faint: Vec::new(),
    }
}

/// Draws `outline` with `to_screen`, its faint segments fainter; segments with an end
/// behind the camera are left out.
pub fn draw_outline(painter: &egui::Painter, outline: &Outline, to_screen: impl Fn(Vec3) -> Option<egui::Pos2>) {
    for (segments, alpha) in [(&outline.solid, 150), (&outline.faint, 70)] {
        for [a, b] in segments {
            if let (Some(a), Some(b)) = (to_screen(*a), to_screen(*b)) {
                painter.line_segment([a, b], egui::Stroke::new(1.0, egui::Color32::from_white_alpha(alpha)));
            }
        }
    }
}

/// The points Keep strokes hold, as small teal dots over the render (stronger while the
/// Keep tool is in hand), so the artist sees which areas later strokes spare.
pub fn draw_kept_points(
    painter: &egui::Painter,
    points: &[Vec3],
    emphasised: bool,
    to_screen: impl Fn(Vec3) -> Option<egui::Pos2>,
) {
    let colour = egui::Color32::from_rgba_unmultiplied(60, 220, 200, if emphasised { 230 } else { 120 });
    for &p in points {
        if let Some(at) = to_screen(p) {
            painter.circle_filled(at, 2.0, colour);
        }
    }
}

/// The ellipse centre + cos θ·a + sin θ·b as segments.
fn circle(centre: Vec3, a: Vec3, b: Vec3) -> Vec<[Vec3; 2]> {
    let point = |k: usize| {
        let angle = TAU * k as f32 / CIRCLE_SEGMENTS as f32;
        centre + a * angle.cos() + b * angle.sin()
    };
    (0..CIRCLE_SEGMENTS).map(|k| [point(k), point(k + 1)]).collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn light(kind: LightKind, direction: Vec3) -> Light {
        Light {
            name: "light".into(),
            kind,
            color: Vec3::ONE,
            intensity: 1.0,
            position: Vec3::new(1.0, 3.0, -2.0),
            direction: direction.normalize(),
            range: None,
            locked: false,
        }
    }

    #[test]
    fn a_spots_cone_opens_at_its_outer_angle_and_its_rim_at_the_inner() {
        let (inner, outer) = (0.3f32, 0.5f32);
        let spot = light(
            LightKind::Spot {
                inner_cone_rad: inner,
                outer_cone_rad: outer,
            },
            Vec3::new(0.2, -1.0, 0.4),
        );
        let outline = light_outline(&spot, 2.5);
        let angle = |p: Vec3| (p - spot.position).angle_between(spot.direction);
        for [a, b] in &outline.solid {
            // Every point of the cone's rim and edges, the apex aside, is at the outer angle.
            for p in [a, b].into_iter().filter(|p| p.distance(spot.position) > 1e-4) {
                assert!((angle(*p) - outer).abs() < 1e-4, "{}", angle(*p));
                assert!(((*p - spot.position).dot(spot.direction) - 2.5).abs() < 1e-4);
            }
        }
        assert!(outline.faint.iter().flatten().all(|p| (angle(*p) - inner).abs() < 1e-4));
    }

    #[test]
    fn a_rects_outline_is_its_emitter_turned_as_rendered() {
        let turned = light(
            LightKind::Rect {
                width_m: 0.8,
                height_m: 0.3,
                turn_rad: 0.7,
            },
            Vec3::NEG_Y,
        );
        let outline = light_outline(&turned, 1.0);
        assert_eq!(outline.solid.len(), 4);
        let (width, height) = turned.area_axes();
        for [a, _] in &outline.solid {
            let offset = *a - turned.position;
            assert!(offset.dot(turned.direction).abs() < 1e-6, "in the emitting plane");
            assert!((offset.dot(width).abs() - 0.4).abs() < 1e-5);
            assert!((offset.dot(height).abs() - 0.15).abs() < 1e-5);
        }
        // The width follows the turn.
        assert!(width.dot(Vec3::X).abs() < 0.99);
    }

    #[test]
    fn a_box_has_its_twelve_edges_each_along_one_axis() {
        let bounds = Aabb::from_points(&[Vec3::new(-1.0, 0.0, 2.0), Vec3::new(0.5, 2.0, 3.0)]);
        let outline = box_outline(&bounds);
        assert_eq!(outline.solid.len(), 12);
        let mut lengths: Vec<f32> = outline.solid.iter().map(|[a, b]| a.distance(*b)).collect();
        lengths.sort_by(f32::total_cmp);
        assert_eq!(lengths, [1.0, 1.0, 1.0, 1.0, 1.5, 1.5, 1.5, 1.5, 2.0, 2.0, 2.0, 2.0]);
        assert_eq!(box_outline(&Aabb::EMPTY), Outline::default());
    }

    #[test]
    fn a_disk_and_a_sphere_are_drawn_at_their_radius_and_a_point_not_at_all() {
        let disk = light(LightKind::Disk { radius_m: 0.25 }, Vec3::new(1.0, -1.0, 0.0));
        for [a, _] in light_outline(&disk, 1.0).solid {
            assert!((a.distance(disk.position) - 0.25).abs() < 1e-5);
            assert!((a - disk.position).dot(disk.direction).abs() < 1e-5);
        }
        let sphere = light(LightKind::Sphere { radius_m: 0.1 }, Vec3::NEG_Y);
        let outline = light_outline(&sphere, 1.0);
        assert_eq!(outline.solid.len(), 3 * CIRCLE_SEGMENTS);
        assert!(
            outline
                .solid
                .iter()
                .flatten()
                .all(|p| (p.distance(sphere.position) - 0.1).abs() < 1e-5)
        );
        assert_eq!(
            light_outline(&light(LightKind::Point, Vec3::NEG_Y), 1.0),
            Outline::default()
        );
    }
}
