//! The 3D viewport: shows the frames of the scene renderer ([`SceneRenderer`], the one
//! the CLI renders with too) as an egui texture, and turns mouse input into orbit (left
//! drag), pan (right or middle drag, or shift + left drag) and zoom (scroll); with a brush
//! tool the left drag belongs to the brush (`brush_input.rs`) and the right drag orbits.
//! While the camera moves, frames are shaded at half the resolution in each direction (a
//! quarter of the pixels) and per vertex, so orbiting stays fluid on a software GPU; the
//! full frame follows as soon as the camera rests.

use super::viewport_image::ViewportImage;
use crate::blockers::Sphere;
use crate::render::renderer::same_but_terrain;
use crate::render::{AntiAliasing, Compilation, FrameQuality, SceneRenderer};
use crate::scene::{Environment, Light, OrbitCamera, Scene};
use crate::shading::{BakedIndirect, RenderSettings, ShadowSettings};

/// What the texture shows, to skip redundant renders.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Shown {
    orbit: OrbitCamera,
    settings: RenderSettings,
    size: [u32; 2],
    full_resolution: bool,
}

pub struct Viewport {
    renderer: SceneRenderer,
    /// The rendered frame as egui draws it (None before the first frame).
    image: Option<ViewportImage>,
    pub orbit: OrbitCamera,
    rendered: Option<Shown>,
    /// Milliseconds the last scene render took on the CPU side (submission included).
    pub last_render_ms: f32,
    /// Where the viewport was last shown, in points.
    pub rect: egui::Rect,
}

/// Where world point `p` appears on screen (points) in a viewport at `rect` seen through
/// `view` (its size in points), None behind the eye; not clipped to `rect`.
pub fn screen_point(view: &crate::paint::View, rect: egui::Rect, p: glam::Vec3) -> Option<egui::Pos2> {
    view.project(p).map(|q| rect.min + egui::vec2(q.x, q.y))
}

/// Radians of orbit per point of mouse drag.
const ORBIT_RAD_PER_POINT: f32 = 0.008;

/// How the viewport smooths edges: the edge filter (compiled once by the renderer and
/// shared by the targets made as the size changes), a few milliseconds on lavapipe where
/// multisampling more than doubles the frame time.
const ANTI_ALIASING: AntiAliasing = AntiAliasing::EdgeFilter;

impl Viewport {
    /// A viewport on `scene`, seen from `orbit` or, without one, from the scene's camera.
    pub fn new(
        render_state: &egui_wgpu::RenderState,
        scene: &Scene,
        orbit: Option<OrbitCamera>,
        blockers: &[Sphere],
        shadows: &ShadowSettings,
    ) -> Viewport {
        let renderer = SceneRenderer::new(
            &render_state.device,
            &render_state.queue,
            scene,
            blockers,
            shadows,
            ANTI_ALIASING,
            Compilation::Background,
        );
        Viewport {
            renderer,
            image: None,
            orbit: orbit.unwrap_or_else(|| scene.initial_orbit()),
            rendered: None,
            last_render_ms: 0.0,
            rect: egui::Rect::NOTHING,
        }
    }

    /// For each of `lights`: the shadow path it takes under `settings`, and
    /// its angular radius seen from `point` in degrees.
    pub fn light_paths_at(
        &self,
        lights: &[Light],
        point: glam::Vec3,
        settings: &ShadowSettings,
    ) -> Vec<(crate::shading::ShadowPath, f64)> {
        self.renderer.light_paths_at(lights, point, settings)
    }

    /// Uploads changed lights; the next frame shows them.
    pub fn set_lights(&mut self, lights: &[Light]) {
        self.renderer.set_lights(lights);
        self.rendered = None;
    }

    /// Shows per-vertex `values` (one list per scene object) as a heat map against
    /// `scale` instead of the shading; None goes back to the shading.
    pub fn set_heat_map(&mut self, values: Option<(&[Vec<f32>], f32)>) {
        self.renderer.set_heat_map(values);
        self.rendered = None;
    }

    /// Hides the objects `hidden` lists (indices into the scene's objects); shows the rest.
    pub fn set_hidden(&mut self, hidden: &std::collections::BTreeSet<usize>) {
        self.renderer.set_hidden(hidden);
        self.rendered = None;
    }

    /// Replaces the baked indirect light (None: none); the next frame shows it.
    pub fn set_baked_indirect(&mut self, indirect: Option<&BakedIndirect>) {
        self.renderer.set_baked_indirect(indirect);
        self.rendered = None;
    }

