//! The inspector (right panel): the selection (a light's editor or an object's summary),
//! painting, every light's intensity and colour, render settings, shadows, the
//! environment and the terrain. Each section edits the open document; the app applies
//! the consequences (uploads, refits, re-bakes).

use super::EditorApp;
use super::brush_panel::{PaintAction, painting_section};
use super::light_inspector::{LightEdit, light_inspector};
use super::outliner::Selection;
use super::shadow_panel::shadow_section;
use super::terrain_panel::terrain_section;
use crate::project::Document;
use crate::project::sphere_cache;

impl EditorApp {
    pub(super) fn inspector(&mut self, ui: &mut egui::Ui) {
        let mut action = None;
        let mut light_edit = LightEdit::default();
        let mut delete = None;
        egui::Panel::right("inspector").default_size(300.0).show(ui, |ui| {
            egui::ScrollArea::vertical().show(ui, |ui| {
                (light_edit, delete) = self.selection_section(ui);
                action = self.painting_and_lights(ui, &mut light_edit);
                self.render_sections(ui);
                self.terrain_section(ui);
            });
        });
        if light_edit.changed {
            self.lights_edited(light_edit.moved);
        }
        if let Some(index) = delete {
            self.delete_light(index);
        }
        match action {
            Some(PaintAction::Undo) => self.undo(),
            Some(PaintAction::Redo) => self.redo(),
            Some(PaintAction::StartBake) => {
                if let Some(session) = &mut self.session {
                    let document = &session.document;
                    session
                        .painting
                        .start_bake(&document.scene, document.project_path.as_deref());
                }
            }
            None => {}
        }
    }

    /// The selected light's editor or the selected object's summary; the light edit, and
    /// the light to delete if its Delete button was clicked.
    fn selection_section(&mut self, ui: &mut egui::Ui) -> (LightEdit, Option<usize>) {
        let mut delete = None;
        let Some(document) = self.session.as_mut().map(|s| &mut s.document) else {
            return (LightEdit::default(), delete);
        };
        let pivot = self.viewport.as_ref().map_or(glam::Vec3::ZERO, |v| v.orbit.target);
        match self.selection {
            Some(Selection::Light(index)) if index < document.scene.lights.len() => {
                let (lights, shadows) = (&document.scene.lights, &document.settings.shadows);
                let paths = match &self.viewport {
                    Some(viewport) => viewport.light_paths_at(lights, pivot, shadows),
                    None => {
                        let context = crate::shading::LightPathContext::of_bounds(&document.scene.bounds());
                        crate::shading::light_paths_at(lights, pivot, shadows, &context)
                    }
                };
                let (path, angle_deg) = paths[index];
                // The choice is made at the scene's centre: its size there says why.
                let centre = document.scene.bounds().center();
                let gpu_light = crate::shading::gpu_types::GpuLight::new(&lights[index]);
                let centre_deg = crate::shading::paths_and_sizes_at(&[gpu_light], centre)[0].1;
                let reason = crate::shading::path_reason(path, gpu_light.source_size > 0.0, centre_deg, shadows);
                let light = &mut document.scene.lights[index];
                ui.heading(format!("Light: {}", light.name));
                let distance = light.position.distance(pivot).max(0.1);
                let edit = light_inspector(ui, light, distance);
                ui.weak(format!(
                    "shadow: {} ({angle_deg:.1}° in radius at the view's pivot)",
                    path.words()
                ))
                .on_hover_text(reason);
                ui.weak(reason);
                ui.checkbox(&mut self.preferences.show_heat_map, "heat map of where it reaches")
                    .on_hover_text(
                        "Colours the scene by the luminance this light adds at each vertex \
                         (baked maps once baked, else the direct estimate)",
                    );
                if ui.button("Delete light").clicked() {
                    delete = Some(index);
                }
                if let Some((_, scale)) = &self.heat_map {
                    ui.weak(format!(
                        "dark blue: 0, pale yellow: {scale:.3} cd/m² (99th percentile; square-root scale)"
                    ));
                }
                ui.separator();
                (edit, delete)
            }
            Some(Selection::Object(index)) if index < document.scene.objects.len() => {
                object_summary(ui, document, &self.blockers, index);
                ui.separator();
                (LightEdit::default(), delete)
            }
            _ => {
                ui.weak("Click a light or an object (outliner or viewport) to inspect it.");
                ui.separator();
                (LightEdit::default(), delete)
            }
        }
    }

