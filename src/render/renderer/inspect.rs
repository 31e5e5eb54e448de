//! What a [`SceneRenderer`] can tell about its frames without changing them: the shadow
//! maps' views, the objects drawn from the camera, the pixels the upsampling left, each
//! pass's GPU time, the last frame's image.

use super::SceneRenderer;
use crate::render::RenderError;
use crate::render::pass_timer::PassTimer;
use crate::render::passes::ListedPixels;

impl SceneRenderer {
    /// The shadow maps' views and memory in words (`ShadowAtlas::in_words`), None when no
    /// light takes a map.
    pub fn shadow_maps_in_words(&self) -> Option<String> {
        (!self.map_views.views.is_empty()).then(|| self.map_views.atlas.in_words())
    }

    /// See [`crate::render::GpuScene::set_view_culling`].
    pub fn set_view_culling(&mut self, enabled: bool) {
        self.gpu_scene.set_view_culling(enabled);
    }

    /// See [`crate::render::GpuScene::set_back_face_culling`].
    pub fn set_back_face_culling(&mut self, enabled: bool) {
        self.gpu_scene.set_back_face_culling(enabled);
    }

    /// See [`crate::render::GpuScene::objects_seen_from_outside`]: those whose back faces
    /// per-vertex frames cull.
    pub fn objects_seen_from_outside(&self) -> usize {
        self.gpu_scene.objects_seen_from_outside()
    }

    /// See [`crate::render::GpuScene::set_detail_levels`].
    pub fn set_detail_levels(&mut self, enabled: bool) {
        self.gpu_scene.set_detail_levels(enabled);
    }

    /// The lights' grid's boxes and how many lights a box lists on average, when the
    /// frames walk it.
    pub fn light_grid_in_words(&self) -> Option<String> {
        self.walks_light_grid().then(|| {
            let grid = self.gpu_scene.light_grid();
            format!(
                "{} × {} × {} boxes of {:.2} m, {:.1} lights listed a box on average",
                grid.boxes.x,
                grid.boxes.y,
                grid.boxes.z,
                grid.box_side_m,
                grid.mean_listed()
            )
        })
    }

    /// Whether the pipeline drawing the frames walks the lights' grid (LIGHT_GRID; see
    /// [`Self::set_light_grid`]).
    pub fn walks_light_grid(&self) -> bool {
        self.shadows.key.paths.light_grid
    }

    /// The triangles of the objects the last frame's camera may see (the rest were not
    /// drawn from it), and of every object shown.
    pub fn triangles_in_view(&self) -> (u64, u64) {
        self.gpu_scene.triangles_in_view()
    }

    /// The shadow-map views the last redraw of the maps drew and the triangles it drew
    /// into them (each view leaves out the objects outside its frustum, unless view
    /// culling is off).
    pub fn shadow_map_triangles(&self) -> (u64, u64) {
        self.shadow_maps.last_drawn()
    }

    /// The vertices whose visibility the last frame computed per vertex: those of the
    /// objects it saw first since the lights, blockers, settings or scene changed (0 when
    /// it was not shaded per vertex).
    pub fn vertices_computed(&self) -> u64 {
        self.vertices_computed
    }

    /// The objects the last frame lit at their vertices (`shading::vertex_lighting`; 0
    /// when it was not shaded per vertex).
    pub fn objects_lit_at_vertices(&self) -> usize {
        self.objects_lit_at_vertices
    }

    /// How many pixels the last frame's upsampling left to the soft layer and shaded in
    /// full, and how many samples the soft layer left (None where the frame was not drawn
    /// deferred at full resolution).
    pub fn listed_pixels(&self) -> Option<Result<ListedPixels, RenderError>> {
        let low = self.shadows.low_resolution.as_ref()?;
        let images = low.full_resolution.as_ref()?;
        let listed = |pixels: ListedPixels| -> Result<ListedPixels, RenderError> {
            let samples_in_full = match &low.listed_samples {
                Some(samples) => samples.count(&self.device, &self.queue)?,
                None => 0,
            };
            Ok(ListedPixels {
                samples_in_full,
                ..pixels
            })
        };
        Some(images.listed_pixels(&self.device, &self.queue).and_then(listed))
    }

    /// From now on, times each pass of every frame on the GPU, if the device has
    /// timestamps (false: it has not).
    pub fn time_passes(&mut self) -> bool {
        self.pass_timer = PassTimer::new(&self.device);
        self.pass_timer.is_some()
    }

    /// Waits for the frames drawn so far and adds their passes' times up (nothing unless
    /// [`Self::time_passes`]).
    pub fn collect_pass_times(&mut self) -> Result<(), RenderError> {
        match &mut self.pass_timer {
            Some(timer) => timer
                .collect(&self.device, &self.queue)
                .map_err(|e| RenderError::Readback(e.to_string())),
            None => Ok(()),
        }
    }

    /// Mean GPU milliseconds per frame of each pass timed so far, in the order they run.
    pub fn pass_times_ms(&self) -> Vec<(&'static str, f64)> {
        self.pass_timer.as_ref().map(PassTimer::mean_ms).unwrap_or_default()
    }

    /// The last frame, read back from the GPU (None before the first frame).
    pub fn read_image(&self) -> Option<Result<image::RgbaImage, RenderError>> {
        let target = self.target.as_ref()?;
        let encoder = self.device.create_command_encoder(&Default::default());
        Some(crate::render::readback::read_target_image(
            &self.device,
            &self.queue,
            encoder,
            target,
        ))
    }
}
