//! The editor's painting state, its one owner in a session: the tool, brush and
//! strategies, the `Painter` with this session's applied strokes, and where the transfer
//! comes from (baked maps once a background bake finished, the log-SH direct estimate
//! until then, so painting never waits). The logic is the library's (`paint`); this file
//! only holds state and turns a viewport stroke into a stroke record.

use std::sync::Arc;

use glam::Vec2;

use super::bake_job::{BakeJob, BakePoll};
use crate::bake::scene_bvh::SceneBvh;
use crate::bake::{BakeSettings, ImportanceMaps};
use crate::blockers::Sphere;
use crate::paint::{
    Brush, BrushKind, PaintSettings, Painter, StrokeRecord, StrokeReport, Transfer, View, ViewRecord, dabs_along,
};
use crate::project::bake_cache::light_hash;
use crate::project::{Document, PaintingState};
use crate::scene::{Camera, Scene};
use crate::shading::RenderSettings;

/// A stroke as the viewport took it: its points relative to the viewport's top-left
/// corner and the viewport's size, in the viewport's pixels.
#[derive(Debug, Clone, PartialEq)]
pub struct ScreenStroke {
    pub points_px: Vec<Vec2>,
    pub viewport_size_px: Vec2,
}

/// What the left mouse button does in the viewport.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Tool {
    #[default]
    Navigate,
    Brush(BrushKind),
}

pub struct Painting {
    pub tool: Tool,
    /// Radius, falloff, strength and target of the brush (its kind comes from the tool).
    pub brush: Brush,
    /// The brush the project file named (None: it had none, and the default applies).
    opened_brush: Option<Brush>,
    pub settings: PaintSettings,
    /// This session's applied strokes (undone ones are in the session's history).
    pub(super) painter: Painter,
    /// Strokes the document's log held when it was opened (applied, not undoable here).
    earlier: Vec<StrokeRecord>,
    bvh: Option<Arc<SceneBvh>>,
    /// The picking BVH being built in the background since the document opened.
    bvh_job: Option<std::thread::JoinHandle<SceneBvh>>,
    maps: Option<ImportanceMaps>,
    /// What each light's maps were baked for ([`light_hash`]): a light moved since has
    /// stale maps until it is re-baked.
    maps_lights: Vec<[u8; 32]>,
    /// The same for the running bake's scene.
    bake_lights: Vec<[u8; 32]>,
    pub bake: Option<BakeJob>,
    pub bake_settings: BakeSettings,
    /// The cache file the maps were last written to or read from, and their key then.
    cached_at: Option<(std::path::PathBuf, crate::project::bake_cache::BakeKey)>,
    /// The cache file of the running bake, if it has one, and the key it bakes for.
    bake_cache: Option<std::path::PathBuf>,
    bake_key: Option<crate::project::bake_cache::BakeKey>,
    next_seed: u64,
    pub last_report: Option<StrokeReport>,
    /// The intensities the project opened with, at which the strokes of earlier sessions
    /// are taken up on the first stroke (`Painter::carry_over`), until they are.
    opened_intensities: Option<Vec<f32>>,
}

impl Painting {
    pub fn for_document(document: &Document) -> Painting {
        let state = &document.painting;
        Painting {
            tool: Tool::Navigate,
            brush: state.brush.unwrap_or_else(|| Brush::new(BrushKind::Positive)),
            opened_brush: state.brush,
            settings: state.settings,
            painter: Painter::new(),
            earlier: state.strokes.clone(),
            bvh: None,
            bvh_job: {
                // Built before the first stroke needs it: a large scene takes seconds.
                let scene = document.scene.clone();
                Some(std::thread::spawn(move || SceneBvh::build(&scene)))
            },
            maps: None,
            maps_lights: Vec::new(),
            bake_lights: Vec::new(),
            bake: None,
            bake_settings: BakeSettings::default(),
            cached_at: None,
            bake_cache: None,
            bake_key: None,
            next_seed: state.strokes.len() as u64 + 1,
            last_report: None,
            opened_intensities: Some(document.scene.light_intensities()),
        }
    }

    /// The painting state the project saves: every applied stroke, brush and settings.
    pub fn state(&self) -> PaintingState {
        let mut strokes = self.earlier.clone();
        strokes.extend(self.painter.log().cloned());
        PaintingState {
            strokes,
            brush: self.brush_for_file(),
            settings: self.settings,
        }
    }

    /// The brush as the project file names it: an untouched default brush stays unnamed,
    /// so opening a project is not a change.
    pub fn brush_for_file(&self) -> Option<Brush> {
        let untouched = self.opened_brush.is_none() && self.brush == Brush::new(BrushKind::Positive);
        (!untouched).then_some(self.brush)
    }

    /// Strokes applied in this session (undone ones not counted).
    pub fn stroke_count(&self) -> usize {
        self.painter.log().count()
    }

