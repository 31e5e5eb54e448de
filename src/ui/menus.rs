//! The menu bar and the file actions behind it. Every dialog only picks a path; the
//! action itself (`request_open`, `save_to`, `export_png`, `request_new`) is a public
//! method, so tests and scripts reach it without a dialog.

use std::path::Path;

use super::unsaved_prompt::Pending;
use super::{EditorApp, file_dialog};
use crate::project::PROJECT_EXTENSION;

impl EditorApp {
    pub(super) fn menu_bar(&mut self, ui: &mut egui::Ui) {
        egui::Panel::top("menu").show(ui, |ui| {
            egui::MenuBar::new().ui(ui, |ui| {
                ui.menu_button("File", |ui| self.file_menu(ui));
                ui.menu_button("Edit", |ui| {
                    let (can_undo, can_redo) = (self.can_undo(), self.can_redo());
                    if ui.add_enabled(can_undo, egui::Button::new("Undo (Ctrl+Z)")).clicked() {
                        self.undo();
                    }
                    if ui
                        .add_enabled(can_redo, egui::Button::new("Redo (Ctrl+Shift+Z)"))
                        .clicked()
                    {
                        self.redo();
                    }
                });
                ui.menu_button("View", |ui| {
                    if ui.button("Frame selection (F)").clicked() {
                        self.frame_selection();
                    }
                    ui.separator();
                    let preferences = &mut self.preferences;
                    ui.checkbox(&mut preferences.show_outliner, "Outliner");
                    ui.checkbox(&mut preferences.show_inspector, "Inspector");
                    ui.checkbox(&mut preferences.show_light_markers, "Light markers and gizmo");
                    ui.checkbox(&mut preferences.show_heat_map, "Heat map of the selected light");
                    ui.checkbox(&mut preferences.show_blockers, "Blocker spheres");
                });
            });
        });
    }

    fn file_menu(&mut self, ui: &mut egui::Ui) {
        if ui.button("New (Ctrl+N)").clicked() {
            self.request_new();
        }
        if ui.button("Open… (Ctrl+O)").clicked() {
            self.open_dialog();
        }
        ui.add_enabled_ui(!self.preferences.recent_files.is_empty(), |ui| {
            ui.menu_button("Open Recent", |ui| {
                for path in self.preferences.recent_files.clone() {
                    let name = path
                        .file_name()
                        .map_or_else(|| path.display().to_string(), |n| n.to_string_lossy().into_owned());
                    if ui.button(name).on_hover_text(path.display().to_string()).clicked() {
                        self.request_open(&path);
                    }
                }
            });
        });
        if ui.button("Import glTF…").clicked() {
            self.import_dialog();
        }
        ui.separator();
        let open = self.session.is_some();
        if ui.add_enabled(open, egui::Button::new("Save (Ctrl+S)")).clicked() {
            self.save_document();
        }
        if ui.add_enabled(open, egui::Button::new("Save As…")).clicked() {
            self.save_as_dialog();
        }
        if ui
            .add_enabled(self.viewport.is_some(), egui::Button::new("Export render as PNG…"))
            .clicked()
        {
            self.open_export_window(ui.ctx().pixels_per_point());
        }
        ui.separator();
        if ui.button("Quit").clicked() {
            ui.ctx().send_viewport_cmd(egui::ViewportCommand::Close);
        }
    }

    /// File ▸ New: closes the document (asking to save unsaved changes first).
    pub fn request_new(&mut self) {
        if self.ready_or_ask(Pending::New) {
            self.close_document();
        }
    }

    /// Saves to the document's project file, or asks where when it has none.
    pub(super) fn save_document(&mut self) {
        match self
            .session
            .as_ref()
            .map(|s| &s.document)
            .and_then(|d| d.project_path.clone())
        {
            Some(path) => self.save_to(&path),
            None => self.save_as_dialog(),
        }
    }

    fn save_as_dialog(&mut self) {
        let Some(document) = self.session.as_ref().map(|s| &s.document) else {
            return;
        };
        let (folder, name) = file_dialog::save_as_start(document.project_path.as_deref(), &document.scene_path);
        let dialog = rfd::FileDialog::new().add_filter("lightpaint project", &[PROJECT_EXTENSION]);
        let dialog = file_dialog::start_in(dialog, &folder, &name);
        if let Some(path) = self.ask(|| dialog.save_file()) {
            self.save_to(&path);
        }
    }

    /// Runs a file dialog and returns what it chose; says in the window when no dialog
    /// could open (see [`file_dialog`]), rather than doing nothing as a cancel does.
    pub(super) fn ask(&mut self, dialog: impl FnOnce() -> Option<std::path::PathBuf>) -> Option<std::path::PathBuf> {
        if let Some(reason) = file_dialog::unavailable_here() {
            self.report_error(reason);
            return None;
        }
        let started = std::time::Instant::now();
        let picked = dialog();
        match file_dialog::outcome(picked, started.elapsed()) {
            Ok(picked) => picked,
            Err(message) => {
                self.report_error(message);
                None
            }
        }
    }

    pub(super) fn open_dialog(&mut self) {
        let extensions = [PROJECT_EXTENSION, "gltf", "glb"];
        self.pick_and_open("lightpaint project or glTF scene", &extensions);
    }

    /// A new, unsaved project on a glTF scene.
    fn import_dialog(&mut self) {
        self.pick_and_open("glTF scene", &["gltf", "glb"]);
    }

    /// Asks for a file of `extensions` and opens it (asking to save changes first).
    fn pick_and_open(&mut self, filter: &str, extensions: &[&str]) {
        let dialog = rfd::FileDialog::new().add_filter(filter, extensions);
        if let Some(path) = self.ask(|| dialog.pick_file()) {
            self.request_open(&path);
        }
    }

    /// Writes the image the viewport shows to `path` as PNG (atomically: a failed export
    /// leaves an existing file as it was).
    pub fn export_png(&mut self, path: &Path) {
        let Some(viewport) = &self.viewport else {
            return self.report_error("nothing to export: no scene is shown".to_string());
        };
        let image = match viewport.read_image() {
            Some(Ok(image)) => image,
            Some(Err(e)) => return self.report_error(format!("could not read the render back: {e}")),
            None => return self.report_error("nothing to export yet: the viewport has not drawn".to_string()),
        };
        self.write_png(path, image);
    }
}
