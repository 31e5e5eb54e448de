//! Lights drawn over the viewport and moved by hand. Every light with a position has a
//! marker (its colour, ringed when selected); directional lights have a sun marker on a
//! sphere around the view's pivot. The selected light gets a gizmo: three axis arrows
//! that move it along world x, y and z, its marker moves it in the view plane, and an aim
//! handle at the tip of its direction turns it, and its shape is outlined (a spot's cone,
//! an area light's emitter: `outlines`). Dragging the sun turns a directional light. The geometry is pure functions of the view ([`View`]); this file also draws.

use glam::{Vec2, Vec3};

use super::outlines::{draw_outline, light_outline};
use super::viewport::screen_point;
use crate::paint::View;
use crate::scene::Light;

/// Screen length of the gizmo's arrows, points.
const ARROW_PX: f32 = 70.0;
/// Radius of a marker and of a handle, points.
const MARKER_PX: f32 = 7.0;

/// What the user did with the markers and the gizmo this frame.
#[derive(Debug, Clone, Default)]
pub struct GizmoOutput {
    /// A light marker was clicked or grabbed.
    pub select: Option<usize>,
    /// The light being dragged, as edited (index and new value).
    pub edited: Option<(usize, Light)>,
}

/// The world length that appears `pixels` long at `p`'s depth.
fn world_per_pixels(view: &View, p: Vec3, pixels: f32) -> f32 {
    let camera = &view.camera;
    let depth = (p - camera.position).dot(camera.forward).max(camera.znear);
    pixels * 2.0 * depth * (0.5 * camera.yfov_rad).tan() / view.height_px.max(1) as f32
}

/// Where the eye ray through `pixel` meets the plane through `point` facing the camera.
fn on_view_plane(view: &View, pixel: Vec2, point: Vec3) -> Option<Vec3> {
    let (origin, direction) = view.ray_through(pixel)?;
    let normal = view.camera.forward;
    let denominator = direction.dot(normal);
    if denominator.abs() < 1e-6 {
        return None;
    }
    let t = (point - origin).dot(normal) / denominator;
    (t > 0.0).then(|| origin + t * direction)
}

/// The point of the sphere (`center`, `radius`) under `pixel`: the near intersection of
/// the eye ray, or the sphere point nearest the ray when it misses.
fn on_sphere(view: &View, pixel: Vec2, center: Vec3, radius: f32) -> Option<Vec3> {
    let (origin, direction) = view.ray_through(pixel)?;
    let to_center = center - origin;
    let along = to_center.dot(direction);
    let miss2 = to_center.length_squared() - along * along;
    let point = if miss2 <= radius * radius {
        origin + (along - (radius * radius - miss2).sqrt()) * direction
    } else {
        let nearest = origin + along * direction;
        center + (nearest - center).normalize_or_zero() * radius
    };
    point.is_finite().then_some(point)
}

/// Moves `position` along world `axis` by a pointer drag `delta_px`: the drag's share
/// along the axis' screen image, at the world length per pixel along it.
pub fn moved_along_axis(view: &View, position: Vec3, axis: Vec3, delta_px: Vec2) -> Vec3 {
    let length = world_per_pixels(view, position, ARROW_PX);
    let (Some(a), Some(b)) = (view.project(position), view.project(position + axis * length)) else {
        return position;
    };
    let screen = b - a;
    let screen_length = screen.length();
    if screen_length < 4.0 {
        // The axis points at the eye: dragging along it would be erratic.
        return position;
    }
    position + axis * (delta_px.dot(screen / screen_length) * length / screen_length)
}

/// The sun marker of a directional light: on the sphere of `radius` around `pivot`, on
/// the side the light comes from.
pub fn sun_position(pivot: Vec3, radius: f32, direction: Vec3) -> Vec3 {
    pivot - direction * radius
}

/// The radius of the sun sphere for a view whose pivot is `orbit_distance` away.
pub fn sun_radius(orbit_distance: f32) -> f32 {
    0.4 * orbit_distance
}

/// Handles of the selected light, by what a drag on them does.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Handle {
    Axis(Vec3),
    Aim,
}

/// The lights a gizmo draws: the lights, which one is selected, and the shadow path of
/// each.
pub struct GizmoLights<'a> {
    pub lights: &'a [Light],
    pub selected: Option<usize>,
    pub paths: &'a [crate::shading::ShadowPath],
}

