//! The `lightpaint` command: the editor, and headless commands for scripts and CI.
//! Exit codes: 0 success, 1 failure, 2 bad input or usage. Errors are reported once, on
//! one line, naming the file and the cause.

use std::path::{Path, PathBuf};
use std::process::ExitCode;

use clap::{Parser, Subcommand};
use lightpaint::blockers::{SphereBudget, fit_scene};
use lightpaint::project::{Document, ProjectError};
use lightpaint::render::{
    AntiAliasing, BakedIndirect, BrdfShading, GpuContext, LightPaths, RenderError, ShadowFrame, ShadowRenderer,
    ShadowSettings, parse_exp_method, render_cpu_image, render_image, render_logsh_image,
};
use lightpaint::scene::SceneError;
use lightpaint::sh::ExpMethod;

#[derive(Parser)]
#[command(name = "lightpaint", version, about = "Light a 3D scene by painting on it")]
#[command(args_conflicts_with_subcommands = true)]
struct Cli {
    #[command(subcommand)]
    command: Option<Command>,
    /// A project (.lightpaint) or a .gltf/.glb scene to open in the editor (default: the
    /// bundled sample project).
    file: Option<PathBuf>,
}

#[derive(Subcommand)]
enum Command {
    /// Render a project or scene offscreen with wgpu (or the reference path tracer) and
    /// write a PNG.
    Render(RenderArgs),
    /// Measure the real-time renderer's knobs against the reference path tracer: CSV,
    /// markdown table, Pareto plot and side-by-side images in the output directory.
    Study {
        /// A small grid (17 settings) on the sample at 160×90: seconds, not minutes.
        #[arg(long)]
        quick: bool,
        /// Directory for study.csv, study.md, pareto.png and images/.
        #[arg(short, long)]
        output: PathBuf,
        /// Only this sample scene (repeatable: sample, studio, interior, large, terrain),
        /// without the stability and small-light suites.
        #[arg(long = "scene", value_parser = parse_sample)]
        scenes: Vec<lightpaint::samples::Sample>,
        /// Only the settings whose label contains this (e.g. "brdf", "vertex", "-s"), with
        /// the no-shadow baseline and the defaults, without the stability and small-light
        /// suites.
        #[arg(long)]
        knobs: Option<String>,
    },
    /// Validate a project or scene file; print every problem found, exit 2 if there is one.
    Check {
        /// The project (.lightpaint) or .gltf/.glb file to check.
        file: PathBuf,
    },
    /// Bake the source-importance maps (direct light and diffuse bounces of every light at
    /// every vertex, as SH) and report their size and the time taken.
    Bake {
        /// The project (.lightpaint) or .gltf/.glb scene.
        file: PathBuf,
        /// SH order of the maps (1–8).
        #[arg(long, default_value_t = 3, value_parser = clap::value_parser!(u8).range(1..=8))]
        order: u8,
        /// Emitter samples per extended light (sphere, rect, disk) and vertex.
        #[arg(long, visible_alias = "samples", default_value_t = 16, value_parser = clap::value_parser!(u16).range(1..=4096))]
        light_samples: u16,
        /// Diffuse bounces of indirect light (0–8; Russian roulette from the third).
        #[arg(long, default_value_t = 1, value_parser = clap::value_parser!(u8).range(0..=8))]
        bounces: u8,
        /// Hemisphere directions per vertex for the bounce.
        #[arg(long, default_value_t = 32, value_parser = clap::value_parser!(u16).range(1..=4096))]
        directions: u16,
        /// Drop a vertex's entry for a light under this share of the light's peak (0–1).
        #[arg(long, default_value_t = 1e-4, value_parser = parse_threshold)]
        threshold: f32,
        /// Store the coefficients in half precision (half the memory, 3 digits).
        #[arg(long)]
        f16: bool,
    },
    /// Apply scripted strokes (docs/strokes.md) to a project or scene and save the result,
    /// with the strokes in its log, as a project.
    Paint {
        /// The project (.lightpaint) or .gltf/.glb scene to paint.
        file: PathBuf,
        /// The stroke script (JSON).
        #[arg(long)]
        strokes: PathBuf,
        /// The project file to write (.lightpaint).
        #[arg(short, long)]
        output: PathBuf,
        /// Diffuse bounces in the bake the strokes read (0–8).
        #[arg(long, default_value_t = 1, value_parser = clap::value_parser!(u8).range(0..=8))]
        bounces: u8,
        /// Read the transfer from the real-time log-SH shading (direct light only) instead
        /// of baking.
        #[arg(long, conflicts_with = "bounces")]
        no_bake: bool,
    },
}

