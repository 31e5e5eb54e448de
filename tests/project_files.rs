//! Project files: exact round trips, reopening renders identically, and bad files give
//! their own error, name the file, and are left untouched.

mod common;

use std::path::{Path, PathBuf};

use lightpaint::project::{Document, FORMAT_VERSION, ProjectError, read_project_file};
use lightpaint::render::render_image;

fn sample_project() -> PathBuf {
    common::repo_path(lightpaint::samples::SAMPLE_PROJECT)
}

/// A copy of the sample scene and project in a fresh directory.
fn sample_copy() -> (tempfile::TempDir, PathBuf) {
    let dir = tempfile::tempdir().unwrap();
    lightpaint::samples::write_sample_project(dir.path()).expect("sample written");
    let path = dir.path().join("sample.lightpaint");
    (dir, path)
}

#[test]
fn save_load_save_is_byte_identical() {
    let (dir, path) = sample_copy();
    let mut document = Document::open(&path).unwrap();
    document.settings.exposure_ev = -0.7;
    document.scene.lights[1].intensity = 12.345_679;
    document.camera = Some(lightpaint::scene::OrbitCamera {
        target: glam::Vec3::new(0.1, 0.2, 0.3),
        distance: 7.25,
        yaw_rad: 0.123_456_79,
        pitch_rad: -0.3,
        yfov_rad: 0.8,
    });
    let first = dir.path().join("first.lightpaint");
    let second = dir.path().join("second.lightpaint");
    document.save(&first).unwrap();
    Document::open(&first).unwrap().save(&second).unwrap();
    assert_eq!(std::fs::read(&first).unwrap(), std::fs::read(&second).unwrap());
    let reopened = Document::open(&second).unwrap();
    assert_eq!(reopened.scene.lights, document.scene.lights);
    assert_eq!(reopened.settings, document.settings);
    assert_eq!(reopened.camera, document.camera);
}

#[test]
fn a_reopened_project_renders_pixel_identically() {
    let Some(gpu) = common::gpu() else { return };
    let (dir, path) = sample_copy();
    let mut document = Document::open(&path).unwrap();
    document.settings.exposure_ev = 0.5;
    document.scene.lights[0].intensity *= 0.5;
    let mut orbit = lightpaint::scene::OrbitCamera::framing(&document.scene.bounds());
    orbit.orbit(0.4, 0.1);
    document.camera = Some(orbit);
    let render = |d: &Document| {
        let camera = d.camera.expect("camera saved").camera();
        render_image(&gpu, &d.scene, &camera, &d.settings, 160, 90).expect("render")
    };
    let before = render(&document);
    let saved = dir.path().join("edited.lightpaint");
    document.save(&saved).unwrap();
    let after = render(&Document::open(&saved).unwrap());
    assert!(before == after, "the reopened project renders differently");
}

/// Writes `text` as a project beside a copy of the sample scene, opens it, and checks the
/// file is left as it was.
fn open_bad(name: &str, text: &[u8]) -> ProjectError {
    let (dir, _) = sample_copy();
    let path = dir.path().join(name);
    std::fs::write(&path, text).unwrap();
    let error = Document::open(&path).expect_err("a bad project must not open");
    assert_eq!(std::fs::read(&path).unwrap(), text, "the file was modified");
    let message = error.to_string();
    assert!(
        message.contains(&path.display().to_string()),
        "message does not name the file: {message}"
    );
    drop(dir);
    error
}

fn sample_text() -> String {
    std::fs::read_to_string(sample_project()).unwrap()
}

#[test]
fn json_syntax_errors_give_line_and_column() {
    let text = sample_text().replacen("\"lights\": [", "\"lights\": [[", 1);
    match open_bad("syntax.lightpaint", text.as_bytes()) {
        ProjectError::Syntax { line, column, .. } => assert!(line > 1 && column > 0),
        other => panic!("{other:?}"),
    }
}

#[test]
fn wrong_types_name_the_field() {
    let text = sample_text().replacen("\"intensity\": 180.0", "\"intensity\": \"bright\"", 1);
    match open_bad("type.lightpaint", text.as_bytes()) {
        ProjectError::Field { field, line, .. } => {
            assert_eq!(field, "lights[0].intensity");
            assert!(line.is_some());
        }
        other => panic!("{other:?}"),
    }
}

