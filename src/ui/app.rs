use std::path::{Path, PathBuf};
use std::time::Instant;

use super::Viewport;
use super::brush_input::{BrushInput, FinishedStroke};
use super::brush_panel::{PaintAction, painting_section, tool_bar};
use super::painting::{Painting, Tool};
use super::shadow_panel::shadow_section;
use super::terrain_panel::{TerrainEdit, image_terrain, terrain_section};
use super::unsaved_prompt::{self, Answer, Pending};
use crate::blockers::{BlockerSettings, SceneBlockers, fit_scene};
use crate::paint::BrushKind;
use crate::project::{Document, PROJECT_EXTENSION, ProjectFile};
use crate::render::describe_adapter;

/// How the editor starts.
#[derive(Debug, Clone, Default)]
pub struct EditorOptions {
    /// The project or scene to open.
    pub file: PathBuf,
    /// Scripted runs (the smoke test): close the window cleanly once this file exists.
    pub close_when_file_exists: Option<PathBuf>,
    /// Leave frame timings out of the status bar, so screenshots are reproducible.
    pub hide_frame_timings: bool,
}

/// Line printed on stderr once the first frame with the scene has been drawn; scripts
/// wait for it before they look at the window.
pub const FIRST_FRAME_LINE: &str = "lightpaint: first frame drawn";

pub struct EditorApp {
    document: Option<Document>,
    /// The project as last opened or saved, to tell whether there are unsaved changes.
    saved: Option<ProjectFile>,
    viewport: Option<Viewport>,
    /// Sphere blockers fitted to the document's meshes, and the settings they were fitted with.
    blockers: SceneBlockers,
    fitted_with: BlockerSettings,
    adapter: String,
    /// The last thing worth telling the user, shown in the status bar.
    message: String,
    /// An error waiting to be acknowledged in a window.
    error: Option<String>,
    options: EditorOptions,
    last_frame: Option<Instant>,
    frame_ms: f32,
    first_frame_reported: bool,
    /// The document's painting state (None without a document).
    painting: Option<Painting>,
    brush_input: BrushInput,
    /// A close or open waiting for the answer to "save the changes?".
    pending: Option<Pending>,
    /// The window may close without asking (answered, or a scripted close).
    closing: bool,
    /// The viewport's baked indirect light no longer matches the lights, maps or setting.
    indirect_stale: bool,
    /// The terrain spec being edited in the inspector (applied when an edit is committed).
    terrain_editing: Option<crate::scene::TerrainSpec>,
}

impl EditorApp {
    pub fn new(cc: &eframe::CreationContext<'_>, options: EditorOptions) -> EditorApp {
        let adapter = cc
            .wgpu_render_state
            .as_ref()
            .map(|rs| describe_adapter(&rs.adapter.get_info()))
            .unwrap_or_else(|| "no wgpu adapter".into());
        let mut app = EditorApp {
            document: None,
            saved: None,
            viewport: None,
            blockers: SceneBlockers::default(),
            fitted_with: BlockerSettings::default(),
            adapter,
            message: String::new(),
            error: None,
            options: options.clone(),
            last_frame: None,
            frame_ms: 0.0,
            first_frame_reported: false,
            painting: None,
            brush_input: BrushInput::default(),
            pending: None,
            closing: false,
            indirect_stale: true,
            terrain_editing: None,
        };
        app.open(&options.file, cc.wgpu_render_state.as_ref());
        app
    }

    /// Opens a project or a glTF scene, replacing the current document; on failure the
    /// current document stays and the error is shown.
    pub fn open(&mut self, path: &Path, render_state: Option<&egui_wgpu::RenderState>) {
        match Document::open(path) {
            Ok(document) => {
                let name = path
                    .file_name()
                    .map_or_else(|| path.display().to_string(), |n| n.to_string_lossy().into());
                self.install(document, &format!("opened {name}"), render_state);
                self.saved = self.document.as_ref().and_then(|document| {
                    let mut saved = document.to_project_file(document.project_path.as_ref()?);
                    // A project without a camera opens on the scene's view: that view is
                    // what was saved, not a change.
                    if let Some(viewport) = &self.viewport {
                        saved.camera = Some(viewport.orbit);
                    }
                    Some(saved)
                });
            }
            Err(e) => self.report_error(e.to_string()),
        }
    }

