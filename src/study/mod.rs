//! The speed/accuracy study: each sample scene rendered by the real-time renderer over a
//! grid of knobs ([`grid`]), each frame timed and compared with the converged reference
//! path tracer in direct-light mode (the real-time renderer draws direct light), on the
//! displayed image ([`metrics`]); the defaults also against the reference with one bounce,
//! with and without the bake's indirect light (maps baked at the default settings). Results go to a CSV, a markdown table, a Pareto plot and
//! side-by-side images ([`report`]); docs/speed-accuracy.md presents them.
//!
//! So that the errors are those of the shading, not of texture filtering or edges, the
//! reference starts its paths at the rasteriser's visible surface points (one sample at
//! each pixel centre, as [`capture_surfaces`] gives them) and the real-time frames are
//! drawn with one sample per pixel. The reference is rendered as two independent halves
//! (two seeds): their difference measures its own noise, reported beside the errors so
//! that no error below the noise is read as meaningful.

mod equal_error;
pub mod grid;
pub mod metrics;
pub mod penumbra;
pub mod report;
pub mod sphere_fit;

pub use equal_error::EqualError;
pub mod stability;

use std::path::PathBuf;
use std::time::Instant;

use crate::blockers::{BlockerSettings, SphereBudget, fit_scene};
use crate::project::{Document, ProjectError};
use crate::reference::{ProgressiveRender, ReferenceImage, SurfaceHit};
use crate::render::{
    AntiAliasing, GpuContext, RasterRenderer, Redraw, RenderError, ShadowFrame, ShadowRenderer, capture_surfaces,
    shade_surfaces,
};
use crate::samples::Sample;
use crate::scene::{Camera, Scene};
use crate::shading::cpu::SurfacePoint;
use crate::shading::{BakedIndirect, RenderSettings, ShadowSettings};
use grid::{Knobs, Lighting, knob_grid};
use metrics::{DisplayImage, ImageErrors, image_errors};

/// How big a study to run.
#[derive(Debug, Clone, PartialEq)]
pub struct StudyOptions {
    /// A small grid on one scene at 160×90 (seconds on two cores; CI runs it).
    pub quick: bool,
    pub output_dir: PathBuf,
    /// Only these sample scenes, and without the scene-independent suites (stability,
    /// small lights); None: the scenes of `quick` or the full study, and every suite.
    pub only_scenes: Option<Vec<Sample>>,
    /// Only the grid points whose label contains this (e.g. "brdf"), with the no-shadow
    /// baseline and the defaults beside them, and without the scene-independent suites.
    pub only_knobs: Option<String>,
}

impl StudyOptions {
    fn scenes(&self) -> Vec<Sample> {
        match &self.only_scenes {
            Some(scenes) => scenes.clone(),
            None if self.quick => vec![Sample::Sample],
            None => vec![Sample::Sample, Sample::Studio, Sample::Interior, Sample::Terrain],
        }
    }

    /// Whether the scene-independent suites (stability, small lights) run.
    fn runs_suites(&self) -> bool {
        self.only_scenes.is_none() && self.only_knobs.is_none()
    }

    /// Whether this study measures `knobs`, a point of the grid of a scene whose sphere
    /// budget is `default_blockers`.
    fn keeps(&self, knobs: &Knobs, default_blockers: SphereBudget) -> bool {
        let Some(wanted) = &self.only_knobs else {
            return true;
        };
        let defaults = Knobs {
            shadows: Some(ShadowSettings::default().every_pixel()),
            blockers: default_blockers,
            lighting: Lighting::Direct,
        };
        knobs.shadows.is_none()
            || *knobs == defaults
            || *knobs == grid::shipped_defaults(default_blockers)
            || knobs.label().contains(wanted.as_str())
    }

    fn size(&self) -> (u32, u32) {
        if self.quick { (160, 90) } else { (480, 270) }
    }

    fn reference_spp(&self) -> u32 {
        if self.quick { 128 } else { 1024 }
    }

    fn timed_frames(&self) -> u32 {
        if self.quick { 3 } else { 10 }
    }

    /// Image size of the stability cases.
    pub fn stability_size(&self) -> (u32, u32) {
        if self.quick { (64, 48) } else { (256, 192) }
    }
}

