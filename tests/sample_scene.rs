//! The samples are what the committed generators make, and are the scenes the issues ask
//! for: the default sample has several shadow-casting objects, 3+ lights of different
//! colours and 10k+ vertices; studio, interior and large have their sizes and light counts.

mod common;

use lightpaint::scene::{LightKind, Scene};

#[test]
fn sample_has_objects_coloured_lights_and_enough_vertices() {
    let scene = Scene::load(&common::repo_path(lightpaint::samples::SAMPLE_SCENE)).expect("sample loads");
    assert!(scene.warnings.is_empty(), "{:?}", scene.warnings);
    assert!(scene.objects.len() >= 5);
    assert!(scene.vertex_count() >= 10_000, "{} vertices", scene.vertex_count());
    assert!(scene.camera.is_some());
    let local_lights: Vec<_> = scene
        .lights
        .iter()
        .filter(|l| l.kind != LightKind::Directional)
        .collect();
    assert!(local_lights.len() >= 3);
    for (i, a) in scene.lights.iter().enumerate() {
        for b in &scene.lights[i + 1..] {
            assert!(
                (a.color - b.color).length() > 0.1,
                "{} and {} share a colour",
                a.name,
                b.name
            );
        }
    }
    assert_eq!(scene.textures.len(), 1, "the floor is textured");
}

/// Every sample: the committed ones match their generator; all load with the counts the
/// issue asks for and render headlessly.
#[test]
fn every_sample_matches_its_generator_loads_and_renders() {
    use lightpaint::project::Document;
    use lightpaint::samples::Sample;
    let gpu = common::gpu();
    for sample in Sample::ALL {
        let dir = tempfile::tempdir().unwrap();
        let project = sample.write(dir.path()).expect("sample written");
        if sample.is_committed() {
            for name in [
                format!("{}.glb", sample.name()),
                format!("{}.lightpaint", sample.name()),
                "sky.hdr".into(),
            ] {
                let committed = std::fs::read(common::repo_path(&format!("projects/{}/{name}", sample.name())))
                    .unwrap_or_else(|e| panic!("{name}: {e}"));
                assert!(
                    committed == std::fs::read(dir.path().join(&name)).unwrap(),
                    "projects/{}/{name} is stale: run `cargo run --bin make-sample`",
                    sample.name()
                );
            }
        }
        let document = Document::open(&project).expect("sample opens");
        assert!(
            document.warnings.is_empty(),
            "{}: {:?}",
            sample.name(),
            document.warnings
        );
        let (vertices, lights) = (document.scene.vertex_count(), document.scene.lights.len());
        let (min_vertices, min_lights) = match sample {
            Sample::Sample => (10_000, 3),
            Sample::Studio => (9_000, 9),
            Sample::Interior => (150_000, 16),
            Sample::Large => (500_000, 22),
            Sample::Terrain => (20_000, 2),
            Sample::LampRoom => (50_000, 30),
        };
        assert!(
            vertices >= min_vertices && lights >= min_lights,
            "{}: {vertices} vertices, {lights} lights",
            sample.name()
        );
        if let Some(gpu) = &gpu {
            let image = lightpaint::render::render_image(
                gpu,
                &document.scene,
                &document.scene.initial_camera(),
                &document.settings,
                96,
                54,
            )
            .expect("render");
            let distinct: std::collections::HashSet<[u8; 4]> = image.pixels().map(|p| p.0).collect();
            assert!(distinct.len() > 100, "{} renders nearly blank", sample.name());
        }
    }
}
