//! glTF import from real files: .gltf with an external .bin, node hierarchies, lights,
//! cameras, generated normals, and a missing texture that is reported but not fatal.

mod common;

use glam::{Quat, Vec3};
use lightpaint::scene::gltf_write::{GltfBuilder, LightSpec, MaterialSpec};
use lightpaint::scene::{LightKind, Scene, SceneError};

/// Writes `builder` as `scene.gltf` + `scene.bin` in a new directory.
fn write_gltf(
    builder: &GltfBuilder,
    edit: impl FnOnce(&mut serde_json::Value),
) -> (tempfile::TempDir, std::path::PathBuf) {
    let dir = tempfile::tempdir().unwrap();
    let mut document = builder.document(Some("scene.bin"));
    edit(&mut document);
    std::fs::write(dir.path().join("scene.bin"), builder.bin()).unwrap();
    let path = dir.path().join("scene.gltf");
    std::fs::write(&path, serde_json::to_string_pretty(&document).unwrap()).unwrap();
    (dir, path)
}

fn triangle_builder() -> (GltfBuilder, usize) {
    let mut b = GltfBuilder::new();
    let positions = [Vec3::ZERO, Vec3::X, Vec3::NEG_Z];
    let mesh = b.add_mesh("tri", &positions, None, None, &[0, 1, 2], None);
    (b, mesh)
}

#[test]
fn node_hierarchy_transforms_compose_and_normals_are_generated() {
    let (mut b, mesh) = triangle_builder();
    let child = b.add_mesh_node(
        "child",
        mesh,
        Vec3::new(1.0, 0.0, 0.0),
        Quat::IDENTITY,
        Vec3::splat(2.0),
    );
    b.add_light_node(
        "sun",
        &LightSpec::Directional {
            color: [1.0, 0.5, 0.25],
            illuminance_lux: 3.0,
        },
        Vec3::ZERO,
        Vec3::NEG_Y,
    );
    let (_dir, path) = write_gltf(&b, |doc| {
        // Parent node: rotate 90° about +y and lift by 10; the mesh node becomes its child.
        let q = Quat::from_rotation_y(std::f32::consts::FRAC_PI_2);
        doc["nodes"].as_array_mut().unwrap().push(serde_json::json!({
            "name": "parent", "children": [child], "translation": [0.0, 10.0, 0.0], "rotation": q.to_array(),
        }));
        doc["scenes"][0]["nodes"] = serde_json::json!([1, 2]);
    });
    let scene = Scene::load(&path).expect("loads");
    assert_eq!(scene.objects.len(), 1);
    let object = &scene.objects[0];
    // world = parent(T(0,10,0) R_y(90°)) · child(T(1,0,0) S(2)): local X ↦ R_y(2 + 1)·X.
    let r = Quat::from_rotation_y(std::f32::consts::FRAC_PI_2);
    let expected = Vec3::new(0.0, 10.0, 0.0) + r * (Vec3::new(1.0, 0.0, 0.0) + 2.0 * Vec3::X);
    assert!(
        (object.positions[1] - expected).length() < 1e-5,
        "{} vs {expected}",
        object.positions[1]
    );
    // The triangle (0,0,0), (1,0,0), (0,0,−1) winds counter-clockwise seen from +y.
    for n in &object.normals {
        assert!((*n - Vec3::Y).length() < 1e-5, "generated normal {n}");
    }
    assert_eq!(scene.lights.len(), 1);
    assert_eq!(scene.lights[0].kind, LightKind::Directional);
    assert!((scene.lights[0].direction - Vec3::NEG_Y).length() < 1e-5);
    assert_eq!(scene.lights[0].intensity, 3.0);
}

#[test]
fn missing_texture_is_a_warning_and_the_colour_factor_is_kept() {
    let (mut b, mesh) = triangle_builder();
    let material = b.add_material(&MaterialSpec {
        base_color_png: Some(lightpaint::samples::checker_png(4, 2, [255, 255, 255], [0, 0, 0])),
        ..MaterialSpec::plain("textured", [0.5, 0.25, 1.0], 0.5)
    });
    b.add_mesh_node("tri", mesh, Vec3::ZERO, Quat::IDENTITY, Vec3::ONE);
    let (_dir, path) = write_gltf(&b, |doc| {
        doc["meshes"][0]["primitives"][0]["material"] = serde_json::json!(material);
        doc["images"][0] = serde_json::json!({"uri": "missing.png"});
    });
    let scene = Scene::load(&path).expect("a missing texture is not fatal");
    assert!(
        scene.warnings.iter().any(|w| w.contains("missing.png")),
        "{:?}",
        scene.warnings
    );
    assert_eq!(scene.materials[0].base_color_texture, None);
    assert_eq!(scene.materials[0].base_color.truncate(), Vec3::new(0.5, 0.25, 1.0));
}

