//! The 3D viewport: renders the scene offscreen with the [`ScenePipeline`] into a texture
//! that egui shows, and turns mouse input into orbit (left drag), pan (right or middle
//! drag, or shift + left drag) and zoom (scroll).

use crate::render::{GpuScene, RenderSettings, RenderTarget, ScenePipeline};
use crate::scene::{Environment, Light, OrbitCamera, Scene};

pub struct Viewport {
    pipeline: ScenePipeline,
    gpu_scene: GpuScene,
    target: Option<RenderTarget>,
    texture_id: Option<egui::TextureId>,
    pub orbit: OrbitCamera,
    /// Settings and camera of the image in the texture, to skip redundant renders.
    rendered: Option<(OrbitCamera, RenderSettings, [u32; 2])>,
    /// Milliseconds the last scene render took on the CPU side (submission included).
    pub last_render_ms: f32,
}

/// The orbit camera matching the scene's initial camera, pivoting at the scene's centre
/// distance.
pub fn scene_orbit(scene: &Scene) -> OrbitCamera {
    let camera = scene.initial_camera();
    let pivot = (scene.bounds().center() - camera.position).length().max(0.1);
    OrbitCamera::from_camera(&camera, pivot)
}

/// Radians of orbit per point of mouse drag.
const ORBIT_RAD_PER_POINT: f32 = 0.008;

impl Viewport {
    /// A viewport on `scene`, seen from `orbit` or, without one, from the scene's camera.
    pub fn new(render_state: &egui_wgpu::RenderState, scene: &Scene, orbit: Option<OrbitCamera>) -> Viewport {
        let pipeline = ScenePipeline::new(&render_state.device);
        let gpu_scene = GpuScene::upload(&render_state.device, &render_state.queue, &pipeline.layouts, scene);
        Viewport {
            pipeline,
            gpu_scene,
            target: None,
            texture_id: None,
            orbit: orbit.unwrap_or_else(|| scene_orbit(scene)),
            rendered: None,
            last_render_ms: 0.0,
        }
    }

    /// Uploads changed lights; the next frame shows them.
    pub fn set_lights(&mut self, render_state: &egui_wgpu::RenderState, lights: &[Light]) {
        self.gpu_scene.update_lights(
            &render_state.device,
            &render_state.queue,
            &self.pipeline.layouts,
            lights,
        );
        self.rendered = None;
    }

    /// Replaces the environment light; the next frame shows it.
    pub fn set_environment(&mut self, environment: Option<&Environment>) {
        self.gpu_scene.set_environment(environment);
        self.rendered = None;
    }

    /// Frames the whole scene.
    pub fn frame_all(&mut self, scene: &Scene) {
        let framing = OrbitCamera::framing(&scene.bounds());
        self.orbit = framing;
    }

    /// Lays out the viewport in the remaining space of `ui`, handles its input and paints it.
    pub fn show(&mut self, ui: &mut egui::Ui, render_state: &egui_wgpu::RenderState, settings: &RenderSettings) {
        let rect = ui.available_rect_before_wrap();
        let response = ui.allocate_rect(rect, egui::Sense::click_and_drag());
        self.handle_input(ui, &response);

        let pixels_per_point = ui.ctx().pixels_per_point();
        let size = [
            ((rect.width() * pixels_per_point).round() as u32).max(1),
            ((rect.height() * pixels_per_point).round() as u32).max(1),
        ];
        let wanted = (self.orbit, *settings, size);
        if self.rendered != Some(wanted) {
            self.render(render_state, settings, size);
            self.rendered = Some(wanted);
        }
        if let Some(id) = self.texture_id {
            let uv = egui::Rect::from_min_max(egui::pos2(0.0, 0.0), egui::pos2(1.0, 1.0));
            ui.painter().image(id, rect, uv, egui::Color32::WHITE);
        }
    }

    fn handle_input(&mut self, ui: &egui::Ui, response: &egui::Response) {
        let shift = ui.input(|i| i.modifiers.shift);
        let delta = response.drag_delta();
        let height = response.rect.height().max(1.0);
        if response.dragged_by(egui::PointerButton::Primary) && !shift {
            self.orbit
                .orbit(-delta.x * ORBIT_RAD_PER_POINT, delta.y * ORBIT_RAD_PER_POINT);
        } else if response.dragged_by(egui::PointerButton::Secondary)
            || response.dragged_by(egui::PointerButton::Middle)
            || (response.dragged_by(egui::PointerButton::Primary) && shift)
        {
            self.orbit.pan(-delta.x / height, delta.y / height);
        }
        if response.hovered() {
            let scroll = ui.input(|i| i.smooth_scroll_delta.y);
            if scroll != 0.0 {
                self.orbit.zoom((-scroll * 0.002).exp());
            }
        }
    }

    fn render(&mut self, render_state: &egui_wgpu::RenderState, settings: &RenderSettings, size: [u32; 2]) {
        let started = std::time::Instant::now();
        let device = &render_state.device;
        let resized = self.target.as_ref().is_none_or(|t| [t.width, t.height] != size);
        if resized {
            let target = RenderTarget::new(device, size[0], size[1]);
            let mut renderer = render_state.renderer.write();
            match self.texture_id {
                Some(id) => renderer.update_egui_texture_from_wgpu_texture(
                    device,
                    &target.display_view,
                    wgpu::FilterMode::Linear,
                    id,
                ),
                None => {
                    self.texture_id =
                        Some(renderer.register_native_texture(device, &target.display_view, wgpu::FilterMode::Linear))
                }
            }
            self.target = Some(target);
        }
        let Some(target) = &self.target else { return };
        let camera = self.orbit.camera();
        self.gpu_scene.write_frame(
            &render_state.queue,
            &camera,
            size[0] as f32 / size[1] as f32,
            settings.exposure_ev,
        );
        let mut encoder = device.create_command_encoder(&Default::default());
        self.pipeline
            .draw(&mut encoder, target, &self.gpu_scene, settings.background_linear());
        render_state.queue.submit([encoder.finish()]);
        self.last_render_ms = started.elapsed().as_secs_f32() * 1000.0;
    }
}
