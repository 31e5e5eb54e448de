//! The `lightpaint` command: the editor, and headless commands for scripts and CI.
//! Exit codes: 0 success, 1 failure, 2 bad input or usage. Errors are reported once, on
//! one line, naming the file and the cause.

use std::path::{Path, PathBuf};
use std::process::ExitCode;

use clap::{Parser, Subcommand};
use lightpaint::render::{GpuContext, RenderError, RenderSettings, render_image};
use lightpaint::scene::{Scene, SceneError};

#[derive(Parser)]
#[command(name = "lightpaint", version, about = "Light a 3D scene by painting on it")]
#[command(args_conflicts_with_subcommands = true)]
struct Cli {
    #[command(subcommand)]
    command: Option<Command>,
    /// A .gltf or .glb scene to open in the editor (default: the bundled sample).
    file: Option<PathBuf>,
}

#[derive(Subcommand)]
enum Command {
    /// Render a scene offscreen with wgpu and write a PNG.
    Render(RenderArgs),
    /// Validate a scene file and print every problem found.
    Check {
        /// The .gltf or .glb file to check.
        file: PathBuf,
    },
}

#[derive(clap::Args)]
struct RenderArgs {
    /// The .gltf or .glb scene.
    file: PathBuf,
    /// Output PNG file.
    #[arg(short, long)]
    output: PathBuf,
    #[arg(long, default_value_t = 1280)]
    width: u32,
    #[arg(long, default_value_t = 720)]
    height: u32,
    /// Exposure in stops (radiance × 2^EV before tone mapping).
    #[arg(long, default_value_t = 0.0, allow_negative_numbers = true)]
    exposure: f32,
    /// Background colour as 8-bit sRGB "R,G,B".
    #[arg(long, value_parser = parse_srgb8)]
    background: Option<[u8; 3]>,
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
    Render(#[from] RenderError),
    #[error("{path}: cannot write image: {source}")]
    WriteImage {
        path: PathBuf,
        #[source]
        source: image::ImageError,
    },
    #[error("the editor failed: {0}")]
    Editor(String),
}

impl CliError {
    fn exit_code(&self) -> ExitCode {
        match self {
            CliError::Scene(_) | CliError::Render(RenderError::BadSize { .. }) => ExitCode::from(2),
            _ => ExitCode::from(1),
        }
    }
}

fn main() -> ExitCode {
    env_logger::Builder::from_env(env_logger::Env::default().default_filter_or("warn")).init();
    let cli = Cli::parse();
    let result = match cli.command {
        Some(Command::Render(args)) => render(&args),
        Some(Command::Check { file }) => check(&file),
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
    let scene = Scene::load(&args.file)?;
    for warning in &scene.warnings {
        eprintln!("warning: {}: {warning}", args.file.display());
    }
    let gpu = GpuContext::headless()?;
    let mut settings = RenderSettings {
        exposure_ev: args.exposure,
        ..RenderSettings::default()
    };
    if let Some(background) = args.background {
        settings.background_srgb8 = background;
    }
    let camera = scene.initial_camera();
    let started = std::time::Instant::now();
    let image = render_image(&gpu, &scene, &camera, &settings, args.width, args.height)?;
    let elapsed = started.elapsed();
    image.save(&args.output).map_err(|source| CliError::WriteImage {
        path: args.output.clone(),
        source,
    })?;
    println!(
        "rendered {} ({}×{}) with {} in {:.0} ms → {}",
        args.file.display(),
        args.width,
        args.height,
        gpu.adapter_summary(),
        elapsed.as_secs_f64() * 1000.0,
        args.output.display()
    );
    Ok(())
}

fn check(file: &Path) -> Result<(), CliError> {
    let scene = Scene::load(file)?;
    for warning in &scene.warnings {
        println!("warning: {}: {warning}", file.display());
    }
    println!(
        "{}: ok — {} objects, {} vertices, {} triangles, {} materials, {} textures, {} lights, {}",
        file.display(),
        scene.objects.len(),
        scene.vertex_count(),
        scene.triangle_count(),
        scene.materials.len(),
        scene.textures.len(),
        scene.lights.len(),
        if scene.camera.is_some() { "camera" } else { "no camera" }
    );
    Ok(())
}

/// The bundled sample: beside the executable's source tree in a checkout, or in the
/// current directory.
fn bundled_sample() -> PathBuf {
    let in_checkout = Path::new(env!("CARGO_MANIFEST_DIR")).join(lightpaint::samples::SAMPLE_SCENE);
    if in_checkout.exists() {
        in_checkout
    } else {
        PathBuf::from(lightpaint::samples::SAMPLE_SCENE)
    }
}

fn editor(file: Option<PathBuf>) -> Result<(), CliError> {
    let file = file.unwrap_or_else(bundled_sample);
    // Fail before opening a window when the file cannot be read at all.
    if !file.exists() {
        return Err(SceneError::NotFound { path: file }.into());
    }
    let options = lightpaint::ui::EditorOptions {
        file,
        close_when_file_exists: std::env::var_os("LIGHTPAINT_CLOSE_WHEN_FILE_EXISTS").map(PathBuf::from),
    };
    lightpaint::ui::run_editor(options).map_err(|e| CliError::Editor(e.to_string()))
}
