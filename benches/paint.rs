//! Latency of one dab on the large sample (over 500k vertices, 24 lights): pick (project
//! every vertex, depth-test the ones in the disc), transfer, importance, selection and
//! modification, as one `Painter::paint` of a one-dab stroke. `cargo bench --bench paint`.
//! The transfer comes from the log-SH direct estimate the editor uses before a bake, from
//! a direct-only bake's maps (exact visibility, order-3 SH), and from what the editor
//! reads after a bake (the estimate plus the maps' bounced light).

use std::hint::black_box;
use std::path::Path;

use criterion::{Criterion, criterion_group, criterion_main};
use glam::Vec3;
use lightpaint::bake::scene_bvh::SceneBvh;
use lightpaint::bake::{BakeSettings, bake_maps};
use lightpaint::blockers::{BlockerSettings, fit_scene};
use lightpaint::paint::{
    BakedTransfer, Brush, BrushKind, PaintSettings, Painter, StrokeRecord, Transfer, View, ViewRecord,
};
use lightpaint::scene::{Camera, Scene, parse_gltf};
use lightpaint::shading::ShadowSettings;
use lightpaint::shading::frame_transfer::FrameTransfer;
use lightpaint::shading::paint_estimate::DirectEstimate;

fn stroke(scene: &Scene) -> StrokeRecord {
    let eye = Vec3::new(0.0, 14.0, 18.0);
    // The sphere of object 6-6 (radius 0.8 m, 3456 vertices): the dab covers most of what
    // the camera sees of it.
    let target = Vec3::new(1.5, 0.8, 1.5);
    let view = ViewRecord::of(&View {
        camera: Camera::looking_at(eye, target, 50f32.to_radians(), 0.01),
        width_px: 1280,
        height_px: 720,
    });
    let centre = view.view().project(target).expect("in view");
    assert!(!scene.objects.is_empty());
    StrokeRecord {
        view,
        dabs_px: vec![centre],
        brush: Brush {
            radius_px: 40.0,
            ..Brush::new(BrushKind::Positive)
        },
        settings: PaintSettings::default(),
        seed: 1,
        hidden_objects: Vec::new(),
        locked_lights: Vec::new(),
    }
}

fn dab(c: &mut Criterion) {
    let scene = parse_gltf(Path::new("large.glb"), &lightpaint::samples::Sample::Large.glb()).expect("large sample");
    eprintln!(
        "large sample: {} vertices, {} lights",
        scene.vertex_count(),
        scene.lights.len()
    );
    let bvh = SceneBvh::build(&scene);
    let record = stroke(&scene);
    let start = scene.light_intensities();
    let mut run = |name: &str, transfer: &dyn Transfer| {
        let mut intensities = start.clone();
        let report = Painter::new().paint(&scene, &bvh, transfer, &mut intensities, record.clone());
        eprintln!(
            "{name}: {} vertices hit, {:?}: {}",
            report.hit_vertices, report.outcome, report.message
        );
        c.bench_function(name, |b| {
            b.iter(|| {
                let mut intensities = start.clone();
                let report = Painter::new().paint(&scene, &bvh, transfer, &mut intensities, record.clone());
                black_box((report, intensities))
            })
        });
    };
    let blockers = fit_scene(&scene, &BlockerSettings::default()).spheres();
    let estimate = DirectEstimate::new(&scene, blockers.clone(), ShadowSettings::default());
    run("dab/large/log-SH direct estimate", &estimate);
    let settings = BakeSettings {
        bounces: 0,
        light_samples: 4,
        ..BakeSettings::default()
    };
    let maps = bake_maps(&scene, &settings);
    run("dab/large/baked maps", &BakedTransfer::new(&scene, &maps));
    // What the editor and `paint` read after a bake: the estimate plus the maps' bounces.
    let after_bake = DirectEstimate::new(&scene, blockers, ShadowSettings::default());
    run(
        "dab/large/after a bake (frame transfer)",
        &FrameTransfer::new(after_bake, &scene, &maps),
    );
}

criterion_group! {
    name = benches;
    config = Criterion::default().sample_size(20);
    targets = dab
}
criterion_main!(benches);
