//! The editor application: its state (`EditorApp`), how it starts, and each frame's
//! layout; its other duties live in the child modules (documents, lights, strokes, the
//! window's chrome), each an `impl EditorApp` of its own.

use std::path::{Path, PathBuf};
use std::time::Instant;

use super::Viewport;
use super::blocker_overlay::{BlockerSummary, draw_blocker_summary, draw_blockers, draw_meshes_without_spheres};
use super::brush_input::BrushInput;
use super::brush_panel::tool_bar;
use super::light_gizmo::{GizmoLights, GizmoOutput, light_gizmo};
use super::outliner::{OutlinerAction, OutlinerState, Selection, outliner};
use super::outlines::{box_outline, draw_kept_points, draw_outline};
use super::preferences::Preferences;
use super::terrain_panel::{TerrainEdit, image_terrain};
use super::unsaved_prompt::{self, Answer, Pending};
use crate::blockers::{BlockerSettings, SceneBlockers};
use crate::paint::BrushKind;
use crate::project::sphere_cache;
use crate::project::{Document, ProjectFile};
use crate::render::describe_adapter;
use crate::scene::Light;
use crate::session::{EditorSession, Painting, ScreenStroke, Tool};

mod chrome;
mod documents;
mod lights;
mod strokes;

/// How the editor starts.
#[derive(Debug, Clone, Default)]
pub struct EditorOptions {
    /// The project or scene to open.
    pub file: PathBuf,
    /// Scripted runs (the smoke test): close the window cleanly once this file exists.
    pub close_when_file_exists: Option<PathBuf>,
    /// Leave frame timings out of the status bar, so screenshots are reproducible.
    pub hide_frame_timings: bool,
    /// Measurement runs (scripts/editor-frame-rate.sh): draw every frame and print the
    /// frame rate on stderr every two seconds.
    pub measure_frame_rate: FrameRateMeasurement,
}

/// What a measurement run of the editor draws every frame.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum FrameRateMeasurement {
    /// Nothing: frames follow input, as usual.
    #[default]
    Off,
    /// The viewport's frame at full quality after the lights were set again (as during a
    /// stroke: the view rests, the lights change), and the interface.
    AfterLightEdit,
    /// The viewport's frame drawn from nothing at full quality (as the first frame after
    /// the camera stops), and the interface.
    NewView,
    /// The interface around the frame drawn before: what the editor costs besides the
    /// renderer.
    InterfaceOnly,
}

