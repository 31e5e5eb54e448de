//! Helpers shared by the integration tests.
#![allow(dead_code)]

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

use lightpaint::render::GpuContext;

/// The environment variable with which a run says explicitly that it wants no GPU.
pub const NO_GPU_ENV: &str = "LIGHTPAINT_NO_GPU";

/// A GPU for a test. Without an adapter the test fails, unless the run set
/// `LIGHTPAINT_NO_GPU=1`, in which case it says so loudly and the test returns early.
pub fn gpu() -> Option<GpuContext> {
    if no_gpu_wanted() {
        eprintln!("GPU test not run: {NO_GPU_ENV}=1 says this run wants no GPU");
        return None;
    }
    match GpuContext::headless() {
        Ok(gpu) => {
            eprintln!("wgpu adapter: {}", gpu.adapter_summary());
            Some(gpu)
        }
        Err(e) => panic!("{e} (set {NO_GPU_ENV}=1 to run without a GPU on purpose)"),
    }
}

pub fn no_gpu_wanted() -> bool {
    std::env::var(NO_GPU_ENV).is_ok_and(|v| v == "1")
}

pub fn repo_path(relative: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join(relative)
}

/// Runs the `lightpaint` binary with a private XDG_RUNTIME_DIR.
pub fn run_lightpaint(args: &[&std::ffi::OsStr]) -> Output {
    let runtime = tempfile::tempdir().expect("temp dir");
    Command::new(env!("CARGO_BIN_EXE_lightpaint"))
        .args(args)
        .env("XDG_RUNTIME_DIR", runtime.path())
        .output()
        .expect("the lightpaint binary runs")
}

/// sRGB encode of a linear value in [0, 1] (IEC 61966-2-1), written here independently of
/// the renderer.
pub fn srgb_encode(linear: f64) -> f64 {
    if linear <= 0.0031308 {
        12.92 * linear
    } else {
        1.055 * linear.powf(1.0 / 2.4) - 0.055
    }
}

/// The documented tone curve (Narkowicz's ACES fit), written here independently.
pub fn aces_fit(x: f64) -> f64 {
    (x * (2.51 * x + 0.03) / (x * (2.43 * x + 0.59) + 0.14)).clamp(0.0, 1.0)
}

/// Expected 8-bit value of a grey surface of linear radiance `radiance` at exposure `ev`.
pub fn expected_8bit(radiance: f64, ev: f64) -> f64 {
    255.0 * srgb_encode(aces_fit(radiance * ev.exp2()))
}
pub mod scenes;