    /// Shows scene `index` of the document's glTF file (a file can hold several): its
    /// objects and lights, with the document's settings; the stroke log starts afresh. The
    /// project file is untouched until the next save. On failure nothing changes.
    pub fn show_gltf_scene(&mut self, index: usize, render_state: Option<&egui_wgpu::RenderState>) {
        let Some(current) = &self.document else { return };
        match current.with_gltf_scene(index) {
            Ok(document) => {
                let label = document.scene.gltf_scene_label(index);
                self.install(document, &format!("showing glTF scene {label}"), render_state);
            }
            Err(e) => self.report_error(e.to_string()),
        }
    }

    /// Applies a terrain edit: the scene gets the new terrain mesh and is reinstalled (the
    /// sphere fit and the viewport follow; bake maps of the old geometry no longer apply).
    /// A height map that cannot be read is reported and changes nothing.
    pub fn apply_terrain_edit(&mut self, edit: TerrainEdit, render_state: Option<&egui_wgpu::RenderState>) {
        let Some(current) = &self.document else { return };
        let spec = match edit {
            TerrainEdit::Remove => None,
            TerrainEdit::Set(spec) => Some(spec),
            TerrainEdit::PickImage => {
                let picked = rfd::FileDialog::new()
                    .add_filter("height map", &["png", "jpg", "jpeg", "hdr"])
                    .pick_file();
                let Some(path) = picked else { return };
                let like = current.scene.terrain.as_ref().map(|t| &t.spec);
                Some(image_terrain(path, like, &current.scene))
            }
        };
        // The heights first: a map that cannot be read leaves the document as it is.
        let terrain = match spec {
            Some(spec) => {
                let directory = current
                    .project_path
                    .as_deref()
                    .and_then(Path::parent)
                    .unwrap_or(Path::new(""));
                match spec.height_field(directory) {
                    Ok(field) => Some((spec, field)),
                    Err(e) => return self.report_error(e.to_string()),
                }
            }
            None => None,
        };
        let what = if terrain.is_some() {
            "terrain updated"
        } else {
            "terrain removed"
        };
        let Some(mut document) = self.document.take() else {
            return;
        };
        document.scene.set_terrain(terrain);
        if let Some(viewport) = &self.viewport {
            document.camera = Some(viewport.orbit);
        }
        self.install(document, what, render_state);
    }

    /// Shows glTF scene `index`, first asking to save when there are unsaved changes.
    pub fn request_gltf_scene(&mut self, index: usize, render_state: Option<&egui_wgpu::RenderState>) {
        if self.has_unsaved_changes() && self.document.is_some() {
            self.pending = Some(Pending::ShowGltfScene(index));
        } else {
            self.show_gltf_scene(index, render_state);
        }
    }

    /// Makes `document` the open one: fits its blockers, builds the viewport and the
    /// painting state, and reports `what` happened in the status bar.
    fn install(&mut self, document: Document, what: &str, render_state: Option<&egui_wgpu::RenderState>) {
        let scene = &document.scene;
        self.message = format!(
            "{what} — {} objects, {} vertices, {} lights{}",
            scene.objects.len(),
            scene.vertex_count(),
            scene.lights.len(),
            if document.warnings.is_empty() {
                String::new()
            } else {
                format!(
                    ", {} warning(s): {}",
                    document.warnings.len(),
                    document.warnings.join("; ")
                )
            }
        );
        self.blockers = fit_scene(scene, &document.settings.blockers);
        self.fitted_with = document.settings.blockers;
        let spheres = self.blockers.spheres();
        self.viewport =
            render_state.map(|rs| Viewport::new(rs, scene, document.camera, &spheres, &document.settings.shadows));
        let mut painting = Painting::for_document(&document);
        painting.resume_cached_bake(&document.scene, document.project_path.as_deref());
        self.painting = Some(painting);
        self.document = Some(document);
        self.indirect_stale = true;
        // An edit in progress belonged to the previous document's terrain.
        self.terrain_editing = None;
    }

