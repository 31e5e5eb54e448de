use std::path::{Path, PathBuf};
use std::time::Instant;

use super::Viewport;
use super::blocker_overlay::{draw_blockers, draw_meshes_without_spheres};
use super::brush_input::{BrushInput, FinishedStroke};
use super::brush_panel::tool_bar;
use super::history::{History, Step};
use super::light_gizmo::{GizmoLights, GizmoOutput, light_gizmo};
use super::outliner::{OutlinerAction, OutlinerState, Selection, outliner};
use super::outlines::{box_outline, draw_outline};
use super::painting::{Painting, Tool};
use super::preferences::Preferences;
use super::terrain_panel::{TerrainEdit, image_terrain};
use super::unsaved_prompt::{self, Answer, Pending};
use crate::blockers::{BlockerSettings, SceneBlockers};
use crate::paint::BrushKind;
use crate::project::sphere_cache;
use crate::project::{Document, ProjectFile};
use crate::render::describe_adapter;
use crate::scene::Light;

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

/// Which way through the history a step is carried out.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Direction {
    Undo,
    Redo,
}

/// How long a status message reads as news; after that, and once the undo history has
/// changed under it, it is shown faded.
const FRESH_MESSAGE: std::time::Duration = std::time::Duration::from_secs(10);

/// A status message as the status bar first showed it.
struct SeenMessage {
    text: String,
    at: std::time::Instant,
    /// (can undo, can redo) at that moment.
    history: (bool, bool),
}

pub struct EditorApp {
    pub(super) document: Option<Document>,
    /// The project as last opened or saved, to tell whether there are unsaved changes.
    pub(super) saved: Option<ProjectFile>,
    pub(super) viewport: Option<Viewport>,
    /// Sphere blockers fitted to the document's meshes, and the settings they were fitted with.
    pub(super) blockers: SceneBlockers,
    pub(super) fitted_with: BlockerSettings,
    pub(super) adapter: String,
    /// The last thing worth telling the user, shown in the status bar.
    pub(super) message: String,
    /// When the status bar first showed `message`, and the undo history then.
    message_seen: SeenMessage,
    /// The export window's size in pixels (kept between exports), and whether it is open.
    pub(super) export_size: Option<[u32; 2]>,
    pub(super) export_window_open: bool,
    /// An error waiting to be acknowledged in a window.
    pub(super) error: Option<String>,
    pub(super) options: EditorOptions,
    pub(super) frame_clock: super::frame_clock::FrameClock,
    /// The window's title as last sent (sent again only when it changes).
    window_title: String,
    pub(super) first_frame_reported: bool,
    /// The document's painting state (None without a document).
    pub(super) painting: Option<Painting>,
    pub(super) brush_input: BrushInput,
    /// A close or open waiting for the answer to "save the changes?".
    pub(super) pending: Option<Pending>,
    /// The window may close without asking (answered, or a scripted close).
    pub(super) closing: bool,
    /// The viewport's baked indirect light no longer matches the lights, maps or setting.
    pub(super) indirect_stale: bool,
    /// The terrain spec being edited in the inspector (applied when an edit is committed).
    pub(super) terrain_editing: Option<crate::scene::TerrainSpec>,
    /// The light or object the inspector edits.
    pub(super) selection: Option<Selection>,
    /// The light shown alone in the viewport (a view setting, not saved).
    pub(super) solo_light: Option<usize>,
    /// A light moved or changed shape and its maps wait to be re-baked once the edit ends.
    pub(super) lights_moved: bool,
    /// Recent files and view choices, kept between runs.
    pub(super) preferences: Preferences,
    /// What the viewport's heat map shows (None: no heat map) and the value its
    /// brightest colour stands for (cd/m²).
    pub(super) heat_map: Option<(HeatMapKey, f32)>,
    /// Strokes and light edits, for undo and redo.
    pub(super) history: History,
}