    /// Replaces the environment light; the next frame shows it.
    pub fn set_environment(&mut self, environment: Option<&Environment>) {
        self.renderer.set_environment(environment);
        self.rendered = None;
    }

    /// Draws the next frame from nothing even if nothing changed, as after a move of the
    /// camera (frame-rate measurements).
    pub fn draw_anew(&mut self) {
        self.renderer.forget_surfaces();
        self.rendered = None;
    }

    /// The shadow maps' views and memory in words, None when no light takes a map.
    pub fn shadow_maps_in_words(&self) -> Option<String> {
        self.renderer.shadow_maps_in_words()
    }

    /// The lights' grid the frames walk, in words (None when they walk every light).
    pub fn light_grid_in_words(&self) -> Option<String> {
        self.renderer.light_grid_in_words()
    }

    /// Whether shaders for new shadow settings are being compiled (the viewport shows
    /// the previous settings until they are ready).
    pub fn is_compiling_shaders(&self) -> bool {
        self.renderer.compiling().is_some()
    }

    /// Replaces the blockers; the next frame shows their shadows.
    pub fn set_blockers(&mut self, blockers: &[Sphere]) {
        self.renderer.set_blockers(blockers);
        self.rendered = None;
    }

    /// The image the viewport shows, read back from the GPU (None before the first frame).
    pub fn read_image(&self) -> Option<Result<image::RgbaImage, crate::render::RenderError>> {
        self.renderer.read_image()
    }

    /// The frame the viewport shows, drawn again at `size` pixels (same camera, settings
    /// and lights, full quality) and read back; the viewport draws at its own size again
    /// when next shown.
    pub fn render_image_at(
        &mut self,
        size: [u32; 2],
        settings: &RenderSettings,
    ) -> Option<Result<image::RgbaImage, crate::render::RenderError>> {
        self.renderer
            .render(&self.orbit.camera(), size, settings, FrameQuality::default());
        self.rendered = None;
        self.renderer.read_image()
    }

    /// The camera and the viewport's size in points, as the brush and the gizmo see it.
    pub fn view(&self) -> crate::paint::View {
        crate::paint::View {
            camera: self.orbit.camera(),
            width_px: self.rect.width().round().max(1.0) as u32,
            height_px: self.rect.height().round().max(1.0) as u32,
        }
    }

    /// Frames the whole scene.
    pub fn frame_all(&mut self, scene: &Scene) {
        self.frame_bounds(&scene.bounds());
    }

    /// Frames `bounds` (an object, or the space around a light).
    pub fn frame_bounds(&mut self, bounds: &crate::scene::Aabb) {
        self.orbit = OrbitCamera::framing(bounds);
    }

    /// Lays out the viewport in the remaining space of `ui`, handles its input and paints it.
    /// Draws the viewport and handles camera input; returns the viewport's response so a
    /// brush can read the pointer (`brush_tool`: the left drag is the brush's).
    pub fn show(
        &mut self,
        ui: &mut egui::Ui,
        render_state: &egui_wgpu::RenderState,
        settings: &RenderSettings,
        brush_tool: bool,
    ) -> egui::Response {
        // A terrain knob rebuilds the terrain's model (its surface cache is marched anew):
        // while a slider is dragged the viewport keeps the old one, and takes the new on release.
        let dragging = ui.input(|i| i.pointer.any_down());
        if self.renderer.poll() {
            self.rendered = None;
        }
        let drawn = *self.renderer.shadow_settings();
        let only_terrain_changed = same_but_terrain(&settings.shadows, &drawn);
        let asked = self.renderer.compiling().copied().unwrap_or(drawn);
        if settings.shadows != asked && !(only_terrain_changed && dragging) {
            self.renderer.set_shadow_settings(settings.shadows);
            self.rendered = None;
        }
        if self.renderer.compiling().is_some() {
            // Look again for the compiled pipeline while the frame stays as it is.
            ui.ctx().request_repaint_after(std::time::Duration::from_millis(100));
        }
        let rect = ui.available_rect_before_wrap();
        self.rect = rect;
        let response = ui.allocate_rect(rect, egui::Sense::click_and_drag());
        let moving = self.handle_input(ui, &response, brush_tool);

        let pixels_per_point = ui.ctx().pixels_per_point();
        let scale = pixels_per_point * settings.viewport_resolution_scale.clamp(0.25, 1.0);
        let full = [
            ((rect.width() * scale).round() as u32).max(1),
            ((rect.height() * scale).round() as u32).max(1),
        ];
        let size = if moving {
            full.map(|side| side.div_ceil(2))
        } else {
            full
        };
        let wanted = Shown {
            orbit: self.orbit,
            settings: *settings,
            size,
            full_resolution: !moving,
        };
        if !dragging && self.renderer.maps_drafted() {
            // A light's drag ended: its maps drawn in full.
            self.rendered = None;
        }
        if self.rendered != Some(wanted) {
            self.render(render_state, settings, size, moving, dragging);
            self.rendered = Some(wanted);
        }
        if moving {
            // Come back for the full-resolution frame once the camera rests.
            ui.ctx().request_repaint();
        }
        if let Some(image) = &self.image {
            image.paint(ui.painter(), rect);
        }
        if let Some(compiling) = self.renderer.compiling() {
            let text = format!("compiling shaders for order {} ({:?})…", compiling.order, compiling.exp);
            let at = rect.left_bottom() + egui::vec2(8.0, -8.0);
            let painter = ui.painter_at(rect);
            let galley = painter.layout_no_wrap(text, egui::FontId::proportional(14.0), egui::Color32::WHITE);
            let backing = egui::Rect::from_min_size(at - egui::vec2(0.0, galley.size().y), galley.size()).expand(4.0);
            painter.rect_filled(backing, 4.0, egui::Color32::from_black_alpha(160));
            painter.galley(backing.min + egui::vec2(4.0, 4.0), galley, egui::Color32::WHITE);
        }
        response
    }