#[derive(clap::Args)]
struct RenderArgs {
    /// The project (.lightpaint) or .gltf/.glb scene.
    file: PathBuf,
    /// Output PNG file.
    #[arg(short, long)]
    output: PathBuf,
    #[arg(long, default_value_t = 1280)]
    width: u32,
    #[arg(long, default_value_t = 720)]
    height: u32,
    /// Exposure in stops (radiance × 2^EV before tone mapping); default: the project's, or 0.
    #[arg(long, allow_negative_numbers = true, value_parser = parse_exposure)]
    exposure: Option<f32>,
    /// Background colour as 8-bit sRGB "R,G,B".
    #[arg(long, value_parser = parse_srgb8)]
    background: Option<[u8; 3]>,
    /// SH order of the shadows (bands, 2–8 on the GPU); default: the project's, or 4.
    #[arg(long)]
    order: Option<usize>,
    /// Exponentiation: dc, ol, hyb, ps<k> (power series of k terms) or ref (CPU only);
    /// default: the project's, or hyb.
    #[arg(long, value_parser = parse_exp_method)]
    exp: Option<ExpMethod>,
    /// Log-visibility of a blocked direction is ln(eps); default: the project's, or 0.1.
    #[arg(long)]
    eps: Option<f32>,
    /// Sphere blockers: "auto" (per-mesh error budget) or a total count for the scene;
    /// default: the project's.
    #[arg(long, value_parser = parse_blockers)]
    blockers: Option<SphereBudget>,
    /// Scale each blocker's log-visibility by r/d (Ren's ratio attenuation).
    #[arg(long)]
    ratio_attenuation: bool,
    /// Which lights are shadowed exactly, per light, instead of through the SH: auto
    /// (extended lights under 40° of angular radius), harmonics (none) or exact (all);
    /// default: the project's.
    #[arg(long, value_parser = parse_light_paths)]
    light_paths: Option<LightPaths>,
    /// Under --light-paths auto, at most this many lights go the exact way (sphere and area
    /// lights, those whose shadows fall on most of the scene first, 0-64); default: the
    /// project's, or 4.
    #[arg(long)]
    exact_lights: Option<u32>,
    /// How the BRDF meets the visibility: separate (each light's exact BRDF times its
    /// visibility), log (the log-BRDF added before exponentiating) or product (the BRDF
    /// multiplied in by the SH product); default: the project's, or separate.
    #[arg(long, value_parser = BrdfShading::parse)]
    brdf: Option<BrdfShading>,
    /// Terrain: marching directions per receiver (W, 3–64); default: the project's, or 16.
    #[arg(long)]
    terrain_azimuths: Option<u32>,
    /// Terrain: height pyramid levels read while marching (1–12); default: the project's, or 6.
    #[arg(long)]
    terrain_levels: Option<u32>,
    /// Exponentiate the visibility at the vertices and interpolate it (faster; orders ≤ 6).
    #[arg(long, conflicts_with = "cpu")]
    per_vertex: bool,
    /// Shade one pixel in every d × d and upsample the rest from the samples on each
    /// pixel's surface (1 shades every pixel; 1–4); default: the project's, or 3.
    #[arg(long, conflicts_with = "cpu")]
    shading_downsample: Option<u32>,
    /// Antialiasing of log-SH frames: filter (one sample per pixel, then an edge filter),
    /// msaa (4 samples per pixel) or none (one sample at each pixel centre, as --cpu
    /// shades). --no-shadows frames are multisampled.
    #[arg(long, default_value = "filter", value_parser = parse_anti_aliasing)]
    aa: AntiAliasing,
    /// Also time this many more GPU frames (after one warm-up) and print ms per frame.
    #[arg(long, default_value_t = 0, conflicts_with_all = ["cpu", "no_shadows"])]
    time_frames: u32,
    /// Shade on the CPU in f64 (the reference), from surfaces rasterised on the GPU.
    #[arg(long, conflicts_with = "no_shadows")]
    cpu: bool,
    /// Render without shadows (the plain raster pass).
    #[arg(long)]
    no_shadows: bool,
    /// Leave out the baked indirect light (by default a project whose setting is on adds
    /// it from its bake cache, when there is one: see `lightpaint bake`).
    #[arg(long)]
    no_baked_indirect: bool,
    /// Render the ground truth with the path tracer (real geometry, no sphere proxies).
    #[arg(long, conflicts_with_all = ["cpu", "no_shadows", "per_vertex", "time_frames"])]
    reference: bool,
    /// Reference samples (paths) per pixel.
    #[arg(long, default_value_t = 64, requires = "reference", value_parser = clap::value_parser!(u32).range(1..=1_000_000))]
    spp: u32,
    /// Reference indirect bounces: 0 = direct light only.
    #[arg(long, default_value_t = 4, requires = "reference", value_parser = clap::value_parser!(u32).range(0..=lightpaint::reference::MAX_BOUNCES as i64))]
    bounces: u32,
    /// Seed of the reference's random numbers (the same seed gives the same image).
    #[arg(long, default_value_t = 1, requires = "reference")]
    seed: u64,
}

