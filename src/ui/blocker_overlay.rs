//! The blocker overlay: every shadow sphere drawn over the viewport as the outline of its
//! silhouette (a disc blocker as its rim), so an artist can see what casts the soft shadows and how well the sphere
//! fit follows each mesh; and, at each shown mesh that has no spheres, a label saying so
//! and why (its shadows then come from the shadow maps alone); and how many blockers a
//! surface point sees on average.

use super::viewport::screen_point;
use crate::blockers::Sphere;
use crate::paint::View;

/// Radius in pixels of the silhouette of `sphere` seen by `view`, at its centre's depth
/// (exact for a sphere on the view axis, a close estimate elsewhere); None behind the eye.
pub fn silhouette_radius_px(view: &View, sphere: &Sphere) -> Option<f32> {
    let camera = &view.camera;
    let center = sphere.center;
    let depth = (center - camera.position).dot(camera.forward);
    if depth <= sphere.radius_m.max(camera.znear) {
        return None;
    }
    // A sphere of radius r at distance d subtends a half-angle asin(r/d).
    let distance = (center - camera.position).length();
    let half_angle = (sphere.radius_m / distance).clamp(0.0, 1.0).asin();
    let pixels_per_tan = view.height_px as f32 / (2.0 * (0.5 * camera.yfov_rad).tan());
    Some(half_angle.tan() * pixels_per_tan)
}

/// Draws the outline of every sphere of `spheres` over `rect`.
pub fn draw_blockers(painter: &egui::Painter, rect: egui::Rect, view: &View, spheres: &[Sphere]) {
    let stroke = egui::Stroke::new(1.0, egui::Color32::from_rgba_unmultiplied(90, 220, 255, 150));
    for sphere in spheres {
        if sphere.is_disc() {
            // A disc's rim, projected point by point.
            let (u, v) = sphere.disc_normal.any_orthonormal_pair();
            let rim: Option<Vec<egui::Pos2>> = (0..32)
                .map(|k| {
                    let angle = k as f32 * std::f32::consts::TAU / 32.0;
                    let at = sphere.center + sphere.radius_m * (angle.cos() * u + angle.sin() * v);
                    screen_point(view, rect, at)
                })
                .collect();
            if let Some(rim) = rim {
                painter.add(egui::Shape::closed_line(rim, stroke));
            }
            continue;
        }
        let center = screen_point(view, rect, sphere.center);
        let (Some(center), Some(radius)) = (center, silhouette_radius_px(view, sphere)) else {
            continue;
        };
        painter.circle_stroke(center, radius, stroke);
    }
}

/// Receivers the overlay's mean blocker counts are taken over: fewer with more blockers,
/// so working them out takes at most about this many receiver–blocker tests.
const OVERLAY_TESTS: usize = 200_000;

/// What the summary was worked out from: the blockers, the reach threshold's bits, the
/// hidden objects and the meshes' vertex counts.
type SummaryInputs = (Vec<Sphere>, u32, Vec<usize>, Vec<usize>);

/// The overlay's summary line — how many blockers are shown and what the SH path's walk of
/// them costs and finds per surface point (`shading::blocker_reach`), averaged over the
/// shown meshes' vertices — kept with what it was worked out from, so that it is worked out
/// again only when one of those changes, not every frame.
#[derive(Default)]
pub struct BlockerSummary {
    last: Option<(SummaryInputs, String)>,
}

impl BlockerSummary {
    /// The line for `spheres` shown over `scene` less `hidden` under `shadows`.
    fn text(
        &mut self,
        spheres: &[Sphere],
        (scene, hidden): (&crate::scene::Scene, &std::collections::BTreeSet<usize>),
        shadows: &crate::shading::ShadowSettings,
    ) -> &str {
        let threshold = shadows.min_cap_ratio.to_bits();
        let hidden_list: Vec<usize> = hidden.iter().copied().collect();
        let vertex_counts: Vec<usize> = scene.objects.iter().map(|o| o.positions.len()).collect();
        let current = matches!(
            &self.last,
            Some(((seen, seen_threshold, seen_hidden, seen_counts), _))
                if seen.as_slice() == spheres
                    && (*seen_threshold, seen_hidden, seen_counts) == (threshold, &hidden_list, &vertex_counts)
        );
        if !current {
            let receivers = (OVERLAY_TESTS / spheres.len().max(1)).clamp(16, 2000);
            let reach =
                crate::shading::blocker_reach::mean_blockers_in_reach(shadows, spheres, scene, hidden, receivers);
            let text = match reach {
                Some(mean) if !spheres.is_empty() => format!("{} blockers: {}", spheres.len(), mean.in_words()),
                _ => format!("{} blockers", spheres.len()),
            };
            self.last = Some(((spheres.to_vec(), threshold, hidden_list, vertex_counts), text));
        }
        self.last.as_ref().map_or("", |(_, text)| text.as_str())
    }
}

