//! File ▸ Export render as PNG: a small window asks the image's size — the viewport's,
//! a preset, or any other up to [`MAX_EXPORT_SIDE_PX`] — then where to write it; the
//! viewport's renderer draws the frame again at that size (same camera, lights and
//! settings, full quality), as `lightpaint render --width --height` would.

use std::path::Path;

use super::{EditorApp, file_dialog};

/// The longest side an export may have (lavapipe's and most GPUs' largest texture).
pub const MAX_EXPORT_SIDE_PX: u32 = 8192;

/// Sizes offered besides the viewport's.
const PRESETS: [(&str, [u32; 2]); 3] = [
    ("HD 1280 × 720", [1280, 720]),
    ("Full HD 1920 × 1080", [1920, 1080]),
    ("4K 3840 × 2160", [3840, 2160]),
];

impl EditorApp {
    /// Opens the export window, sized as the viewport's pixels to begin with.
    pub fn open_export_window(&mut self, pixels_per_point: f32) {
        let Some(size) = self.viewport_pixels(pixels_per_point) else {
            return self.report_error("nothing to export: no scene is shown".to_string());
        };
        self.export_size = Some(self.export_size.unwrap_or(size));
        self.export_window_open = true;
    }

    /// The viewport's size in pixels, within what an export may have (None: no viewport).
    fn viewport_pixels(&self, pixels_per_point: f32) -> Option<[u32; 2]> {
        let rect = self.viewport.as_ref()?.rect;
        Some(
            [rect.width(), rect.height()]
                .map(|side| ((side * pixels_per_point).round() as u32).clamp(1, MAX_EXPORT_SIDE_PX)),
        )
    }

    /// Whether the export window is open.
    pub fn is_export_window_open(&self) -> bool {
        self.export_window_open
    }

    pub(super) fn export_window(&mut self, ctx: &egui::Context) {
        if !self.export_window_open {
            return;
        }
        let Some(mut size) = self.export_size else { return };
        let viewport_size = self.viewport_pixels(ctx.pixels_per_point());
        let mut open = true;
        let mut export = false;
        egui::Window::new("Export render as PNG")
            .collapsible(false)
            .resizable(false)
            .open(&mut open)
            .show(ctx, |ui| {
                ui.horizontal(|ui| {
                    let label = ui.label("size").id;
                    for side in &mut size {
                        ui.add(egui::DragValue::new(side).range(1..=MAX_EXPORT_SIDE_PX).suffix(" px"))
                            .labelled_by(label);
                    }
                });
                ui.horizontal_wrapped(|ui| {
                    if let Some(viewport_size) = viewport_size
                        && ui
                            .button("as the viewport")
                            .on_hover_text("The viewport's own size in pixels")
                            .clicked()
                    {
                        size = viewport_size;
                    }
                    for (name, preset) in PRESETS {
                        if ui.button(name).clicked() {
                            size = preset;
                        }
                    }
                });
                ui.label("The same view, lights and settings, drawn again at this size at full quality.");
                export = ui.button("Export…").clicked();
            });
        self.export_size = Some(size);
        if export {
            self.export_window_open = false;
            let (folder, stem) = self.export_start();
            let dialog = rfd::FileDialog::new().add_filter("PNG image", &["png"]);
            let dialog = file_dialog::start_in(dialog, &folder, &format!("{stem}.png"));
            if let Some(path) = self.ask(|| dialog.save_file()) {
                self.export_png_sized(&path, size);
            }
        } else if !open {
            self.export_window_open = false;
        }
    }

    /// Where the export dialog starts: the project's folder and name.
    fn export_start(&self) -> (std::path::PathBuf, String) {
        self.session.as_ref().map(|s| &s.document).map_or_else(
            || (std::path::PathBuf::from("."), "render".to_string()),
            |d| {
                let (folder, name) = file_dialog::save_as_start(d.project_path.as_deref(), &d.scene_path);
                let stem = Path::new(&name)
                    .file_stem()
                    .map_or_else(|| "render".to_string(), |s| s.to_string_lossy().into_owned());
                (folder, stem)
            },
        )
    }

    /// Draws the view again at `size` pixels and writes it to `path` as PNG (atomically:
    /// a failed export leaves an existing file as it was).
    pub fn export_png_sized(&mut self, path: &Path, size: [u32; 2]) {
        let size = size.map(|side| side.clamp(1, MAX_EXPORT_SIDE_PX));
        let (Some(viewport), Some(document)) = (&mut self.viewport, self.session.as_ref().map(|s| &s.document)) else {
            return self.report_error("nothing to export: no scene is shown".to_string());
        };
        let settings = document.settings;
        match viewport.render_image_at(size, &settings) {
            Some(Ok(image)) => self.write_png(path, image),
            Some(Err(e)) => self.report_error(format!("could not read the render back: {e}")),
            None => self.report_error("nothing to export: the renderer drew nothing".to_string()),
        }
    }

    /// Writes `image` to `path` as PNG, atomically.
    pub(super) fn write_png(&mut self, path: &Path, image: image::RgbaImage) {
        let (width, height) = image.dimensions();
        let mut bytes = Vec::new();
        let encoded = image::DynamicImage::ImageRgba8(image)
            .to_rgb8()
            .write_to(&mut std::io::Cursor::new(&mut bytes), image::ImageFormat::Png);
        let written = encoded
            .map_err(|e| e.to_string())
            .and_then(|()| crate::project::replace_atomically(path, &bytes).map_err(|e| e.to_string()));
        match written {
            Ok(()) => self.message = format!("exported {} ({width} × {height})", path.display()),
            Err(e) => self.report_error(format!("could not write {}: {e}", path.display())),
        }
    }
}