    /// Gives the viewport the baked indirect light of the current lights, when the
    /// setting is on and maps baked for this geometry exist (none otherwise).
    fn refresh_baked_indirect(&mut self, render_state: Option<&egui_wgpu::RenderState>) {
        let (Some(document), Some(viewport), Some(rs)) = (&self.document, &mut self.viewport, render_state) else {
            return;
        };
        let maps = document
            .settings
            .baked_indirect
            .then(|| self.painting.as_ref()?.maps_for(&document.scene))
            .flatten();
        let indirect = maps.map(|maps| crate::render::BakedIndirect::from_maps(&document.scene, maps));
        viewport.set_baked_indirect(rs, indirect.as_ref());
        self.indirect_stale = false;
    }

    /// Where world point `p` appears on screen (points), if the viewport shows it.
    pub fn screen_position(&self, p: glam::Vec3) -> Option<egui::Pos2> {
        let viewport = self.viewport.as_ref()?;
        let rect = viewport.rect;
        let view = crate::paint::View {
            camera: viewport.orbit.camera(),
            width_px: rect.width().round().max(1.0) as u32,
            height_px: rect.height().round().max(1.0) as u32,
        };
        let q = view.project(p)?;
        let pos = rect.min + egui::vec2(q.x, q.y);
        rect.contains(pos).then_some(pos)
    }

    /// Where the viewport is on screen, in points (nothing before the first frame).
    pub fn viewport_rect(&self) -> egui::Rect {
        self.viewport.as_ref().map_or(egui::Rect::NOTHING, |v| v.rect)
    }

    /// Intensities of the document's lights, in order.
    pub fn light_intensities(&self) -> Vec<f32> {
        self.document
            .as_ref()
            .map(|d| d.scene.light_intensities())
            .unwrap_or_default()
    }

    /// Opens `path`, first asking to save when the document has unsaved changes.
    pub fn request_open(&mut self, path: &Path, render_state: Option<&egui_wgpu::RenderState>) {
        if self.has_unsaved_changes() && self.document.is_some() {
            self.pending = Some(Pending::Open(path.to_path_buf()));
        } else {
            self.open(path, render_state);
        }
    }

    /// Whether the editor is waiting for the answer to "save the changes?".
    pub fn is_asking_to_save(&self) -> bool {
        self.pending.is_some()
    }

    /// Whether the window has been cleared to close.
    pub fn is_closing(&self) -> bool {
        self.closing
    }

    /// Intercepts a close of the window with unsaved changes, and acts on the answer.
    fn guard_unsaved_changes(&mut self, ctx: &egui::Context, render_state: Option<&egui_wgpu::RenderState>) {
        if ctx.input(|i| i.viewport().close_requested()) && !self.closing {
            if self.has_unsaved_changes() && self.document.is_some() {
                ctx.send_viewport_cmd(egui::ViewportCommand::CancelClose);
                self.pending = Some(Pending::Close);
            } else {
                self.closing = true;
            }
        }
        let Some(pending) = self.pending.clone() else { return };
        let Some(answer) = unsaved_prompt::ask(ctx, &pending) else {
            return;
        };
        self.pending = None;
        let go_on = match answer {
            Answer::Cancel => false,
            Answer::Discard => true,
            Answer::Save => {
                self.save();
                !self.has_unsaved_changes()
            }
        };
        if !go_on {
            return;
        }
        match pending {
            Pending::Close => {
                self.closing = true;
                ctx.send_viewport_cmd(egui::ViewportCommand::Close);
            }
            Pending::Open(path) => self.open(&path, render_state),
            Pending::ShowGltfScene(index) => self.show_gltf_scene(index, render_state),
        }
    }

    /// The current tool (what a left drag in the viewport does).
    pub fn tool(&self) -> Tool {
        self.painting.as_ref().map_or(Tool::Navigate, |p| p.tool)
    }

    pub fn set_tool(&mut self, tool: Tool) {
        if let Some(painting) = &mut self.painting {
            painting.tool = tool;
        }
    }

    /// The painting state (brush, strategies, stroke history), if a document is open.
    pub fn painting_mut(&mut self) -> Option<&mut Painting> {
        self.painting.as_mut()
    }

