//! Opening, installing, saving and closing the editor's document, and the guard that
//! asks before unsaved changes are lost.

use super::*;

impl EditorApp {
    /// Opens a project or a glTF scene, replacing the current document; on failure the
    /// current document stays and the error is shown.
    pub fn open(&mut self, path: &Path) {
        match Document::open(path) {
            Ok(document) => {
                self.preferences.remember(path);
                let name = path
                    .file_name()
                    .map_or_else(|| path.display().to_string(), |n| n.to_string_lossy().into());
                self.install(document, &format!("opened {name}"));
                self.saved = self.session.as_ref().and_then(|session| {
                    let mut saved = session.project_file(session.document.project_path.as_ref()?);
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
    pub fn show_gltf_scene(&mut self, index: usize) {
        let Some(session) = &self.session else { return };
        match session.document.with_gltf_scene(index) {
            Ok(mut document) => {
                // The brush and strategies as they are now (the stroke log starts afresh).
                let now = session.painting_state();
                document.painting.brush = now.brush;
                document.painting.settings = now.settings;
                let label = document.scene.gltf_scene_label(index);
                self.install(document, &format!("showing glTF scene {label}"));
            }
            Err(e) => self.report_error(e.to_string()),
        }
    }

    /// Applies a terrain edit: the scene gets the new terrain mesh and is reinstalled (the
    /// sphere fit and the viewport follow; bake maps of the old geometry no longer apply).
    /// A height map that cannot be read is reported and changes nothing.
    pub fn apply_terrain_edit(&mut self, edit: TerrainEdit) {
        let Some(current) = self.session.as_ref().map(|s| &s.document) else {
            return;
        };
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
        let Some(mut document) = self.session.take().map(EditorSession::into_document) else {
            return;
        };
        document.scene.set_terrain(terrain);
        if let Some(viewport) = &self.viewport {
            document.camera = Some(viewport.orbit);
        }
        self.install(document, what);
    }

    /// Shows glTF scene `index`, first asking to save when there are unsaved changes.
    pub fn request_gltf_scene(&mut self, index: usize) {
        if self.ready_or_ask(Pending::ShowGltfScene(index)) {
            self.show_gltf_scene(index);
        }
    }

    /// True when an action that replaces the document may go ahead now; with unsaved
    /// changes it waits as `pending` for the answer to "save the changes?" instead.
    pub(in crate::ui) fn ready_or_ask(&mut self, pending: Pending) -> bool {
        let ready = !(self.has_unsaved_changes() && self.session.is_some());
        if !ready {
            self.pending = Some(pending);
        }
        ready
    }

    /// Makes `document` the open one: fits its blockers, builds the viewport and the
    /// painting state, and reports `what` happened in the status bar.
    pub(super) fn install(&mut self, document: Document, what: &str) {
        let scene = &document.scene;
        self.message = format!(
            "{what} — {} objects, {} vertices, {}{}{}",
            scene.objects.len(),
            scene.vertex_count(),
            match scene.lights.len() {
                0 => "no lights yet: Add light in the outliner".to_string(),
                n => format!("{n} lights"),
            },
            if document.warnings.is_empty() {
                String::new()
            } else {
                format!(
                    ", {} warning(s): {}",
                    document.warnings.len(),
                    document.warnings.join("; ")
                )
            },
            document
                .notes
                .iter()
                .map(|note| format!("; {note}"))
                .collect::<String>()
        );
        let project = document.project_path.as_deref();
        self.blockers = sphere_cache::fit_with_cache(scene, &document.settings.blockers, project);
        self.fitted_with = document.settings.blockers;
        let spheres = self.blockers.shown_spheres(&document.hidden_objects);
        self.viewport = self.render_state.as_ref().map(|rs| {
            let mut viewport = Viewport::new(rs, scene, document.camera, &spheres, &document.settings.shadows);
            viewport.set_hidden(&document.hidden_objects);
            viewport
        });
        self.session = Some(EditorSession::new(document));
        self.indirect_stale = true;
        // An edit in progress and the selection belonged to the previous document.
        self.terrain_editing = None;
        self.selection = None;
        // The new viewport has no heat map yet.
        self.heat_map = None;
    }

    /// Opens `path`, first asking to save when the document has unsaved changes.
    pub fn request_open(&mut self, path: &Path) {
        if self.ready_or_ask(Pending::Open(path.to_path_buf())) {
            self.open(path);
        }
    }

    /// Whether the editor is waiting for the answer to "save the changes?".
    pub fn is_asking_to_save(&self) -> bool {
        self.pending.is_some()
    }

    /// Closes the document without asking (File ▸ New after the unsaved-changes prompt):
    /// the start page with the recent files is shown.
    pub fn close_document(&mut self) {
        self.session = None;
        self.saved = None;
        self.viewport = None;
        self.blockers = SceneBlockers::default();
        self.selection = None;
        self.terrain_editing = None;
        self.heat_map = None;
        self.message = "nothing open".to_string();
    }

    /// Whether the window has been cleared to close.
    pub fn is_closing(&self) -> bool {
        self.closing
    }

    /// Intercepts a close of the window with unsaved changes, and acts on the answer.
    pub(super) fn guard_unsaved_changes(&mut self, ctx: &egui::Context) {
        if ctx.input(|i| i.viewport().close_requested()) && !self.closing {
            if self.ready_or_ask(Pending::Close) {
                self.closing = true;
            } else {
                ctx.send_viewport_cmd(egui::ViewportCommand::CancelClose);
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
                self.save_document();
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
            Pending::New => self.close_document(),
            Pending::Open(path) => self.open(&path),
            Pending::ShowGltfScene(index) => self.show_gltf_scene(index),
        }
    }

    /// Saves the document to `path` (a project file), recording the current camera.
    pub fn save_to(&mut self, path: &Path) {
        let Some(session) = &mut self.session else { return };
        if let Some(viewport) = &self.viewport {
            session.document.camera = Some(viewport.orbit);
        }
        match session.save(path) {
            Ok(()) => {
                self.preferences.remember(path);
                // The fit goes beside the project too, so it reopens without refitting.
                let spheres = sphere_cache::cache_path(path);
                let scene = &session.document.scene;
                if let Err(e) = sphere_cache::save(&spheres, scene, &self.fitted_with, &self.blockers) {
                    log::warn!("the sphere fit could not be cached at {}: {e}", spheres.display());
                }
                self.saved = Some(session.project_file(path));
                self.message = format!("saved {}", path.display());
                if let Some(problem) = session.painting.save_cache(scene, path) {
                    self.message = problem;
                }
            }
            Err(e) => self.report_error(e.to_string()),
        }
    }

    pub(in crate::ui) fn report_error(&mut self, message: String) {
        log::error!("{message}");
        self.message = message.clone();
        self.error = Some(message);
    }

    /// The open document, if any.
    pub fn document(&self) -> Option<&Document> {
        self.session.as_ref().map(|s| &s.document)
    }

    /// Whether the document differs from its file (a document never saved counts as
    /// changed).
    /// Whether the document differs from the file it was opened from or saved to. Where
    /// the camera looks is not a change (saving records it all the same): looking around
    /// and quitting must not ask to save.
    pub fn has_unsaved_changes(&self) -> bool {
        let Some(session) = &self.session else { return false };
        match (&session.document.project_path, &self.saved) {
            (Some(path), Some(saved)) => {
                let mut current = session.project_file(path);
                current.camera = saved.camera;
                current != *saved
            }
            _ => true,
        }
    }
}