#[derive(Debug, thiserror::Error)]
pub enum StudyError {
    #[error(transparent)]
    Project(#[from] ProjectError),
    #[error(transparent)]
    Render(#[from] RenderError),
    #[error("{path}: cannot write: {source}")]
    Write {
        path: PathBuf,
        #[source]
        source: std::io::Error,
    },
    #[error("{path}: cannot write image: {source}")]
    Image {
        path: PathBuf,
        #[source]
        source: image::ImageError,
    },
}

/// One measured point: a scene, the knobs, the time and the errors.
#[derive(Debug, Clone, PartialEq)]
pub struct StudyRow {
    pub scene: String,
    pub knobs: Knobs,
    pub blocker_count: usize,
    /// Mean time per frame in milliseconds (GPU frames, or CPU shading for the reference
    /// exponential).
    pub ms_per_frame: f64,
    pub errors: ImageErrors,
    /// Pixels with a channel at 0 or 255 where the reference has neither: NaN and inf
    /// show up so, as do shadows too dark to display (counted, not hidden).
    pub extreme_pixels: usize,
}

/// The reference of one scene and what it says about its own noise.
#[derive(Debug, Clone, PartialEq)]
pub struct SceneReference {
    pub scene: String,
    /// 0: direct light only.
    pub bounces: u32,
    pub samples_per_pixel: u32,
    pub seconds: f64,
    /// RMSE of the full reference's noise, estimated from its two halves.
    pub noise_rmse: f64,
}

/// Everything a study measured.
#[derive(Debug, Clone, PartialEq)]
pub struct StudyResults {
    pub width: u32,
    pub height: u32,
    pub adapter: String,
    pub references: Vec<SceneReference>,
    pub rows: Vec<StudyRow>,
    /// The stability suite's cases, at [`StudyOptions::stability_size`].
    pub stability: Vec<stability::StabilityResult>,
    /// Small lights: penumbra errors of the SH and exact paths.
    pub penumbrae: Vec<penumbra::PenumbraRow>,
    /// Small lights over mesh blockers: the exact path's error by sphere budget.
    pub sphere_fit: Vec<sphere_fit::SphereFitRow>,
    /// The shadow maps over the sphere-fit suite's meshes (no spheres needed).
    pub mesh_maps: Option<penumbra::PenumbraRow>,
    /// Per scene: the path tracer's samples per pixel (and time) to match the default
    /// frame's shadowed-pixel RMSE.
    pub equal_error: Vec<EqualError>,
    /// ms per frame of 8 small lights and 50 blockers, by path, at `cost_size`² pixels.
    pub eight_light_cost: Vec<(crate::shading::LightPaths, f64)>,
    pub cost_size: u32,
    pub stability_size: (u32, u32),
}

/// Runs the study, writing its outputs into `options.output_dir`; `say` receives one line
/// per step.
pub fn run_study(
    gpu: &GpuContext,
    options: &StudyOptions,
    mut say: impl FnMut(&str),
) -> Result<StudyResults, StudyError> {
    let (width, height) = options.size();
    std::fs::create_dir_all(options.output_dir.join("images")).map_err(|source| StudyError::Write {
        path: options.output_dir.clone(),
        source,
    })?;
    let scratch = tempfile::tempdir().map_err(|source| StudyError::Write {
        path: std::env::temp_dir(),
        source,
    })?;
    let mut results = StudyResults {
        width,
        height,
        adapter: gpu.adapter_summary(),
        references: Vec::new(),
        rows: Vec::new(),
        stability: Vec::new(),
        stability_size: options.stability_size(),
        penumbrae: Vec::new(),
        sphere_fit: Vec::new(),
        mesh_maps: None,
        equal_error: Vec::new(),
        eight_light_cost: Vec::new(),
        cost_size: if options.quick { 128 } else { 540 },
    };
    for sample in options.scenes() {
        let document = Document::open(&sample.write(scratch.path())?)?;
        let camera = document.view().camera();
        let scene_study = SceneStudy {
            gpu,
            name: sample.name(),
            scene: &document.scene,
            camera: &camera,
            settings: &document.settings,
            width,
            height,
            frames: options.timed_frames(),
            surfaces: capture_surfaces(gpu, &document.scene, &camera, None, width, height)?,
        };
        let grid: Vec<Knobs> = knob_grid(
            options.quick,
            document.settings.blockers.budget,
            document.scene.terrain.is_some(),
        )
        .into_iter()
        .filter(|knobs| options.keeps(knobs, document.settings.blockers.budget))
        .collect();
        let gi_bounces = crate::bake::BakeSettings::default().bounces as u32;
        let wants_gi = grid.iter().any(|k| k.lighting != Lighting::Direct);
        let mut references = Vec::new();
        for bounces in std::iter::once(0).chain(wants_gi.then_some(gi_bounces)) {
            let started = Instant::now();
            let (image, noise_rmse) = scene_study.converged_reference(options.reference_spp(), bounces);
            let entry = SceneReference {
                scene: sample.name().into(),
                bounces,
                samples_per_pixel: options.reference_spp(),
                seconds: started.elapsed().as_secs_f64(),
                noise_rmse,
            };
            say(&format!(
                "{}: reference ({} bounces) {} spp in {:.1} s, noise RMSE {:.4}",
                entry.scene, bounces, entry.samples_per_pixel, entry.seconds, noise_rmse
            ));
            results.references.push(entry);
            references.push(image);
        }
        let references = References {
            direct: &references[0],
            gi: references.get(1),
        };
        let rows = scene_study.measure_grid(&references, &grid, &options.output_dir, &mut say)?;
        // The frame the artist sees: the shipped defaults.
        let shipped = grid::shipped_defaults(document.settings.blockers.budget);
        let default_row = rows.iter().find(|r| r.knobs == shipped);
        if let Some(row) = default_row
            && let Some(target) = row.errors.shadow_rmse
        {
            let max_spp = if options.quick { 64 } else { options.reference_spp() / 4 };
            let trace = scene_study.equal_error_spp(references.direct, target, max_spp);
            let (spp, trace_ms) = (trace.samples_per_pixel, trace.trace_ms);
            let entry = EqualError {
                scene: sample.name().into(),
                frame_shadow_rmse: target,
                frame_ms: row.ms_per_frame,
                samples_per_pixel: spp,
                trace_ms,
                curve: trace.curve,
            };
            say(&format!(
                "{}: the path tracer matches the default frame's shadow RMSE {:.4} at {} spp in {:.0} ms ({:.1}× the frame's {:.1} ms)",
                entry.scene,
                target,
                spp.map_or(format!("over {max_spp}"), |n| n.to_string()),
                trace_ms,
                trace_ms / row.ms_per_frame.max(1e-3),
                row.ms_per_frame
            ));
            results.equal_error.push(entry);
        }
        results.rows.extend(rows);
    }
    if !options.runs_suites() {
        report::write_all(&results, &options.output_dir)?;
        return Ok(results);
    }
    let (stability_width, stability_height) = options.stability_size();
    for case in stability::stability_cases() {
        let result = stability::measure(gpu, &case, stability_width, stability_height)?;
        say(&format!(
            "stability, {}: {} non-finite, {} negative, {} above unshadowed; GPU {:.2} % within 2/255, worst {}/255",
            result.name,
            result.non_finite,
            result.negative,
            result.above_unshadowed,
            100.0 * result.gpu_within_2,
            result.gpu_worst
        ));
        results.stability.push(result);
    }
    for row in penumbra::measure_penumbrae(gpu, options.quick)? {
        say(&format!(
            "small lights, {} via {}{:?}: penumbra RMS {:.4} ({} px), umbra RMS {}, {:.1} ms",
            row.light,
            if row.defaults { "defaults: " } else { "" },
            row.path,
            row.penumbra_rms,
            row.penumbra_pixels,
            row.umbra_rms.map_or("–".into(), |e| format!("{e:.4}")),
            row.ms_per_frame
        ));
        results.penumbrae.push(row);
    }
    for row in sphere_fit::measure_sphere_fit(gpu, options.quick)? {
        say(&format!(
            "sphere fit on meshes, budget {}: {} spheres, fit error {:.3}; penumbra RMS exact {:.4}, SH {:.4}",
            row.budget, row.spheres, row.fit_error, row.exact_penumbra_rms, row.sh_penumbra_rms
        ));
        results.sphere_fit.push(row);
    }
    let maps = sphere_fit::measure_mesh_maps(gpu, options.quick)?;
    say(&format!(
        "shadow maps on the same meshes: penumbra RMS {:.4}, umbra RMS {}",
        maps.penumbra_rms,
        maps.umbra_rms.map_or("–".into(), |e| format!("{e:.4}"))
    ));
    results.mesh_maps = Some(maps);
    results.eight_light_cost = penumbra::cost_of_eight_lights(gpu, results.cost_size, options.timed_frames())?;
    for (path, ms) in &results.eight_light_cost {
        say(&format!(
            "8 small lights × 50 blockers via {path:?}: {ms:.1} ms per frame"
        ));
    }
    report::write_all(&results, &options.output_dir)?;
    Ok(results)
}

/// A scene's displayed references: direct light, and with one bounce when the grid asks.
struct References<'a> {
    direct: &'a image::RgbaImage,
    gi: Option<&'a image::RgbaImage>,
}

/// One scene's share of the study.
struct SceneStudy<'a> {
    gpu: &'a GpuContext,
    name: &'static str,
    scene: &'a Scene,
    camera: &'a Camera,
    settings: &'a RenderSettings,
    width: u32,
    height: u32,
    frames: u32,
    /// The rasteriser's visible surface of each pixel (one sample at its centre).
    surfaces: Vec<Option<SurfacePoint>>,
}

