//! The 3D viewport: renders the scene offscreen — with log-SH soft shadows
//! ([`LogShPipeline`]) or the plain raster ([`ScenePipeline`]) — into a texture that egui
//! shows, and turns mouse input into orbit (left drag), pan (right or middle drag, or
//! shift + left drag) and zoom (scroll); with a brush tool the left drag belongs to the
//! brush (`brush_input.rs`) and the right drag orbits. While the camera moves, frames are shaded at half
//! the resolution in each direction (a quarter of the pixels) and per vertex, so orbiting
//! stays fluid on a software GPU; the full frame follows as soon as the camera rests.

use crate::blockers::Sphere;
use crate::render::edge_filter::EdgeFilter;
use crate::render::gpu_types::GpuLight;
use crate::render::heat_map::HeatMapPipeline;
use crate::render::logsh::{GpuBlockers, LogShPipeline, Shading};
use crate::render::per_vertex::VertexVisibility;
use crate::render::reduced_shading::LowResolutionTargets;
use crate::render::{
    AntiAliasing, BakedIndirect, CompiledPaths, GpuScene, LightPathContext, RenderSettings, RenderTarget,
    SceneLighting, ScenePipeline, ShadowSettings, compiled_paths,
};
use crate::scene::{Environment, Light, OrbitCamera, Scene};

/// Log-SH shadow state of a viewport.
struct Shadows {
    /// The settings the pipeline and buffers were made for.
    settings: ShadowSettings,
    pipeline: LogShPipeline,
    blockers: GpuBlockers,
    /// Per-vertex visibility buffers of the scene for the pipeline's order.
    visibility: Option<VertexVisibility>,
    /// The reduced-resolution images of the pipeline for the last frame size, if it
    /// shades at a reduced resolution.
    low_resolution: Option<LowResolutionTargets>,
}

/// Log-SH pipelines for new settings, compiling on a background thread: lavapipe takes
/// over a second for a high order (order 8), and the editor must keep drawing meanwhile.
struct Compiling {
    settings: ShadowSettings,
    paths: CompiledPaths,
    handle: std::thread::JoinHandle<LogShPipeline>,
}

/// Each light's shadow path as chosen for `lights` under `settings`.
struct PathChoice {
    lights: Vec<Light>,
    settings: ShadowSettings,
    shaded: Vec<GpuLight>,
}

/// What the texture shows, to skip redundant renders.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Shown {
    orbit: OrbitCamera,
    settings: RenderSettings,
    size: [u32; 2],
    full_resolution: bool,
}

pub struct Viewport {
    pipeline: ScenePipeline,
    /// Draws the importance heat map instead of the shading while it has values.
    heat_map: HeatMapPipeline,
    /// The edge filter's pipelines, for each new target (the size changes as the camera
    /// moves and stops).
    edge_filter: EdgeFilter,
    gpu_scene: GpuScene,
    shadows: Shadows,
    /// The pipeline being compiled for the settings asked for last, if any.
    compiling: Option<Compiling>,
    /// The scene's lights as last uploaded: whether any can take the exact shadow path
    /// decides what the pipeline compiles.
    lights: Vec<Light>,
    /// What the choice of each light's shadow path looks at (the scene's centre, some of
    /// its surface points, the blockers).
    path_context: LightPathContext,
    /// The last choice of the lights' paths ([`Self::shaded_lights`]).
    path_choice: std::cell::RefCell<Option<PathChoice>>,
    /// Whether an environment or a terrain is there (each compiles in shading code).
    lighting: SceneLighting,
    target: Option<RenderTarget>,
    texture_id: Option<egui::TextureId>,
    pub orbit: OrbitCamera,
    rendered: Option<Shown>,
    /// Milliseconds the last scene render took on the CPU side (submission included).
    pub last_render_ms: f32,
    /// Where the viewport was last shown, in points.
    pub rect: egui::Rect,
}

/// The orbit camera matching the scene's initial camera, pivoting at the scene's centre
/// distance.
pub fn scene_orbit(scene: &Scene) -> OrbitCamera {
    let camera = scene.initial_camera();
    let pivot = (scene.bounds().center() - camera.position).length().max(0.1);
    OrbitCamera::from_camera(&camera, pivot)
}

/// Where world point `p` appears on screen (points) in a viewport at `rect` seen through
/// `view` (its size in points), None behind the eye; not clipped to `rect`.
pub fn screen_point(view: &crate::paint::View, rect: egui::Rect, p: glam::Vec3) -> Option<egui::Pos2> {
    view.project(p).map(|q| rect.min + egui::vec2(q.x, q.y))
}

