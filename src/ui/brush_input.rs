//! The brush in the viewport: collects the points of a left drag (a click is a one-dab
//! stroke), hands the stroke over on release, and draws the brush outline and the stroke
//! so far.

use egui::{Pos2, Vec2};

use crate::session::ScreenStroke;

#[derive(Debug, Default)]
pub struct BrushInput {
    points: Vec<Vec2>,
}

impl BrushInput {
    /// Follows the pointer on `response` (the viewport's); the stroke on release, in the
    /// viewport's points.
    pub fn update(&mut self, ui: &egui::Ui, response: &egui::Response) -> Option<ScreenStroke> {
        let shift = ui.input(|i| i.modifiers.shift);
        let origin = response.rect.min;
        let pointer = response.interact_pointer_pos().or(response.hover_pos());
        if response.dragged_by(egui::PointerButton::Primary)
            && !shift
            && let Some(p) = pointer
        {
            let point = p - origin;
            if self.points.last() != Some(&point) {
                self.points.push(point);
            }
        }
        let released = response.drag_stopped_by(egui::PointerButton::Primary);
        let clicked = response.clicked_by(egui::PointerButton::Primary) && !shift;
        if clicked && self.points.is_empty() {
            self.points.extend(pointer.map(|p| p - origin));
        }
        if (released || clicked) && !self.points.is_empty() {
            let glam = |v: Vec2| glam::Vec2::new(v.x, v.y);
            return Some(ScreenStroke {
                points_px: std::mem::take(&mut self.points).into_iter().map(glam).collect(),
                viewport_size_px: glam(response.rect.size()),
            });
        }
        None
    }

    /// The brush outline (radius in points) under the pointer and the stroke so far.
    pub fn draw(&self, ui: &egui::Ui, response: &egui::Response, radius: f32) {
        let painter = ui.painter_at(response.rect);
        let origin = response.rect.min;
        let light = egui::Stroke::new(1.5, egui::Color32::from_rgba_unmultiplied(255, 214, 120, 220));
        let shadow = egui::Stroke::new(1.0, egui::Color32::from_black_alpha(140));
        if self.points.len() > 1 {
            let points: Vec<Pos2> = self.points.iter().map(|p| origin + *p).collect();
            painter.add(egui::Shape::line(points, light));
        }
        if let Some(p) = response.hover_pos() {
            painter.circle_stroke(p, radius + 1.5, shadow);
            painter.circle_stroke(p, radius, light);
        }
    }
}
