//! The one renderer of a scene, which the editor's viewport and the CLI both draw with
//! ([`SceneRenderer`]): it owns the scene's GPU resources (meshes, lights, blockers,
//! heat map, per-vertex and low-resolution buffers), the lights' shadow paths, a cache of
//! log-SH pipelines keyed by what is compiled into them (`pipeline_cache`) and the target
//! frames are drawn into. Callers say what changed (`set_*`) and ask for frames
//! ([`SceneRenderer::render`]); how new pipelines are compiled is theirs to choose
//! ([`Compilation`]): the editor keeps drawing with the previous pipeline while a new one
//! compiles in the background.

mod pipeline_cache;

use std::cell::RefCell;
use std::collections::BTreeSet;
use std::sync::Arc;

mod inspect;

pub use pipeline_cache::{Compilation, PipelineKey};

use super::pass_timer::{self, PassTimer, TimedEncoder};
use super::passes::heat_map::HeatMapPipeline;
use super::passes::logsh::{LogShPipeline, Shading};
use super::passes::per_vertex::VertexVisibility;
use super::passes::raster::ScenePipeline;
use super::passes::reduced_shading::{
    FrameInputs, LowResolutionTargets, MappedLightKey, MappedVisibilityKey, SoftLayerKey, SurfacesKey,
};
use super::resources::{Detail, GpuBlockers, GpuScene, ShadowMaps};
use super::target::edge_filter::EdgeFilter;
use super::target::{AntiAliasing, RenderTarget};
use crate::blockers::Sphere;
use crate::scene::{Aabb, Camera, Environment, Light, Scene};
use crate::shading::gpu_types::{GpuLight, NO_SHADOW_VIEW, SHADOW_PATH_EXACT, SHADOW_PATH_MAP, SHADOW_PATH_SH};
use crate::shading::shadow_maps::{ShadowViews, shadow_views};
use crate::shading::{
    BakedIndirect, CompiledPaths, LightPathContext, RenderSettings, SceneLighting, ShadowSettings, compiled_paths,
};
use pipeline_cache::PipelineCache;

/// The log-SH state frames are drawn with.
struct Shadows {
    /// The settings the pipeline and buffers are for.
    settings: ShadowSettings,
    pipeline: Arc<LogShPipeline>,
    /// What `pipeline` was compiled for.
    key: PipelineKey,
    blockers: GpuBlockers,
    /// Per-vertex visibility and light buffers of the scene for the pipeline's order, made
    /// by the first frame shaded per vertex since the pipeline was installed (frames
    /// shaded otherwise need none of them).
    visibility: Option<VertexVisibility>,
    /// The reduced-resolution images for the last frame size, if the pipeline shades at a
    /// reduced resolution.
    low_resolution: Option<LowResolutionTargets>,
}

/// Each light's shadow path as chosen for `lights` under `settings`.
struct PathChoice {
    lights: Vec<Light>,
    settings: ShadowSettings,
    shaded: Vec<GpuLight>,
}

/// How a frame is shaded besides its settings.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct FrameQuality {
    /// Shade per vertex where the order allows, whatever the settings say (the editor's
    /// preview while the camera moves).
    pub per_vertex_preview: bool,
    /// Draw the maps of lights that moved since the last frame at half their resolution
    /// where that is cheaper (the editor's frames while a light is dragged); a later frame
    /// without it draws them in full ([`SceneRenderer::maps_drafted`]).
    pub draft_moved_maps: bool,
}