impl SceneStudy<'_> {
    /// The reference at `spp` with `bounces` as the mean of two independent halves, and
    /// the RMSE of its noise: for halves a and b, var(a − b) = 2σ²_half and
    /// σ_full = σ_half/√2, so σ_full = rms(a − b)/2 (on the displayed image).
    fn converged_reference(&self, spp: u32, bounces: u32) -> (image::RgbaImage, f64) {
        let hits: Vec<Option<SurfaceHit>> = self.surfaces.iter().map(|s| s.as_ref().map(surface_hit)).collect();
        let half = |seed: u64| {
            let mut render = ProgressiveRender::from_surfaces(
                self.scene,
                hits.clone(),
                self.camera.position,
                self.width,
                bounces,
                seed,
            );
            for _ in 0..(spp / 2).max(1) {
                render.run_pass();
            }
            render.image()
        };
        let (a, b) = (half(1), half(2));
        let display = |r: &ReferenceImage| r.to_srgb8(self.settings.exposure_ev as f64, self.settings.background_srgb8);
        let noise = image_errors(
            &DisplayImage::from_rgba8(&display(&a)),
            &DisplayImage::from_rgba8(&display(&b)),
            &[],
        )
        .rmse
            / 2.0;
        // Both halves see the same surfaces, so their coverage is the same.
        let mean = ReferenceImage {
            radiance: a
                .radiance
                .iter()
                .zip(&b.radiance)
                .map(|(x, y)| (*x + *y) / 2.0)
                .collect(),
            samples_per_pixel: a.samples_per_pixel + b.samples_per_pixel,
            discarded_samples: a.discarded_samples + b.discarded_samples,
            rays_cast: a.rays_cast + b.rays_cast,
            ..a
        };
        (display(&mean), noise)
    }

    fn measure_grid(
        &self,
        references: &References,
        grid: &[Knobs],
        output_dir: &std::path::Path,
        say: &mut impl FnMut(&str),
    ) -> Result<Vec<StudyRow>, StudyError> {
        let direct_display = DisplayImage::from_rgba8(references.direct);
        let gi_display = references.gi.map(DisplayImage::from_rgba8);
        let unshadowed = self.unshadowed()?;
        // Shadows are where direct light is blocked, whatever the reference.
        let shadowed = shadow_mask(&direct_display, &DisplayImage::from_rgba8(&unshadowed));
        let baked = grid
            .iter()
            .any(|k| k.lighting == Lighting::Gi { baked_indirect: true })
            .then(|| self.baked_indirect());
        let mut rows = Vec::new();
        for knobs in grid {
            let (reference, reference_display) = match (knobs.lighting, references.gi, &gi_display) {
                (Lighting::Gi { .. }, Some(gi), Some(gi_display)) => (gi, gi_display),
                _ => (references.direct, &direct_display),
            };
            let indirect = match knobs.lighting {
                Lighting::Gi { baked_indirect: true } => baked.as_ref(),
                _ => None,
            };
            let (image, ms_per_frame, blocker_count) = self.render(knobs, &unshadowed, indirect)?;
            let display = DisplayImage::from_rgba8(&image);
            let row = StudyRow {
                scene: self.name.into(),
                knobs: *knobs,
                blocker_count,
                ms_per_frame,
                errors: image_errors(&display, reference_display, &shadowed),
                extreme_pixels: extreme_pixels(&image, reference),
            };
            say(&format!(
                "{} {}: {:.1} ms, RMSE {:.4}, SSIM {:.4}",
                self.name,
                knobs.label(),
                ms_per_frame,
                row.errors.rmse,
                row.errors.ssim
            ));
            if report::wants_side_by_side(knobs) {
                let path = output_dir
                    .join("images")
                    .join(format!("{}-{}.png", self.name, knobs.label()));
                report::side_by_side(reference, &image, reference_display, &display)
                    .save(&path)
                    .map_err(|source| StudyError::Image { path, source })?;
            }
            rows.push(row);
        }
        Ok(rows)
    }

    /// The frame without shadows, pixel for pixel as the rasteriser sees it: the CPU
    /// shading of the captured surfaces with no blockers (G = 1, the raster pass's
    /// shading exactly).
    fn unshadowed(&self) -> Result<image::RgbaImage, StudyError> {
        // No shadow maps either: with them the f64 shading casts rays for the mapped
        // lights, and this baseline (and the shadowed-pixel mask drawn from it) had the
        // maps' shadows in it once maps were on by default.
        let shadows = crate::shading::ShadowSettings {
            shadow_map_size: 0,
            ..crate::shading::ShadowSettings::default()
        };
        let frame = ShadowFrame {
            baked_indirect: None,
            scene: self.scene,
            camera: self.camera,
            settings: self.settings,
            shadows: &shadows,
            blockers: &[],
            width: self.width,
            height: self.height,
        };
        Ok(shade_surfaces(&self.surfaces, &frame)?)
    }

    /// The indirect light of maps baked at the default settings (the bake's own time is in
    /// docs/performance.md, not in the frame time).
    fn baked_indirect(&self) -> BakedIndirect {
        let maps = crate::bake::bake_maps(self.scene, &crate::bake::BakeSettings::default());
        BakedIndirect::from_maps(self.scene, &maps)
    }

    /// The image of `knobs` (with `indirect` light added), its mean time per frame and its
    /// blocker count.
    fn render(
        &self,
        knobs: &Knobs,
        unshadowed: &image::RgbaImage,
        indirect: Option<&BakedIndirect>,
    ) -> Result<(image::RgbaImage, f64, usize), StudyError> {
        let Some(shadows) = &knobs.shadows else {
            let raster = RasterRenderer::new(
                self.gpu,
                self.scene,
                self.camera,
                self.settings,
                self.width,
                self.height,
                1,
            )?;
            raster.draw_and_wait()?;
            let ms = mean_frame_ms(self.frames, || raster.draw_and_wait())?;
            return Ok((unshadowed.clone(), ms, 0));
        };
        let blocker_settings = BlockerSettings {
            budget: knobs.blockers,
            ..self.settings.blockers
        };
        let blockers = fit_scene(self.scene, &blocker_settings).spheres();
        let frame = ShadowFrame {
            baked_indirect: indirect,
            scene: self.scene,
            camera: self.camera,
            settings: self.settings,
            shadows,
            blockers: &blockers,
            width: self.width,
            height: self.height,
        };
        if knobs.on_cpu() {
            let started = Instant::now();
            let image = shade_surfaces(&self.surfaces, &frame)?;
            return Ok((image, started.elapsed().as_secs_f64() * 1000.0, blockers.len()));
        }
        let mut renderer = ShadowRenderer::new(self.gpu, &frame, AntiAliasing::None)?;
        let image = renderer.read_image()?;
        let ms = mean_frame_ms(self.frames, || renderer.draw_and_wait(Redraw::Everything))?;
        Ok((image, ms, blockers.len()))
    }
}