#[test]
fn unknown_fields_are_refused() {
    let version = format!("\"format_version\": {FORMAT_VERSION},");
    let text = sample_text().replacen(&version, &format!("{version}\n  \"colour_grading\": 3,"), 1);
    assert_ne!(text, sample_text());
    assert!(matches!(
        open_bad("unknown.lightpaint", text.as_bytes()),
        ProjectError::Field { .. }
    ));
}

#[test]
fn every_bad_value_is_reported_at_once() {
    let text = sample_text()
        .replacen("\"intensity\": 180.0", "\"intensity\": -5.0", 1)
        .replacen("\"outer_cone_rad\": 0.8853982", "\"outer_cone_rad\": 2.0", 1)
        .replacen("\"exposure_ev\": 0.0", "\"exposure_ev\": 1e30", 1);
    match open_bad("values.lightpaint", text.as_bytes()) {
        ProjectError::Invalid { problems, .. } => {
            let fields: Vec<&str> = problems.iter().map(|p| p.field.as_str()).collect();
            assert_eq!(
                fields,
                ["lights[0].intensity", "lights[0].kind", "render.exposure_ev"],
                "{problems:?}"
            );
        }
        other => panic!("{other:?}"),
    }
}

#[test]
fn a_newer_format_is_refused_clearly() {
    let text = sample_text().replacen(
        &format!("\"format_version\": {FORMAT_VERSION}"),
        "\"format_version\": 99",
        1,
    );
    assert_ne!(text, sample_text());
    let error = open_bad("newer.lightpaint", text.as_bytes());
    assert!(matches!(
        error,
        ProjectError::NewerVersion {
            found: 99,
            supported: FORMAT_VERSION,
            ..
        }
    ));
    assert!(error.to_string().contains("made by a newer lightpaint"));
}

#[test]
fn not_utf8_and_not_a_project_are_refused() {
    assert!(matches!(
        open_bad("binary.lightpaint", &[0x7b, 0xff, 0xfe, 0x00]),
        ProjectError::Syntax { .. }
    ));
    assert!(matches!(
        open_bad("other.lightpaint", b"{\"name\": 3}"),
        ProjectError::Field { .. }
    ));
}

#[test]
fn a_missing_scene_is_named() {
    let text = sample_text().replacen("\"gltf\": \"sample.glb\"", "\"gltf\": \"gone.glb\"", 1);
    match open_bad("missing.lightpaint", text.as_bytes()) {
        ProjectError::MissingScene { scene, .. } => assert!(scene.ends_with("gone.glb")),
        other => panic!("{other:?}"),
    }
}

#[test]
fn a_changed_scene_opens_with_a_warning_and_keeps_the_project_lights() {
    let (dir, path) = sample_copy();
    let triangle = common::scenes::triangle([glam::Vec3::ZERO, glam::Vec3::X, glam::Vec3::NEG_Z]);
    std::fs::write(dir.path().join("sample.glb"), triangle).unwrap();
    let document = Document::open(&path).expect("a changed scene still opens");
    assert!(
        document.warnings.iter().any(|w| w.contains("changed since")),
        "{:?}",
        document.warnings
    );
    assert_eq!(document.scene.lights.len(), 4);
    assert_eq!(document.scene.objects.len(), 1);
}

#[test]
fn check_reports_problems_with_exit_code_2() {
    let (dir, _) = sample_copy();
    let path = dir.path().join("bad.lightpaint");
    std::fs::write(
        &path,
        sample_text().replacen("\"intensity\": 180.0", "\"intensity\": -1.0", 1),
    )
    .unwrap();
    let out = common::run_lightpaint(&[std::ffi::OsStr::new("check"), path.as_os_str()]);
    assert_eq!(out.status.code(), Some(2));
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(stdout.contains("lights[0].intensity"), "{stdout}");
}

#[test]
fn read_project_file_accepts_the_sample() {
    let file = read_project_file(&sample_project()).expect("valid");
    assert_eq!(file.format_version, FORMAT_VERSION);
    assert_eq!(file.scene.gltf, Path::new("sample.glb"));
}

