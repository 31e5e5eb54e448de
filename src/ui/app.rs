use std::path::{Path, PathBuf};
use std::time::Instant;

use super::Viewport;
use crate::render::{RenderSettings, describe_adapter};
use crate::scene::Scene;

/// How the editor starts.
#[derive(Debug, Clone, Default)]
pub struct EditorOptions {
    /// The scene to open.
    pub file: PathBuf,
    /// Scripted runs (the smoke test): close the window cleanly once this file exists.
    pub close_when_file_exists: Option<PathBuf>,
}

/// Line printed on stderr once the first frame with the scene has been drawn; scripts
/// wait for it before they look at the window.
pub const FIRST_FRAME_LINE: &str = "lightpaint: first frame drawn";

const SETTINGS_KEY: &str = "render_settings";

pub struct EditorApp {
    scene: Scene,
    scene_path: PathBuf,
    viewport: Option<Viewport>,
    settings: RenderSettings,
    adapter: String,
    /// The last thing worth telling the user, shown in the status bar.
    message: String,
    /// A load error waiting to be acknowledged in a window.
    error: Option<String>,
    options: EditorOptions,
    last_frame: Option<Instant>,
    frame_ms: f32,
    first_frame_reported: bool,
}

impl EditorApp {
    pub fn new(cc: &eframe::CreationContext<'_>, options: EditorOptions) -> EditorApp {
        let settings = cc
            .storage
            .and_then(|s| eframe::get_value(s, SETTINGS_KEY))
            .unwrap_or_default();
        let adapter = cc
            .wgpu_render_state
            .as_ref()
            .map(|rs| describe_adapter(&rs.adapter.get_info()))
            .unwrap_or_else(|| "no wgpu adapter".into());
        let mut app = EditorApp {
            scene: Scene::default(),
            scene_path: options.file.clone(),
            viewport: None,
            settings,
            adapter,
            message: String::new(),
            error: None,
            options: options.clone(),
            last_frame: None,
            frame_ms: 0.0,
            first_frame_reported: false,
        };
        app.open(&options.file, cc.wgpu_render_state.as_ref());
        app
    }

    /// Loads a scene and replaces the current one; on failure the current scene stays and
    /// the error is shown.
    pub fn open(&mut self, path: &Path, render_state: Option<&egui_wgpu::RenderState>) {
        match Scene::load(path) {
            Ok(scene) => {
                self.message = format!(
                    "opened {} — {} objects, {} vertices, {} lights{}",
                    path.display(),
                    scene.objects.len(),
                    scene.vertex_count(),
                    scene.lights.len(),
                    if scene.warnings.is_empty() {
                        String::new()
                    } else {
                        format!(", {} warning(s): {}", scene.warnings.len(), scene.warnings.join("; "))
                    }
                );
                self.viewport = render_state.map(|rs| Viewport::new(rs, &scene));
                self.scene = scene;
                self.scene_path = path.to_path_buf();
            }
            Err(e) => {
                log::error!("{e}");
                self.message = e.to_string();
                self.error = Some(e.to_string());
            }
        }
    }

    fn menu_bar(&mut self, ui: &mut egui::Ui, render_state: Option<&egui_wgpu::RenderState>) {
        egui::Panel::top("menu").show(ui, |ui| {
            egui::MenuBar::new().ui(ui, |ui| {
                ui.menu_button("File", |ui| {
                    if ui.button("Open glTF…").clicked() {
                        self.open_dialog(render_state);
                    }
                    ui.separator();
                    if ui.button("Quit").clicked() {
                        ui.ctx().send_viewport_cmd(egui::ViewportCommand::Close);
                    }
                });
                ui.menu_button("View", |ui| {
                    if ui.button("Frame all (F)").clicked()
                        && let Some(viewport) = &mut self.viewport
                    {
                        viewport.frame_all(&self.scene);
                    }
                });
            });
        });
    }