    /// The Painting section and the table of every light's intensity and colour.
    fn painting_and_lights(&mut self, ui: &mut egui::Ui, light_edit: &mut LightEdit) -> Option<PaintAction> {
        let session = self.session.as_mut()?;
        let mut action = None;
        let history = (session.can_undo(), session.can_redo());
        let (document, painting) = (&mut session.document, &mut session.painting);
        egui::CollapsingHeader::new("Painting")
            .default_open(true)
            .show(ui, |ui| action = painting_section(ui, painting, document, history));
        egui::CollapsingHeader::new("Lights").default_open(true).show(ui, |ui| {
            egui::Grid::new("lights").striped(true).num_columns(4).show(ui, |ui| {
                for (index, light) in document.scene.lights.iter_mut().enumerate() {
                    let selected = self.selection == Some(Selection::Light(index));
                    let name = ui.selectable_label(selected, &light.name);
                    if name.clicked() {
                        self.selection = Some(Selection::Light(index));
                    }
                    // Drag speed proportional to the value, so dim and bright lights
                    // both adjust smoothly.
                    let speed = (light.intensity.abs() * 0.01).max(0.001);
                    let intensity = egui::DragValue::new(&mut light.intensity)
                        .range(0.0..=1.0e7)
                        .speed(speed)
                        .suffix(format!(" {}", light.kind.intensity_unit()));
                    light_edit.changed |= ui.add(intensity).labelled_by(name.id).changed();
                    let mut color = light.color.to_array();
                    if ui.color_edit_button_rgb(&mut color).labelled_by(name.id).changed() {
                        light.color = glam::Vec3::from(color);
                        light_edit.changed = true;
                    }
                    let lock = ui
                        .toggle_value(&mut light.locked, "lock")
                        .on_hover_text(super::light_inspector::LOCK_HINT)
                        .labelled_by(name.id);
                    light_edit.changed |= lock.changed();
                    ui.end_row();
                }
            });
        });
        action
    }

    /// Render settings, shadows and the environment.
    fn render_sections(&mut self, ui: &mut egui::Ui) {
        let Some(document) = self.session.as_mut().map(|s| &mut s.document) else {
            return;
        };
        egui::CollapsingHeader::new("Render").default_open(true).show(ui, |ui| {
            self.indirect_stale |= render_settings(ui, &mut document.settings);
        });
        egui::CollapsingHeader::new("Shadows")
            .default_open(true)
            .show(ui, |ui| {
                shadow_section(ui, &mut document.settings, &self.blockers, &document.scene);
                if let Some(maps) = self.viewport.as_ref().and_then(|v| v.shadow_maps_in_words()) {
                    ui.weak(format!("shadow maps: {maps}"));
                }
                if let Some(grid) = self.viewport.as_ref().and_then(|v| v.light_grid_in_words()) {
                    ui.weak(format!("lights' grid: {grid}")).on_hover_text(
                        "Each point shades only the lights with a range or a cone that can reach its box",
                    );
                }
                ui.checkbox(&mut self.preferences.show_blockers, "show blocker spheres")
                    .on_hover_text("Outlines the spheres that stand in for the meshes as shadow casters");
            });
        // Refit once the slider is let go: a fit takes a good part of a second.
        if document.settings.blockers != self.fitted_with
            && document.settings.blockers.problems().is_empty()
            && !ui.input(|i| i.pointer.any_down())
            && let Some(viewport) = &mut self.viewport
        {
            let project = document.project_path.as_deref();
            self.blockers = sphere_cache::fit_with_cache(&document.scene, &document.settings.blockers, project);
            self.fitted_with = document.settings.blockers;
            viewport.set_blockers(&self.blockers.shown_spheres(&document.hidden_objects));
        }
        if let Some(environment) = &mut document.scene.environment {
            egui::CollapsingHeader::new("Environment")
                .default_open(true)
                .show(ui, |ui| {
                    let name = environment
                        .hdr
                        .file_name()
                        .map_or_else(String::new, |n| n.to_string_lossy().into_owned());
                    let mut changed = false;
                    ui.horizontal(|ui| {
                        ui.label(name);
                        let intensity = egui::DragValue::new(&mut environment.intensity)
                            .range(0.0..=1.0e4)
                            .speed(0.01)
                            .prefix("×");
                        changed |= ui.add(intensity).changed();
                    });
                    let half_turn = std::f32::consts::PI;
                    let rotation =
                        egui::Slider::new(&mut environment.rotation_rad, -half_turn..=half_turn).text("rotation (rad)");
                    changed |= ui.add(rotation).changed();
                    if changed && let Some(viewport) = &mut self.viewport {
                        viewport.set_environment(Some(environment));
                    }
                });
        }
    }

