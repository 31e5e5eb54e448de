//! The `lightpaint` command: the editor, and headless commands for scripts and CI
//! (`cli`). Exit codes: 0 success, 1 failure, 2 bad input or usage. Errors are reported
//! once, here, on one line, naming the file and the cause.

mod cli;

use std::process::ExitCode;

use clap::Parser;
use cli::{Cli, Command};

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

/// Gives a run without a usable XDG_RUNTIME_DIR (a headless session: CI, ssh, a
/// container) a private one for its lifetime: the Vulkan loader's window-system layer
/// asks for it while wgpu starts, and without it every headless command printed
/// "error: XDG_RUNTIME_DIR is invalid or not set in the environment" twice, which is
/// not an error of ours. The directory is removed when the returned guard drops.
fn private_runtime_dir_if_missing() -> Option<tempfile::TempDir> {
    const VARIABLE: &str = "XDG_RUNTIME_DIR";
    let usable = std::env::var_os(VARIABLE).is_some_and(|dir| std::path::Path::new(&dir).is_dir());
    if usable {
        return None;
    }
    // tempfile creates it readable by this user only, as the variable's spec asks.
    let dir = tempfile::Builder::new().prefix("lightpaint-runtime-").tempdir().ok()?;
    // SAFETY: called at the start of main, while this is the process's only thread.
    unsafe { std::env::set_var(VARIABLE, dir.path()) };
    Some(dir)
}

fn main() -> ExitCode {
    prefer_two_rasterizer_threads_per_core();
    let _runtime_dir = private_runtime_dir_if_missing();
    env_logger::Builder::from_env(env_logger::Env::default().default_filter_or("warn")).init();
    lightpaint::panic_guard::install_quiet_panic_hook();
    let cli = Cli::parse();
    let result = match cli.command {
        Some(Command::Render(args)) => cli::render::render(&args),
        Some(Command::Check { file }) => cli::check::check(&file),
        Some(Command::Study {
            quick,
            output,
            scenes,
            knobs,
        }) => cli::study::study(quick, output, scenes, knobs),
        Some(Command::Bake {
            file,
            order,
            light_samples,
            bounces,
            directions,
            threshold,
            f32,
            f16: _,
        }) => {
            let settings = lightpaint::bake::BakeSettings {
                order: order as usize,
                light_samples: light_samples as usize,
                bounces: bounces as usize,
                indirect_directions: directions as usize,
                relative_threshold: threshold,
                precision: if f32 {
                    lightpaint::bake::Precision::F32
                } else {
                    lightpaint::bake::Precision::F16
                },
                ..Default::default()
            };
            cli::bake::bake(&file, &settings)
        }
        Some(Command::Paint {
            file,
            strokes,
            output,
            bounces,
            no_bake,
        }) => cli::paint::paint(&file, &strokes, &output, (!no_bake).then_some(bounces as usize)),
        None => cli::editor::editor(cli.file),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("error: {e}");
            e.exit_code()
        }
    }
}
