//! The inspector's Painting section and the tool bar: tool, brush, selection and
//! modification strategies with every parameter, ranking, solve mode, constraints, and
//! the bake (progress, ETA, cancel). Every control says in plain words what it does and
//! has a one-line tooltip; the research names (Rozon 2009) are in the tooltips and in
//! docs/strokes.md, the long form.

use crate::paint::{BrushKind, Falloff, ModificationStrategy, Ranking, SelectionStrategy, SolveMode};
use crate::session::{Painting, Tool};

/// What the section asks the app to do.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum PaintAction {
    StartBake,
    Undo,
    Redo,
}

/// The tool buttons (also B, N, C, U and Escape for navigate).
pub fn tool_bar(ui: &mut egui::Ui, tool: &mut Tool) {
    ui.horizontal(|ui| {
        ui.selectable_value(tool, Tool::Navigate, "Navigate (Esc)")
            .on_hover_text("Orbit (drag), pan (right drag), zoom (wheel) and select lights and objects");
        ui.selectable_value(tool, Tool::Brush(BrushKind::Positive), "Brighten (B)")
            .on_hover_text("Paint where the picture should be brighter: the lights reaching it go up");
        ui.selectable_value(tool, Tool::Brush(BrushKind::Negative), "Darken (N)")
            .on_hover_text("Paint where the picture should be darker: the lights reaching it go down");
        ui.selectable_value(tool, Tool::Brush(BrushKind::Constraint), "Keep (C)")
            .on_hover_text("Paint what should stay as it is: later strokes avoid the lights that reach it");
        ui.selectable_value(tool, Tool::Brush(BrushKind::Release), "Release (U)")
            .on_hover_text("Paint over Keep areas (the teal dots) to let them go: later strokes may change them again");
    });
}

