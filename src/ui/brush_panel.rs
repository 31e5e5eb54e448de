//! The inspector's Painting section and the tool bar: tool, brush, selection and
//! modification strategies with every parameter, ranking, solve mode, constraints, and
//! the bake (progress, ETA, cancel).

use super::painting::{Painting, Tool};
use crate::paint::{BrushKind, Falloff, ModificationStrategy, Ranking, SelectionStrategy, SolveMode};

/// What the section asks the app to do.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum PaintAction {
    StartBake,
    Undo,
    Redo,
}

/// The tool buttons (also B, N, C and Escape for navigate).
pub fn tool_bar(ui: &mut egui::Ui, tool: &mut Tool) {
    ui.horizontal(|ui| {
        ui.selectable_value(tool, Tool::Navigate, "Navigate (Esc)");
        ui.selectable_value(tool, Tool::Brush(BrushKind::Positive), "Brighten (B)");
        ui.selectable_value(tool, Tool::Brush(BrushKind::Negative), "Darken (N)");
        ui.selectable_value(tool, Tool::Brush(BrushKind::Constraint), "Keep (C)");
    });
}

/// The Painting section: brush, strategies, undo and redo, the transfer and the bake.
/// `history` says whether there is something to undo and to redo (strokes and light edits).
pub fn painting_section(
    ui: &mut egui::Ui,
    painting: &mut Painting,
    scene: &crate::scene::Scene,
    history: (bool, bool),
) -> Option<PaintAction> {
    let mut action = None;
    let brush = &mut painting.brush;
    ui.add(egui::Slider::new(&mut brush.radius_px, 2.0..=200.0).text("radius (px)"));
    ui.horizontal(|ui| {
        ui.label("falloff");
        ui.selectable_value(&mut brush.falloff, Falloff::Smooth, "smooth");
        ui.selectable_value(&mut brush.falloff, Falloff::Hard, "hard");
    });
    ui.add(egui::Slider::new(&mut brush.strength, 0.05..=1.0).text("strength"));
    let settings = &mut painting.settings;
    let target_speed = (brush.target_luminance_nits * 0.01).max(0.001);
    let target = egui::DragValue::new(&mut brush.target_luminance_nits)
        .range(0.0..=1.0e6)
        .speed(target_speed)
        .suffix(" cd/m²");
    ui.add_enabled_ui(settings.modification.uses_target(), |ui| {
        ui.horizontal(|ui| {
            ui.label("target");
            ui.add(target);
        });
    });
    selection_ui(ui, &mut settings.selection);
    modification_ui(ui, &mut settings.modification);
    egui::ComboBox::from_label("rank lights by")
        .selected_text(match settings.ranking {
            Ranking::Received => "light received",
            Ranking::Transfer => "transfer (finds lights that are off)",
        })
        .show_ui(ui, |ui| {
            ui.selectable_value(&mut settings.ranking, Ranking::Received, "light received");
            ui.selectable_value(
                &mut settings.ranking,
                Ranking::Transfer,
                "transfer (finds lights that are off)",
            );
        });
    ui.horizontal(|ui| {
        ui.selectable_value(&mut settings.solve, SolveMode::Additive, "additive");
        ui.selectable_value(&mut settings.solve, SolveMode::Global, "solve all strokes together");
    });
    ui.add(egui::Slider::new(&mut settings.constraint_penalty, 0.0..=100.0).text("constraint penalty λ"));
    ui.add(
        egui::Slider::new(&mut settings.constraint_tolerance, 0.0..=0.5)
            .text("constraint tolerance")
            .custom_formatter(|v, _| format!("{:.0} %", 100.0 * v)),
    );
    ui.horizontal(|ui| {
        if ui.add_enabled(history.0, egui::Button::new("Undo")).clicked() {
            action = Some(PaintAction::Undo);
        }
        if ui.add_enabled(history.1, egui::Button::new("Redo")).clicked() {
            action = Some(PaintAction::Redo);
        }
    });
    if let Some(report) = &painting.last_report {
        ui.label(&report.message);
    }
    ui.separator();
    ui.label(format!("Transfer: {}", painting.transfer_label(scene)));
    match &painting.bake {
        Some(job) => {
            let eta = job.eta().map_or_else(String::new, |eta| {
                format!(", about {:.0} s left", eta.as_secs_f32().ceil())
            });
            ui.add(egui::ProgressBar::new(job.fraction()).text(format!("baking {:.0} %{eta}", 100.0 * job.fraction())));
            if ui.button("Cancel bake").clicked() {
                job.cancel();
            }
            ui.ctx().request_repaint_after(std::time::Duration::from_millis(200));
        }
        None => {
            ui.horizontal(|ui| {
                ui.label("samples");
                ui.add(egui::DragValue::new(&mut painting.bake_settings.light_samples).range(1..=1024))
                    .on_hover_text("emitter samples per extended light and vertex");
                ui.label("bounces");
                ui.add(egui::DragValue::new(&mut painting.bake_settings.bounces).range(0..=8))
                    .on_hover_text("bounces of indirect light (diffuse and glossy)");
            });
            let mut half = painting.bake_settings.precision == crate::bake::Precision::F16;
            if ui
                .checkbox(&mut half, "half-precision maps")
                .on_hover_text("half the memory, three significant digits")
                .changed()
            {
                painting.bake_settings.precision = if half {
                    crate::bake::Precision::F16
                } else {
                    crate::bake::Precision::F32
                };
            }
            if ui.button("Bake importance maps").clicked() {
                action = Some(PaintAction::StartBake);
            }
        }
    }
    action
}

fn selection_ui(ui: &mut egui::Ui, selection: &mut SelectionStrategy) {
    let share = match *selection {
        SelectionStrategy::Histogram { share } => share,
        _ => 0.5,
    };
    egui::ComboBox::from_label("selection")
        .selected_text(selection.label())
        .show_ui(ui, |ui| {
            ui.selectable_value(selection, SelectionStrategy::MostImportant, "most important");
            ui.selectable_value(selection, SelectionStrategy::Histogram { share }, "histogram");
            ui.selectable_value(selection, SelectionStrategy::RussianRoulette, "Russian roulette");
        });
    if let SelectionStrategy::Histogram { share } = selection {
        ui.add(egui::Slider::new(share, 0.05..=1.0).text("share τ"));
    }
}

fn modification_ui(ui: &mut egui::Ui, modification: &mut ModificationStrategy) {
    egui::ComboBox::from_label("modification")
        .selected_text(modification.label())
        .show_ui(ui, |ui| {
            let choices = [
                ModificationStrategy::Constant { amount: 1.0 },
                ModificationStrategy::Double { factor: 2.0 },
                ModificationStrategy::Direct,
                ModificationStrategy::FractionOfDirect { fraction: 0.5 },
            ];
            for choice in choices {
                let same_kind = std::mem::discriminant(&choice) == std::mem::discriminant(modification);
                if ui.selectable_label(same_kind, choice.label()).clicked() && !same_kind {
                    *modification = choice;
                }
            }
        });
    match modification {
        ModificationStrategy::Constant { amount } => {
            let speed = (*amount * 0.01).max(1e-3);
            ui.add(egui::DragValue::new(amount).range(1e-4..=1e6).speed(speed).prefix("± "));
        }
        ModificationStrategy::Double { factor } => {
            ui.add(egui::Slider::new(factor, 1.05..=8.0).text("factor"));
        }
        ModificationStrategy::FractionOfDirect { fraction } => {
            ui.add(egui::Slider::new(fraction, 0.01..=1.0).text("fraction"));
        }
        ModificationStrategy::Direct => {}
    }
}
