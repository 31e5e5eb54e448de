//! The inspector's "Shadows" section: on/off, SH order, exponentiation method, ε, and the
//! sphere blockers fitted to the scene's meshes (count and fit per object).

use crate::blockers::SceneBlockers;
use crate::render::ShadowSettings;
use crate::scene::Scene;
use crate::sh::ExpMethod;

/// What the user changed in the section this frame.
#[derive(Debug, Default, Clone, Copy, PartialEq)]
pub struct ShadowEdit {
    pub settings_changed: bool,
}

/// Draws the section; edits `settings` and `enabled` in place.
pub fn shadow_section(
    ui: &mut egui::Ui,
    settings: &mut ShadowSettings,
    enabled: &mut bool,
    blockers: &SceneBlockers,
    scene: &Scene,
) -> ShadowEdit {
    let mut changed = ui.checkbox(enabled, "log-SH soft shadows").changed();
    ui.add_enabled_ui(*enabled, |ui| {
        egui::Grid::new("shadow settings").num_columns(2).show(ui, |ui| {
            ui.label("SH order");
            changed |= ui
                .add(egui::Slider::new(
                    &mut settings.order,
                    2..=crate::sh::MAX_REALTIME_ORDER,
                ))
                .on_hover_text("Bands of the visibility SH: higher is sharper and slower (n² coefficients).")
                .changed();
            ui.end_row();
            ui.label("ε (blocked)");
            changed |= ui
                .add(egui::Slider::new(&mut settings.epsilon, 0.01..=0.5).logarithmic(true))
                .on_hover_text("Log-visibility of a blocked direction is ln ε; 0.1 is the measured sweet spot.")
                .changed();
            ui.end_row();
            changed |= ui
                .checkbox(&mut settings.ratio_attenuation, "ratio attenuation r/d")
                .changed();
            ui.end_row();
        });
        egui::ComboBox::from_label("exponentiation")
            .selected_text(method_label(settings.exp))
            .show_ui(ui, |ui| {
                for method in [ExpMethod::Dc, ExpMethod::Ol, ExpMethod::Hyb, ExpMethod::Ps(8)] {
                    changed |= ui
                        .selectable_value(&mut settings.exp, method, method_label(method))
                        .changed();
                }
            });
        ui.label(format!("{} sphere blockers", blockers.sphere_count()));
        egui::CollapsingHeader::new("blocker fit").show(ui, |ui| {
            for line in blockers.report(scene) {
                ui.label(line);
            }
        });
    });
    ShadowEdit {
        settings_changed: changed,
    }
}

fn method_label(method: ExpMethod) -> String {
    match method {
        ExpMethod::Dc => "DC (fastest)".into(),
        ExpMethod::Ol => "optimal linear".into(),
        ExpMethod::Hyb => "hybrid (default)".into(),
        ExpMethod::Ps(terms) => format!("power series ({terms} terms)"),
        ExpMethod::Reference => "reference (CPU)".into(),
    }
}