    /// Applies a stroke painted in the viewport with the current tool and brush.
    pub fn paint_stroke(&mut self, stroke: &FinishedStroke, render_state: Option<&egui_wgpu::RenderState>) {
        let (Some(document), Some(painting), Some(viewport)) = (&mut self.document, &mut self.painting, &self.viewport)
        else {
            return;
        };
        let spheres = self.blockers.spheres();
        let camera = viewport.orbit.camera();
        let shadows = document.settings.shadows;
        if let Some(report) = painting.paint(&mut document.scene, camera, stroke, &spheres, &shadows) {
            self.message = report.message;
            self.lights_changed(render_state);
        }
    }

    /// Undoes the last stroke (Ctrl+Z).
    pub fn undo(&mut self, render_state: Option<&egui_wgpu::RenderState>) {
        let (Some(document), Some(painting)) = (&mut self.document, &mut self.painting) else {
            return;
        };
        self.message = if painting.undo(&mut document.scene) {
            "undid the last stroke".into()
        } else {
            "nothing to undo".into()
        };
        self.lights_changed(render_state);
    }

    /// Redoes the last undone stroke (Ctrl+Shift+Z or Ctrl+Y).
    pub fn redo(&mut self, render_state: Option<&egui_wgpu::RenderState>) {
        let (Some(document), Some(painting)) = (&mut self.document, &mut self.painting) else {
            return;
        };
        self.message = if painting.redo(&mut document.scene) {
            "redid the stroke".into()
        } else {
            "nothing to redo".into()
        };
        self.lights_changed(render_state);
    }

    fn lights_changed(&mut self, render_state: Option<&egui_wgpu::RenderState>) {
        if let (Some(document), Some(painting)) = (&mut self.document, &self.painting) {
            document.painting = painting.state();
        }
        if let (Some(viewport), Some(document), Some(rs)) = (&mut self.viewport, &self.document, render_state) {
            viewport.set_lights(rs, &document.scene.lights);
        }
        self.refresh_baked_indirect(render_state);
    }

    /// Saves the document to `path` (a project file), recording the current camera.
    pub fn save_to(&mut self, path: &Path) {
        let Some(document) = &mut self.document else { return };
        if let Some(viewport) = &self.viewport {
            document.camera = Some(viewport.orbit);
        }
        match document.save(path) {
            Ok(()) => {
                self.saved = Some(document.to_project_file(path));
                self.message = format!("saved {}", path.display());
                if let Some(problem) = self.painting.as_mut().and_then(|p| p.save_cache(&document.scene, path)) {
                    self.message = problem;
                }
            }
            Err(e) => self.report_error(e.to_string()),
        }
    }

    fn report_error(&mut self, message: String) {
        log::error!("{message}");
        self.message = message.clone();
        self.error = Some(message);
    }

    /// The open document, if any.
    pub fn document(&self) -> Option<&Document> {
        self.document.as_ref()
    }

    /// Whether the document differs from its file (a document never saved counts as
    /// changed).
    pub fn has_unsaved_changes(&self) -> bool {
        let Some(document) = &self.document else { return false };
        match (&document.project_path, &self.saved) {
            (Some(path), Some(saved)) => {
                let mut current = document.to_project_file(path);
                if let Some(viewport) = &self.viewport {
                    current.camera = Some(viewport.orbit);
                }
                current != *saved
            }
            _ => true,
        }
    }

    fn save(&mut self) {
        match self.document.as_ref().and_then(|d| d.project_path.clone()) {
            Some(path) => self.save_to(&path),
            None => self.save_as_dialog(),
        }
    }

    fn save_as_dialog(&mut self) {
        let picked = rfd::FileDialog::new()
            .add_filter("lightpaint project", &[PROJECT_EXTENSION])
            .set_file_name(format!("untitled.{PROJECT_EXTENSION}"))
            .save_file();
        if let Some(path) = picked {
            self.save_to(&path);
        }
    }

    fn open_dialog(&mut self, render_state: Option<&egui_wgpu::RenderState>) {
        let picked = rfd::FileDialog::new()
            .add_filter("lightpaint project or glTF scene", &[PROJECT_EXTENSION, "gltf", "glb"])
            .pick_file();
        if let Some(path) = picked {
            self.request_open(&path, render_state);
        }
    }