    fn open_dialog(&mut self, render_state: Option<&egui_wgpu::RenderState>) {
        let picked = rfd::FileDialog::new()
            .add_filter("glTF scene", &["gltf", "glb"])
            .pick_file();
        if let Some(path) = picked {
            self.open(&path, render_state);
        }
    }

    fn outliner(&mut self, ui: &mut egui::Ui) {
        egui::Panel::left("outliner").default_size(220.0).show(ui, |ui| {
            ui.heading("Scene");
            egui::ScrollArea::vertical().show(ui, |ui| {
                egui::CollapsingHeader::new(format!("Objects ({})", self.scene.objects.len()))
                    .default_open(true)
                    .show(ui, |ui| {
                        for object in &self.scene.objects {
                            ui.label(&object.name);
                        }
                    });
                egui::CollapsingHeader::new(format!("Lights ({})", self.scene.lights.len()))
                    .default_open(true)
                    .show(ui, |ui| {
                        for light in &self.scene.lights {
                            ui.label(format!("{} — {}", light.name, light.kind.label()));
                        }
                    });
            });
        });
    }

    fn inspector(&mut self, ui: &mut egui::Ui) {
        egui::Panel::right("inspector").default_size(240.0).show(ui, |ui| {
            ui.heading("Render");
            ui.add(egui::Slider::new(&mut self.settings.exposure_ev, -8.0..=8.0).text("exposure (EV)"));
            ui.horizontal(|ui| {
                ui.label("background");
                ui.color_edit_button_srgb(&mut self.settings.background_srgb8);
            });
            ui.separator();
            ui.heading("Lights");
            egui::Grid::new("lights").striped(true).show(ui, |ui| {
                for light in &self.scene.lights {
                    let unit = match light.kind {
                        crate::scene::LightKind::Directional => "lx",
                        _ => "cd",
                    };
                    ui.label(&light.name);
                    ui.label(format!("{:.3} {unit}", light.intensity));
                    ui.end_row();
                }
            });
        });
    }

    fn status_bar(&mut self, ui: &mut egui::Ui) {
        egui::Panel::bottom("status").show(ui, |ui| {
            ui.horizontal(|ui| {
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
                ui.label(&self.adapter);
                ui.separator();
                ui.label(&self.message);
            });
        });
    }

    fn error_window(&mut self, ctx: &egui::Context) {
        let Some(error) = self.error.clone() else { return };
        let mut open = true;
        egui::Window::new("Cannot open file")
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
        let (frame_key, open_key, dropped) = ctx.input(|i| {
            (
                i.key_pressed(egui::Key::F) && !i.modifiers.any(),
                i.key_pressed(egui::Key::O) && i.modifiers.command,
                i.raw.dropped_files.first().map(|f| f.path().to_path_buf()),
            )
        });
        if frame_key
            && !ctx.egui_wants_keyboard_input()
            && let Some(viewport) = &mut self.viewport
        {
            viewport.frame_all(&self.scene);
        }
        if open_key {
            self.open_dialog(render_state);
        }
        if let Some(path) = dropped {
            self.open(&path, render_state);
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
        self.status_bar(ui);
        self.outliner(ui);
        self.inspector(ui);
        egui::CentralPanel::default().frame(egui::Frame::NONE).show(ui, |ui| {
            match (&mut self.viewport, &render_state) {
                (Some(viewport), Some(rs)) => viewport.show(ui, rs, &self.settings),
                _ => {
                    ui.centered_and_justified(|ui| ui.label("No scene loaded. File ▸ Open glTF…"));
                }
            }
        });
        self.error_window(&ctx);
        if !self.first_frame_reported {
            self.first_frame_reported = true;
            eprintln!("{FIRST_FRAME_LINE}");
        }
        self.scripted_close(&ctx);
    }

    fn save(&mut self, storage: &mut dyn eframe::Storage) {
        eframe::set_value(storage, SETTINGS_KEY, &self.settings);
    }
}
