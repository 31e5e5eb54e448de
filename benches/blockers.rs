//! The sphere fit of a sample scene, fitted cold (voxelisation and k-means of every mesh)
//! against read from the project's sphere cache (`NAME.lightpaint.spheres`), which is what
//! reopening a project costs. Run: `cargo bench --profile dev --bench blockers`.

use std::path::Path;

use criterion::{BatchSize, Criterion, criterion_group, criterion_main};
use lightpaint::blockers::{BlockerSettings, fit_scene};
use lightpaint::project::sphere_cache;
use lightpaint::samples::Sample;
use lightpaint::scene::{Scene, parse_gltf};

fn fit(c: &mut Criterion) {
    for sample in [Sample::Sample, Sample::Studio] {
        let name = format!("{sample:?}").to_lowercase();
        let scene = parse_gltf(Path::new("sample.glb"), &sample.glb()).expect("sample scene");
        let settings = BlockerSettings::default();
        let mut nudge = 0u32;
        // Each run fits a copy moved by a new sub-micrometre offset, so the in-memory
        // cache (keyed by the geometry) never answers: a cold fit, as on opening.
        c.bench_function(&format!("sphere fit/{name}/cold"), |b| {
            b.iter_batched(
                || {
                    nudge += 1;
                    nudged(&scene, nudge)
                },
                |scene| fit_scene(&scene, &settings),
                BatchSize::LargeInput,
            )
        });
        let dir = tempfile::tempdir().expect("temp dir");
        let project = dir.path().join("bench.lightpaint");
        sphere_cache::fit_with_cache(&scene, &settings, Some(&project));
        let path = sphere_cache::cache_path(&project);
        c.bench_function(&format!("sphere fit/{name}/from the project's cache"), |b| {
            b.iter(|| sphere_cache::load(&path, &scene, &settings).expect("a fresh cache"))
        });
    }
}

fn nudged(scene: &Scene, nudge: u32) -> Scene {
    let mut scene = scene.clone();
    let offset = nudge as f32 * 1e-7;
    for object in &mut scene.objects {
        for p in &mut object.positions {
            p.x += offset;
        }
    }
    scene
}

criterion_group! {
    name = benches;
    config = Criterion::default().sample_size(10);
    targets = fit
}
criterion_main!(benches);