pub struct SceneRenderer {
    device: wgpu::Device,
    queue: wgpu::Queue,
    anti_aliasing: AntiAliasing,
    raster: ScenePipeline,
    /// Draws the importance heat map instead of the shading while it has values.
    heat_map: HeatMapPipeline,
    /// The edge filter's pipelines, shared by every target made for a new size.
    edge_filter: EdgeFilter,
    gpu_scene: GpuScene,
    shadows: Shadows,
    pipelines: PipelineCache,
    /// Settings waiting for their pipeline (compiling in the background).
    pending: Option<ShadowSettings>,
    /// The scene's lights as last set: which paths they take decides what the pipeline
    /// compiles.
    lights: Vec<Light>,
    /// What the choice of each light's shadow path looks at (the scene's centre, some of
    /// its surface points, the blockers).
    path_context: LightPathContext,
    /// The last choice of the lights' paths ([`Self::shaded_lights`]).
    path_choice: RefCell<Option<PathChoice>>,
    /// Whether an environment or a terrain is there (each compiles in shading code).
    lighting: SceneLighting,
    /// The shadow maps of the lights on the shadow-map path, their views, and whether
    /// they must be drawn again before the next frame (a light, an object's visibility or
    /// the map size changed).
    shadow_maps: ShadowMaps,
    map_views: ShadowViews,
    maps_stale: bool,
    /// Some views were drawn as drafts (`FrameQuality::draft_moved_maps`) and want
    /// drawing in full.
    maps_drafted: bool,
    /// The scene's bounds, which the maps' views cover.
    bounds: Aabb,
    target: Option<RenderTarget>,
    /// The GPU time of each pass, when asked for ([`Self::time_passes`]).
    pass_timer: Option<PassTimer>,
    /// The next frame draws its surfaces anew even if the view and scene are unchanged
    /// ([`Self::forget_surfaces`]).
    surfaces_forgotten: bool,
    /// Vertices whose visibility the last frame computed (per vertex; 0 otherwise).
    vertices_computed: u64,
    /// Objects the last frame lit at their vertices (per vertex; 0 otherwise).
    objects_lit_at_vertices: usize,
    /// Changes with every [`Self::set_blockers`] (what the soft layer shows depends on it).
    blockers_generation: u64,
    /// Whether frames worth it walk the lights' grid (on unless a test compares frames
    /// without it: [`Self::set_light_grid`]).
    light_grid: bool,
}

impl SceneRenderer {
    /// A renderer of `scene` with `blockers`, drawing with `shadows` (invalid settings:
    /// the defaults; see [`ShadowSettings::gpu_problems`]) into targets antialiased as
    /// `anti_aliasing` says. The first pipeline is compiled at once.
    pub fn new(
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        scene: &Scene,
        blockers: &[Sphere],
        shadows: &ShadowSettings,
        anti_aliasing: AntiAliasing,
        compilation: Compilation,
    ) -> SceneRenderer {
        let samples = anti_aliasing.samples();
        let raster = ScenePipeline::with_samples(device, samples);
        let gpu_scene = GpuScene::upload(device, queue, &raster.layouts, scene);
        let settings = if shadows.gpu_problems().is_empty() {
            *shadows
        } else {
            ShadowSettings::default()
        };
        let path_context = LightPathContext::of_scene(scene, blockers);
        let lighting = SceneLighting::of(scene);
        let paths = compiled_paths(
            &crate::shading::shading_lights(&scene.lights, &settings, &path_context),
            lighting,
            blockers.len(),
        );
        let mut pipelines = PipelineCache::new(device, &raster.layouts, compilation);
        let key = PipelineKey::new(&settings, samples, paths);
        let pipeline = pipelines.get_now(key);
        let shadow_maps = ShadowMaps::new(device);
        let gpu_blockers = GpuBlockers::upload(
            device,
            queue,
            &pipeline.shadow_layout,
            blockers,
            scene.terrain.as_ref().map(|t| &t.field),
            &settings,
            shadow_maps.binding(),
        );
        let heat_map = HeatMapPipeline::new(device, &raster.layouts, samples);
        let mut renderer = SceneRenderer {
            device: device.clone(),
            queue: queue.clone(),
            anti_aliasing,
            raster,
            heat_map,
            edge_filter: EdgeFilter::new(device),
            gpu_scene,
            shadows: Shadows {
                settings,
                pipeline,
                key,
                blockers: gpu_blockers,
                visibility: None,
                low_resolution: None,
            },
            pipelines,
            pending: None,
            lights: scene.lights.clone(),
            path_context,
            path_choice: RefCell::new(None),
            lighting,
            shadow_maps,
            map_views: ShadowViews::default(),
            maps_stale: false,
            maps_drafted: false,
            bounds: scene.bounds(),
            target: None,
            pass_timer: None,
            surfaces_forgotten: false,
            vertices_computed: 0,
            objects_lit_at_vertices: 0,
            blockers_generation: 0,
            light_grid: true,
        };
        renderer.write_lights();
        renderer
    }