/// What a heat map was computed from: the light, its placement and intensity, whether
/// the transfer came from fresh baked maps, and (for the direct estimate) the shadows.
#[derive(Debug, Clone, PartialEq)]
pub(super) struct HeatMapKey {
    light: usize,
    placement: [u8; 32],
    intensity: f32,
    baked: bool,
    shadows: crate::shading::ShadowSettings,
    blockers: BlockerSettings,
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
            message_seen: SeenMessage {
                text: String::new(),
                at: std::time::Instant::now(),
                history: (false, false),
            },
            error: None,
            export_size: None,
            export_window_open: false,
            options: options.clone(),
            frame_clock: Default::default(),
            window_title: String::new(),
            first_frame_reported: false,
            painting: None,
            brush_input: BrushInput::default(),
            pending: None,
            closing: false,
            indirect_stale: true,
            terrain_editing: None,
            selection: None,
            solo_light: None,
            lights_moved: false,
            preferences: Preferences::load(cc.storage),
            heat_map: None,
            history: History::default(),
        };
        app.open(&options.file, cc.wgpu_render_state.as_ref());
        app
    }

    /// Opens a project or a glTF scene, replacing the current document; on failure the
    /// current document stays and the error is shown.
    pub fn open(&mut self, path: &Path, render_state: Option<&egui_wgpu::RenderState>) {
        match Document::open(path) {
            Ok(document) => {
                self.preferences.remember(path);
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
        if self.ready_or_ask(Pending::ShowGltfScene(index)) {
            self.show_gltf_scene(index, render_state);
        }
    }

    /// True when an action that replaces the document may go ahead now; with unsaved
    /// changes it waits as `pending` for the answer to "save the changes?" instead.
    pub(super) fn ready_or_ask(&mut self, pending: Pending) -> bool {
        let ready = !(self.has_unsaved_changes() && self.document.is_some());
        if !ready {
            self.pending = Some(pending);
        }
        ready
    }

    /// Makes `document` the open one: fits its blockers, builds the viewport and the
    /// painting state, and reports `what` happened in the status bar.
    fn install(&mut self, document: Document, what: &str, render_state: Option<&egui_wgpu::RenderState>) {
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
        self.viewport = render_state.map(|rs| {
            let mut viewport = Viewport::new(rs, scene, document.camera, &spheres, &document.settings.shadows);
            viewport.set_hidden(&document.hidden_objects);
            viewport
        });
        let mut painting = Painting::for_document(&document);
        painting.resume_cached_bake(&document.scene, document.project_path.as_deref());
        self.painting = Some(painting);
        self.document = Some(document);
        self.indirect_stale = true;
        // An edit in progress, the selection and the solo belonged to the previous document.
        self.terrain_editing = None;
        self.selection = None;
        self.solo_light = None;
        self.lights_moved = false;
        // The new viewport has no heat map yet.
        self.heat_map = None;
        self.history = History::new(self.document.as_ref().map_or(&[][..], |d| &d.scene.lights));
    }

    /// The lights as the viewport shows them: all, or only the soloed one.
    fn displayed_lights(&self) -> Vec<Light> {
        let Some(document) = &self.document else {
            return Vec::new();
        };
        let mut lights = document.scene.lights.clone();
        if let Some(solo) = self.solo_light {
            for (index, light) in lights.iter_mut().enumerate() {
                if index != solo {
                    light.intensity = 0.0;
                }
            }
        }
        lights
    }

    /// Shows only `light` in the viewport (None: every light). A view setting: painting,
    /// saving and the bake see every light.
    pub fn solo(&mut self, light: Option<usize>) {
        let count = self.document.as_ref().map_or(0, |d| d.scene.lights.len());
        self.solo_light = light.filter(|&l| l < count);
        self.message = match self
            .solo_light
            .and_then(|l| Some(&self.document.as_ref()?.scene.lights[l]))
        {
            Some(light) => format!("showing {} alone", light.name),
            None => "showing every light".to_string(),
        };
        self.upload_lights();
    }

    /// Selects what the viewport shows at `offset` (points from its top-left corner): the
    /// nearest shown object under it, or nothing.
    pub fn select_at(&mut self, offset: glam::Vec2) {
        let (Some(document), Some(viewport), Some(painting)) = (&self.document, &self.viewport, &mut self.painting)
        else {
            return;
        };
        let Some((origin, direction)) = viewport.view().ray_through(offset) else {
            return;
        };
        let hidden: Vec<u32> = document.hidden_objects.iter().map(|&o| o as u32).collect();
        // What the viewport draws: not hidden objects, nor back faces where it culls them.
        let culls_back_faces = document.scene.every_material_single_sided();
        let bvh = painting.picking_bvh(&document.scene);
        let hit = bvh.closest_hit_where(origin, direction, f32::INFINITY, |hit| {
            !hidden.contains(&(hit.object as u32)) && (hit.front_facing || !culls_back_faces)
        });
        self.selection = hit.map(|hit| Selection::Object(hit.object));
        if let Some(object) = hit.and_then(|hit| document.scene.objects.get(hit.object)) {
            self.message = format!("selected {}", object.name);
        }
    }

    /// Adds a white 20 cd point light 2 m above the view's pivot and selects it (one
    /// undoable edit). Its maps are baked in the background when the others are baked.
    pub fn add_light(&mut self) {
        let pivot = self.viewport.as_ref().map(|v| v.orbit.target);
        let Some(document) = &mut self.document else { return };
        let pivot = pivot.unwrap_or_else(|| document.scene.bounds().center());
        let taken = |name: &str| document.scene.lights.iter().any(|l| l.name == name);
        let name = (1..)
            .map(|n| format!("Light {n}"))
            .find(|name| !taken(name))
            .unwrap_or_default();
        document.scene.lights.push(Light {
            name: name.clone(),
            kind: crate::scene::LightKind::Point,
            color: glam::Vec3::ONE,
            intensity: 20.0,
            position: pivot + 2.0 * glam::Vec3::Y,
            direction: glam::Vec3::NEG_Y,
            range: None,
        });
        self.selection = Some(Selection::Light(document.scene.lights.len() - 1));
        self.history.settle(&document.scene.lights);
        self.message = format!("added {name}");
        self.lights_edited(true);
    }

    /// Deletes light `index` (one undoable edit).
    pub fn delete_light(&mut self, index: usize) {
        let Some(document) = &mut self.document else { return };
        if index >= document.scene.lights.len() {
            return;
        }
        // Whatever was still settling is its own edit, before the deletion.
        self.history.settle(&document.scene.lights);
        let light = document.scene.lights.remove(index);
        self.history.settle(&document.scene.lights);
        self.selection = None;
        self.solo_light = match self.solo_light {
            Some(solo) if solo == index => None,
            Some(solo) if solo > index => Some(solo - 1),
            other => other,
        };
        self.message = format!("deleted {} (Ctrl+Z brings it back)", light.name);
        self.lights_edited(true);
    }

    /// The status bar's message, as it reads now.
    pub fn status_message(&self) -> &str {
        &self.message
    }

    /// Whether the status bar shows its message faded: shown more than [`FRESH_MESSAGE`]
    /// ago, or the undo history changed since (a new message is fresh until the status
    /// bar has shown it).
    pub fn status_message_is_stale(&self) -> bool {
        self.message_seen.text == self.message
            && (self.message_seen.at.elapsed() > FRESH_MESSAGE
                || self.message_seen.history != (self.can_undo(), self.can_redo()))
    }

    /// Replaces light `index` (a gizmo drag); values with problems are ignored.
    pub fn set_light(&mut self, index: usize, light: Light) {
        let Some(slot) = self.document.as_mut().and_then(|d| d.scene.lights.get_mut(index)) else {
            return;
        };
        if !light.problems().is_empty() || *slot == light {
            return;
        }
        let moved = crate::project::bake_cache::light_hash(slot) != crate::project::bake_cache::light_hash(&light);
        *slot = light;
        self.lights_edited(moved);
    }

    /// Whether the viewport is compiling shaders for new shadow settings (it keeps drawing
    /// the previous ones meanwhile).
    pub fn is_compiling_shaders(&self) -> bool {
        self.viewport.as_ref().is_some_and(Viewport::is_compiling_shaders)
    }

    /// The open document's render settings, to change them as the inspector does.
    pub fn render_settings_mut(&mut self) -> Option<&mut crate::shading::RenderSettings> {
        self.document.as_mut().map(|d| &mut d.settings)
    }

    /// The current selection in the outliner, inspector and viewport.
    pub fn selection(&self) -> Option<Selection> {
        self.selection
    }

    pub fn select(&mut self, selection: Option<Selection>) {
        self.selection = selection;
    }

    /// Hides object `index` in the viewport if shown, shows it if hidden.
    pub fn toggle_hidden(&mut self, index: usize) {
        let Some(document) = &mut self.document else { return };
        let Some(object) = document.scene.objects.get(index) else {
            return;
        };
        let now_hidden = !document.hidden_objects.remove(&index);
        if now_hidden {
            document.hidden_objects.insert(index);
        }
        self.message = format!("{} {}", object.name, if now_hidden { "hidden" } else { "shown" });
        if let Some(viewport) = &mut self.viewport {
            viewport.set_hidden(&document.hidden_objects);
            viewport.set_blockers(&self.blockers.shown_spheres(&document.hidden_objects));
        }
    }

    /// Keeps the viewport's heat map in step with the selected light (computing it again
    /// only when the light, its intensity or the transfer's source changed).
    fn refresh_heat_map(&mut self) {
        let wanted = match (
            self.preferences.show_heat_map,
            self.selection,
            &self.document,
            &self.painting,
        ) {
            (true, Some(Selection::Light(light)), Some(document), Some(painting)) => {
                document.scene.lights.get(light).map(|l| HeatMapKey {
                    light,
                    placement: crate::project::bake_cache::light_hash(l),
                    intensity: l.intensity,
                    baked: painting.has_fresh_maps(&document.scene),
                    shadows: document.settings.shadows,
                    blockers: self.fitted_with,
                })
            }
            _ => None,
        };
        if wanted.as_ref() == self.heat_map.as_ref().map(|(key, _)| key) {
            return;
        }
        let Some(viewport) = &mut self.viewport else {
            return;
        };
        let (Some(key), Some(document), Some(painting)) = (wanted, &self.document, &self.painting) else {
            viewport.set_heat_map(None);
            self.heat_map = None;
            return;
        };
        let spheres = self.blockers.shown_spheres(&document.hidden_objects);
        let transfer = painting.transfer(&document.scene, &spheres, &document.settings.shadows);
        let eye = viewport.orbit.camera().position;
        let values =
            crate::paint::light_reach::light_reach_per_vertex(&document.scene, transfer.as_ref(), key.light, eye);
        let all: Vec<f32> = values.iter().flatten().copied().collect();
        let scale = crate::render::passes::heat_map::heat_scale(&all);
        viewport.set_heat_map(Some((&values, scale)));
        self.heat_map = Some((key, scale));
    }

    /// The value the heat map's brightest colour stands for (cd/m²), while one is shown.
    pub fn heat_map_scale(&self) -> Option<f32> {
        self.heat_map.as_ref().map(|(_, scale)| *scale)
    }

    /// Sends the displayed lights to the viewport.
    fn upload_lights(&mut self) {
        let lights = self.displayed_lights();
        if let Some(viewport) = &mut self.viewport {
            viewport.set_lights(&lights);
        }
    }

    /// After an edit of lights in the inspector: the viewport shows them, the baked
    /// indirect light follows, and `moved` lights get their maps re-baked once the edit ends.
    pub(super) fn lights_edited(&mut self, moved: bool) {
        self.upload_lights();
        self.indirect_stale = true;
        self.lights_moved |= moved;
    }

    /// Once a light is let go after a move, re-bakes only its maps (when there are maps).
    fn rebake_moved_lights(&mut self, ctx: &egui::Context) {
        if !self.lights_moved || ctx.input(|i| i.pointer.any_down()) {
            return;
        }
        let (Some(document), Some(painting)) = (&self.document, &mut self.painting) else {
            return;
        };
        if painting.bake.is_some() {
            // After the running bake: its maps are for the lights as they were.
            return;
        }
        self.lights_moved = false;
        if painting.rebake_moved_lights(&document.scene) {
            self.message = "re-baking the moved light's importance maps…".to_string();
        }
    }

    /// Gives the viewport the baked indirect light of the current lights, when the
    /// setting is on and maps baked for this geometry exist (none otherwise).
    fn refresh_baked_indirect(&mut self) {
        let (Some(document), Some(viewport)) = (&self.document, &mut self.viewport) else {
            return;
        };
        let maps = document
            .settings
            .baked_indirect
            .then(|| self.painting.as_ref()?.maps_for(&document.scene))
            .flatten();
        let indirect = maps.map(|maps| crate::shading::BakedIndirect::from_maps(&document.scene, maps));
        viewport.set_baked_indirect(indirect.as_ref());
        self.indirect_stale = false;
    }

    /// Where world point `p` appears on screen (points), if the viewport shows it.
    pub fn screen_position(&self, p: glam::Vec3) -> Option<egui::Pos2> {
        let viewport = self.viewport.as_ref()?;
        let pos = super::viewport::screen_point(&viewport.view(), viewport.rect, p)?;
        viewport.rect.contains(pos).then_some(pos)
    }

    /// Where the viewport is on screen, in points (nothing before the first frame).
    pub fn viewport_rect(&self) -> egui::Rect {
        self.viewport.as_ref().map_or(egui::Rect::NOTHING, |v| v.rect)
    }

    /// Where the viewport's camera looks from (None without a viewport).
    pub fn orbit(&self) -> Option<crate::scene::OrbitCamera> {
        self.viewport.as_ref().map(|v| v.orbit)
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
        if self.ready_or_ask(Pending::Open(path.to_path_buf())) {
            self.open(path, render_state);
        }
    }

    /// Whether the editor is waiting for the answer to "save the changes?".
    pub fn is_asking_to_save(&self) -> bool {
        self.pending.is_some()
    }

    /// Closes the document without asking (File ▸ New after the unsaved-changes prompt):
    /// the start page with the recent files is shown.
    pub fn close_document(&mut self) {
        self.document = None;
        self.saved = None;
        self.viewport = None;
        self.painting = None;
        self.blockers = SceneBlockers::default();
        self.selection = None;
        self.solo_light = None;
        self.lights_moved = false;
        self.terrain_editing = None;
        self.heat_map = None;
        self.history = History::default();
        self.message = "nothing open".to_string();
    }

    /// Whether the window has been cleared to close.
    pub fn is_closing(&self) -> bool {
        self.closing
    }

    /// Intercepts a close of the window with unsaved changes, and acts on the answer.
    fn guard_unsaved_changes(&mut self, ctx: &egui::Context, render_state: Option<&egui_wgpu::RenderState>) {
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
    pub fn paint_stroke(&mut self, stroke: &FinishedStroke) {
        let (Some(document), Some(painting), Some(viewport)) = (&mut self.document, &mut self.painting, &self.viewport)
        else {
            return;
        };
        let spheres = self.blockers.shown_spheres(&document.hidden_objects);
        let camera = viewport.orbit.camera();
        let shadows = document.settings.shadows;
        let hidden = &document.hidden_objects;
        // A light edit still settling belongs before the stroke in the history.
        self.history.settle(&document.scene.lights);
        let strokes_before = painting.stroke_count();
        if let Some(report) = painting.paint(&mut document.scene, camera, stroke, &spheres, &shadows, hidden) {
            if painting.stroke_count() > strokes_before {
                self.history.stroke_done(&document.scene.lights);
            } else {
                self.history.resettle(&document.scene.lights);
            }
            self.message = report.message;
            self.lights_changed();
        }
    }

    /// Undoes the last stroke or light edit (Ctrl+Z).
    pub fn undo(&mut self) {
        if let Some(document) = &self.document {
            self.history.settle(&document.scene.lights);
        }
        let step = self.history.undo();
        let message = self.carry_out(step, Direction::Undo);
        self.say_again(message);
    }

    /// Redoes the last undone stroke or light edit (Ctrl+Shift+Z or Ctrl+Y).
    pub fn redo(&mut self) {
        let step = self.history.redo();
        let message = self.carry_out(step, Direction::Redo);
        self.say_again(message);
    }

    /// Shows `message` as news even when it reads as the last one did ("nothing to undo"
    /// twice): the status bar times it afresh.
    fn say_again(&mut self, message: String) {
        self.message = message;
        self.message_seen.text.clear();
    }

    /// Whether Edit ▸ Undo and Redo have anything to do.
    pub fn can_undo(&self) -> bool {
        self.history.can_undo()
    }

    pub fn can_redo(&self) -> bool {
        self.history.can_redo()
    }

    /// Carries out an undo or redo step; the message to show.
    fn carry_out(&mut self, step: Option<Step>, direction: Direction) -> String {
        let (verb, nothing) = match direction {
            Direction::Undo => ("undid", "nothing to undo"),
            Direction::Redo => ("redid", "nothing to redo"),
        };
        let (Some(document), Some(painting), Some(step)) = (&mut self.document, &mut self.painting, step) else {
            return nothing.to_string();
        };
        let message = match step {
            Step::Stroke => {
                let done = match direction {
                    Direction::Undo => painting.undo(&mut document.scene),
                    Direction::Redo => painting.redo(&mut document.scene),
                };
                if done {
                    format!("{verb} the stroke")
                } else {
                    nothing.to_string()
                }
            }
            Step::SetLights(lights) => {
                let moved = lights.iter().zip(&document.scene.lights).any(|(a, b)| {
                    crate::project::bake_cache::light_hash(a) != crate::project::bake_cache::light_hash(b)
                });
                document.scene.lights = lights;
                self.lights_moved |= moved;
                format!("{verb} the light edit")
            }
        };
        self.history.resettle(&document.scene.lights);
        self.indirect_stale = true;
        self.lights_changed();
        message
    }

    /// Records a finished light edit (the pointer let go, no field focused) in the history.
    fn settle_light_edits(&mut self, ctx: &egui::Context) {
        let busy = ctx.input(|i| i.pointer.any_down()) || ctx.memory(|m| m.focused().is_some());
        if let (false, Some(document)) = (busy, &self.document) {
            self.history.settle(&document.scene.lights);
        }
    }

    fn lights_changed(&mut self) {
        if let (Some(document), Some(painting)) = (&mut self.document, &self.painting) {
            document.painting = painting.state();
        }
        self.upload_lights();
        self.refresh_baked_indirect();
    }

    /// Saves the document to `path` (a project file), recording the current camera.
    pub fn save_to(&mut self, path: &Path) {
        let Some(document) = &mut self.document else { return };
        if let Some(viewport) = &self.viewport {
            document.camera = Some(viewport.orbit);
        }
        match document.save(path) {
            Ok(()) => {
                self.preferences.remember(path);
                // The fit goes beside the project too, so it reopens without refitting.
                let spheres = sphere_cache::cache_path(path);
                if let Err(e) = sphere_cache::save(&spheres, &document.scene, &self.fitted_with, &self.blockers) {
                    log::warn!("the sphere fit could not be cached at {}: {e}", spheres.display());
                }
                self.saved = Some(document.to_project_file(path));
                self.message = format!("saved {}", path.display());
                if let Some(problem) = self.painting.as_mut().and_then(|p| p.save_cache(&document.scene, path)) {
                    self.message = problem;
                }
            }
            Err(e) => self.report_error(e.to_string()),
        }
    }

    pub(super) fn report_error(&mut self, message: String) {
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
    /// Whether the document differs from the file it was opened from or saved to. Where
    /// the camera looks is not a change (saving records it all the same): looking around
    /// and quitting must not ask to save.
    pub fn has_unsaved_changes(&self) -> bool {
        let Some(document) = &self.document else { return false };
        match (&document.project_path, &self.saved) {
            (Some(path), Some(saved)) => {
                let mut current = document.to_project_file(path);
                current.camera = saved.camera;
                current != *saved
            }
            _ => true,
        }
    }

    fn tool_bar(&mut self, ui: &mut egui::Ui) {
        let Some(painting) = &mut self.painting else { return };
        egui::Panel::top("tools").show(ui, |ui| tool_bar(ui, &mut painting.tool));
    }

    /// Frames the selection (F): the selected object, the space around the selected light
    /// (1 m each way), or everything when nothing (or a directional light) is selected.
    pub fn frame_selection(&mut self) {
        let (Some(viewport), Some(document)) = (&mut self.viewport, &self.document) else {
            return;
        };
        let scene = &document.scene;
        let bounds = match self.selection {
            Some(Selection::Object(index)) => scene.objects.get(index).map(|o| o.bounds()),
            Some(Selection::Light(index)) => scene.lights.get(index).filter(|l| l.kind.has_position()).map(|l| {
                crate::scene::Aabb::from_points(&[l.position - glam::Vec3::ONE, l.position + glam::Vec3::ONE])
            }),
            None => None,
        };
        match bounds.filter(|b| !b.is_empty()) {
            Some(bounds) => viewport.frame_bounds(&bounds),
            None => viewport.frame_all(scene),
        }
    }

    fn outliner(&mut self, ui: &mut egui::Ui, render_state: Option<&egui_wgpu::RenderState>) {
        let mut action = None;
        egui::Panel::left("outliner").default_size(220.0).show(ui, |ui| {
            ui.heading("Scene");
            let Some(document) = &self.document else { return };
            let hidden: Vec<bool> = (0..document.scene.objects.len())
                .map(|i| document.hidden_objects.contains(&i))
                .collect();
            let state = OutlinerState {
                selection: self.selection,
                hidden: &hidden,
                solo: self.solo_light,
            };
            action = outliner(ui, &document.scene, &state);
        });
        match action {
            Some(OutlinerAction::Select(selection)) => self.selection = Some(selection),
            Some(OutlinerAction::ToggleHidden(index)) => self.toggle_hidden(index),
            Some(OutlinerAction::Solo(light)) => self.solo(light),
            Some(OutlinerAction::AddLight) => self.add_light(),
            Some(OutlinerAction::ShowGltfScene(index)) => self.request_gltf_scene(index, render_state),
            None => {}
        }
    }

    fn status_bar(&mut self, ui: &mut egui::Ui, unsaved: bool) {
        egui::Panel::bottom("status").show(ui, |ui| {
            ui.horizontal(|ui| {
                if !self.options.hide_frame_timings {
                    let rate = match self.frame_clock.ms_per_frame() {
                        Some(ms) => format!("{:.0} fps ({ms:.1} ms)", 1000.0 / ms.max(1e-3)),
                        None => "– fps".to_string(),
                    };
                    ui.label(rate).on_hover_text(
                        "Frames per second while the view redraws (orbiting, painting, dragging); \
                         the editor at rest draws nothing and is not counted",
                    );
                    if let Some(viewport) = &self.viewport {
                        ui.label(format!("3D view sent in {:.1} ms", viewport.last_render_ms))
                            .on_hover_text(
                                "CPU time the last frame took to prepare and submit the 3D view's drawing; \
                                 the GPU's own time shows in the frame rate",
                            );
                    }
                    ui.separator();
                }
                ui.label(&self.adapter);
                ui.separator();
                if unsaved {
                    ui.colored_label(ui.visuals().warn_fg_color, "unsaved changes");
                    ui.separator();
                }
                // A message stays until another replaces it; once it is old, or the undo
                // history has changed since ("nothing to undo" after a new edit), it is
                // shown faded: it describes a moment that has passed.
                if self.message_seen.text != self.message {
                    self.message_seen = SeenMessage {
                        text: self.message.clone(),
                        at: std::time::Instant::now(),
                        history: (self.can_undo(), self.can_redo()),
                    };
                }
                let stale = self.status_message_is_stale();
                let color = if stale {
                    ui.visuals().weak_text_color()
                } else {
                    ui.visuals().text_color()
                };
                // Cut at the window's edge with an ellipsis; the whole of it on hover.
                ui.add(egui::Label::new(egui::RichText::new(&self.message).color(color)).truncate())
                    .on_hover_text(&self.message);
                if !stale {
                    ui.ctx().request_repaint_after(FRESH_MESSAGE);
                }
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
        let new_key = ctx.input(|i| i.key_pressed(egui::Key::N) && i.modifiers.command);
        if new_key {
            self.request_new();
        }
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
                self.undo();
            }
            if redo_key {
                self.redo();
            }
        }
        if frame_key && !typing {
            self.frame_selection();
        }
        if open_key {
            self.open_dialog(render_state);
        }
        if save_key {
            self.save_document();
        }
        if let Some(path) = dropped {
            self.request_open(&path, render_state);
        }
    }

    fn track_frame_time(&mut self) {
        self.frame_clock.tick(Instant::now());
    }

    /// "NAME.lightpaint • — lightpaint" (the dot: unsaved changes), as window managers
    /// and task bars show it.
    fn update_window_title(&mut self, ctx: &egui::Context, unsaved: bool) {
        let title = match &self.document {
            Some(document) => {
                let path = document.project_path.as_ref().unwrap_or(&document.scene_path);
                let name = path.file_name().map_or("untitled".into(), |n| n.to_string_lossy());
                let mark = if unsaved { " •" } else { "" };
                format!("{name}{mark} — lightpaint")
            }
            None => "lightpaint".to_string(),
        };
        if title != self.window_title {
            ctx.send_viewport_cmd(egui::ViewportCommand::Title(title.clone()));
            self.window_title = title;
        }
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
        // Compared with the saved file once a frame, for the title and the status bar.
        let unsaved = self.has_unsaved_changes();
        self.update_window_title(&ctx, unsaved);
        self.status_bar(ui, unsaved);
        if self.preferences.show_outliner {
            self.outliner(ui, render_state.as_ref());
        }
        if self.preferences.show_inspector {
            self.inspector(ui, render_state.as_ref());
        }
        if let Some(message) = self.painting.as_mut().and_then(Painting::poll_bake) {
            self.message = message;
            self.indirect_stale = true;
        }
        self.settle_light_edits(&ctx);
        self.rebake_moved_lights(&ctx);
        self.refresh_heat_map();
        if self.indirect_stale {
            self.refresh_baked_indirect();
        }
        let brush_radius = match self.painting.as_ref() {
            Some(p) if p.tool != Tool::Navigate => Some(p.brush.radius_px),
            _ => None,
        };
        let mut finished = None;
        let mut gizmo = GizmoOutput::default();
        let mut clicked_at = None;
        let mut recent = None;
        egui::CentralPanel::default().frame(egui::Frame::NONE).show(ui, |ui| {
            match (&mut self.viewport, &self.document, &render_state) {
                (Some(viewport), Some(document), Some(rs)) => {
                    let response = viewport.show(ui, rs, &document.settings, brush_radius.is_some());
                    if self.preferences.show_blockers {
                        let painter = ui.painter_at(response.rect);
                        let shown = self.blockers.shown_spheres(&document.hidden_objects);
                        draw_blockers(&painter, response.rect, &viewport.view(), &shown);
                        draw_meshes_without_spheres(
                            &painter,
                            response.rect,
                            &viewport.view(),
                            &document.scene,
                            &self.blockers,
                            &document.hidden_objects,
                        );
                    }
                    if let Some(Selection::Object(index)) = self.selection
                        && let Some(object) = document.scene.objects.get(index)
                    {
                        let view = viewport.view();
                        let rect = response.rect;
                        draw_outline(&ui.painter_at(rect), &box_outline(&object.bounds()), |p| {
                            super::viewport::screen_point(&view, rect, p)
                        });
                    }
                    if self.preferences.show_light_markers {
                        let selected = match self.selection {
                            Some(Selection::Light(index)) => Some(index),
                            _ => None,
                        };
                        let (pivot, distance) = (viewport.orbit.target, viewport.orbit.distance);
                        let paths: Vec<_> = viewport
                            .light_paths_at(&document.scene.lights, pivot, &document.settings.shadows)
                            .into_iter()
                            .map(|(path, _)| path)
                            .collect();
                        let lights = GizmoLights {
                            lights: &document.scene.lights,
                            selected,
                            paths: &paths,
                        };
                        gizmo = light_gizmo(ui, response.rect, &viewport.view(), lights, pivot, distance);
                    }
                    if let Some(radius) = brush_radius {
                        finished = self.brush_input.update(ui, &response);
                        self.brush_input.draw(ui, &response, radius);
                    } else if response.clicked_by(egui::PointerButton::Primary) {
                        clicked_at = response.interact_pointer_pos().map(|p| p - response.rect.min);
                    }
                }
                _ => recent = start_page(ui, &self.preferences.recent_files),
            }
        });
        if let Some(stroke) = finished {
            self.paint_stroke(&stroke);
        }
        if let Some(index) = gizmo.select {
            self.selection = Some(Selection::Light(index));
        } else if let Some(offset) = clicked_at {
            self.select_at(glam::Vec2::new(offset.x, offset.y));
        }
        if let Some((index, light)) = gizmo.edited {
            self.set_light(index, light);
        }
        if let Some(path) = recent {
            self.request_open(&path, render_state.as_ref());
        }
        if let (Some(document), Some(painting)) = (&mut self.document, &self.painting) {
            // Brush and strategy edits are part of the project (restored on reopening); the
            // strokes are copied only when they change (`lights_changed`), not every frame.
            document.painting.brush = painting.brush_for_file();
            document.painting.settings = painting.settings;
        }
        self.error_window(&ctx);
        self.export_window(&ctx);
        self.guard_unsaved_changes(&ctx, render_state.as_ref());
        if !self.first_frame_reported {
            self.first_frame_reported = true;
            eprintln!("{FIRST_FRAME_LINE}");
        }
        self.scripted_close(&ctx);
    }

    fn save(&mut self, storage: &mut dyn eframe::Storage) {
        self.preferences.store(storage);
    }
}

/// What the central panel shows without a document: how to start, and the recent files;
/// the one clicked, if any.
fn start_page(ui: &mut egui::Ui, recent_files: &[PathBuf]) -> Option<PathBuf> {
    let mut picked = None;
    ui.vertical_centered(|ui| {
        ui.add_space(ui.available_height() * 0.3);
        ui.heading("Nothing open");
        ui.label("File > Open… a project, or File > Import glTF… a scene (or drop one here).");
        if !recent_files.is_empty() {
            ui.add_space(12.0);
            ui.strong("Recent");
            for path in recent_files {
                let name = path
                    .file_name()
                    .map_or_else(|| path.display().to_string(), |n| n.to_string_lossy().into_owned());
                if ui.link(name).on_hover_text(path.display().to_string()).clicked() {
                    picked = Some(path.clone());
                }
            }
        }
    });
    picked
}