fn parse_light_paths(text: &str) -> Result<LightPaths, String> {
    match text.trim() {
        "auto" => Ok(LightPaths::Auto),
        "harmonics" | "sh" => Ok(LightPaths::Harmonics),
        "exact" => Ok(LightPaths::Exact),
        other => Err(format!("'{other}' is not one of auto, harmonics, exact")),
    }
}

fn parse_anti_aliasing(text: &str) -> Result<AntiAliasing, String> {
    match text.trim() {
        "filter" => Ok(AntiAliasing::EdgeFilter),
        "msaa" => Ok(AntiAliasing::Multisample),
        "none" => Ok(AntiAliasing::None),
        other => Err(format!("'{other}' is not one of filter, msaa, none")),
    }
}

fn parse_blockers(text: &str) -> Result<SphereBudget, String> {
    if text.trim().eq_ignore_ascii_case("auto") {
        return Ok(lightpaint::blockers::BlockerSettings::default().budget);
    }
    match text.trim().parse::<usize>() {
        Ok(count) if count <= 100_000 => Ok(SphereBudget::Total(count)),
        _ => Err(format!("expected 'auto' or a sphere count up to 100000, got '{text}'")),
    }
}

fn parse_threshold(text: &str) -> Result<f32, String> {
    match text.parse::<f32>() {
        Ok(t) if (0.0..=1.0).contains(&t) => Ok(t),
        _ => Err(format!("expected a share between 0 and 1, got '{text}'")),
    }
}

fn parse_exposure(text: &str) -> Result<f32, String> {
    match text.parse::<f32>() {
        Ok(ev) if ev.is_finite() && ev.abs() <= 64.0 => Ok(ev),
        _ => Err(format!("expected an exposure between -64 and 64 EV, got '{text}'")),
    }
}

fn parse_srgb8(text: &str) -> Result<[u8; 3], String> {
    let parts: Vec<&str> = text.split(',').map(str::trim).collect();
    let values: Result<Vec<u8>, _> = parts.iter().map(|p| p.parse::<u8>()).collect();
    match values {
        Ok(v) if v.len() == 3 => Ok([v[0], v[1], v[2]]),
        _ => Err(format!("expected three integers 0–255 as R,G,B, got '{text}'")),
    }
}