    fn menu_bar(&mut self, ui: &mut egui::Ui, render_state: Option<&egui_wgpu::RenderState>) {
        egui::Panel::top("menu").show(ui, |ui| {
            egui::MenuBar::new().ui(ui, |ui| {
                ui.menu_button("File", |ui| {
                    if ui.button("Open… (Ctrl+O)").clicked() {
                        self.open_dialog(render_state);
                    }
                    if ui.button("Save (Ctrl+S)").clicked() {
                        self.save();
                    }
                    if ui.button("Save As…").clicked() {
                        self.save_as_dialog();
                    }
                    ui.separator();
                    if ui.button("Quit").clicked() {
                        ui.ctx().send_viewport_cmd(egui::ViewportCommand::Close);
                    }
                });
                ui.menu_button("Edit", |ui| {
                    let (can_undo, can_redo) = self
                        .painting
                        .as_ref()
                        .map_or((false, false), |p| (p.can_undo(), p.can_redo()));
                    if ui
                        .add_enabled(can_undo, egui::Button::new("Undo stroke (Ctrl+Z)"))
                        .clicked()
                    {
                        self.undo(render_state);
                    }
                    if ui
                        .add_enabled(can_redo, egui::Button::new("Redo stroke (Ctrl+Shift+Z)"))
                        .clicked()
                    {
                        self.redo(render_state);
                    }
                });
                ui.menu_button("View", |ui| {
                    if ui.button("Frame all (F)").clicked() {
                        self.frame_all();
                    }
                });
            });
        });
    }

    fn tool_bar(&mut self, ui: &mut egui::Ui) {
        let Some(painting) = &mut self.painting else { return };
        egui::Panel::top("tools").show(ui, |ui| tool_bar(ui, &mut painting.tool));
    }

    fn frame_all(&mut self) {
        if let (Some(viewport), Some(document)) = (&mut self.viewport, &self.document) {
            viewport.frame_all(&document.scene);
        }
    }

    fn outliner(&mut self, ui: &mut egui::Ui, render_state: Option<&egui_wgpu::RenderState>) {
        egui::Panel::left("outliner").default_size(220.0).show(ui, |ui| {
            ui.heading("Scene");
            if let Some(index) = self.document.as_ref().and_then(|d| gltf_scene_picker(ui, &d.scene)) {
                self.request_gltf_scene(index, render_state);
            }
            let Some(document) = &self.document else { return };
            egui::ScrollArea::vertical().show(ui, |ui| {
                egui::CollapsingHeader::new(format!("Objects ({})", document.scene.objects.len()))
                    .default_open(true)
                    .show(ui, |ui| {
                        for object in &document.scene.objects {
                            let material = document.scene.materials.get(object.material);
                            let summary = material.map_or_else(|| "default material".to_string(), |m| m.summary());
                            ui.label(&object.name)
                                .on_hover_text(format!("{} vertices; {summary}", object.positions.len()));
                        }
                    });
                egui::CollapsingHeader::new(format!("Lights ({})", document.scene.lights.len()))
                    .default_open(true)
                    .show(ui, |ui| {
                        for light in &document.scene.lights {
                            ui.label(format!("{} — {}", light.name, light.kind.label()));
                        }
                    });
            });
        });
    }

    fn inspector(&mut self, ui: &mut egui::Ui, render_state: Option<&egui_wgpu::RenderState>) {
        let mut pending_history = None;
        egui::Panel::right("inspector").default_size(280.0).show(ui, |ui| {
            egui::ScrollArea::vertical().show(ui, |ui| self.inspector_contents(ui, render_state, &mut pending_history));
        });
        match pending_history {
            Some(PaintAction::Undo) => self.undo(render_state),
            Some(PaintAction::Redo) => self.redo(render_state),
            _ => {}
        }
    }