/// Opens the committed fixture of format `version`, checks it keeps the sample's lights
/// and settings and saves as the current format; returns the opened document.
fn open_old_fixture(version: u64) -> lightpaint::project::Document {
    let path = common::repo_path(&format!("tests/fixtures/format-{version}.lightpaint"));
    let text = std::fs::read_to_string(&path).expect("fixture");
    assert!(
        text.contains(&format!("\"format_version\": {version}")),
        "the fixture is format {version}"
    );
    let mut document = lightpaint::project::Document::open(&path).expect("an older project opens");
    let current = lightpaint::project::Document::open(&sample_project()).expect("sample");
    assert_eq!(document.scene.lights, current.scene.lights);
    // Formats before 4 drew no baked indirect light and shadowed every light through the
    // SH, so they keep both; formats before 7 shaded every pixel.
    let mut every_pixel = if version < 7 {
        current.settings.shadows.every_pixel()
    } else {
        current.settings.shadows
    };
    // Formats before 8 had no budget of exact lights: any number could go exact.
    if version < 8 {
        every_pixel.exact_light_budget = lightpaint::shading::MAX_EXACT_LIGHT_BUDGET;
    }
    // The format-7 fixture saved the shading resolution of its day, one pixel in 2 × 2.
    if version == 7 {
        every_pixel.shading_downsample = 2;
    }
    let expected = if version < 4 {
        lightpaint::shading::RenderSettings {
            baked_indirect: false,
            shadows: lightpaint::shading::ShadowSettings {
                light_paths: lightpaint::shading::LightPaths::Harmonics,
                ..every_pixel
            },
            ..current.settings
        }
    } else {
        lightpaint::shading::RenderSettings {
            shadows: every_pixel,
            ..current.settings
        }
    };
    assert_eq!(document.settings, expected);
    let dir = tempfile::tempdir().expect("temp dir");
    let saved = dir.path().join("saved.lightpaint");
    document.save(&saved).expect("save");
    let file = read_project_file(&saved).expect("the saved file reads back");
    assert_eq!(file.format_version, FORMAT_VERSION);
    document
}

/// A project saved by format 1 (lightpaint before shadows) opens with the default shadow
/// and blocker settings of format 2 (every light through the SH), keeps everything it
/// had, and is saved back as the current format.
#[test]
fn a_format_1_project_opens_and_saves_as_the_current_format() {
    let document = open_old_fixture(1);
    let format_2_shadows = lightpaint::shading::ShadowSettings {
        light_paths: lightpaint::shading::LightPaths::Harmonics,
        exact_light_budget: lightpaint::shading::MAX_EXACT_LIGHT_BUDGET,
        ..lightpaint::shading::ShadowSettings::default().every_pixel()
    };
    assert_eq!(document.settings.shadows, format_2_shadows);
    assert_eq!(
        document.settings.blockers,
        lightpaint::blockers::BlockerSettings::default()
    );
}

/// A project saved by format 2 (before painting) opens with an empty stroke log and the
/// default painting strategies, keeps its lights and settings, and saves as the current
/// format.
#[test]
fn a_format_2_project_opens_with_an_empty_stroke_log() {
    let document = open_old_fixture(2);
    assert!(document.painting.strokes.is_empty());
    assert_eq!(document.painting.settings, lightpaint::paint::PaintSettings::default());
}

/// A project saved by format 3 (before a glTF scene could be chosen) opens on the file's
/// default scene with its strokes and settings, and saves as the current format.
#[test]
fn a_format_3_project_opens_on_the_default_scene() {
    let document = open_old_fixture(3);
    assert_eq!(document.scene.gltf_scene, Some(0));
    assert_eq!(document.scene.gltf_scenes.len(), 1);
}

/// Format 4 had no terrain: it opens without one and with the default terrain sampling.
#[test]
fn a_format_4_project_opens_without_terrain() {
    let document = open_old_fixture(4);
    assert!(document.scene.terrain.is_none());
    assert_eq!(
        document.settings.shadows.terrain,
        lightpaint::shading::TerrainShading::default()
    );
}

/// Format 5 had no hidden objects: every object is shown.
#[test]
fn a_format_5_project_opens_with_every_object_shown() {
    let document = open_old_fixture(5);
    assert!(document.hidden_objects.is_empty());
    assert!(document.scene.terrain.is_none());
}

