//! Frame time of the log-SH renderer on this machine's GPU (lavapipe in CI), at 960×540:
//! `cargo bench --profile dev --bench frame`. Groups:
//! - `frame/blockers/<scene>`: order 4, HYB (the defaults, every pixel shaded) with the
//!   scene's fitted spheres and with 10, 50, 400 and 2,000 synthetic spheres scattered
//!   over the scene;
//! - `frame/order-method`: the studio scene with 50 synthetic spheres at orders 2, 3, 4, 6,
//!   8 and each GPU exponentiation method;
//! - `frame/shading-downsample`: the studio with its fitted spheres, one shaded pixel
//!   per d × d for d = 1 to 4;
//! - `frame/sphere-count`: the blocker bench scene (`samples::blocker_bench`: thin casters
//!   of about 45,000 triangles over a floor under one rect light) with none, 600, 2,000,
//!   5,000, 10,000 and 20,000 spheres spread over the casters, at the shipped defaults
//!   (one pixel in 3 × 3 shaded) with the light on the SH path: how the frame grows with
//!   the sphere count (none: what the frame costs without a blocker walk;
//!   `cargo run --release --example sphere_count_plot` draws the curve), and per vertex
//!   (`thin-casters-per-vertex`) with 600 and 20,000;
//! - `frame/lamp-count`: the same set with 600 spheres and none, 64 or 256 lamps with a
//!   range (`blocker_bench::add_lamps`), at the shipped defaults: each point walks the
//!   lamps of its box of the lights' grid (`thin-casters-lamps`) or every lamp
//!   (`thin-casters-lamps-every-light`);
//! - `cpu-reference`: the f64 CPU shading of the same studio frame (all cores).
//!
//! Throughput is pixels × blockers per frame: the receiver-blocker pairs a renderer
//! without culling would evaluate (culled pairs cost almost nothing).

use std::time::Duration;

use criterion::{BenchmarkId, Criterion, Throughput, criterion_group, criterion_main};
use glam::Vec3;
use lightpaint::blockers::{BlockerSettings, Sphere, fit_scene};
use lightpaint::project::Document;
use lightpaint::render::{
    AntiAliasing, GpuContext, Redraw, ShadowFrame, ShadowRenderer, capture_surfaces, shade_surfaces,
};
use lightpaint::scene::{Camera, Scene};
use lightpaint::sh::ExpMethod;
use lightpaint::shading::{RenderSettings, ShadowSettings};

const WIDTH: u32 = 960;
const HEIGHT: u32 = 540;

/// A sample project's scene, camera and render settings.
struct Sample {
    scene: Scene,
    camera: Camera,
    settings: RenderSettings,
}

impl Sample {
    fn open(relative: &str) -> Sample {
        let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join(relative);
        let document = Document::open(&path).expect("sample project opens");
        let camera = document
            .camera
            .map(|orbit| orbit.camera())
            .unwrap_or_else(|| document.scene.initial_camera());
        Sample {
            scene: document.scene,
            camera,
            settings: document.settings,
        }
    }

    /// Its frame at WIDTH × HEIGHT with `shadows` and `blockers`.
    fn frame<'a>(&'a self, shadows: &'a ShadowSettings, blockers: &'a [Sphere]) -> ShadowFrame<'a> {
        ShadowFrame {
            baked_indirect: None,
            scene: &self.scene,
            camera: &self.camera,
            settings: &self.settings,
            shadows,
            blockers,
            width: WIDTH,
            height: HEIGHT,
        }
    }
}

/// `count` spheres on a jittered grid over the lower half of the scene's bounds, each a
/// quarter of the grid spacing in radius.
fn scattered(scene: &Scene, count: usize) -> Vec<Sphere> {
    let bounds = scene.bounds();
    let size = bounds.max - bounds.min;
    let per_axis = (count as f32).cbrt().ceil() as usize;
    let spacing = size / per_axis as f32;
    (0..count)
        .map(|i| {
            let (x, y, z) = (i % per_axis, (i / per_axis) % per_axis, i / (per_axis * per_axis));
            let jitter = ((i as f32 * 0.618).fract() - 0.5) * 0.3;
            let cell = Vec3::new(x as f32 + 0.5 + jitter, (y as f32 + 0.5) * 0.5, z as f32 + 0.5 - jitter);
            Sphere {
                center: bounds.min + cell * spacing,
                radius_m: 0.25 * spacing.min_element().max(0.02),
                disc_normal: glam::Vec3::ZERO,
            }
        })
        .collect()
}

fn time_frame(
    c: &mut criterion::BenchmarkGroup<'_, criterion::measurement::WallTime>,
    id: BenchmarkId,
    gpu: &GpuContext,
    frame: &ShadowFrame,
) {
    let mut renderer = ShadowRenderer::new(gpu, frame, AntiAliasing::default()).expect("renderer");
    renderer.draw_and_wait(Redraw::Everything).expect("warm-up frame");
    c.throughput(Throughput::Elements(
        (WIDTH * HEIGHT) as u64 * frame.blockers.len().max(1) as u64,
    ));
    c.bench_function(id, |b| {
        b.iter(|| renderer.draw_and_wait(Redraw::Everything).expect("frame"))
    });
}