/// Line printed on stderr once the first frame with the scene has been drawn; scripts
/// wait for it before they look at the window.
pub const FIRST_FRAME_LINE: &str = "lightpaint: first frame drawn";

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
    /// The window's wgpu device, queue and egui renderer (None in harnesses without a GPU):
    /// what the viewport draws with.
    render_state: Option<egui_wgpu::RenderState>,
    /// The open document with its painting state and undo history (None: nothing open).
    pub(super) session: Option<EditorSession>,
    /// The project as last opened or saved, to tell whether there are unsaved changes.
    pub(super) saved: Option<ProjectFile>,
    pub(super) viewport: Option<Viewport>,
    /// Sphere blockers fitted to the document's meshes, and the settings they were fitted with.
    pub(super) blockers: SceneBlockers,
    pub(super) fitted_with: BlockerSettings,
    /// The blocker overlay's summary line, worked out again only when its inputs change.
    blocker_summary: BlockerSummary,
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
    /// When the frame rate was last printed (EditorOptions::measure_frame_rate).
    pub(super) frame_rate_printed_at: Option<std::time::Instant>,
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
    /// Recent files and view choices, kept between runs.
    pub(super) preferences: Preferences,
    /// What the viewport's heat map shows (None: no heat map) and the value its
    /// brightest colour stands for (cd/m²).
    pub(super) heat_map: Option<(HeatMapKey, f32)>,
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
            session: None,
            saved: None,
            viewport: None,
            blockers: SceneBlockers::default(),
            fitted_with: BlockerSettings::default(),
            blocker_summary: BlockerSummary::default(),
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
            frame_rate_printed_at: None,
            brush_input: BrushInput::default(),
            pending: None,
            closing: false,
            indirect_stale: true,
            terrain_editing: None,
            selection: None,
            preferences: Preferences::load(cc.storage),
            heat_map: None,
            render_state: cc.wgpu_render_state.clone(),
        };
        app.open(&options.file);
        app
    }

    /// Selects what the viewport shows at `offset` (points from its top-left corner): the
    /// nearest shown object under it, or nothing.
    pub fn select_at(&mut self, offset: glam::Vec2) {
        let (Some(session), Some(viewport)) = (&mut self.session, &self.viewport) else {
            return;
        };
        let (document, painting) = (&session.document, &mut session.painting);
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

    /// Whether the viewport is compiling shaders for new shadow settings (it keeps drawing
    /// the previous ones meanwhile).
    pub fn is_compiling_shaders(&self) -> bool {
        self.viewport.as_ref().is_some_and(Viewport::is_compiling_shaders)
    }

    /// The open document's render settings, to change them as the inspector does.
    pub fn render_settings_mut(&mut self) -> Option<&mut crate::shading::RenderSettings> {
        self.session.as_mut().map(|s| &mut s.document).map(|d| &mut d.settings)
    }

    /// The current selection in the outliner, inspector and viewport.
    pub fn selection(&self) -> Option<Selection> {
        self.selection
    }

    pub fn select(&mut self, selection: Option<Selection>) {
        self.selection = selection;
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

    /// The viewport's last frame as the renderer drew it, read back (None without one).
    pub fn viewport_image(&self) -> Option<Result<image::RgbaImage, crate::render::RenderError>> {
        self.viewport.as_ref()?.read_image()
    }

    /// Where the viewport's camera looks from (None without a viewport).
    pub fn orbit(&self) -> Option<crate::scene::OrbitCamera> {
        self.viewport.as_ref().map(|v| v.orbit)
    }

    /// Intensities of the document's lights, in order.
    pub fn light_intensities(&self) -> Vec<f32> {
        self.document().map(|d| d.scene.light_intensities()).unwrap_or_default()
    }

    /// Frames the selection (F): the selected object, the space around the selected light
    /// (1 m each way), or everything when nothing (or a directional light) is selected.
    pub fn frame_selection(&mut self) {
        let (Some(viewport), Some(document)) = (&mut self.viewport, self.session.as_ref().map(|s| &s.document)) else {
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
}

impl eframe::App for EditorApp {
    /// The theme's panel colour: the editor's window draws its panels without a fill
    /// (`run_editor`), so the clear colour is their background.
    fn clear_color(&self, visuals: &egui::Visuals) -> [f32; 4] {
        let theme = if visuals.dark_mode {
            egui::Visuals::dark()
        } else {
            egui::Visuals::light()
        };
        theme.panel_fill.to_normalized_gamma_f32()
    }

    fn ui(&mut self, ui: &mut egui::Ui, _frame: &mut eframe::Frame) {
        let ctx = ui.ctx().clone();
        self.track_frame_time(&ctx);
        self.handle_shortcuts_and_drops(&ctx);
        self.take_up_saved_strokes();
        self.menu_bar(ui);
        self.tool_bar(ui);
        // Compared with the saved file once a frame, for the title and the status bar.
        let unsaved = self.has_unsaved_changes();
        self.update_window_title(&ctx, unsaved);
        self.status_bar(ui, unsaved);
        if self.preferences.show_outliner {
            self.outliner(ui);
        }
        if self.preferences.show_inspector {
            self.inspector(ui);
        }
        if let Some(message) = self
            .session
            .as_mut()
            .map(|s| &mut s.painting)
            .and_then(Painting::poll_bake)
        {
            self.message = message;
            self.indirect_stale = true;
        }
        self.settle_light_edits(&ctx);
        self.rebake_moved_lights(&ctx);
        self.refresh_heat_map();
        if self.indirect_stale {
            self.refresh_baked_indirect();
        }
        let brush_radius = match self.session.as_ref().map(|s| &s.painting) {
            Some(p) if p.tool != Tool::Navigate => Some(p.brush.radius_px),
            _ => None,
        };
        let mut finished = None;
        let mut gizmo = GizmoOutput::default();
        let mut clicked_at = None;
        let mut recent = None;
        egui::CentralPanel::default().frame(egui::Frame::NONE).show(ui, |ui| {
            match (
                &mut self.viewport,
                self.session.as_ref().map(|s| &s.document),
                &self.render_state,
            ) {
                (Some(viewport), Some(document), Some(rs)) => {
                    let response = viewport.show(ui, rs, &document.settings, brush_radius.is_some());
                    if self.preferences.show_blockers {
                        let painter = ui.painter_at(response.rect);
                        let shown = self.blockers.shown_spheres(&document.hidden_objects);
                        draw_blockers(&painter, response.rect, &viewport.view(), &shown);
                        draw_blocker_summary(
                            &painter,
                            response.rect,
                            &mut self.blocker_summary,
                            &shown,
                            (&document.scene, &document.hidden_objects),
                            &document.settings.shadows,
                        );
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
                    if let Some(painting) = self.session.as_ref().map(|s| &s.painting) {
                        let kept: Vec<glam::Vec3> = painting.kept_points(&document.scene);
                        let (view, rect) = (viewport.view(), response.rect);
                        // Stronger while a tool that works on them is in hand.
                        let keeping = matches!(painting.tool, Tool::Brush(BrushKind::Constraint | BrushKind::Release));
                        draw_kept_points(&ui.painter_at(rect), &kept, keeping, |p| {
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
            self.request_open(&path);
        }
        self.error_window(&ctx);
        self.export_window(&ctx);
        self.guard_unsaved_changes(&ctx);
        if !self.first_frame_reported {
            self.first_frame_reported = true;
            eprintln!("{FIRST_FRAME_LINE}");
        }
        self.scripted_close(&ctx);
        self.measure_frame_rate(&ctx);
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
