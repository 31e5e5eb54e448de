//! The eframe editor shell: a viewport with an orbit camera, the scene outliner, render
//! settings and a status bar. Every action calls into the library.

mod app;
mod blocker_overlay;
mod brush_input;
mod brush_panel;
mod export;
mod file_dialog;
mod frame_clock;
mod inspector;
mod light_gizmo;
mod light_inspector;
mod menus;
mod outliner;
mod outlines;
mod preferences;
mod shadow_panel;
mod terrain_panel;
mod unsaved_prompt;
mod viewport;
mod viewport_image;

pub use crate::session::Tool;
pub use app::{EditorApp, EditorOptions, FIRST_FRAME_LINE, FrameRateMeasurement};
pub use outliner::Selection;
pub use viewport::Viewport;

/// Opens the editor window and runs until it is closed.
pub fn run_editor(options: EditorOptions) -> Result<(), eframe::Error> {
    let native_options = eframe::NativeOptions {
        viewport: egui::ViewportBuilder::default()
            .with_title("lightpaint")
            .with_inner_size([1280.0, 800.0])
            .with_min_inner_size([640.0, 400.0]),
        renderer: eframe::Renderer::Wgpu,
        wgpu_options: primary_backends_unless_env(),
        persist_window: true,
        ..Default::default()
    };
    eframe::run_native(
        "lightpaint",
        native_options,
        Box::new(move |cc| {
            // The panels' background is the window's clear colour (EditorApp::clear_color)
            // rather than a rectangle egui shades per pixel: on lavapipe egui's shader cost
            // about 11 ms a frame for the panels of a 1513 × 618 window
            // (docs/performance.md). Test harnesses, which clear to transparent, keep the
            // filled panels.
            cc.egui_ctx
                .all_styles_mut(|style| style.visuals.panel_fill = egui::Color32::TRANSPARENT);
            Ok(Box::new(EditorApp::new(cc, options)))
        }),
    )
}

/// egui's wgpu set-up with only the primary backends (Vulkan, Metal, DX12) unless
/// `WGPU_BACKEND` says otherwise, as `render::GpuContext::headless` opens: the GL backend
/// cannot translate the shadow maps' `textureLoad` of depth textures, so on a machine
/// without Vulkan the editor failed at its first pipeline instead of saying that it
/// needs one (eframe's error names the missing adapter).
fn primary_backends_unless_env() -> eframe::egui_wgpu::WgpuConfiguration {
    let mut options = eframe::egui_wgpu::WgpuConfiguration::default();
    if let eframe::egui_wgpu::WgpuSetup::CreateNew(create_new) = &mut options.wgpu_setup
        && std::env::var_os("WGPU_BACKEND").is_none()
    {
        create_new.instance_descriptor.backends = eframe::wgpu::Backends::PRIMARY;
    }
    options
}