/// Draws the markers of the lights and the gizmo of the selected one over `rect`, and
/// turns drags on them into light edits. `pivot` and `orbit_distance` place the sun
/// markers of directional lights. A light shadowed exactly has a ring inside its marker.
pub fn light_gizmo(
    ui: &mut egui::Ui,
    rect: egui::Rect,
    view: &View,
    lights: GizmoLights,
    pivot: Vec3,
    orbit_distance: f32,
) -> GizmoOutput {
    let GizmoLights {
        lights,
        selected,
        paths,
    } = lights;
    let mut output = GizmoOutput::default();
    let painter = ui.painter_at(rect);
    let to_screen = |p: Vec3| screen_point(view, rect, p);
    let to_view = |p: egui::Pos2| Vec2::new(p.x - rect.min.x, p.y - rect.min.y);
    let sun_radius = sun_radius(orbit_distance);
    for (index, light) in lights.iter().enumerate() {
        let anchor = if light.kind.has_position() {
            light.position
        } else {
            sun_position(pivot, sun_radius, light.direction)
        };
        let Some(at) = to_screen(anchor).filter(|p| rect.contains(*p)) else {
            continue;
        };
        let is_selected = selected == Some(index);
        let path = paths
            .get(index)
            .copied()
            .unwrap_or(crate::shading::ShadowPath::Harmonics);
        let exact_path = path == crate::shading::ShadowPath::Exact;
        let id = ui.scope_id().with(("light marker", index));
        let response = ui
            .interact(
                egui::Rect::from_center_size(at, egui::Vec2::splat(2.5 * MARKER_PX)),
                id,
                egui::Sense::click_and_drag(),
            )
            .on_hover_text(format!(
                "{} ({}; {} shadows at the view's pivot)",
                light.name,
                light.kind.label(),
                path.words()
            ));
        if response.clicked() || response.drag_started() {
            output.select = Some(index);
        }
        if let Some(pointer) = drag_pointer(ui, &response) {
            let mut edited = light.clone();
            if light.kind.has_position() {
                if let Some(p) = on_view_plane(view, to_view(pointer), light.position) {
                    edited.position = p;
                }
            } else if let Some(p) = on_sphere(view, to_view(pointer), pivot, sun_radius) {
                edited.direction = (pivot - p).normalize_or(light.direction);
            }
            output.edited = Some((index, edited));
        }
        if is_selected {
            // What it lights reaches about as far as the view's pivot.
            let reach_m = (pivot - light.position).length().max(0.5);
            draw_outline(&painter, &light_outline(light, reach_m), to_screen);
        }
        draw_marker(&painter, at, light, is_selected, response.hovered());
        if exact_path {
            painter.circle_stroke(
                at,
                0.45 * MARKER_PX,
                egui::Stroke::new(1.5, egui::Color32::from_black_alpha(200)),
            );
        }
        if is_selected && light.kind.has_position() {
            if let Some(edit) = gizmo_handles(ui, &painter, rect, view, index, light) {
                output.edited = Some((index, edit));
            }
        } else if is_selected && let Some(center) = to_screen(pivot) {
            // The sun's ray to the pivot shows where a directional light comes from.
            painter.line_segment(
                [at, center],
                egui::Stroke::new(1.0, egui::Color32::from_white_alpha(90)),
            );
        }
    }
    output
}

/// The selected positioned light's axis arrows and aim handle; the edited light if one
/// was dragged.
fn gizmo_handles(
    ui: &mut egui::Ui,
    painter: &egui::Painter,
    rect: egui::Rect,
    view: &View,
    index: usize,
    light: &Light,
) -> Option<Light> {
    let to_screen = |p: Vec3| screen_point(view, rect, p);
    let at = to_screen(light.position)?;
    let length = world_per_pixels(view, light.position, ARROW_PX);
    let mut handles = vec![
        (Handle::Axis(Vec3::X), egui::Color32::from_rgb(230, 80, 80)),
        (Handle::Axis(Vec3::Y), egui::Color32::from_rgb(110, 210, 90)),
        (Handle::Axis(Vec3::Z), egui::Color32::from_rgb(90, 140, 240)),
    ];
    if light.kind.has_direction() {
        handles.push((Handle::Aim, egui::Color32::from_rgb(255, 214, 120)));
    }
    let mut edited = None;
    for (handle, color) in handles {
        let tip_world = match handle {
            Handle::Axis(axis) => light.position + axis * length,
            Handle::Aim => light.position + light.direction * length,
        };
        let Some(tip) = to_screen(tip_world) else { continue };
        let id = ui.scope_id().with(("light handle", index, format!("{handle:?}")));
        let response = ui.interact(
            egui::Rect::from_center_size(tip, egui::Vec2::splat(2.5 * MARKER_PX)),
            id,
            egui::Sense::drag(),
        );
        let width = if response.hovered() || response.dragged() {
            3.0
        } else {
            2.0
        };
        painter.line_segment([at, tip], egui::Stroke::new(width, color));
        if handle == Handle::Aim {
            painter.circle_stroke(tip, MARKER_PX, egui::Stroke::new(width, color));
        } else {
            painter.circle_filled(tip, 0.6 * MARKER_PX + width - 2.0, color);
        }
        if response.drag_started()
            && let Some(pressed) = ui.input(|i| i.pointer.press_origin())
        {
            ui.data_mut(|d| d.insert_temp(id, (light.position, pressed)));
        }
        let Some(pointer) = drag_pointer(ui, &response) else {
            continue;
        };
        let mut light = light.clone();
        match handle {
            Handle::Axis(axis) => {
                // From where the drag started, not summed per frame: at a few frames a
                // second per-frame deltas lose motion.
                let (start, pressed) = ui.data(|d| d.get_temp::<(Vec3, egui::Pos2)>(id))?;
                let dragged = pointer - pressed;
                light.position = moved_along_axis(view, start, axis, Vec2::new(dragged.x, dragged.y));
            }
            Handle::Aim => {
                let pixel = Vec2::new(pointer.x - rect.min.x, pointer.y - rect.min.y);
                let target = on_view_plane(view, pixel, tip_world)?;
                light.direction = (target - light.position).normalize_or(light.direction);
            }
        }
        edited = Some(light);
    }
    edited
}