    fn inspector_contents(
        &mut self,
        ui: &mut egui::Ui,
        render_state: Option<&egui_wgpu::RenderState>,
        pending_history: &mut Option<PaintAction>,
    ) {
        {
            let Some(document) = &mut self.document else { return };
            ui.heading("Render");
            ui.add(egui::Slider::new(&mut document.settings.exposure_ev, -8.0..=8.0).text("exposure (EV)"));
            ui.horizontal(|ui| {
                ui.label("background");
                ui.color_edit_button_srgb(&mut document.settings.background_srgb8);
            });
            ui.add(
                egui::Slider::new(&mut document.settings.viewport_resolution_scale, 0.25..=1.0)
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
            self.indirect_stale |= ui
                .checkbox(&mut document.settings.baked_indirect, "baked indirect light")
                .on_hover_text(
                    "Adds the light of the baked bounces once importance maps are baked \
                     (Painting ▸ Bake importance maps); it follows every intensity change.",
                )
                .changed();
            // The slider clamps typed values, but not NaN: a saved project must reopen.
            let scale = &mut document.settings.viewport_resolution_scale;
            *scale = if scale.is_finite() { scale.clamp(0.25, 1.0) } else { 1.0 };
            ui.separator();
            ui.heading("Shadows");
            shadow_section(ui, &mut document.settings, &self.blockers, &document.scene);
            // Refit once the slider is let go: a fit takes a good part of a second.
            if document.settings.blockers != self.fitted_with
                && document.settings.blockers.problems().is_empty()
                && !ui.input(|i| i.pointer.any_down())
                && let (Some(viewport), Some(rs)) = (&mut self.viewport, render_state)
            {
                self.blockers = fit_scene(&document.scene, &document.settings.blockers);
                self.fitted_with = document.settings.blockers;
                viewport.set_blockers(rs, &self.blockers.spheres());
            }
            ui.separator();
            let mut action = None;
            if let Some(painting) = &mut self.painting {
                egui::CollapsingHeader::new("Painting")
                    .default_open(true)
                    .show(ui, |ui| action = painting_section(ui, painting));
            }
            match action {
                Some(PaintAction::StartBake) => {
                    if let Some(painting) = &mut self.painting {
                        painting.start_bake(&document.scene, document.project_path.as_deref());
                    }
                }
                Some(PaintAction::Undo) => *pending_history = Some(PaintAction::Undo),
                Some(PaintAction::Redo) => *pending_history = Some(PaintAction::Redo),
                None => {}
            }
            ui.separator();
            ui.heading("Lights");
            let mut changed = false;
            let pivot = self.viewport.as_ref().map_or(glam::Vec3::ZERO, |v| v.orbit.target);
            let paths: Vec<(bool, f64)> = document
                .scene
                .lights
                .iter()
                .map(|light| light_path_at(light, pivot, document.settings.shadows.light_paths))
                .collect();
            egui::ScrollArea::vertical().show(ui, |ui| {
                egui::Grid::new("lights").striped(true).num_columns(4).show(ui, |ui| {
                    for (light, (exact, angle_deg)) in document.scene.lights.iter_mut().zip(paths) {
                        let unit = format!(" {}", light.kind.intensity_unit());
                        ui.label(&light.name);
                        // Drag speed proportional to the value, so dim and bright lights
                        // both adjust smoothly.
                        let speed = (light.intensity.abs() * 0.01).max(0.001);
                        changed |= ui
                            .add(
                                egui::DragValue::new(&mut light.intensity)
                                    .range(0.0..=1.0e7)
                                    .speed(speed)
                                    .suffix(unit),
                            )
                            .changed();
                        let mut color = light.color.to_array();
                        if ui.color_edit_button_rgb(&mut color).changed() {
                            light.color = glam::Vec3::from(color);
                            changed = true;
                        }
                        ui.label(if exact { "exact" } else { "SH" }).on_hover_text(format!(
                            "Shadow path at the view's pivot, where the light looks {angle_deg:.1}° in radius \
                             (Shadows ▸ light shadows)"
                        ));
                        ui.end_row();
                    }
                });
            });
            if changed && let (Some(viewport), Some(rs)) = (&mut self.viewport, render_state) {
                viewport.set_lights(rs, &document.scene.lights);
                self.indirect_stale = true;
            }
            if let Some(environment) = &mut document.scene.environment {
                ui.separator();
                ui.heading("Environment");
                let name = environment
                    .hdr
                    .file_name()
                    .map_or_else(String::new, |n| n.to_string_lossy().into_owned());
                let mut environment_changed = false;
                ui.horizontal(|ui| {
                    ui.label(name);
                    let intensity = egui::DragValue::new(&mut environment.intensity)
                        .range(0.0..=1.0e4)
                        .speed(0.01)
                        .prefix("×");
                    environment_changed |= ui.add(intensity).changed();
                });
                let half_turn = std::f32::consts::PI;
                let rotation =
                    egui::Slider::new(&mut environment.rotation_rad, -half_turn..=half_turn).text("rotation (rad)");
                environment_changed |= ui.add(rotation).changed();
                if environment_changed && let Some(viewport) = &mut self.viewport {
                    viewport.set_environment(Some(environment));
                }
            }
        }
        let Some(document) = &self.document else { return };
        ui.separator();
        ui.heading("Terrain");
        if let Some(edit) = terrain_section(ui, &document.scene, &mut self.terrain_editing) {
            self.apply_terrain_edit(edit, render_state);
        }
    }

    fn status_bar(&mut self, ui: &mut egui::Ui) {
        let unsaved = self.has_unsaved_changes();
        egui::Panel::bottom("status").show(ui, |ui| {
            ui.horizontal(|ui| {
                if !self.options.hide_frame_timings {
                    let fps = if self.frame_ms > 0.0 {
                        1000.0 / self.frame_ms
                    } else {
                        0.0
                    };
                    ui.label(format!("{fps:.0} fps ({:.1} ms)", self.frame_ms));
                    if let Some(viewport) = &self.viewport {
                        ui.label(format!("scene {:.1} ms", viewport.last_render_ms));
                    }
                    ui.separator();
                }
                ui.label(&self.adapter);
                ui.separator();
                if unsaved {
                    ui.colored_label(ui.visuals().warn_fg_color, "unsaved changes");
                    ui.separator();
                }
                ui.label(&self.message);
            });
        });
    }

    fn error_window(&mut self, ctx: &egui::Context) {
        let Some(error) = self.error.clone() else { return };
        let mut open = true;
        egui::Window::new("Error")
            .collapsible(false)
            .open(&mut open)
            .show(ctx, |ui| {
                ui.label(&error);
                if ui.button("OK").clicked() {
                    self.error = None;
                }
            });
        if !open {
            self.error = None;
        }
    }

    fn handle_shortcuts_and_drops(&mut self, ctx: &egui::Context, render_state: Option<&egui_wgpu::RenderState>) {
        let typing = ctx.egui_wants_keyboard_input();
        let (frame_key, open_key, save_key, dropped) = ctx.input(|i| {
            (
                i.key_pressed(egui::Key::F) && !i.modifiers.any(),
                i.key_pressed(egui::Key::O) && i.modifiers.command,
                i.key_pressed(egui::Key::S) && i.modifiers.command,
                i.raw.dropped_files.first().map(|f| f.path().to_path_buf()),
            )
        });
        let (undo_key, redo_key) = ctx.input(|i| {
            let z = i.key_pressed(egui::Key::Z) && i.modifiers.command;
            (
                z && !i.modifiers.shift,
                (z && i.modifiers.shift) || (i.key_pressed(egui::Key::Y) && i.modifiers.command),
            )
        });
        if !typing {
            let tool = ctx.input(|i| {
                let plain = |key| i.key_pressed(key) && !i.modifiers.any();
                [
                    (egui::Key::B, Tool::Brush(BrushKind::Positive)),
                    (egui::Key::N, Tool::Brush(BrushKind::Negative)),
                    (egui::Key::C, Tool::Brush(BrushKind::Constraint)),
                    (egui::Key::Escape, Tool::Navigate),
                ]
                .into_iter()
                .find(|(key, _)| plain(*key))
                .map(|(_, tool)| tool)
            });
            if let Some(tool) = tool {
                self.set_tool(tool);
            }
            if undo_key {
                self.undo(render_state);
            }
            if redo_key {
                self.redo(render_state);
            }
        }
        if frame_key && !typing {
            self.frame_all();
        }
        if open_key {
            self.open_dialog(render_state);
        }
        if save_key {
            self.save();
        }
        if let Some(path) = dropped {
            self.request_open(&path, render_state);
        }
    }

    fn track_frame_time(&mut self) {
        let now = Instant::now();
        if let Some(last) = self.last_frame {
            let ms = (now - last).as_secs_f32() * 1000.0;
            // Exponential smoothing keeps the readout legible.
            self.frame_ms = if self.frame_ms == 0.0 {
                ms
            } else {
                0.9 * self.frame_ms + 0.1 * ms
            };
        }
        self.last_frame = Some(now);
    }

    fn scripted_close(&mut self, ctx: &egui::Context) {
        if let Some(path) = &self.options.close_when_file_exists {
            if path.exists() {
                self.closing = true;
                ctx.send_viewport_cmd(egui::ViewportCommand::Close);
            }
            ctx.request_repaint_after(std::time::Duration::from_millis(100));
        }
    }
}

impl eframe::App for EditorApp {
    fn ui(&mut self, ui: &mut egui::Ui, frame: &mut eframe::Frame) {
        self.track_frame_time();
        let render_state = frame.wgpu_render_state().cloned();
        let ctx = ui.ctx().clone();
        self.handle_shortcuts_and_drops(&ctx, render_state.as_ref());
        self.menu_bar(ui, render_state.as_ref());
        self.tool_bar(ui);
        self.status_bar(ui);
        self.outliner(ui, render_state.as_ref());
        self.inspector(ui, render_state.as_ref());
        if let Some(message) = self.painting.as_mut().and_then(Painting::poll_bake) {
            self.message = message;
            self.indirect_stale = true;
        }
        if self.indirect_stale {
            self.refresh_baked_indirect(render_state.as_ref());
        }
        let brush_radius = match self.painting.as_ref() {
            Some(p) if p.tool != Tool::Navigate => Some(p.brush.radius_px),
            _ => None,
        };
        let mut finished = None;
        egui::CentralPanel::default().frame(egui::Frame::NONE).show(ui, |ui| {
            match (&mut self.viewport, &self.document, &render_state) {
                (Some(viewport), Some(document), Some(rs)) => {
                    let response = viewport.show(ui, rs, &document.settings, brush_radius.is_some());
                    if let Some(radius) = brush_radius {
                        finished = self.brush_input.update(ui, &response);
                        self.brush_input.draw(ui, &response, radius);
                    }
                }
                _ => {
                    ui.centered_and_justified(|ui| ui.label("Nothing open. File ▸ Open…"));
                }
            }
        });
        if let Some(stroke) = finished {
            self.paint_stroke(&stroke, render_state.as_ref());
        }
        if let (Some(document), Some(painting)) = (&mut self.document, &self.painting) {
            // Brush and strategy edits are part of the project (restored on reopening); the
            // strokes are copied only when they change (`lights_changed`), not every frame.
            document.painting.brush = painting.brush_for_file();
            document.painting.settings = painting.settings;
        }
        self.error_window(&ctx);
        self.guard_unsaved_changes(&ctx, render_state.as_ref());
        if !self.first_frame_reported {
            self.first_frame_reported = true;
            eprintln!("{FIRST_FRAME_LINE}");
        }
        self.scripted_close(&ctx);
    }
}

/// A choice of the glTF file's scenes, when it has several; the index picked, if the user
/// picked another.
fn gltf_scene_picker(ui: &mut egui::Ui, scene: &crate::scene::Scene) -> Option<usize> {
    if scene.gltf_scenes.len() < 2 {
        return None;
    }
    let shown = scene.gltf_scene.unwrap_or(0);
    let mut picked = shown;
    egui::ComboBox::from_label("glTF scene")
        .selected_text(scene.gltf_scene_label(shown))
        .show_ui(ui, |ui| {
            for index in 0..scene.gltf_scenes.len() {
                ui.selectable_value(&mut picked, index, scene.gltf_scene_label(index));
            }
        })
        .response
        .on_hover_text("The file holds several scenes; the project remembers which one it shows");
    (picked != shown).then_some(picked)
}

/// Whether `light` takes the exact shadow path at `point` under `paths`, and its angular
/// radius there in degrees (the shaders decide per receiver; this is the view's pivot).
fn light_path_at(light: &crate::scene::Light, point: glam::Vec3, paths: crate::render::LightPaths) -> (bool, f64) {
    let gpu_light = crate::render::gpu_types::GpuLight::new(light);
    let cap_ratio = crate::render::cpu::incidence(&gpu_light, point.as_dvec3()).cap_ratio;
    (paths.is_exact(cap_ratio), cap_ratio.clamp(0.0, 1.0).asin().to_degrees())
}