/// Format 6 shaded every pixel, and keeps doing so; today's projects shade one in 3 × 3.
#[test]
fn a_format_6_project_opens_shading_every_pixel() {
    let document = open_old_fixture(6);
    assert_eq!(document.settings.shadows.shading_downsample, 1);
    let current = lightpaint::project::Document::open(&sample_project()).expect("sample");
    assert_eq!(current.settings.shadows.shading_downsample, 3);
}

/// Format 7 shaded each light's exact BRDF through its visibility, as the default does.
#[test]
fn a_format_7_project_opens_with_the_brdf_outside_the_sh() {
    let document = open_old_fixture(7);
    assert_eq!(
        document.settings.shadows.brdf,
        lightpaint::shading::BrdfShading::Separate
    );
    assert_eq!(document.settings.shadows.shading_downsample, 2);
}

/// Format 8 had no turn of rect lights: its rects open unturned, lying as they did (width
/// along world up × direction), and a turned rect is saved as the current format and reopens turned,
/// its width along the former height axis after a quarter turn.
#[test]
fn a_format_8_project_opens_and_rect_lights_turn_about_their_normal() {
    use lightpaint::scene::{Light, LightKind};
    let document = open_old_fixture(8);
    assert!(
        document
            .scene
            .lights
            .iter()
            .all(|l| !matches!(l.kind, LightKind::Rect { .. }))
    );
    let dir = tempfile::tempdir().expect("temp dir");
    let fixture = std::fs::read_to_string(common::repo_path("tests/fixtures/format-8.lightpaint")).expect("fixture");
    let mut json: serde_json::Value = serde_json::from_str(&fixture).expect("JSON");
    let rect = serde_json::json!({
        "name": "Softbox",
        "kind": { "type": "rect", "width_m": 0.8, "height_m": 0.3 },
        "color": [1.0, 1.0, 1.0],
        "intensity": 40.0,
        "position": [0.0, 3.0, 0.0],
        "direction": [0.6, -0.8, 0.0]
    });
    json["lights"].as_array_mut().expect("lights").push(rect);
    let in_sample = |file: &str| {
        serde_json::Value::from(
            common::repo_path(&format!("projects/sample/{file}"))
                .to_string_lossy()
                .to_string(),
        )
    };
    json["scene"]["gltf"] = in_sample("sample.glb");
    json["environment"]["hdr"] = in_sample("sky.hdr");
    let old = dir.path().join("format-8-rect.lightpaint");
    std::fs::write(&old, serde_json::to_string_pretty(&json).expect("JSON")).expect("write");
    let mut document = lightpaint::project::Document::open(&old).expect("a format-8 rect opens");
    let light: Light = document.scene.lights.last().expect("the rect").clone();
    assert_eq!(
        light.kind,
        LightKind::Rect {
            width_m: 0.8,
            height_m: 0.3,
            turn_rad: 0.0
        }
    );
    let direction = light.direction;
    let untouched = glam::Vec3::Y.cross(direction).normalize();
    assert!((light.area_width_axis() - untouched).length() < 1e-6);
    let (_, height_axis) = light.area_axes();

    let turned = Light {
        kind: LightKind::Rect {
            width_m: 0.8,
            height_m: 0.3,
            turn_rad: std::f32::consts::FRAC_PI_2,
        },
        ..light
    };
    *document.scene.lights.last_mut().expect("the rect") = turned.clone();
    let saved = dir.path().join("turned.lightpaint");
    document.save(&saved).expect("save");
    assert_eq!(read_project_file(&saved).expect("reads").format_version, FORMAT_VERSION);
    let reopened = lightpaint::project::Document::open(&saved).expect("reopen");
    let light = reopened.scene.lights.last().expect("the rect");
    assert_eq!(light, &turned);
    assert!(
        (light.area_width_axis() - height_axis).length() < 1e-5,
        "a quarter turn lays the width along the former height axis"
    );
    assert!(light.area_width_axis().dot(direction).abs() < 1e-6);
}