    /// Where strokes read the transfer from under the frame `settings`, for the panel.
    pub fn transfer_label(&self, scene: &Scene, settings: &RenderSettings) -> String {
        match (&self.maps, self.maps_for(scene)) {
            (_, Some(maps)) if settings.baked_indirect => format!(
                "baked maps: the view's direct light and their bounce ({} vertex-light pairs)",
                maps.entry_count()
            ),
            (_, Some(_)) => "direct estimate from the view's shadows (the frame adds no baked light)".to_string(),
            (Some(_), None) => "direct estimate from the view's shadows (maps out of date: lights moved)".to_string(),
            (None, None) => "direct estimate from the view's shadows (no bake yet)".to_string(),
        }
    }

    /// The baked maps, if there are maps baked for `scene`'s geometry and lights as they
    /// are now.
    pub fn maps_for(&self, scene: &Scene) -> Option<&ImportanceMaps> {
        self.maps
            .as_ref()
            .filter(|maps| maps.fits(scene) && self.moved_lights(scene).is_empty())
    }

    /// The lights of `scene` moved (or reshaped) since their maps were baked, and those
    /// added since; empty without maps. Every light once a light was deleted (the maps'
    /// light numbers no longer match).
    pub fn moved_lights(&self, scene: &Scene) -> Vec<usize> {
        if self.maps.is_none() {
            return Vec::new();
        }
        if self.maps_lights.len() > scene.lights.len() {
            return (0..scene.lights.len()).collect();
        }
        let now = scene.lights.iter().map(light_hash);
        let mut moved: Vec<usize> = now
            .zip(&self.maps_lights)
            .enumerate()
            .filter(|(_, (now, baked))| now != *baked)
            .map(|(index, _)| index)
            .collect();
        moved.extend(self.maps_lights.len()..scene.lights.len());
        moved
    }

    /// Re-bakes, in the background, only the lights that moved or were added since the
    /// maps were baked, keeping the others' maps (all of them after a deletion); false if
    /// there is nothing to do (no maps, nothing moved, or a bake already running).
    pub fn rebake_moved_lights(&mut self, scene: &Scene) -> bool {
        let moved = self.moved_lights(scene);
        let Some(maps) = self.maps.as_ref().filter(|m| m.fits(scene)) else {
            return false;
        };
        if moved.is_empty() || self.bake.is_some() {
            return false;
        }
        let deleted = self.maps_lights.len() > scene.lights.len();
        self.bake_lights = scene.lights.iter().map(light_hash).collect();
        self.bake_cache = None;
        self.bake_key = None;
        self.bake = Some(if deleted {
            // The maps number lights as they were: bake them all afresh.
            BakeJob::start(scene, self.bake_settings, None)
        } else {
            BakeJob::start_rebake(scene, self.bake_settings, maps.clone(), moved)
        });
        true
    }

    /// Bakes in the background; a saved project's maps go to (or come from) its cache.
    pub fn start_bake(&mut self, scene: &Scene, project: Option<&std::path::Path>) {
        let cache = project.map(crate::project::bake_cache::cache_path);
        self.bake_cache = cache.clone();
        self.bake_key = Some(crate::project::bake_cache::BakeKey::of(scene, &self.bake_settings));
        self.bake_lights = scene.lights.iter().map(light_hash).collect();
        self.bake = Some(BakeJob::start(scene, self.bake_settings, cache));
    }

    /// On opening a project with a bake cache: load it (or re-bake what changed) in the
    /// background, so strokes get the baked maps without asking.
    pub fn resume_cached_bake(&mut self, scene: &Scene, project: Option<&std::path::Path>) {
        if let Some(project) = project
            && crate::project::bake_cache::cache_path(project).exists()
        {
            self.start_bake(scene, Some(project));
        }
    }

    /// Writes the maps to the cache of `project` (after Save As, or the first save).
    pub fn save_cache(&mut self, scene: &Scene, project: &std::path::Path) -> Option<String> {
        let maps = self.maps.as_ref()?;
        let key = crate::project::bake_cache::BakeKey::of(scene, &self.bake_settings);
        let path = crate::project::bake_cache::cache_path(project);
        if self.cached_at.as_ref() == Some(&(path.clone(), key.clone())) {
            return None;
        }
        match crate::project::bake_cache::save(&path, &key, maps) {
            Ok(()) => {
                self.cached_at = Some((path, key));
                None
            }
            Err(e) => Some(format!(
                "the bake cache could not be written to {}: {e}",
                path.display()
            )),
        }
    }

    /// Takes the maps of a finished bake; the message to show, if something finished.
    pub fn poll_bake(&mut self) -> Option<String> {
        let job = self.bake.as_mut()?;
        let seconds = job.elapsed().as_secs_f32();
        match job.poll() {
            BakePoll::Running => None,
            BakePoll::Finished(maps, what) => {
                self.bake = None;
                let message = format!("{what}: {} vertex-light pairs in {seconds:.1} s", maps.entry_count());
                if let (Some(path), Some(key)) = (self.bake_cache.take(), self.bake_key.take()) {
                    self.cached_at = Some((path, key));
                }
                self.maps = Some(maps);
                self.maps_lights = std::mem::take(&mut self.bake_lights);
                Some(message)
            }
            BakePoll::Cancelled => {
                self.bake = None;
                self.bake_cache = None;
                self.bake_key = None;
                Some("bake cancelled; strokes keep using the direct estimate".to_string())
            }
        }
    }