    fn terrain_section(&mut self, ui: &mut egui::Ui) {
        let Some(document) = self.session.as_ref().map(|s| &s.document) else {
            return;
        };
        let mut edit = None;
        egui::CollapsingHeader::new("Terrain")
            .default_open(true)
            .show(ui, |ui| {
                edit = terrain_section(ui, &document.scene, &mut self.terrain_editing);
            });
        if let Some(edit) = edit {
            self.apply_terrain_edit(edit);
        }
    }
}

/// Exposure, background, viewport resolution and baked indirect light; true if the
/// baked indirect setting changed.
fn render_settings(ui: &mut egui::Ui, settings: &mut crate::shading::RenderSettings) -> bool {
    ui.add(egui::Slider::new(&mut settings.exposure_ev, -8.0..=8.0).text("exposure (EV)"));
    ui.horizontal(|ui| {
        ui.label("background");
        ui.color_edit_button_srgb(&mut settings.background_srgb8);
    });
    ui.add(
        egui::Slider::new(&mut settings.viewport_resolution_scale, 0.25..=1.0)
            .text("viewport resolution")
            .custom_formatter(|v, _| format!("{:.0} %", 100.0 * v))
            .custom_parser(|text| {
                text.trim()
                    .trim_end_matches('%')
                    .trim()
                    .parse::<f64>()
                    .ok()
                    .map(|p| p / 100.0)
            }),
    )
    .on_hover_text("Share of the viewport's pixels shaded along each side: lower is faster.");
    let indirect_changed = ui
        .checkbox(&mut settings.baked_indirect, "baked indirect light")
        .on_hover_text(
            "Adds the light of the baked bounces once importance maps are baked \
             (Painting > Bake importance maps); it follows every intensity change.",
        )
        .changed();
    // The slider clamps typed values, but not NaN: a saved project must reopen.
    let scale = &mut settings.viewport_resolution_scale;
    *scale = if scale.is_finite() { scale.clamp(0.25, 1.0) } else { 1.0 };
    indirect_changed
}

/// Name, size, material and shadow proxy of object `index`.
fn object_summary(ui: &mut egui::Ui, document: &mut Document, blockers: &crate::blockers::SceneBlockers, index: usize) {
    ui.heading(format!("Object: {}", document.scene.objects[index].name));
    egui::Grid::new("selected object").num_columns(2).show(ui, |ui| {
        let label = ui.label("name");
        let mut name = document.scene.objects[index].name.clone();
        if ui.text_edit_singleline(&mut name).labelled_by(label.id).changed() {
            document.scene.objects[index].name = name.clone();
            document.object_names.insert(index, name);
        }
        ui.end_row();
        let object = &document.scene.objects[index];
        ui.label("vertices");
        ui.label(format!(
            "{} ({} triangles)",
            object.positions.len(),
            object.indices.len() / 3
        ));
        ui.end_row();
        let bounds = object.bounds();
        ui.label("size (m)");
        let size = bounds.max - bounds.min;
        ui.label(format!("{:.2} × {:.2} × {:.2}", size.x, size.y, size.z));
        ui.end_row();
        ui.label("shown");
        ui.label(if document.hidden_objects.contains(&index) {
            "hidden (casts no shadow)"
        } else {
            "yes"
        });
        ui.end_row();
        ui.label("shadow proxy");
        let proxy = blockers
            .per_object
            .get(index)
            .map_or_else(|| "none".to_string(), |set| set.describe());
        ui.label(proxy);
        ui.end_row();
    });
    let material = document.scene.objects[index].material;
    if let Some(material) = document.scene.materials.get(material) {
        // At the body size: the small style was about 8 px tall.
        ui.label(material.summary());
    }
}