/// Where the pointer is while `response` is dragged, and where it was let go in the
/// frame the drag ends (a slow frame can hold the last move and the release together).
fn drag_pointer(ui: &egui::Ui, response: &egui::Response) -> Option<egui::Pos2> {
    if response.dragged() {
        response.interact_pointer_pos()
    } else if response.drag_stopped() {
        ui.input(|i| i.pointer.latest_pos())
    } else {
        None
    }
}

/// A light's marker: a disc of its colour, ringed in white (amber when selected).
fn draw_marker(painter: &egui::Painter, at: egui::Pos2, light: &Light, selected: bool, hovered: bool) {
    let peak = light.color.max_element().max(1e-6);
    let c = (light.color / peak).clamp(Vec3::ZERO, Vec3::ONE);
    let fill = egui::Color32::from(egui::Rgba::from_rgb(c.x, c.y, c.z));
    let ring = if selected {
        egui::Stroke::new(2.5, egui::Color32::from_rgb(255, 190, 60))
    } else if hovered {
        egui::Stroke::new(2.0, egui::Color32::WHITE)
    } else {
        egui::Stroke::new(1.5, egui::Color32::from_white_alpha(200))
    };
    painter.circle_filled(at, MARKER_PX + 2.0, egui::Color32::from_black_alpha(120));
    painter.circle(at, MARKER_PX, fill, ring);
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::Camera;

    fn view() -> View {
        View {
            camera: Camera {
                position: Vec3::new(0.0, 2.0, 8.0),
                forward: Vec3::new(0.0, -0.25, -1.0).normalize(),
                up: Vec3::Y,
                yfov_rad: 45f32.to_radians(),
                znear: 0.01,
                zfar: None,
            },
            width_px: 800,
            height_px: 500,
        }
    }

    #[test]
    fn an_axis_drag_follows_the_pointer_along_the_axis_image() {
        let view = view();
        let p = Vec3::new(0.5, 1.0, 0.0);
        let screen = view.project(p).unwrap();
        for axis in [Vec3::X, Vec3::Y] {
            let target = p + axis * 0.3;
            let delta = view.project(target).unwrap() - screen;
            let moved = moved_along_axis(&view, p, axis, delta);
            // Perspective makes screen length slightly non-linear along the axis: close.
            assert!(moved.distance(target) < 0.01, "{axis}: {moved} vs {target}");
            let sideways = Vec2::new(-delta.y, delta.x);
            assert!(moved_along_axis(&view, p, axis, sideways).distance(p) < 1e-3);
        }
    }

    #[test]
    fn the_view_plane_point_under_a_pixel_projects_back_to_it() {
        let view = view();
        let anchor = Vec3::new(-1.0, 0.5, -2.0);
        let pixel = Vec2::new(250.0, 320.0);
        let p = on_view_plane(&view, pixel, anchor).expect("in front");
        assert!(view.project(p).unwrap().distance(pixel) < 0.05);
        assert!(
            (p - anchor).dot(view.camera.forward).abs() < 1e-4,
            "on the plane through the anchor"
        );
    }

    #[test]
    fn the_sun_under_the_pointer_lies_on_its_sphere() {
        let view = view();
        let (pivot, radius) = (Vec3::ZERO, 3.0);
        for pixel in [Vec2::new(400.0, 250.0), Vec2::new(430.0, 100.0), Vec2::new(5.0, 5.0)] {
            let p = on_sphere(&view, pixel, pivot, radius).expect("a point");
            assert!((p.distance(pivot) - radius).abs() < 1e-4, "{pixel}: {p}");
        }
        let direction = Vec3::new(0.3, -0.8, 0.2).normalize();
        let sun = sun_position(pivot, radius, direction);
        assert!(((pivot - sun).normalize() - direction).length() < 1e-6);
    }
}