    /// Paints a stroke finished in the viewport, seen by `camera`, and writes the new
    /// intensities into `scene`'s lights.
    pub fn paint(
        &mut self,
        scene: &mut Scene,
        camera: Camera,
        stroke: &ScreenStroke,
        blockers: &[Sphere],
        settings: &RenderSettings,
        hidden: &std::collections::BTreeSet<usize>,
    ) -> Option<StrokeReport> {
        let Tool::Brush(kind) = self.tool else { return None };
        let view = View {
            camera,
            width_px: stroke.viewport_size_px.x.round().max(1.0) as u32,
            height_px: stroke.viewport_size_px.y.round().max(1.0) as u32,
        };
        let points = &stroke.points_px;
        let brush = Brush { kind, ..self.brush };
        let record = StrokeRecord {
            view: ViewRecord::of(&view),
            dabs_px: dabs_along(points, (brush.radius_px * 0.25).max(1.0)),
            brush,
            settings: self.settings,
            seed: self.next_seed,
            hidden_objects: hidden.iter().map(|&o| o as u32).collect(),
            locked_lights: scene.locked_lights(),
        };
        self.next_seed += 1;
        let bvh = self.picking_bvh(scene);
        let mut intensities = scene.light_intensities();
        let report = {
            let scene: &Scene = scene;
            // `maps_for` borrows all of `self`; the field alone leaves the painter free.
            let fresh = self.maps_for(scene).is_some();
            let maps = self.maps.as_ref().filter(|_| fresh);
            let transfer = crate::shading::frame_transfer::transfer_for(maps, scene, blockers, settings);
            self.painter
                .paint(scene, &bvh, transfer.as_ref(), &mut intensities, record)
        };
        scene.set_light_intensities(&intensities);
        self.last_report = Some(report.clone());
        Some(report)
    }

    /// Takes up what the saved strokes ask (their Keep areas, and their rows of the global
    /// solve: `Painter::carry_over`) at the intensities the project opened with, as soon
    /// as the picking BVH has been built in the background; how many Keep areas, when it
    /// did. Cheap while waiting or once done.
    pub fn take_up_saved_strokes(
        &mut self,
        scene: &Scene,
        blockers: impl FnOnce() -> Vec<Sphere>,
        settings: &RenderSettings,
    ) -> Option<usize> {
        let built = self.bvh.is_some() || self.bvh_job.as_ref().is_some_and(|job| job.is_finished());
        if self.opened_intensities.is_none() || !built {
            return None;
        }
        let opened = self.opened_intensities.take()?;
        let bvh = self.picking_bvh(scene);
        let fresh = self.maps_for(scene).is_some();
        let maps = self.maps.as_ref().filter(|_| fresh);
        let transfer = crate::shading::frame_transfer::transfer_for(maps, scene, &blockers(), settings);
        let keeps = self
            .painter
            .carry_over(scene, &bvh, transfer.as_ref(), &opened, &self.earlier);
        Some(keeps)
    }

    /// The points of `scene` that Keep strokes hold (this session's and the saved ones
    /// taken up), for the viewport to show.
    pub fn kept_points(&self, scene: &Scene) -> Vec<glam::Vec3> {
        self.painter
            .kept_vertices()
            .into_iter()
            .filter_map(|v| {
                scene
                    .objects
                    .get(v.object as usize)?
                    .positions
                    .get(v.vertex as usize)
                    .copied()
            })
            .collect()
    }

    /// The transfer strokes read now: the baked maps when they are fresh for `scene`,
    /// else the direct estimate through `blockers`.
    pub fn transfer<'a>(
        &'a self,
        scene: &'a Scene,
        blockers: &[Sphere],
        settings: &RenderSettings,
    ) -> Box<dyn Transfer + 'a> {
        crate::shading::frame_transfer::transfer_for(self.maps_for(scene), scene, blockers, settings)
    }

    /// Whether strokes read baked maps (fresh for `scene`) rather than the estimate.
    pub fn has_fresh_maps(&self, scene: &Scene) -> bool {
        self.maps_for(scene).is_some()
    }

    /// The BVH of `scene`'s triangles for picking (waits for the background build, or
    /// builds it if that failed).
    pub fn picking_bvh(&mut self, scene: &Scene) -> Arc<SceneBvh> {
        if let Some(bvh) = &self.bvh {
            return bvh.clone();
        }
        let built = self.bvh_job.take().and_then(|job| job.join().ok());
        let bvh = Arc::new(built.unwrap_or_else(|| SceneBvh::build(scene)));
        self.bvh = Some(bvh.clone());
        bvh
    }
}
