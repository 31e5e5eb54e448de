//! The `lightpaint` command line: the arguments (`args`), what can go wrong and its exit
//! code (`CliError`), and one file per command. Exit codes: 0 success, 1 failure, 2 bad
//! input or usage. Errors are reported once, by `main`, on one line, naming the file and
//! the cause.

use std::path::PathBuf;
use std::process::ExitCode;

use clap::{Parser, Subcommand};
use lightpaint::project::ProjectError;
use lightpaint::render::RenderError;
use lightpaint::scene::SceneError;

/// Prints a line to stdout, ignoring a closed pipe (`lightpaint check FILE | head` must not
/// panic); `println!` would.
macro_rules! say {
    ($($arg:tt)*) => {{
        use std::io::Write as _;
        let _ = writeln!(std::io::stdout(), $($arg)*);
    }};
}

pub mod args;
pub mod bake;
pub mod check;
pub mod editor;
pub mod output;
pub mod paint;
pub mod render;
pub mod study;

/// Opens `file` as `render`, `paint` and `bake` do, telling its warnings and what was
/// done on opening (a default light rig) on stderr.
pub fn open_document(file: &std::path::Path) -> Result<lightpaint::project::Document, CliError> {
    let document = lightpaint::project::Document::open(file)?;
    for warning in &document.warnings {
        eprintln!("warning: {}: {warning}", file.display());
    }
    for note in &document.notes {
        eprintln!("note: {}: {note}", file.display());
    }
    Ok(document)
}

use args::{RenderArgs, parse_sample, parse_threshold};

#[derive(Parser)]
#[command(name = "lightpaint", version, about = "Light a 3D scene by painting on it")]
#[command(args_conflicts_with_subcommands = true)]
pub struct Cli {
    #[command(subcommand)]
    pub command: Option<Command>,
    /// A project (.lightpaint) or a .gltf/.glb scene to open in the editor (default: the
    /// bundled sample project).
    pub file: Option<PathBuf>,
}

#[derive(Subcommand)]
pub enum Command {
    /// Render a project or scene offscreen with wgpu (or the reference path tracer) and
    /// write a PNG.
    Render(RenderArgs),
    /// Measure the real-time renderer's knobs against the reference path tracer: CSV,
    /// markdown table, Pareto plot and side-by-side images in the output directory.
    Study {
        /// A small grid of settings on the sample at 160×90, and the small-light suites at small
        /// sizes: about a minute on 2 cores, not hours.
        #[arg(long)]
        quick: bool,
        /// Directory for study.csv, study.md, pareto.png and images/.
        #[arg(short, long)]
        output: PathBuf,
        /// Only this sample scene (repeatable: sample, studio, interior, large, terrain, lamp-room),
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
        /// Store the coefficients in single precision (twice the memory of the default half
        /// precision, scaled per object and light: 3 significant digits).
        #[arg(long, conflicts_with = "f16")]
        f32: bool,
        /// Half precision, the default (kept for scripts that ask for it).
        #[arg(long, hide = true)]
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

/// What went wrong, and which exit code it deserves.
#[derive(Debug, thiserror::Error)]
pub enum CliError {
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
    pub fn exit_code(&self) -> ExitCode {
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
