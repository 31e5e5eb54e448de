//! Cost of terrain shadows against the azimuth count W and the pyramid levels:
//! `cargo bench --profile dev --bench terrain`. Groups:
//! - `terrain/frame`: a GPU frame of the terrain sample (480×270, one sample per pixel,
//!   order 4, HYB, the fitted spheres) for W = 4, 8, 16, 32 and 1, 3, 6 levels;
//! - `terrain/cpu`: the f64 twin's log-visibility at one receiver on the hills (read from
//!   the surface cache) and 1 m above them (marched).

use std::time::Duration;

use criterion::{BenchmarkId, Criterion, criterion_group, criterion_main};
use glam::DVec3;
use lightpaint::blockers::{BlockerSettings, fit_scene};
use lightpaint::project::Document;
use lightpaint::render::{AntiAliasing, GpuContext, Redraw, ShadowFrame, ShadowRenderer};
use lightpaint::shading::{ShadowSettings, TerrainShading};
use lightpaint::terrain::{HeightPyramid, TerrainShadow};

const PROJECT: &str = "projects/terrain/terrain.lightpaint";

fn terrain(c: &mut Criterion) {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join(PROJECT);
    let document = Document::open(&path).expect("terrain sample opens");
    let camera = document
        .camera
        .map_or_else(|| document.scene.initial_camera(), |orbit| orbit.camera());
    let blockers = fit_scene(&document.scene, &BlockerSettings::default()).spheres();
    let gpu = GpuContext::headless().expect("a GPU adapter (lavapipe on CI)");
    eprintln!("adapter: {}", gpu.adapter_summary());

    let mut group = c.benchmark_group("terrain/frame");
    group.sample_size(10).measurement_time(Duration::from_secs(8));
    for pyramid_levels in [1, 3, 6] {
        for azimuths in [4, 8, 16, 32] {
            let shadows = ShadowSettings {
                terrain: TerrainShading {
                    azimuths,
                    pyramid_levels,
                },
                ..document.settings.shadows
            };
            let frame = ShadowFrame {
                scene: &document.scene,
                camera: &camera,
                settings: &document.settings,
                shadows: &shadows,
                blockers: &blockers,
                baked_indirect: None,
                width: 480,
                height: 270,
            };
            let mut renderer = ShadowRenderer::new(&gpu, &frame, AntiAliasing::None).expect("renderer");
            renderer.draw_and_wait(Redraw::Everything).expect("warm-up frame");
            group.bench_function(BenchmarkId::new(format!("levels-{pyramid_levels}"), azimuths), |b| {
                b.iter(|| renderer.draw_and_wait(Redraw::Everything).expect("frame"))
            });
        }
    }
    group.finish();

    let field = document
        .scene
        .terrain
        .as_ref()
        .expect("the sample has terrain")
        .field
        .clone();
    let on_ground = DVec3::new(1.0, field.height_at(1.0, 2.0), 2.0);
    let above = on_ground + DVec3::new(0.0, 1.0, 0.0);
    let mut group = c.benchmark_group("terrain/cpu");
    for levels in [1, 6] {
        for azimuths in [8, 16, 32] {
            let model = TerrainShadow::new(HeightPyramid::new(field.clone(), levels), 4, azimuths, levels);
            for (label, receiver) in [("surface", on_ground), ("marched", above)] {
                group.bench_function(BenchmarkId::new(format!("{label}/levels-{levels}"), azimuths), |b| {
                    b.iter(|| model.log_visibility(receiver, 0.1f64.ln()))
                });
            }
        }
    }
    group.finish();
}

criterion_group!(benches, terrain);
criterion_main!(benches);