/// A format-9 project (before locks) opens with every light unlocked; a locked light and
/// a stroke's locked lights are saved and reopen as they were, and an unlocked light
/// writes no lock.
#[test]
fn locked_lights_are_saved_and_reopened() {
    use lightpaint::paint::{Brush, BrushKind, PaintSettings, StrokeRecord, View, ViewRecord};
    let mut document = open_old_fixture(9);
    assert!(document.scene.lights.iter().all(|l| !l.locked));
    document.scene.lights[1].locked = true;
    let view = ViewRecord::of(&View {
        camera: document.view().camera(),
        width_px: 320,
        height_px: 240,
    });
    let stroke = StrokeRecord {
        view,
        dabs_px: vec![glam::Vec2::new(160.0, 120.0)],
        brush: Brush::new(BrushKind::Positive),
        settings: PaintSettings::default(),
        seed: 4,
        hidden_objects: Vec::new(),
        locked_lights: document.scene.locked_lights(),
    };
    document.painting.strokes.push(stroke.clone());
    let dir = tempfile::tempdir().expect("temp dir");
    let saved = dir.path().join("locked.lightpaint");
    document.save(&saved).expect("save");
    let text = std::fs::read_to_string(&saved).expect("read");
    assert_eq!(text.matches("\"locked\": true").count(), 1, "one locked light: {text}");
    assert!(!text.contains("\"locked\": false"), "an unlocked light writes no lock");
    let reopened = Document::open(&saved).expect("reopen");
    assert_eq!(reopened.scene.locked_lights(), vec![1]);
    assert_eq!(reopened.painting.strokes.last(), Some(&stroke));
}

/// The BRDF variant is saved and reopened.
#[test]
fn the_brdf_variant_is_saved_and_reopened() {
    let dir = tempfile::tempdir().expect("temp dir");
    let mut document = lightpaint::project::Document::open(&sample_project()).expect("sample");
    for brdf in lightpaint::shading::BrdfShading::ALL {
        document.settings.shadows.brdf = brdf;
        let saved = dir.path().join("brdf.lightpaint");
        document.save(&saved).expect("save");
        let reopened = lightpaint::project::Document::open(&saved).expect("reopen");
        assert_eq!(reopened.settings.shadows.brdf, brdf);
    }
}

/// Keeping the shadow mass is the default and is not written; turned off it is saved and
/// reopens off, and a file without the field (every older project) opens with it on.
#[test]
fn the_shadow_mass_choice_is_saved_only_when_off() {
    let dir = tempfile::tempdir().expect("temp dir");
    let mut document = lightpaint::project::Document::open(&sample_project()).expect("sample");
    assert!(document.settings.shadows.preserve_shadow_mass, "on when absent");
    let saved = dir.path().join("mass.lightpaint");
    document.save(&saved).expect("save");
    let text = std::fs::read_to_string(&saved).expect("read");
    assert!(!text.contains("preserve_shadow_mass"), "{text}");
    document.settings.shadows.preserve_shadow_mass = false;
    document.save(&saved).expect("save");
    assert!(
        std::fs::read_to_string(&saved)
            .expect("read")
            .contains("\"preserve_shadow_mass\": false")
    );
    let reopened = lightpaint::project::Document::open(&saved).expect("reopen");
    assert!(!reopened.settings.shadows.preserve_shadow_mass);
}

/// Hidden objects are saved by index and reopen hidden; an index the scene does not have
/// (the glTF changed) is dropped with a warning instead of failing the open.
#[test]
fn hidden_objects_are_saved_and_reopened() {
    let dir = tempfile::tempdir().expect("temp dir");
    let mut document = lightpaint::project::Document::open(&sample_project()).expect("sample");
    document.hidden_objects = [0, 2].into_iter().collect();
    let saved = dir.path().join("hidden.lightpaint");
    document.save(&saved).expect("save");
    let reopened = lightpaint::project::Document::open(&saved).expect("reopen");
    assert_eq!(reopened.hidden_objects, document.hidden_objects);
    let text = std::fs::read_to_string(&saved).expect("read");
    let count = reopened.scene.objects.len();
    let edited = text.replace(
        "\"hidden_objects\": [\n    0,",
        &format!("\"hidden_objects\": [\n    {count},"),
    );
    assert_ne!(edited, text, "the file lists the hidden objects:\n{text}");
    std::fs::write(&saved, edited).expect("write");
    let reopened = lightpaint::project::Document::open(&saved).expect("an unknown object index is not fatal");
    assert_eq!(reopened.hidden_objects, [2].into_iter().collect());
    assert!(
        reopened.warnings.iter().any(|w| w.contains("hidden objects")),
        "{:?}",
        reopened.warnings
    );
}