    /// Applies orbit, pan and zoom; true while the camera is being moved.
    fn handle_input(&mut self, ui: &egui::Ui, response: &egui::Response, brush_tool: bool) -> bool {
        let shift = ui.input(|i| i.modifiers.shift);
        let delta = response.drag_delta();
        let height = response.rect.height().max(1.0);
        let orbit_button = if brush_tool {
            egui::PointerButton::Secondary
        } else {
            egui::PointerButton::Primary
        };
        let pan_buttons = response.dragged_by(egui::PointerButton::Middle)
            || (!brush_tool && response.dragged_by(egui::PointerButton::Secondary));
        if response.dragged_by(orbit_button) && !shift {
            self.orbit
                .orbit(-delta.x * ORBIT_RAD_PER_POINT, delta.y * ORBIT_RAD_PER_POINT);
        } else if pan_buttons || (response.dragged_by(egui::PointerButton::Primary) && shift) {
            self.orbit.pan(-delta.x / height, delta.y / height);
        }
        let mut zooming = false;
        if response.hovered() {
            let scroll = ui.input(|i| i.smooth_scroll_delta.y);
            if scroll != 0.0 {
                self.orbit.zoom((-scroll * 0.002).exp());
                zooming = true;
            }
        }
        let camera_drag =
            response.dragged() && !(brush_tool && response.dragged_by(egui::PointerButton::Primary) && !shift);
        camera_drag || zooming
    }

    /// Renders into the texture; while `moving`, frames shaded at every pixel are shaded
    /// per vertex instead where the order allows (cheaper, and hard to tell apart in
    /// motion); while `dragging`, moved lights' maps are drafts.
    fn render(
        &mut self,
        render_state: &egui_wgpu::RenderState,
        settings: &RenderSettings,
        size: [u32; 2],
        moving: bool,
        dragging: bool,
    ) {
        let started = std::time::Instant::now();
        // While the camera moves: half resolution, and per-vertex shadows only where the
        // settings shade every pixel. At half of 960 × 540 the deferred reduced shading took
        // 23 ms on the studio and 95 ms on the terrain where per-vertex shading took 35 and
        // 235 ms (27 against 31 on the sample), and its shadows do not jump when the
        // camera stops (docs/performance.md).
        let quality = FrameQuality {
            per_vertex_preview: moving && settings.shadows.shading_downsample <= 1,
            // A light dragged (gizmo or inspector): its single view's map at half
            // resolution, a quarter of the raster work, until the pointer is let go.
            draft_moved_maps: dragging,
        };
        let resized = self.renderer.render(&self.orbit.camera(), size, settings, quality);
        if (resized || self.image.is_none())
            && let Some(target) = self.renderer.target()
        {
            self.image = Some(ViewportImage::new(
                render_state,
                &target.display_view,
                [target.width, target.height],
            ));
        }
        self.last_render_ms = started.elapsed().as_secs_f32() * 1000.0;
    }
}