fn frames(c: &mut Criterion) {
    let gpu = GpuContext::headless().expect("a GPU adapter (lavapipe on CI)");
    eprintln!("adapter: {}", gpu.adapter_summary());
    // Every pixel shaded, as the CPU reference does; `frame/shading-downsample` times the
    // reduced resolutions.
    let defaults = ShadowSettings::default().every_pixel();
    for (name, path) in [
        ("studio", "projects/studio/studio.lightpaint"),
        ("sample", "projects/sample/sample.lightpaint"),
    ] {
        let sample = Sample::open(path);
        let mut group = c.benchmark_group(format!("frame/blockers/{name}"));
        group.sample_size(10).measurement_time(Duration::from_secs(10));
        let fitted = fit_scene(&sample.scene, &BlockerSettings::default()).spheres();
        let sets: Vec<(String, Vec<Sphere>)> = std::iter::once((format!("fitted-{}", fitted.len()), fitted))
            .chain([10, 50, 400, 2000].map(|n| (format!("scattered-{n}"), scattered(&sample.scene, n))))
            .collect();
        for (label, blockers) in &sets {
            let frame = sample.frame(&defaults, blockers);
            time_frame(&mut group, BenchmarkId::from_parameter(label), &gpu, &frame);
        }
        group.finish();
    }

    let sample = Sample::open("projects/studio/studio.lightpaint");
    let blockers = scattered(&sample.scene, 50);
    let mut group = c.benchmark_group("frame/order-method");
    group.sample_size(10).measurement_time(Duration::from_secs(8));
    for order in [2, 3, 4, 6, 8] {
        for exp in [ExpMethod::Dc, ExpMethod::Ol, ExpMethod::Hyb, ExpMethod::Ps(8)] {
            let shadows = ShadowSettings { order, exp, ..defaults };
            let frame = sample.frame(&shadows, &blockers);
            time_frame(&mut group, BenchmarkId::new(format!("{exp:?}"), order), &gpu, &frame);
        }
    }
    group.finish();

    let fitted = fit_scene(&sample.scene, &BlockerSettings::default()).spheres();
    let mut group = c.benchmark_group("frame/shading-downsample");
    group.sample_size(10).measurement_time(Duration::from_secs(8));
    for shading_downsample in 1..=4 {
        let shadows = ShadowSettings {
            shading_downsample,
            ..defaults
        };
        let frame = sample.frame(&shadows, &fitted);
        time_frame(
            &mut group,
            BenchmarkId::new("studio-fitted", shading_downsample),
            &gpu,
            &frame,
        );
    }
    group.finish();

    let set = Sample {
        scene: lightpaint::samples::blocker_bench::thin_casters_scene(),
        camera: lightpaint::samples::blocker_bench::thin_casters_camera(),
        settings: RenderSettings::default(),
    };
    // The shipped defaults with the light through the SH path, whose blocker walk the
    // sphere count weighs on (under Auto the rect light takes the shadow maps, which read
    // no sphere).
    let shipped = ShadowSettings {
        light_paths: lightpaint::shading::LightPaths::Harmonics,
        ..ShadowSettings::default()
    };
    let mut group = c.benchmark_group("frame/sphere-count");
    group.sample_size(10).measurement_time(Duration::from_secs(10));
    for count in [0, 600, 2000, 5000, 10_000, 20_000] {
        let spheres = lightpaint::samples::blocker_bench::spheres_on_casters(&set.scene, count);
        let frame = set.frame(&shipped, &spheres);
        time_frame(&mut group, BenchmarkId::new("thin-casters", count), &gpu, &frame);
    }
    // Per vertex: the visibility exponentiated at the casters' and the floor's vertices.
    let per_vertex = ShadowSettings {
        per_vertex: true,
        ..shipped
    };
    for count in [600, 20_000] {
        let spheres = lightpaint::samples::blocker_bench::spheres_on_casters(&set.scene, count);
        let frame = set.frame(&per_vertex, &spheres);
        time_frame(
            &mut group,
            BenchmarkId::new("thin-casters-per-vertex", count),
            &gpu,
            &frame,
        );
    }
    group.finish();

    // The lamps' count: the same set with 600 spheres and that many lamps with a range,
    // on the paths the shipped defaults choose (the maps' views hold 15 of them, the rest
    // take the SH path); each point walks the lamps of its box of the lights' grid, or
    // (`-every-light`) every lamp.
    let mut group = c.benchmark_group("frame/lamp-count");
    group.sample_size(10).measurement_time(Duration::from_secs(10));
    let spheres = lightpaint::samples::blocker_bench::spheres_on_casters(&set.scene, 600);
    let shadows = ShadowSettings::default();
    for count in [0, 64, 256] {
        let mut lit = Sample {
            scene: set.scene.clone(),
            camera: set.camera.clone(),
            settings: set.settings,
        };
        lightpaint::samples::blocker_bench::add_lamps(&mut lit.scene, count);
        let frame = lit.frame(&shadows, &spheres);
        for (name, grid) in [("thin-casters-lamps", true), ("thin-casters-lamps-every-light", false)] {
            let mut renderer = ShadowRenderer::new(&gpu, &frame, AntiAliasing::default()).expect("renderer");
            renderer.set_light_grid(grid);
            renderer.draw_and_wait(Redraw::Everything).expect("warm-up frame");
            group.bench_function(BenchmarkId::new(name, count), |b| {
                b.iter(|| renderer.draw_and_wait(Redraw::Everything).expect("frame"))
            });
        }
    }
    group.finish();

    let mut group = c.benchmark_group("cpu-reference");
    group.sample_size(10).measurement_time(Duration::from_secs(10));
    let surfaces = capture_surfaces(&gpu, &sample.scene, &sample.camera, None, WIDTH, HEIGHT).expect("surfaces");
    let frame = sample.frame(&defaults, &blockers);
    group.throughput(Throughput::Elements((WIDTH * HEIGHT) as u64 * blockers.len() as u64));
    group.bench_function("studio-scattered-50", |b| {
        b.iter(|| shade_surfaces(&surfaces, &frame).expect("shade"))
    });
    group.finish();
}

criterion_group!(benches, frames);
criterion_main!(benches);