    /// For each of `lights`: the shadow path it takes under `settings`, and
    /// its angular radius seen from `point` in degrees (`shading::light_paths_at` with the
    /// renderer's scene and blockers).
    pub fn light_paths_at(
        &self,
        lights: &[Light],
        point: glam::Vec3,
        settings: &ShadowSettings,
    ) -> Vec<(crate::shading::ShadowPath, f64)> {
        crate::shading::paths_and_sizes_at(&self.shaded_lights(lights, settings), point)
    }

    /// `lights` on the shadow paths `settings` give them (`shading::shading_lights` with
    /// the renderer's scene and blockers). The last choice is kept until the lights, the
    /// settings or the blockers change: the UI asks every frame, and weighing the blockers
    /// that matter is not free.
    fn shaded_lights(&self, lights: &[Light], settings: &ShadowSettings) -> Vec<GpuLight> {
        let mut cache = self.path_choice.borrow_mut();
        match cache.as_ref() {
            Some(choice) if choice.lights == lights && choice.settings == *settings => choice.shaded.clone(),
            _ => {
                let shaded = crate::shading::shading_lights(lights, settings, &self.path_context);
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
    fn write_lights(&mut self) {
        let mut lights = self.shaded_lights(&self.lights, &self.shadows.settings);
        let compiled = self.shadows.key.paths;
        for light in &mut lights {
            if !compiled.shades(light) {
                // The nearest path the pipeline has: the SH, else the exact one.
                light.shadow_path = if compiled.harmonics {
                    SHADOW_PATH_SH
                } else if compiled.exact {
                    SHADOW_PATH_EXACT
                } else {
                    SHADOW_PATH_MAP
                };
                if !compiled.shades(light) {
                    // Its maps unreadable by this pipeline (a single view where only
                    // cubes are compiled in, or no maps at all): unshadowed, its maps not
                    // drawn, until a pipeline that reads them is.
                    light.first_shadow_view = NO_SHADOW_VIEW;
                    light.shadow_view_count = 0;
                }
            }
        }
        let views = shadow_views(&lights, &self.bounds, self.shadows.settings.shadow_map_size);
        if views != self.map_views {
            self.map_views = views;
            self.maps_stale = true;
        }
        self.gpu_scene
            .update_lights(&self.device, &self.queue, &self.raster.layouts, &lights);
    }

    /// Draws the shadow maps again if something they show changed, the single views of
    /// moved lights as drafts when `draft_moved` (`ShadowViews::drafted_where_moved`), or
    /// in full if they were drafts and `draft_moved` is off.
    fn refresh_shadow_maps(&mut self, draft_moved: bool) {
        let refine = self.maps_drafted && !draft_moved;
        if !(self.maps_stale || refine) || self.map_views.views.is_empty() {
            return;
        }
        let views = if draft_moved {
            self.map_views.drafted_where_moved(self.shadow_maps.drawn())
        } else {
            self.map_views.clone()
        };
        self.maps_drafted = views != self.map_views;
        if self
            .shadow_maps
            .draw(&self.device, &self.queue, &self.gpu_scene, &views)
        {
            self.shadows
                .blockers
                .set_shadow_maps(&self.device, self.shadow_maps.binding());
        }
        self.maps_stale = false;
    }

    /// Whether some shadow maps were last drawn as drafts: the next frame drawn without
    /// `FrameQuality::draft_moved_maps` draws them in full.
    pub fn maps_drafted(&self) -> bool {
        self.maps_drafted
    }

    /// Replaces the lights; a light that needs a path the pipeline lacks, or no longer
    /// needs one it has, recompiles it.
    pub fn set_lights(&mut self, lights: &[Light]) {
        self.lights = lights.to_vec();
        self.write_lights();
        self.recompile_if_paths_changed();
    }

    /// The paths `settings` need for the renderer's lights and environment.
    fn paths_for(&self, settings: &ShadowSettings) -> CompiledPaths {
        let paths = compiled_paths(
            &self.shaded_lights(&self.lights, settings),
            self.lighting,
            self.path_context.blockers.len(),
        );
        CompiledPaths {
            light_grid: paths.light_grid && self.light_grid,
            ..paths
        }
    }

    /// Lets frames with enough lights whose reach ends walk the lights of the point's box
    /// of the lights' grid (the default), or makes every frame walk every light: the
    /// frames must be the same either way (tests/light_grid.rs).
    pub fn set_light_grid(&mut self, enabled: bool) {
        self.light_grid = enabled;
        self.recompile_if_paths_changed();
    }

    fn key_for(&self, settings: &ShadowSettings) -> PipelineKey {
        PipelineKey::new(settings, self.anti_aliasing.samples(), self.paths_for(settings))
    }

    /// Asks again for the settings drawn or pending when what they need compiled in has
    /// changed (lights, environment, blockers).
    fn recompile_if_paths_changed(&mut self) {
        let wanted = self.pending.unwrap_or(self.shadows.settings);
        let have = match self.pending {
            Some(_) => self.pipelines.compiling(),
            None => Some(self.shadows.key),
        };
        if have != Some(self.key_for(&wanted)) {
            self.set_shadow_settings(wanted);
        }
    }

    /// Shows per-vertex `values` (one list per scene object) as a heat map against
    /// `scale` instead of the shading; None goes back to the shading.
    pub fn set_heat_map(&mut self, values: Option<(&[Vec<f32>], f32)>) {
        self.heat_map
            .set_values(&self.device, &self.raster.layouts, &self.gpu_scene, values);
    }

    /// Hides the objects `hidden` lists (indices into the scene's objects); shows the rest.
    pub fn set_hidden(&mut self, hidden: &BTreeSet<usize>) {
        self.gpu_scene.set_hidden(hidden);
        self.maps_stale = true;
    }

    /// Replaces the baked indirect light (None: none).
    pub fn set_baked_indirect(&mut self, indirect: Option<&BakedIndirect>) {
        self.gpu_scene.set_baked_indirect(&self.queue, indirect);
    }

    /// Replaces the environment light (one that appears or goes away recompiles).
    pub fn set_environment(&mut self, environment: Option<&Environment>) {
        self.gpu_scene.set_environment(environment);
        self.lighting.has_environment = crate::shading::gpu_types::environment_lights(environment);
        self.recompile_if_paths_changed();
    }

    /// Replaces the blockers.
    pub fn set_blockers(&mut self, blockers: &[Sphere]) {
        self.blockers_generation += 1;
        self.shadows
            .blockers
            .update(&self.device, &self.queue, blockers, &self.shadows.settings);
        // Which blockers matter can change which lights go exact.
        self.path_context.blockers = blockers.to_vec();
        self.path_choice.replace(None);
        self.write_lights();
        self.recompile_if_paths_changed();
    }

    /// The shadow settings frames are drawn with now.
    pub fn shadow_settings(&self) -> &ShadowSettings {
        &self.shadows.settings
    }

    /// The settings whose pipeline is compiling in the background, if any (frames keep
    /// the current settings until it is ready).
    pub fn compiling(&self) -> Option<&ShadowSettings> {
        self.pending.as_ref()
    }

    /// Asks for `settings` (invalid ones are ignored: see
    /// [`ShadowSettings::gpu_problems`]). With a background compilation they apply once
    /// their pipeline is ready ([`Self::poll`]).
    pub fn set_shadow_settings(&mut self, settings: ShadowSettings) {
        if !settings.gpu_problems().is_empty() {
            return;
        }
        let key = self.key_for(&settings);
        let ready = if key == self.shadows.key {
            Some(self.shadows.pipeline.clone())
        } else {
            self.pipelines.request(key)
        };
        match ready {
            Some(pipeline) => {
                self.pending = None;
                self.pipelines.forget_compiling();
                self.install(pipeline, key, settings);
            }
            None => self.pending = Some(settings),
        }
    }

    /// Installs the pending settings if their pipeline has finished compiling; true when
    /// something new will be drawn.
    pub fn poll(&mut self) -> bool {
        let Some(settings) = self.pending else { return false };
        let key = self.key_for(&settings);
        if self.pipelines.compiling() != Some(key) {
            // The lights changed what the settings need meanwhile.
            self.set_shadow_settings(settings);
            return self.pending.is_none();
        }
        match self.pipelines.request(key) {
            Some(pipeline) => {
                self.pending = None;
                self.install(pipeline, key, settings);
                true
            }
            None => false,
        }
    }

    /// Makes `settings` and their `pipeline` the ones drawn.
    fn install(&mut self, pipeline: Arc<LogShPipeline>, key: PipelineKey, settings: ShadowSettings) {
        if !Arc::ptr_eq(&pipeline, &self.shadows.pipeline) {
            self.shadows.pipeline = pipeline;
            self.shadows.key = key;
            // Bound through the old pipeline's layouts.
            self.shadows.low_resolution = None;
            self.shadows.visibility = None;
        }
        self.shadows
            .blockers
            .apply_settings(&self.device, &self.queue, &settings);
        self.shadows.settings = settings;
        // The budget and the paths decide which lights may go the exact way.
        self.write_lights();
    }

    /// The target the last frame was drawn into.
    pub fn target(&self) -> Option<&RenderTarget> {
        self.target.as_ref()
    }

    /// Draws a frame of `size` pixels seen by `camera` with `settings` (their shadows as
    /// drawn now: see [`Self::set_shadow_settings`]) into the renderer's target, made anew
    /// when the size changes; true when it was (a texture showing it must be re-bound).
    pub fn render(
        &mut self,
        camera: &Camera,
        size: [u32; 2],
        settings: &RenderSettings,
        quality: FrameQuality,
    ) -> bool {
        let resized = self.target.as_ref().is_none_or(|t| [t.width, t.height] != size);
        if resized {
            self.target = Some(match self.anti_aliasing {
                AntiAliasing::EdgeFilter => {
                    RenderTarget::with_edge_filter(&self.device, size[0], size[1], &self.edge_filter)
                }
                other => RenderTarget::with_anti_aliasing(&self.device, size[0], size[1], other),
            });
        }
        self.refresh_shadow_maps(quality.draft_moved_maps);
        let Some(target) = &self.target else { return resized };
        let background = settings.background_linear();
        let wants_per_vertex = quality.per_vertex_preview || self.shadows.settings.per_vertex;
        // Per-vertex shading and the heat map show values at the vertices: their triangles
        // as they are.
        let detail = if wants_per_vertex || self.heat_map.is_set() {
            Detail::Whole
        } else {
            Detail::Levels(&self.map_views)
        };
        self.gpu_scene
            .write_frame(&self.queue, camera, size, (settings.exposure_ev, background), detail);
        let mut encoder = self.device.create_command_encoder(&Default::default());
        pass_timer::mark(&mut self.pass_timer, &mut encoder, "frame start");
        if self.heat_map.draw(&mut encoder, target, &self.gpu_scene, background) {
            // The heat map replaces the shading.
            pass_timer::mark(&mut self.pass_timer, &mut encoder, "heat map");
        } else if settings.shadows.enabled
            // While new shaders compile, the shadows keep their previous settings.
            && (same_but_terrain(&self.shadows.settings, &settings.shadows) || self.pending.is_some())
        {
            let shadows = &mut self.shadows;
            if wants_per_vertex && shadows.visibility.is_none() {
                shadows.visibility = shadows.pipeline.vertex_visibility(&self.device, &self.gpu_scene);
            }
            (self.vertices_computed, self.objects_lit_at_vertices) = match &mut shadows.visibility {
                Some(visibility) if wants_per_vertex => visibility.plan_frame(
                    &self.gpu_scene,
                    shadows.settings,
                    self.blockers_generation,
                    camera.position,
                ),
                _ => (0, 0),
            };
            let per_vertex = shadows.visibility.as_ref().filter(|_| wants_per_vertex);
            if per_vertex.is_none() {
                shadows.low_resolution =
                    shadows
                        .pipeline
                        .low_resolution_targets(&self.device, size, shadows.low_resolution.take());
                if let Some(low) = &mut shadows.low_resolution {
                    let inputs = (!std::mem::take(&mut self.surfaces_forgotten)).then(|| FrameInputs {
                        surfaces: SurfacesKey {
                            camera: camera.clone(),
                            scene_generation: self.gpu_scene.surfaces_generation(),
                            levels_generation: self.gpu_scene.levels_generation(),
                        },
                        soft_layer: SoftLayerKey {
                            lighting: self.gpu_scene.harmonic_lighting(),
                            settings: shadows.settings,
                            exposure_ev: settings.exposure_ev,
                            blockers_generation: self.blockers_generation,
                        },
                        mapped_visibility: MappedVisibilityKey {
                            lights: mapped_light_keys(self.gpu_scene.mapped_light_geometry(), self.shadow_maps.drawn()),
                            settings: shadows.settings,
                        },
                    });
                    let mapped_lights = self.gpu_scene.mapped_light_geometry().len();
                    low.expect_inputs((&self.device, &self.queue), inputs, mapped_lights);
                }
            }
            shadows.pipeline.draw(
                &mut TimedEncoder {
                    encoder: &mut encoder,
                    timer: &mut self.pass_timer,
                },
                target,
                &self.gpu_scene,
                &shadows.blockers,
                background,
                Shading::first_of(per_vertex, shadows.low_resolution.as_ref()),
            );
        } else {
            self.raster.draw(&mut encoder, target, &self.gpu_scene, background);
            pass_timer::mark(&mut self.pass_timer, &mut encoder, "plain raster");
        }
        self.queue.submit([encoder.finish()]);
        resized
    }

    /// Has the next frame draw its surfaces and soft layer anew, as after a move of the
    /// camera, though nothing they show changed (timings of whole frames).
    pub fn forget_surfaces(&mut self) {
        self.surfaces_forgotten = true;
    }
}

/// Whether `a` and `b` differ at most in their terrain sampling.
pub fn same_but_terrain(a: &ShadowSettings, b: &ShadowSettings) -> bool {
    ShadowSettings {
        terrain: b.terrain,
        ..*a
    } == *b
}

/// Each mapped light's geometry with the views its maps were drawn from.
fn mapped_light_keys(geometry: &[GpuLight], drawn: &[crate::shading::gpu_types::GpuShadowView]) -> Vec<MappedLightKey> {
    geometry
        .iter()
        .map(|light| {
            let first = light.first_shadow_view as usize;
            let views = drawn
                .get(first..first.saturating_add(light.shadow_view_count as usize))
                .unwrap_or_default();
            MappedLightKey {
                geometry: *light,
                views: views.to_vec(),
            }
        })
        .collect()
}