#[test]
fn embedded_texture_is_decoded() {
    let (mut b, mesh) = triangle_builder();
    b.add_material(&MaterialSpec {
        base_color_png: Some(lightpaint::samples::checker_png(4, 2, [255, 0, 0], [0, 0, 255])),
        ..MaterialSpec::plain("textured", [1.0, 1.0, 1.0], 0.5)
    });
    b.add_mesh_node("tri", mesh, Vec3::ZERO, Quat::IDENTITY, Vec3::ONE);
    let (_dir, path) = write_gltf(&b, |_| {});
    let scene = Scene::load(&path).expect("loads");
    let texture = &scene.textures[scene.materials[0].base_color_texture.expect("texture kept")];
    assert_eq!((texture.width, texture.height), (4, 4));
    assert_eq!(&texture.rgba8[..4], &[255, 0, 0, 255]);
    assert_eq!(&texture.rgba8[8..12], &[0, 0, 255, 255]);
}

#[test]
fn missing_buffer_file_names_the_file_and_the_cause() {
    let (mut b, mesh) = triangle_builder();
    b.add_mesh_node("tri", mesh, Vec3::ZERO, Quat::IDENTITY, Vec3::ONE);
    let (dir, path) = write_gltf(&b, |_| {});
    std::fs::remove_file(dir.path().join("scene.bin")).unwrap();
    let error = Scene::load(&path).unwrap_err();
    assert!(matches!(error, SceneError::Invalid { .. }), "{error:?}");
    let message = error.to_string();
    assert!(
        message.contains("scene.gltf") && message.contains("buffer"),
        "{message}"
    );
}

#[test]
fn out_of_range_indices_are_rejected() {
    let mut b = GltfBuilder::new();
    let mesh = b.add_mesh("tri", &[Vec3::ZERO, Vec3::X, Vec3::Z], None, None, &[0, 1, 7], None);
    b.add_mesh_node("tri", mesh, Vec3::ZERO, Quat::IDENTITY, Vec3::ONE);
    let (_dir, path) = write_gltf(&b, |_| {});
    let message = Scene::load(&path).unwrap_err().to_string();
    assert!(message.contains("index 7 is out of range"), "{message}");
}

#[test]
fn degenerate_triangles_are_dropped_with_a_warning() {
    let mut b = GltfBuilder::new();
    let positions = [Vec3::ZERO, Vec3::X, Vec3::NEG_Z, Vec3::X * 2.0];
    let mesh = b.add_mesh("tris", &positions, None, None, &[0, 1, 2, 0, 1, 3], None);
    b.add_mesh_node("tris", mesh, Vec3::ZERO, Quat::IDENTITY, Vec3::ONE);
    let (_dir, path) = write_gltf(&b, |_| {});
    let scene = Scene::load(&path).expect("loads");
    assert_eq!(scene.objects[0].indices, vec![0, 1, 2]);
    assert!(
        scene.warnings.iter().any(|w| w.contains("1 degenerate")),
        "{:?}",
        scene.warnings
    );
}

#[test]
fn a_file_with_several_scenes_opens_its_default_and_shows_another_on_request() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("scene.glb");
    std::fs::write(&path, common::scenes::day_and_night()).unwrap();

    let default = Scene::load(&path).expect("loads");
    assert_eq!(default.gltf_scenes, ["Day", "Night"]);
    assert_eq!(default.gltf_scene, Some(1));
    assert_eq!(default.bounds().min.x, 5.0, "the default scene is Night");
    assert!(default.lights.is_empty());
    assert!(
        default
            .warnings
            .iter()
            .any(|w| w.contains("2 scenes") && w.contains("Night")),
        "{:?}",
        default.warnings
    );
    assert_eq!(default.gltf_scene_label(0), "0 'Day'");

    let day = Scene::load_choosing(&path, Some(0)).expect("scene 0 loads");
    assert_eq!(day.gltf_scene, Some(0));
    assert_eq!(day.bounds().min.x, 0.0);
    assert_eq!(day.lights.len(), 1);
    assert!(
        !day.warnings.iter().any(|w| w.contains("scenes")),
        "a chosen scene needs no warning: {:?}",
        day.warnings
    );

    let message = Scene::load_choosing(&path, Some(2)).unwrap_err().to_string();
    assert!(message.contains("scene.glb"), "{message}");
    assert!(
        message.contains("scene 2") && message.contains("2 scene(s)"),
        "{message}"
    );
}

#[test]
fn double_sided_is_read_per_material_and_decides_back_face_culling() {
    let (mut b, mesh) = triangle_builder();
    b.add_material(&MaterialSpec::plain("one side", [0.8, 0.8, 0.8], 0.5));
    b.add_material(&MaterialSpec::plain("both sides", [0.8, 0.8, 0.8], 0.5));
    b.add_mesh_node("tri", mesh, Vec3::ZERO, Quat::IDENTITY, Vec3::ONE);
    let load = |double_sided: bool| {
        let (_dir, path) = write_gltf(&b, |doc| {
            doc["materials"][1]["doubleSided"] = serde_json::json!(double_sided);
            doc["meshes"][0]["primitives"][0]["material"] = serde_json::json!(1);
        });
        Scene::load(&path).expect("loads")
    };
    let single = load(false);
    assert!(!single.materials[0].double_sided, "glTF's default is single-sided");
    assert!(!single.materials[1].double_sided);
    assert!(single.every_material_single_sided());
    let double = load(true);
    assert!(double.materials[1].double_sided);
    assert!(
        !double.every_material_single_sided(),
        "the drawn object's material has two sides"
    );
}
