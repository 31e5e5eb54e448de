//! The bundled sample is what the committed generator makes, and is the scene the issue
//! asks for: several shadow-casting objects, 3+ lights of different colours, 10k+ vertices.

mod common;

use lightpaint::scene::{LightKind, Scene};

#[test]
fn committed_sample_is_what_the_generator_makes() {
    let committed = std::fs::read(common::repo_path(lightpaint::samples::SAMPLE_SCENE)).expect("sample is committed");
    assert!(
        committed == lightpaint::samples::sample_scene_glb(),
        "projects/sample/sample.glb is stale: run `cargo run --bin make-sample`"
    );
}

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
