//! Helpers shared by the integration tests.
#![allow(dead_code)]

pub mod snapshot;
pub mod thin_casters;

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

use lightpaint::render::{AntiAliasing, Compilation, FrameQuality, GpuContext, SceneRenderer};

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

/// Pixels whose bytes differ between two images of one size.
pub fn differing_pixels(a: &image::RgbaImage, b: &image::RgbaImage) -> usize {
    a.pixels().zip(b.pixels()).filter(|(p, q)| p != q).count()
}

/// A renderer of `scene` with `blockers` and `settings`' shadows, antialiased as shipped,
/// its pipelines compiled before it returns.
pub fn renderer_for(
    gpu: &GpuContext,
    scene: &lightpaint::scene::Scene,
    blockers: &[lightpaint::blockers::Sphere],
    settings: &lightpaint::shading::RenderSettings,
) -> SceneRenderer {
    SceneRenderer::new(
        &gpu.device,
        &gpu.queue,
        scene,
        blockers,
        &settings.shadows,
        AntiAliasing::default(),
        Compilation::Blocking,
    )
}

/// One frame of `scene` drawn from `camera` at `size` by a new [`SceneRenderer`] set up
/// by `configure` first (a test's switch: view culling, the lights' grid), read back; and
/// the renderer, to ask it about the frame.
pub fn drawn_with(
    gpu: &GpuContext,
    (scene, blockers): (&lightpaint::scene::Scene, &[lightpaint::blockers::Sphere]),
    settings: &lightpaint::shading::RenderSettings,
    (camera, size): (&lightpaint::scene::Camera, [u32; 2]),
    configure: impl FnOnce(&mut SceneRenderer),
) -> (image::RgbaImage, SceneRenderer) {
    let mut renderer = renderer_for(gpu, scene, blockers, settings);
    configure(&mut renderer);
    renderer.render(camera, size, settings, FrameQuality::default());
    let image = renderer.read_image().expect("a frame was drawn").expect("readback");
    (image, renderer)
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
pub mod editor;
pub mod scenes;

/// exp(M_f)·1 of a zonal log-visibility (ln ε inside a cap of cos half-angle `c` about
/// +z), computed without the crate (see [`zonal_exp`]). Returns the zonal coefficients g_l.
pub fn zonal_exp_reference(order: usize, c: f64, ln_epsilon: f64) -> Vec<f64> {
    // The cap is [c, 1] in t: integrate over it alone, so the rule sees no discontinuity.
    zonal_exp(&zonal_projection(order, |_| ln_epsilon, &[(c, 1.0)]))
}

const MIDPOINT_STEPS: usize = 200_000;

/// y_l^0 at t = cos θ, by Bonnet's recurrence.
pub fn zonal_basis(l: usize, t: f64) -> f64 {
    let mut p = [1.0, t];
    for k in 1..l {
        let kf = k as f64;
        p = [p[1], ((2.0 * kf + 1.0) * t * p[1] - kf * p[0]) / (kf + 1.0)];
    }
    let value = if l == 0 { 1.0 } else { p[1] };
    ((2 * l + 1) as f64 / (4.0 * std::f64::consts::PI)).sqrt() * value
}

/// The order-`order` zonal projection f_l = 2π ∫ f(t) y_l^0(t) dt of a function of
/// t = cos θ that is zero outside `panels` (t intervals), by a fine midpoint rule on each;
/// put discontinuities at panel ends.
pub fn zonal_projection(order: usize, f: impl Fn(f64) -> f64, panels: &[(f64, f64)]) -> Vec<f64> {
    (0..order)
        .map(|l| {
            panels
                .iter()
                .map(|&(a, b)| {
                    let dt = (b - a) / MIDPOINT_STEPS as f64;
                    (0..MIDPOINT_STEPS)
                        .map(|i| {
                            let t = a + (i as f64 + 0.5) * dt;
                            2.0 * std::f64::consts::PI * f(t) * zonal_basis(l, t) * dt
                        })
                        .sum::<f64>()
                })
                .sum()
        })
        .collect()
}

/// A zonal SH vector's value at t = cos θ.
pub fn zonal_value(g: &[f64], t: f64) -> f64 {
    g.iter().enumerate().map(|(l, g)| g * zonal_basis(l, t)).sum()
}

/// The truncated product of two zonal vectors, (a∗b)_l = 2π ∫ a(t) b(t) y_l^0(t) dt
/// (the product of zonal functions is zonal, so this is the SH product's m = 0 part).
pub fn zonal_product(a: &[f64], b: &[f64]) -> Vec<f64> {
    zonal_projection(a.len(), |t| zonal_value(a, t) * zonal_value(b, t), &[(-1.0, 1.0)])
}

/// exp(M_f)·1 of a zonal vector f without the crate: the Galerkin matrix
/// M_ab = 2π ∫ f(t) y_a y_b dt of the m = 0 Legendre basis by a fine midpoint rule,
/// exponentiated by its power series to convergence. Returns the zonal coefficients g_l.
pub fn zonal_exp(f: &[f64]) -> Vec<f64> {
    let order = f.len();
    let dt = 2.0 / MIDPOINT_STEPS as f64;
    let mut m = vec![vec![0.0; order]; order];
    for i in 0..MIDPOINT_STEPS {
        let t = -1.0 + (i as f64 + 0.5) * dt;
        let y: Vec<f64> = (0..order).map(|l| zonal_basis(l, t)).collect();
        let f_n: f64 = f.iter().zip(&y).map(|(a, b)| a * b).sum();
        for a in 0..order {
            for b in 0..order {
                m[a][b] += 2.0 * std::f64::consts::PI * f_n * y[a] * y[b] * dt;
            }
        }
    }
    // Σ_k M^k e/k! with e = the constant 1 = (√(4π), 0, …).
    let mut term: Vec<f64> = (0..order)
        .map(|l| {
            if l == 0 {
                (4.0 * std::f64::consts::PI).sqrt()
            } else {
                0.0
            }
        })
        .collect();
    let mut sum = term.clone();
    for k in 1..200 {
        term = (0..order)
            .map(|a| (0..order).map(|b| m[a][b] * term[b]).sum::<f64>() / k as f64)
            .collect();
        for (s, t) in sum.iter_mut().zip(&term) {
            *s += t;
        }
    }
    sum
}