/// Mean milliseconds of `frames` (at least one) calls of `draw`.
fn mean_frame_ms(frames: u32, mut draw: impl FnMut() -> Result<(), RenderError>) -> Result<f64, StudyError> {
    let started = Instant::now();
    for _ in 0..frames.max(1) {
        draw()?;
    }
    Ok(started.elapsed().as_secs_f64() * 1000.0 / frames.max(1) as f64)
}

/// The path tracer's view of a rasterised surface point (its shading normal stands for
/// the face normal, which the capture does not keep).
fn surface_hit(point: &SurfacePoint) -> SurfaceHit {
    let normal = point.normal.as_vec3();
    SurfaceHit {
        position: point.position.as_vec3(),
        geometric_normal: normal,
        normal,
        reflectance: crate::scene::Reflectance {
            k_d: point.k_d,
            k_s: point.k_s,
            phong_exponent: point.phong_exponent,
        },
        emissive: point.emissive,
    }
}

/// Pixels the reference shows at under 80 % of the unshadowed render's luminance (and
/// that are lit at all): where shadows are.
fn shadow_mask(reference: &DisplayImage, unshadowed: &DisplayImage) -> Vec<bool> {
    reference
        .luminance()
        .into_iter()
        .zip(unshadowed.luminance())
        .map(|(r, u)| u > 0.01 && r < 0.8 * u)
        .collect()
}

fn extreme_pixels(image: &image::RgbaImage, reference: &image::RgbaImage) -> usize {
    let extreme = |p: &image::Rgba<u8>| (0..3).any(|c| p[c] == 0 || p[c] == 255);
    image
        .pixels()
        .zip(reference.pixels())
        .filter(|(p, r)| extreme(p) && !extreme(r))
        .count()
}