/// Radians of orbit per point of mouse drag.
const ORBIT_RAD_PER_POINT: f32 = 0.008;

/// How the viewport smooths edges: the edge filter (its pipelines in
/// [`Viewport::edge_filter`]), a few milliseconds on lavapipe where multisampling more
/// than doubles the frame time.
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
        let (device, queue) = (&render_state.device, &render_state.queue);
        let pipeline = ScenePipeline::with_samples(device, ANTI_ALIASING.samples());
        let gpu_scene = GpuScene::upload(device, queue, &pipeline.layouts, scene);
        let settings = if shadows.gpu_problems().is_empty() {
            *shadows
        } else {
            ShadowSettings::default()
        };
        let path_context = LightPathContext::of_scene(scene, blockers);
        let lighting = SceneLighting::of(scene);
        let paths = compiled_paths(
            &crate::render::shading_lights(&scene.lights, &settings, &path_context),
            lighting,
            blockers.len(),
        );
        let logsh = LogShPipeline::new(device, &pipeline.layouts, &settings, ANTI_ALIASING.samples(), paths);
        let gpu_blockers = GpuBlockers::upload(
            device,
            queue,
            &logsh.shadow_layout,
            blockers,
            scene.terrain.as_ref().map(|t| &t.field),
            &settings,
        );
        let visibility = logsh.vertex_visibility(device, &gpu_scene);
        let heat_map = HeatMapPipeline::new(device, &pipeline.layouts, ANTI_ALIASING.samples());
        let mut viewport = Viewport {
            pipeline,
            heat_map,
            edge_filter: EdgeFilter::new(device),
            gpu_scene,
            shadows: Shadows {
                settings,
                pipeline: logsh,
                blockers: gpu_blockers,
                visibility,
                low_resolution: None,
            },
            compiling: None,
            lights: scene.lights.clone(),
            path_context,
            path_choice: std::cell::RefCell::new(None),
            lighting,
            target: None,
            texture_id: None,
            orbit: orbit.unwrap_or_else(|| scene_orbit(scene)),
            rendered: None,
            last_render_ms: 0.0,
            rect: egui::Rect::NOTHING,
        };
        viewport.write_lights(render_state);
        viewport
    }

    /// For each of `lights`: whether it takes the exact shadow path under `settings`, and
    /// its angular radius seen from `point` in degrees (`render::light_paths_at` with the
    /// viewport's scene and blockers).
    pub fn light_paths_at(&self, lights: &[Light], point: glam::Vec3, settings: &ShadowSettings) -> Vec<(bool, f64)> {
        crate::render::paths_and_sizes_at(&self.shaded_lights(lights, settings), point)
    }

    /// `lights` on the shadow paths `settings` give them (`render::shading_lights` with
    /// the viewport's scene and blockers). The last choice is kept until the lights, the
    /// settings or the blockers change: the UI asks every frame, a light edit asks again
    /// to upload and to check the pipeline, and weighing the blockers that matter is not
    /// free.
    fn shaded_lights(&self, lights: &[Light], settings: &ShadowSettings) -> Vec<GpuLight> {
        let mut cache = self.path_choice.borrow_mut();
        match cache.as_ref() {
            Some(choice) if choice.lights == lights && choice.settings == *settings => choice.shaded.clone(),
            _ => {
                let shaded = crate::render::shading_lights(lights, settings, &self.path_context);
                *cache = Some(PathChoice {
                    lights: lights.to_vec(),
                    settings: *settings,
                    shaded: shaded.clone(),
                });
                shaded
            }
        }
    }

    /// Writes the lights on the paths the drawn settings give them. Until a pipeline with
    /// every path they need is compiled, a light whose path the drawn pipeline lacks takes
    /// the other one.
    fn write_lights(&mut self, render_state: &egui_wgpu::RenderState) {
        let mut lights = self.shaded_lights(&self.lights, &self.shadows.settings);
        let compiled = self.shadows.pipeline.paths;
        for light in &mut lights {
            if !compiled.exact {
                light.exact_path = 0;
            } else if !compiled.harmonics {
                light.exact_path = 1;
            }
        }
        self.gpu_scene.update_lights(
            &render_state.device,
            &render_state.queue,
            &self.pipeline.layouts,
            &lights,
        );
    }

    /// Uploads changed lights; the next frame shows them. Lights that need a path the
    /// pipeline lacks, or no longer need one it has, recompile it in the background.
    pub fn set_lights(&mut self, render_state: &egui_wgpu::RenderState, lights: &[Light]) {
        self.lights = lights.to_vec();
        self.write_lights(render_state);
        self.recompile_if_paths_changed(render_state);
        self.rendered = None;
    }

    /// The paths `settings` need for the viewport's lights and environment.
    fn paths_for(&self, settings: &ShadowSettings) -> CompiledPaths {
        compiled_paths(
            &self.shaded_lights(&self.lights, settings),
            self.lighting,
            self.path_context.blockers.len(),
        )
    }

    fn recompile_if_paths_changed(&mut self, render_state: &egui_wgpu::RenderState) {
        let (wanted, paths) = match &self.compiling {
            Some(c) => (c.settings, c.paths),
            None => (self.shadows.settings, self.shadows.pipeline.paths),
        };
        if self.paths_for(&wanted) != paths {
            self.apply_shadow_settings(render_state, wanted);
        }
    }

    /// Shows per-vertex `values` (one list per scene object) as a heat map against
    /// `scale` instead of the shading; None goes back to the shading.
    pub fn set_heat_map(&mut self, render_state: &egui_wgpu::RenderState, values: Option<(&[Vec<f32>], f32)>) {
        self.heat_map
            .set_values(&render_state.device, &self.pipeline.layouts, &self.gpu_scene, values);
        self.rendered = None;
    }

    /// Hides the objects `hidden` lists (indices into the scene's objects); shows the rest.
    pub fn set_hidden(&mut self, hidden: &std::collections::BTreeSet<usize>) {
        self.gpu_scene.set_hidden(hidden);
        self.rendered = None;
    }

    /// Replaces the baked indirect light (None: none); the next frame shows it.
    pub fn set_baked_indirect(&mut self, render_state: &egui_wgpu::RenderState, indirect: Option<&BakedIndirect>) {
        self.gpu_scene.set_baked_indirect(&render_state.queue, indirect);
        self.rendered = None;
    }

    /// Replaces the environment light; the next frame shows it (an environment that
    /// appears or goes away recompiles the pipeline in the background).
    pub fn set_environment(&mut self, render_state: &egui_wgpu::RenderState, environment: Option<&Environment>) {
        self.gpu_scene.set_environment(environment);
        self.lighting.has_environment = environment.is_some();
        self.recompile_if_paths_changed(render_state);
        self.rendered = None;
    }

    /// Whether shaders for new shadow settings are being compiled (the viewport shows
    /// the previous settings until they are ready).
    pub fn is_compiling_shaders(&self) -> bool {
        self.compiling.is_some()
    }

    /// Applies new shadow settings (invalid ones are ignored: see
    /// [`ShadowSettings::gpu_problems`]). A new order or method needs a new pipeline: it
    /// is compiled in the background and the settings apply once it is ready.
    fn apply_shadow_settings(&mut self, render_state: &egui_wgpu::RenderState, settings: ShadowSettings) {
        if !settings.gpu_problems().is_empty() {
            return;
        }
        let paths = self.paths_for(&settings);
        if !self.shadows.pipeline.matches(&settings, paths) {
            let compiling_these = self
                .compiling
                .as_ref()
                .is_some_and(|c| c.settings == settings && c.paths == paths);
            if !compiling_these {
                // An older compile still finishes on its thread; its result is dropped.
                let (device, layouts) = (render_state.device.clone(), self.pipeline.layouts.clone());
                let handle = std::thread::spawn(move || {
                    LogShPipeline::new(&device, &layouts, &settings, ANTI_ALIASING.samples(), paths)
                });
                self.compiling = Some(Compiling {
                    settings,
                    paths,
                    handle,
                });
            }
            return;
        }
        self.compiling = None;
        self.use_shadow_settings(render_state, settings);
    }

    /// Installs a compiled pipeline once its thread has finished.
    fn poll_compiling(&mut self, render_state: &egui_wgpu::RenderState) {
        if self.compiling.as_ref().is_none_or(|c| !c.handle.is_finished()) {
            return;
        }
        let Some(Compiling { settings, handle, .. }) = self.compiling.take() else {
            return;
        };
        if let Ok(pipeline) = handle.join() {
            self.shadows.pipeline = pipeline;
            // Bound through the old pipeline's layout.
            self.shadows.low_resolution = None;
            self.shadows.visibility = self
                .shadows
                .pipeline
                .vertex_visibility(&render_state.device, &self.gpu_scene);
            self.use_shadow_settings(render_state, settings);
        }
    }

    /// Makes `settings` (which the pipeline matches) the ones drawn.
    fn use_shadow_settings(&mut self, render_state: &egui_wgpu::RenderState, settings: ShadowSettings) {
        self.shadows
            .blockers
            .apply_settings(&render_state.device, &render_state.queue, &settings);
        self.shadows.settings = settings;
        // The budget and the paths decide which lights may go the exact way.
        self.write_lights(render_state);
        self.rendered = None;
    }

    /// Replaces the blockers; the next frame shows their shadows.
    pub fn set_blockers(&mut self, render_state: &egui_wgpu::RenderState, blockers: &[Sphere]) {
        self.shadows.blockers.update(
            &render_state.device,
            &render_state.queue,
            blockers,
            &self.shadows.settings,
        );
        // Which blockers matter can change which lights go exact.
        self.path_context.blockers = blockers.to_vec();
        self.path_choice.replace(None);
        self.write_lights(render_state);
        self.recompile_if_paths_changed(render_state);
        self.rendered = None;
    }

    /// The image the viewport shows, read back from the GPU (None before the first frame).
    pub fn read_image(
        &self,
        render_state: &egui_wgpu::RenderState,
    ) -> Option<Result<image::RgbaImage, crate::render::RenderError>> {
        let target = self.target.as_ref()?;
        let encoder = render_state.device.create_command_encoder(&Default::default());
        Some(crate::render::read_target_image(
            &render_state.device,
            &render_state.queue,
            encoder,
            target,
        ))
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
        let only_terrain_changed = same_but_terrain(&settings.shadows, &self.shadows.settings);
        self.poll_compiling(render_state);
        if settings.shadows != self.shadows.settings && !(only_terrain_changed && dragging) {
            self.apply_shadow_settings(render_state, settings.shadows);
        }
        if self.compiling.is_some() {
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
        if self.rendered != Some(wanted) {
            self.render(render_state, settings, size, moving);
            self.rendered = Some(wanted);
        }
        if moving {
            // Come back for the full-resolution frame once the camera rests.
            ui.ctx().request_repaint();
        }
        if let Some(id) = self.texture_id {
            let uv = egui::Rect::from_min_max(egui::pos2(0.0, 0.0), egui::pos2(1.0, 1.0));
            ui.painter().image(id, rect, uv, egui::Color32::WHITE);
        }
        if let Some(compiling) = &self.compiling {
            let text = format!(
                "compiling shaders for order {} ({:?})…",
                compiling.settings.order, compiling.settings.exp
            );
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

    /// Renders into the texture; while `moving`, shadows are shaded per vertex where the
    /// order allows (cheaper, and hard to tell apart from per-pixel in motion).
    fn render(
        &mut self,
        render_state: &egui_wgpu::RenderState,
        settings: &RenderSettings,
        size: [u32; 2],
        moving: bool,
    ) {
        let started = std::time::Instant::now();
        let device = &render_state.device;
        let resized = self.target.as_ref().is_none_or(|t| [t.width, t.height] != size);
        if resized {
            let target = RenderTarget::with_edge_filter(device, size[0], size[1], &self.edge_filter);
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
        self.gpu_scene
            .write_frame(&render_state.queue, &camera, size, settings.exposure_ev);
        let mut encoder = device.create_command_encoder(&Default::default());
        let background = settings.background_linear();
        if self.heat_map.draw(&mut encoder, target, &self.gpu_scene, background) {
            // The heat map replaces the shading.
        } else if settings.shadows.enabled
            // While new shaders compile, the shadows keep their previous settings.
            && (same_but_terrain(&self.shadows.settings, &settings.shadows) || self.compiling.is_some())
        {
            let shadows = &mut self.shadows;
            let per_vertex = shadows
                .visibility
                .as_ref()
                .filter(|_| moving || shadows.settings.per_vertex);
            if per_vertex.is_none() {
                shadows.low_resolution =
                    shadows
                        .pipeline
                        .low_resolution_targets(device, size, shadows.low_resolution.take());
            }
            shadows.pipeline.draw(
                &mut encoder,
                target,
                &self.gpu_scene,
                &shadows.blockers,
                background,
                Shading::first_of(per_vertex, shadows.low_resolution.as_ref()),
            );
        } else {
            self.pipeline.draw(&mut encoder, target, &self.gpu_scene, background);
        }
        render_state.queue.submit([encoder.finish()]);
        self.last_render_ms = started.elapsed().as_secs_f32() * 1000.0;
    }
}

/// Whether `a` and `b` differ at most in their terrain sampling.
fn same_but_terrain(a: &ShadowSettings, b: &ShadowSettings) -> bool {
    ShadowSettings {
        terrain: b.terrain,
        ..*a
    } == *b
}