/// The Painting section: brush, strategies, undo and redo, the transfer and the bake.
/// `history` says whether there is something to undo and to redo (strokes and light edits).
pub fn painting_section(
    ui: &mut egui::Ui,
    painting: &mut Painting,
    document: &crate::project::Document,
    history: (bool, bool),
) -> Option<PaintAction> {
    let mut action = None;
    let brush = &mut painting.brush;
    ui.add(egui::Slider::new(&mut brush.radius_px, 2.0..=200.0).text("radius (px)"))
        .on_hover_text("The brush's size on screen, in pixels");
    ui.horizontal(|ui| {
        ui.label("edge");
        ui.selectable_value(&mut brush.falloff, Falloff::Smooth, "soft")
            .on_hover_text("Paints less toward the brush's rim");
        ui.selectable_value(&mut brush.falloff, Falloff::Hard, "hard")
            .on_hover_text("Paints the whole disc alike");
    });
    ui.add(egui::Slider::new(&mut brush.strength, 0.05..=1.0).text("strength"))
        .on_hover_text("How much of each stroke's change is applied (1: all of it)");
    let settings = &mut painting.settings;
    let target_speed = (brush.target_luminance_nits * 0.01).max(0.001);
    let target = egui::DragValue::new(&mut brush.target_luminance_nits)
        .range(0.0..=1.0e6)
        .speed(target_speed)
        .suffix(" cd/m²");
    ui.add_enabled_ui(settings.modification.uses_target(), |ui| {
        ui.horizontal(|ui| {
            ui.label("target");
            ui.add(target).on_hover_text(
                "The luminance the painted area should reach (for 'set to the target' and 'toward the target')",
            );
        });
    });
    selection_ui(ui, &mut settings.selection);
    modification_ui(ui, &mut settings.modification);
    egui::ComboBox::from_label("judge lights by")
        .selected_text(match settings.ranking {
            Ranking::Received => "the light they give here",
            Ranking::Transfer => "how well they reach here",
        })
        .show_ui(ui, |ui| {
            ui.selectable_value(&mut settings.ranking, Ranking::Received, "the light they give here")
                .on_hover_text("A light counts by how much light it puts on the painted area now");
            ui.selectable_value(&mut settings.ranking, Ranking::Transfer, "how well they reach here")
                .on_hover_text(
                    "A light counts by how much more it reaches here than the rest of the scene, whatever its unit: finds lights that are off",
                );
        })
        .response
        .on_hover_text("How the lights a stroke may change are ranked (importance: received light or transfer)");
    ui.horizontal(|ui| {
        ui.selectable_value(&mut settings.solve, SolveMode::Additive, "one stroke at a time")
            .on_hover_text("Each stroke changes the lights from where the last one left them");
        ui.selectable_value(&mut settings.solve, SolveMode::Global, "all strokes together")
            .on_hover_text("Each stroke re-solves the lights so every stroke so far holds at once (least squares)");
    });
    ui.add(egui::Slider::new(&mut settings.constraint_penalty, 0.0..=100.0).text("keep: avoid lights"))
        .on_hover_text("How strongly strokes avoid the lights that reach Keep areas (penalty λ; 0: not at all)");
    ui.add(
        egui::Slider::new(&mut settings.constraint_tolerance, 0.0..=0.5)
            .text("keep: allowed drift")
            .custom_formatter(|v, _| format!("{:.0} %", 100.0 * v)),
    )
    .on_hover_text("How far a Keep area's light may change before a stroke is cut short");
    ui.horizontal(|ui| {
        if ui
            .add_enabled(history.0, egui::Button::new("Undo"))
            .on_hover_text("Undo the last stroke or light edit (Ctrl+Z)")
            .clicked()
        {
            action = Some(PaintAction::Undo);
        }
        if ui
            .add_enabled(history.1, egui::Button::new("Redo"))
            .on_hover_text("Redo what was undone (Ctrl+Shift+Z)")
            .clicked()
        {
            action = Some(PaintAction::Redo);
        }
    });
    if let Some(report) = &painting.last_report {
        ui.label(&report.message);
    }
    ui.separator();
    ui.label(format!(
        "Transfer: {}",
        painting.transfer_label(&document.scene, &document.settings)
    ));
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
                .on_hover_text("half the memory of single precision, three significant digits (the default; unticked: single precision)")
                .changed()
            {
                painting.bake_settings.precision = if half {
                    crate::bake::Precision::F16
                } else {
                    crate::bake::Precision::F32
                };
            }
            if ui
                .button("Bake importance maps")
                .on_hover_text("Trace which lights reach each vertex, bounces included, so strokes judge lights by the real light transport (in the background)")
                .clicked()
            {
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
    egui::ComboBox::from_label("lights changed")
        .selected_text(selection_words(selection))
        .show_ui(ui, |ui| {
            ui.selectable_value(selection, SelectionStrategy::MostImportant, "the strongest")
                .on_hover_text("Only the light that matters most here (most important)");
            ui.selectable_value(selection, SelectionStrategy::Histogram { share }, "the few strongest")
                .on_hover_text("The fewest lights that together give a share of the light here (histogram)");
            ui.selectable_value(selection, SelectionStrategy::RussianRoulette, "one, drawn by strength")
                .on_hover_text("One light drawn at random, the stronger the likelier (Russian roulette)");
        })
        .response
        .on_hover_text("Which of the lights reaching the painted area a stroke changes");
    if let SelectionStrategy::Histogram { share } = selection {
        ui.add(egui::Slider::new(share, 0.05..=1.0).text("share of the light"))
            .on_hover_text("Lights are taken, strongest first, until they give this share of the light here (τ)");
    }
}

fn modification_ui(ui: &mut egui::Ui, modification: &mut ModificationStrategy) {
    egui::ComboBox::from_label("how they change")
        .selected_text(modification_words(modification))
        .show_ui(ui, |ui| {
            let choices = [
                ModificationStrategy::Constant { amount: 1.0 },
                ModificationStrategy::Double { factor: 2.0 },
                ModificationStrategy::Direct,
                ModificationStrategy::FractionOfDirect { fraction: 0.5 },
            ];
            for choice in choices {
                let same_kind = std::mem::discriminant(&choice) == std::mem::discriminant(modification);
                let tip = match choice {
                    ModificationStrategy::Constant { .. } => {
                        "Add (or take) a fixed amount of each light's unit (constant)"
                    }
                    ModificationStrategy::Double { .. } => "Multiply (or divide) the lights by a factor (double)",
                    ModificationStrategy::Direct => {
                        "Change the lights just enough that the area reaches the target luminance (direct)"
                    }
                    ModificationStrategy::FractionOfDirect { .. } => {
                        "Go part of the way toward the target luminance (fraction of direct)"
                    }
                };
                if ui
                    .selectable_label(same_kind, modification_words(&choice))
                    .on_hover_text(tip)
                    .clicked()
                    && !same_kind
                {
                    *modification = choice;
                }
            }
        })
        .response
        .on_hover_text("How a stroke changes the lights it picked");
    match modification {
        ModificationStrategy::Constant { amount } => {
            let speed = (*amount * 0.01).max(1e-3);
            ui.add(egui::DragValue::new(amount).range(1e-4..=1e6).speed(speed).prefix("± "))
                .on_hover_text("Added by Brighten, taken by Darken, in each light's own unit");
        }
        ModificationStrategy::Double { factor } => {
            ui.add(egui::Slider::new(factor, 1.05..=8.0).text("factor"))
                .on_hover_text("Brighten multiplies by it, Darken divides");
        }
        ModificationStrategy::FractionOfDirect { fraction } => {
            ui.add(egui::Slider::new(fraction, 0.01..=1.0).text("of the way"))
                .on_hover_text("How far toward the target each stroke goes (1: all the way)");
        }
        ModificationStrategy::Direct => {}
    }
}

/// The selection strategy in the panel's words.
fn selection_words(selection: &SelectionStrategy) -> &'static str {
    match selection {
        SelectionStrategy::MostImportant => "the strongest",
        SelectionStrategy::Histogram { .. } => "the few strongest",
        SelectionStrategy::RussianRoulette => "one, drawn by strength",
    }
}

/// The modification strategy in the panel's words.
fn modification_words(modification: &ModificationStrategy) -> &'static str {
    match modification {
        ModificationStrategy::Constant { .. } => "add an amount",
        ModificationStrategy::Double { .. } => "multiply",
        ModificationStrategy::Direct => "set to the target",
        ModificationStrategy::FractionOfDirect { .. } => "toward the target",
    }
}