/// Says at the viewport's top-left the line of `summary` for `spheres` (see
/// [`BlockerSummary`]).
pub fn draw_blocker_summary(
    painter: &egui::Painter,
    rect: egui::Rect,
    summary: &mut BlockerSummary,
    spheres: &[Sphere],
    shown: (&crate::scene::Scene, &std::collections::BTreeSet<usize>),
    shadows: &crate::shading::ShadowSettings,
) {
    let text = summary.text(spheres, shown, shadows).to_string();
    let colour = egui::Color32::from_rgba_unmultiplied(90, 220, 255, 220);
    let at = rect.left_top() + egui::vec2(8.0, 8.0);
    painter.text(
        at,
        egui::Align2::LEFT_TOP,
        text,
        egui::FontId::proportional(12.0),
        colour,
    );
}

/// Labels each shown object of `scene` that `blockers` gave no spheres with the reason,
/// at its bounds' centre: such a mesh casts no soft (SH) shadow, only the shadow maps'.
pub fn draw_meshes_without_spheres(
    painter: &egui::Painter,
    rect: egui::Rect,
    view: &View,
    scene: &crate::scene::Scene,
    blockers: &crate::blockers::SceneBlockers,
    hidden: &std::collections::BTreeSet<usize>,
) {
    let colour = egui::Color32::from_rgba_unmultiplied(90, 220, 255, 200);
    let font = egui::FontId::proportional(11.0);
    for (index, (object, set)) in scene.objects.iter().zip(&blockers.per_object).enumerate() {
        let Some(reason) = set.skipped.as_deref().filter(|_| !hidden.contains(&index)) else {
            continue;
        };
        let Some(at) = super::viewport::screen_point(view, rect, object.bounds().center()) else {
            continue;
        };
        if rect.contains(at) {
            let text = format!("{}: no soft-shadow spheres ({reason})", object.name);
            painter.text(at, egui::Align2::CENTER_CENTER, text, font.clone(), colour);
        }
    }
}

#[cfg(test)]
mod tests {
    use glam::Vec3;

    use super::*;
    use crate::scene::Camera;

    #[test]
    fn a_sphere_on_the_axis_spans_its_projected_diameter() {
        let view = View {
            camera: Camera {
                position: Vec3::ZERO,
                forward: Vec3::NEG_Z,
                up: Vec3::Y,
                yfov_rad: 60f32.to_radians(),
                znear: 0.01,
                zfar: None,
            },
            width_px: 400,
            height_px: 300,
        };
        let sphere = Sphere {
            center: Vec3::new(0.0, 0.0, -5.0),
            radius_m: 1.0,
            disc_normal: glam::Vec3::ZERO,
        };
        let radius = silhouette_radius_px(&view, &sphere).expect("in front");
        // The tangent ray's direction (cos, sin) of the half-angle reaches the image plane
        // at the point a world point on that ray projects to.
        let half_angle = (1.0f32 / 5.0).asin();
        let tangent_point = Vec3::new(half_angle.sin(), 0.0, -half_angle.cos()) * 4.0;
        let edge = view.project(tangent_point).expect("in front");
        assert!((edge.x - 200.0 - radius).abs() < 0.01, "{} vs {radius}", edge.x - 200.0);
        let behind = Sphere {
            center: Vec3::new(0.0, 0.0, 5.0),
            radius_m: 1.0,
            disc_normal: glam::Vec3::ZERO,
        };
        assert!(silhouette_radius_px(&view, &behind).is_none());
    }
}