/// A project on a glTF with several scenes remembers the one chosen: it reopens on it,
/// saves it byte-identically, and a single-scene file's project does not mention it.
#[test]
fn a_chosen_gltf_scene_is_saved_and_reopened() {
    let dir = tempfile::tempdir().unwrap();
    let gltf = dir.path().join("day-night.glb");
    std::fs::write(&gltf, common::scenes::day_and_night()).unwrap();
    let opened = Document::open(&gltf).expect("opens on its default scene");
    assert_eq!(opened.scene.gltf_scene, Some(1));

    let mut day = opened.with_gltf_scene(0).expect("scene 0");
    assert_eq!(day.scene.lights.len(), 1, "the Day scene's sun");
    assert!(day.painting.strokes.is_empty());
    let project = dir.path().join("day.lightpaint");
    day.save(&project).unwrap();
    assert_eq!(read_project_file(&project).unwrap().scene.gltf_scene, Some(0));
    let reopened = Document::open(&project).expect("reopens");
    assert_eq!(reopened.scene.gltf_scene, Some(0));
    assert_eq!(reopened.scene.bounds().min.x, 0.0);
    let again = dir.path().join("again.lightpaint");
    Document::open(&project).unwrap().save(&again).unwrap();
    assert_eq!(std::fs::read(&project).unwrap(), std::fs::read(&again).unwrap());

    assert!(opened.with_gltf_scene(7).is_err());
    let (_sample_dir, sample) = sample_copy();
    let text = std::fs::read_to_string(&sample).unwrap();
    assert!(!text.contains("gltf_scene"), "one scene, nothing to choose");
}

/// A hand-written project needs only its format, its scene's glTF and its lights (each
/// with a name, a kind and an intensity): everything else takes its documented default,
/// and a file missing required fields is told all of them at once.
#[test]
fn a_minimal_hand_written_project_opens_and_every_missing_field_is_named() {
    let dir = tempfile::tempdir().expect("temp dir");
    std::fs::copy(
        common::repo_path("projects/sample/sample.glb"),
        dir.path().join("sample.glb"),
    )
    .expect("copy");
    let minimal = dir.path().join("minimal.lightpaint");
    std::fs::write(
        &minimal,
        r#"{
  "format_version": 10,
  "scene": { "gltf": "sample.glb" },
  "lights": [ { "name": "bulb", "kind": { "type": "point" }, "intensity": 20.0, "position": [0.0, 3.0, 0.0] } ]
}"#,
    )
    .expect("write");
    let document = lightpaint::project::Document::open(&minimal).expect("a minimal project opens");
    assert!(document.warnings.is_empty(), "{:?}", document.warnings);
    assert_eq!(document.settings, lightpaint::shading::RenderSettings::default());
    assert_eq!(document.camera, None);
    assert!(document.painting.strokes.is_empty());
    let bulb = &document.scene.lights[0];
    assert_eq!((bulb.color, bulb.direction), (glam::Vec3::ONE, glam::Vec3::NEG_Y));

    let broken = dir.path().join("broken.lightpaint");
    std::fs::write(
        &broken,
        r#"{
  "format_version": 10,
  "scene": {},
  "lights": [ { "kind": { "type": "disk" } }, { "name": "sun", "kind": { "type": "directional" }, "intensity": 3.0 } ]
}"#,
    )
    .expect("write");
    match lightpaint::project::Document::open(&broken) {
        Err(lightpaint::project::ProjectError::Invalid { problems, .. }) => {
            let fields: Vec<&str> = problems.iter().map(|p| p.field.as_str()).collect();
            assert_eq!(
                fields,
                [
                    "scene.gltf",
                    "lights[0].name",
                    "lights[0].intensity",
                    "lights[0].kind.radius_m"
                ]
            );
        }
        other => panic!("expected every missing field, got {other:?}"),
    }
}