/// What went wrong, and which exit code it deserves.
#[derive(Debug, thiserror::Error)]
enum CliError {
    #[error(transparent)]
    Scene(#[from] SceneError),
    #[error(transparent)]
    Project(#[from] ProjectError),
    #[error("{path}: {count} problem(s) found")]
    Problems { path: PathBuf, count: usize },
    #[error(transparent)]
    Render(#[from] RenderError),
    #[error("{path}: cannot write image: {source}")]
    WriteImage {
        path: PathBuf,
        #[source]
        source: image::ImageError,
    },
    #[error(transparent)]
    Script(#[from] lightpaint::paint::script::ScriptError),
    #[error(transparent)]
    Study(#[from] lightpaint::study::StudyError),
    #[error("{0}")]
    Usage(String),
    #[error("the editor failed: {0}")]
    Editor(String),
}

impl CliError {
    fn exit_code(&self) -> ExitCode {
        match self {
            CliError::Scene(_)
            | CliError::Project(_)
            | CliError::Problems { .. }
            | CliError::Usage(_)
            | CliError::Script(_)
            | CliError::Render(RenderError::BadSettings(_))
            | CliError::Render(RenderError::BadSize { .. }) => ExitCode::from(2),
            _ => ExitCode::from(1),
        }
    }
}

/// Prints a line to stdout, ignoring a closed pipe (`lightpaint check FILE | head` must not
/// panic); `println!` would.
macro_rules! say {
    ($($arg:tt)*) => {{
        use std::io::Write as _;
        let _ = writeln!(std::io::stdout(), $($arg)*);
    }};
}

/// Asks Mesa's software rasterizer (llvmpipe, which runs wgpu on a machine without a GPU
/// and reads this variable once its driver loads) for two threads per core unless the
/// user chose a number. It splits each render pass into 64 × 64 tiles shared among its
/// threads; the reduced-resolution shading pass has few tiles of very uneven cost, and
/// with one thread per core one core idled while the other finished the heaviest. Twice
/// as many threads keep both busy: the studio's default frame a few milliseconds faster
/// on the mean, shading every pixel no faster, four threads per core slower again
/// (docs/performance.md). Other drivers ignore the variable.
fn prefer_two_rasterizer_threads_per_core() {
    const VARIABLE: &str = "LP_NUM_THREADS";
    if std::env::var_os(VARIABLE).is_none() {
        let cores = std::thread::available_parallelism().map_or(1, |n| n.get());
        // SAFETY: the first thing main does, while this is the process's only thread.
        unsafe { std::env::set_var(VARIABLE, (2 * cores).to_string()) };
    }
}

fn main() -> ExitCode {
    prefer_two_rasterizer_threads_per_core();
    env_logger::Builder::from_env(env_logger::Env::default().default_filter_or("warn")).init();
    lightpaint::panic_guard::install_quiet_panic_hook();
    let cli = Cli::parse();
    let result = match cli.command {
        Some(Command::Render(args)) => render(&args),
        Some(Command::Check { file }) => check(&file),
        Some(Command::Study {
            quick,
            output,
            scenes,
            knobs,
        }) => study(quick, output, scenes, knobs),
        Some(Command::Bake {
            file,
            order,
            light_samples,
            bounces,
            directions,
            threshold,
            f16,
        }) => {
            let settings = lightpaint::bake::BakeSettings {
                order: order as usize,
                light_samples: light_samples as usize,
                bounces: bounces as usize,
                indirect_directions: directions as usize,
                relative_threshold: threshold,
                precision: if f16 {
                    lightpaint::bake::Precision::F16
                } else {
                    lightpaint::bake::Precision::F32
                },
                ..Default::default()
            };
            bake(&file, &settings)
        }
        Some(Command::Paint {
            file,
            strokes,
            output,
            bounces,
            no_bake,
        }) => paint(&file, &strokes, &output, (!no_bake).then_some(bounces as usize)),
        None => editor(cli.file),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("error: {e}");
            e.exit_code()
        }
    }
}

fn render(args: &RenderArgs) -> Result<(), CliError> {
    let document = Document::open(&args.file)?;
    for warning in &document.warnings {
        eprintln!("warning: {}: {warning}", args.file.display());
    }
    let mut settings = document.settings;
    if let Some(exposure) = args.exposure {
        settings.exposure_ev = exposure;
    }
    if let Some(background) = args.background {
        settings.background_srgb8 = background;
    }
    let camera = match document.camera {
        Some(orbit) => orbit.camera(),
        None => document.scene.initial_camera(),
    };
    if args.reference {
        let reference = lightpaint::reference::ReferenceSettings {
            samples_per_pixel: args.spp,
            bounces: args.bounces,
            seed: args.seed,
        };
        return render_reference_png(&args.file, &document, &camera, &settings, &reference, args);
    }
    let gpu = GpuContext::headless()?;
    let mut shadows = settings.shadows;
    shadows.order = args.order.unwrap_or(shadows.order);
    shadows.exp = args.exp.unwrap_or(shadows.exp);
    shadows.epsilon = args.eps.unwrap_or(shadows.epsilon);
    shadows.ratio_attenuation |= args.ratio_attenuation;
    shadows.light_paths = args.light_paths.unwrap_or(shadows.light_paths);
    shadows.brdf = args.brdf.unwrap_or(shadows.brdf);
    shadows.exact_light_budget = args.exact_lights.unwrap_or(shadows.exact_light_budget);
    shadows.terrain.azimuths = args.terrain_azimuths.unwrap_or(shadows.terrain.azimuths);
    shadows.terrain.pyramid_levels = args.terrain_levels.unwrap_or(shadows.terrain.pyramid_levels);
    // The CPU reference shades every pixel; a project's per-vertex choice is for the GPU.
    shadows.per_vertex = (shadows.per_vertex || args.per_vertex) && !args.cpu;
    shadows.shading_downsample = match args.cpu {
        true => 1,
        false => args.shading_downsample.unwrap_or(shadows.shading_downsample),
    };
    let no_shadows = args.no_shadows || !shadows.enabled;
    let problems = if args.cpu {
        shadows.problems()
    } else {
        shadows.gpu_problems()
    };
    if !no_shadows && !problems.is_empty() {
        return Err(CliError::Usage(problems.join("; ")));
    }
    let mut blocker_settings = settings.blockers;
    if let Some(budget) = args.blockers {
        blocker_settings.budget = budget;
    }
    let fitted = std::time::Instant::now();
    let blockers = if no_shadows {
        Vec::new()
    } else {
        let fit = fit_scene(&document.scene, &blocker_settings);
        for line in fit.report(&document.scene) {
            log::info!("blockers: {line}");
        }
        fit.spheres()
    };
    let fit_ms = fitted.elapsed().as_secs_f64() * 1000.0;
    let indirect = if settings.baked_indirect && !args.no_baked_indirect {
        baked_indirect(&document)
    } else {
        None
    };
    let frame = ShadowFrame {
        baked_indirect: indirect.as_ref(),
        scene: &document.scene,
        camera: &camera,
        settings: &settings,
        shadows: &shadows,
        blockers: &blockers,
        width: args.width,
        height: args.height,
    };
    let started = std::time::Instant::now();
    let (image, renderer) = if no_shadows {
        (
            render_image(&gpu, &document.scene, &camera, &settings, args.width, args.height)?,
            "raster, no shadows".to_string(),
        )
    } else if args.cpu {
        (
            render_cpu_image(&gpu, &frame)?,
            format!(
                "CPU f64 reference, {}{}",
                describe(&shadows, blockers.len(), &document.scene),
                describe_indirect(&indirect)
            ),
        )
    } else {
        (
            render_logsh_image(&gpu, &frame, args.aa)?,
            format!(
                "log-SH, {}{}",
                describe(&shadows, blockers.len(), &document.scene),
                describe_indirect(&indirect)
            ),
        )
    };
    let elapsed = started.elapsed();
    if args.time_frames > 0 && !no_shadows {
        time_frames(&gpu, &frame, args.time_frames, args.aa)?;
    }
    image.save(&args.output).map_err(|source| CliError::WriteImage {
        path: args.output.clone(),
        source,
    })?;
    say!(
        "rendered {} ({}×{}, {renderer}) with {} in {:.0} ms (sphere fit {fit_ms:.0} ms) → {}",
        args.file.display(),
        args.width,
        args.height,
        gpu.adapter_summary(),
        elapsed.as_secs_f64() * 1000.0,
        args.output.display()
    );
    Ok(())
}

fn parse_sample(text: &str) -> Result<lightpaint::samples::Sample, String> {
    lightpaint::samples::Sample::from_name(text)
        .ok_or_else(|| format!("expected sample, studio, interior, large or terrain, got '{text}'"))
}

fn study(
    quick: bool,
    output_dir: PathBuf,
    scenes: Vec<lightpaint::samples::Sample>,
    knobs: Option<String>,
) -> Result<(), CliError> {
    let gpu = GpuContext::headless()?;
    let options = lightpaint::study::StudyOptions {
        quick,
        output_dir,
        only_scenes: (!scenes.is_empty()).then_some(scenes),
        only_knobs: knobs,
    };
    let started = std::time::Instant::now();
    let results = lightpaint::study::run_study(&gpu, &options, |line| say!("{line}"))?;
    say!(
        "study of {} settings on {} scene(s) in {:.0} s → {}",
        results.rows.len(),
        results.references.iter().filter(|r| r.bounces == 0).count(),
        started.elapsed().as_secs_f64(),
        options.output_dir.display()
    );
    Ok(())
}

/// `render --reference`: the path tracer, with a progress bar over its passes.
fn render_reference_png(
    file: &Path,
    document: &Document,
    camera: &lightpaint::scene::Camera,
    settings: &lightpaint::render::RenderSettings,
    reference: &lightpaint::reference::ReferenceSettings,
    args: &RenderArgs,
) -> Result<(), CliError> {
    if args.width == 0 || args.height == 0 || args.width > 16_384 || args.height > 16_384 {
        return Err(CliError::Usage(format!(
            "a reference image must be 1–16384 pixels on each side, not {}×{}",
            args.width, args.height
        )));
    }
    let started = std::time::Instant::now();
    let bar = indicatif::ProgressBar::new(reference.samples_per_pixel as u64);
    bar.set_style(
        indicatif::ProgressStyle::with_template("path tracing {bar:40} {pos}/{len} samples per pixel, {eta} left")
            .unwrap_or_else(|_| indicatif::ProgressStyle::default_bar()),
    );
    let image = lightpaint::reference::render_reference(
        &document.scene,
        camera,
        args.width,
        args.height,
        reference,
        |passes| bar.set_position(passes as u64),
    );
    bar.finish_and_clear();
    let elapsed = started.elapsed().as_secs_f64();
    image
        .to_srgb8(settings.exposure_ev as f64, settings.background_srgb8)
        .save(&args.output)
        .map_err(|source| CliError::WriteImage {
            path: args.output.clone(),
            source,
        })?;
    if image.discarded_samples > 0 {
        eprintln!(
            "warning: {}: {} samples were not finite and were left out",
            file.display(),
            image.discarded_samples
        );
    }
    let mode = if reference.bounces == 0 {
        "direct light".to_string()
    } else {
        format!("{} bounces", reference.bounces)
    };
    say!(
        "rendered {} ({}×{}, reference path tracer, {} spp, {mode}, seed {}) in {elapsed:.1} s, {:.2} M rays/s → {}",
        file.display(),
        args.width,
        args.height,
        reference.samples_per_pixel,
        reference.seed,
        image.rays_cast as f64 / elapsed.max(1e-9) / 1e6,
        args.output.display()
    );
    Ok(())
}

/// Draws `count` frames after a warm-up and prints the mean and best time per frame.
fn time_frames(gpu: &GpuContext, frame: &ShadowFrame, count: u32, anti_aliasing: AntiAliasing) -> Result<(), CliError> {
    let renderer = ShadowRenderer::new(gpu, frame, anti_aliasing)?;
    renderer.draw_and_wait()?;
    let mut times_ms = Vec::with_capacity(count as usize);
    for _ in 0..count {
        let started = std::time::Instant::now();
        renderer.draw_and_wait()?;
        times_ms.push(started.elapsed().as_secs_f64() * 1000.0);
    }
    let mean = times_ms.iter().sum::<f64>() / times_ms.len() as f64;
    let best = times_ms.iter().copied().fold(f64::INFINITY, f64::min);
    say!(
        "{count} frames: mean {mean:.1} ms ({:.1} fps), best {best:.1} ms",
        1000.0 / mean
    );
    Ok(())
}

/// The baked indirect light of a project from its bake cache, if it has a usable one
/// (a stale or unreadable cache is reported and left out; `lightpaint bake` rebuilds it).
fn baked_indirect(document: &Document) -> Option<BakedIndirect> {
    use lightpaint::project::bake_cache::{self, CacheLookup};
    let project = document.project_path.as_ref()?;
    let path = bake_cache::cache_path(project);
    match bake_cache::load_for_scene(&path, &document.scene) {
        CacheLookup::Fresh(maps) => Some(BakedIndirect::from_maps(&document.scene, &maps)),
        CacheLookup::LightsChanged { maps, lights } => {
            eprintln!(
                "warning: {}: {} light(s) moved since the bake; their indirect light is left out (run `lightpaint bake`)",
                path.display(),
                lights.len()
            );
            Some(BakedIndirect::from_maps(&document.scene, &maps))
        }
        CacheLookup::Missing => None,
        CacheLookup::Unusable(reason) => {
            eprintln!("warning: no baked indirect light: {reason} (run `lightpaint bake`)");
            None
        }
    }
}

fn describe_indirect(indirect: &Option<BakedIndirect>) -> &'static str {
    if indirect.is_some() {
        ", baked indirect light"
    } else {
        ""
    }
}

fn describe(shadows: &ShadowSettings, blocker_count: usize, scene: &lightpaint::scene::Scene) -> String {
    let terrain = if scene.terrain.is_some() {
        format!(
            ", terrain W {} × {} levels",
            shadows.terrain.azimuths, shadows.terrain.pyramid_levels
        )
    } else {
        String::new()
    };
    let resolution = if shadows.per_vertex {
        ", per vertex".to_string()
    } else if shadows.shading_downsample > 1 {
        let d = shadows.shading_downsample;
        format!(", shaded 1 in {d}×{d} pixels")
    } else {
        String::new()
    };
    format!(
        "order {}, {:?}, eps {}, {blocker_count} blockers{resolution}{terrain}, {:?} light paths, {} BRDF",
        shadows.order,
        shadows.exp,
        shadows.epsilon,
        shadows.light_paths,
        shadows.brdf.name()
    )
}

fn bake(file: &Path, settings: &lightpaint::bake::BakeSettings) -> Result<(), CliError> {
    let document = Document::open(file)?;
    for warning in &document.warnings {
        eprintln!("warning: {}: {warning}", file.display());
    }
    let scene = &document.scene;
    let order = settings.order;
    let bar = indicatif::ProgressBar::new(scene.vertex_count() as u64);
    bar.set_style(
        indicatif::ProgressStyle::with_template("baking {bar:40} {pos}/{len} vertices, {eta} left")
            .unwrap_or_else(|_| indicatif::ProgressStyle::default_bar()),
    );
    let started = std::time::Instant::now();
    let never = std::sync::atomic::AtomicBool::new(false);
    let progress = |done: usize, _: usize| bar.set_position(done as u64);
    // A project keeps its maps in the bake cache beside it; a bare scene has none.
    let maps = match &document.project_path {
        Some(project) => {
            let cache = lightpaint::project::bake_cache::cache_path(project);
            lightpaint::project::bake_cache::bake_with_cache(scene, settings, &cache, &progress, &never).map(
                |(maps, what)| {
                    bar.finish_and_clear();
                    say!("{what}");
                    maps
                },
            )
        }
        None => lightpaint::bake::bake_maps_counting(scene, settings, &progress, &never).map(|(maps, rays)| {
            let seconds = started.elapsed().as_secs_f64().max(1e-9);
            bar.finish_and_clear();
            say!("baked ({rays} rays, {:.2} M rays/s)", rays as f64 / seconds / 1e6);
            maps
        }),
    };
    bar.finish_and_clear();
    let Some(maps) = maps else {
        return Err(CliError::Usage("the bake was cancelled".into()));
    };
    let pairs = scene.vertex_count() * scene.lights.len();
    let entries = maps.entry_count();
    say!(
        "maps of {}: {} vertices × {} lights, {entries} (vertex, light) pairs stored ({:.0} % of {pairs}; {:.2} % of the pairs light reaches kept at threshold {}), order {order}, {:.1} MiB in memory, in {:.0} ms ({} bounce(s))",
        file.display(),
        scene.vertex_count(),
        scene.lights.len(),
        if pairs == 0 {
            0.0
        } else {
            100.0 * entries as f64 / pairs as f64
        },
        100.0 * maps.kept_fraction(),
        settings.relative_threshold,
        maps.memory_bytes() as f64 / (1024.0 * 1024.0),
        started.elapsed().as_secs_f64() * 1000.0,
        settings.bounces
    );
    Ok(())
}

/// `paint`: the transfer comes from a bake with `bounces`, or (None) from the direct-only
/// log-SH estimate.
fn paint(file: &Path, strokes: &Path, output: &Path, bounces: Option<usize>) -> Result<(), CliError> {
    use lightpaint::paint::{BakedTransfer, Painter, Transfer, View, ViewRecord, script::Script};
    if !lightpaint::project::is_project_path(output) {
        return Err(CliError::Usage(format!(
            "{}: the output must be a project file (.lightpaint)",
            output.display()
        )));
    }
    let mut document = Document::open(file)?;
    for warning in &document.warnings {
        eprintln!("warning: {}: {warning}", file.display());
    }
    let script = Script::load(strokes)?;
    let camera = match document.camera {
        Some(orbit) => orbit.camera(),
        None => document.scene.initial_camera(),
    };
    let fallback = ViewRecord::of(&View {
        camera,
        width_px: 1280,
        height_px: 720,
    });
    let records = script.records(strokes, fallback)?;
    let started = std::time::Instant::now();
    let scene = &document.scene;
    let maps = bounces.map(|bounces| {
        use lightpaint::project::bake_cache::{self, BakeKey, CacheLookup};
        let settings = lightpaint::bake::BakeSettings {
            bounces,
            ..Default::default()
        };
        let key = BakeKey::of(scene, &settings);
        let cached = document
            .project_path
            .as_deref()
            .map(|p| bake_cache::load(&bake_cache::cache_path(p), &key));
        let maps = match cached {
            Some(CacheLookup::Fresh(maps)) => {
                say!("read the bake cache of {}", file.display());
                maps
            }
            _ => lightpaint::bake::bake_maps(scene, &settings),
        };
        if let Err(e) = bake_cache::save(&bake_cache::cache_path(output), &key, &maps) {
            eprintln!("warning: {}: cannot write the bake cache: {e}", output.display());
        }
        maps
    });
    let estimate_blockers = || fit_scene(scene, &document.settings.blockers).spheres();
    let transfer: Box<dyn Transfer> = match &maps {
        Some(maps) => Box::new(BakedTransfer::new(scene, maps)),
        None => Box::new(lightpaint::render::paint_estimate::DirectEstimate::new(
            scene,
            estimate_blockers(),
            document.settings.shadows,
        )),
    };
    let bvh = lightpaint::bake::scene_bvh::SceneBvh::build(scene);
    say!(
        "{} the transfer of {} lights in {:.0} ms",
        if maps.is_some() {
            "baked"
        } else {
            "estimated (direct light, log-SH shadows)"
        },
        scene.lights.len(),
        started.elapsed().as_secs_f64() * 1000.0
    );
    let mut intensities = scene.light_intensities();
    let mut painter = Painter::new();
    {
        let transfer = transfer.as_ref();
        for (k, record) in records.into_iter().enumerate() {
            let started = std::time::Instant::now();
            let report = painter.paint(scene, &bvh, transfer, &mut intensities, record);
            let names: Vec<&str> = report.selected.iter().map(|&i| scene.lights[i].name.as_str()).collect();
            say!(
                "stroke {k}: {:?}, {} vertices, lights [{}]: {} ({:.1} ms)",
                report.outcome,
                report.hit_vertices,
                names.join(", "),
                report.message,
                started.elapsed().as_secs_f64() * 1000.0
            );
        }
    }
    drop(transfer);
    document.scene.set_light_intensities(&intensities);
    document.painting.strokes.extend(painter.log().cloned());
    document.save(output)?;
    say!(
        "wrote {} ({} strokes in its log)",
        output.display(),
        document.painting.strokes.len()
    );
    Ok(())
}

fn check(file: &Path) -> Result<(), CliError> {
    let document = match Document::open(file) {
        Ok(document) => document,
        Err(ProjectError::Invalid { path, problems }) => {
            for problem in &problems {
                say!("problem: {}: {problem}", path.display());
            }
            return Err(CliError::Problems {
                path,
                count: problems.len(),
            });
        }
        Err(e) => return Err(e.into()),
    };
    for warning in &document.warnings {
        say!("problem: {}: {warning}", file.display());
    }
    let scene = &document.scene;
    say!(
        "{}: {} objects, {} vertices, {} triangles, {} materials, {} textures, {} lights, {}",
        file.display(),
        scene.objects.len(),
        scene.vertex_count(),
        scene.triangle_count(),
        scene.materials.len(),
        scene.textures.len(),
        scene.lights.len(),
        if scene.camera.is_some() { "camera" } else { "no camera" }
    );
    if document.warnings.is_empty() {
        say!("{}: ok", file.display());
        Ok(())
    } else {
        Err(CliError::Problems {
            path: file.to_path_buf(),
            count: document.warnings.len(),
        })
    }
}

/// The bundled sample project: in the source tree the binary was built from, or in the
/// current directory.
fn bundled_sample() -> PathBuf {
    let in_checkout = Path::new(env!("CARGO_MANIFEST_DIR")).join(lightpaint::samples::SAMPLE_PROJECT);
    if in_checkout.exists() {
        in_checkout
    } else {
        PathBuf::from(lightpaint::samples::SAMPLE_PROJECT)
    }
}

fn editor(file: Option<PathBuf>) -> Result<(), CliError> {
    let file = file.unwrap_or_else(bundled_sample);
    // Fail before opening a window when the file is not there at all.
    if !file.exists() {
        return Err(ProjectError::NotFound { path: file }.into());
    }
    let options = lightpaint::ui::EditorOptions {
        file,
        close_when_file_exists: std::env::var_os("LIGHTPAINT_CLOSE_WHEN_FILE_EXISTS").map(PathBuf::from),
        // Screenshots for the docs leave out the numbers that change from run to run.
        hide_frame_timings: std::env::var_os("LIGHTPAINT_HIDE_FRAME_TIMINGS").is_some_and(|v| v == "1"),
    };
    lightpaint::ui::run_editor(options).map_err(|e| CliError::Editor(e.to_string()))
}
