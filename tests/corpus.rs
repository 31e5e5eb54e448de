//! The corpus of bad files in tests/corpus/: each gets its own error kind and message (or
//! opens with its warning), names the file, never panics, and is left unchanged.
//! `cargo test --test corpus -- --ignored regenerate_corpus` rewrites the corpus.

mod common;

use std::path::{Path, PathBuf};

use glam::Vec3;
use lightpaint::project::{Document, ProjectError};
use lightpaint::scene::SceneError;
use lightpaint::scene::gltf_write::{GltfBuilder, LightSpec};

/// What opening a corpus file must give.
enum Expect {
    /// An error of this kind whose message contains the fragment.
    Error(&'static str, &'static str),
    /// The file opens, with a warning containing the fragment.
    Warning(&'static str),
    /// The file opens cleanly, with this many lights.
    Opens { lights: usize },
}

const CASES: &[(&str, Expect)] = &[
    ("empty.glb", Expect::Error("malformed", "the file is empty")),
    ("truncated.glb", Expect::Error("malformed", "truncated")),
    ("wrong-magic.glb", Expect::Error("malformed", "not a valid glTF file")),
    ("json-syntax.gltf", Expect::Error("malformed", "not a valid glTF file")),
    ("missing-bin.gltf", Expect::Error("invalid", "cannot load buffer data")),
    ("accessor-out-of-range.glb", Expect::Error("invalid", "out of range")),
    (
        "dangling-accessor.glb",
        Expect::Error("malformed", "structure is inconsistent"),
    ),
    (
        "index-out-of-range.glb",
        Expect::Error("invalid", "index 7 is out of range"),
    ),
    ("nan-position.glb", Expect::Error("invalid", "is not finite")),
    ("inf-position.glb", Expect::Error("malformed", "POSITION\"].max")),
    ("huge-coordinates.glb", Expect::Error("invalid", "lies beyond")),
    (
        "negative-intensity.glb",
        Expect::Error("invalid", "intensity -1 must be finite and non-negative"),
    ),
    ("cone-over-90.glb", Expect::Error("invalid", "spot cone angles")),
    ("not-a-scene.txt", Expect::Error("extension", "unsupported file type")),
    ("zero-area.glb", Expect::Warning("degenerate triangle")),
    ("zero-normals.glb", Expect::Warning("normals regenerated")),
    // A scene without lights is valid (the editor opens it and lights are added there):
    // no warning; `check` says so as a note (tests/cli.rs).
    // Lit by the default rig's two suns (project::default_rig).
    ("no-lights.glb", Expect::Opens { lights: 2 }),
    ("5000-lights.glb", Expect::Opens { lights: 5000 }),
    (
        "newer-version.lightpaint",
        Expect::Error("newer", "made by a newer lightpaint"),
    ),
    ("missing-gltf.lightpaint", Expect::Error("missing-scene", "is missing")),
    (
        "changed-scene.lightpaint",
        Expect::Warning("changed since the project was saved"),
    ),
    ("project-syntax.lightpaint", Expect::Error("syntax", "line 3")),
    (
        "project-wrong-type.lightpaint",
        Expect::Error("field", "lights[0].intensity"),
    ),
    (
        "project-bad-values.lightpaint",
        Expect::Error("invalid", "lights[0].intensity"),
    ),
    ("project-not-utf8.lightpaint", Expect::Error("syntax", "not UTF-8")),
    (
        "project-broken-scene.lightpaint",
        Expect::Error("scene", "in the scene it references"),
    ),
    (
        "missing-hdr.lightpaint",
        Expect::Error("asset", "gone.hdr: file not found"),
    ),
    (
        "unreadable-hdr.lightpaint",
        Expect::Error("asset", "cannot read the environment image"),
    ),
];

fn corpus_dir() -> PathBuf {
    common::repo_path("tests/corpus")
}

fn kind(error: &ProjectError) -> &'static str {
    match error {
        ProjectError::NotFound { .. } => "not-found",
        ProjectError::Read { .. } | ProjectError::Write { .. } => "io",
        ProjectError::Syntax { .. } => "syntax",
        ProjectError::Field { .. } => "field",
        ProjectError::NewerVersion { .. } => "newer",
        ProjectError::Invalid { .. } => "invalid",
        ProjectError::MissingScene { .. } => "missing-scene",
        ProjectError::Scene { .. } => "scene",
        ProjectError::Asset { .. } => "asset",
        ProjectError::SceneOnly(scene) => match scene {
            SceneError::NotFound { .. } => "not-found",
            SceneError::Io { .. } => "io",
            SceneError::UnsupportedExtension { .. } => "extension",
            SceneError::Malformed { .. } => "malformed",
            SceneError::Invalid { .. } => "invalid",
        },
    }
}

#[test]
fn every_corpus_file_gets_its_asserted_outcome_and_stays_unchanged() {
    assert!(CASES.len() >= 20);
    for (name, expect) in CASES {
        let path = corpus_dir().join(name);
        let before = std::fs::read(&path).unwrap_or_else(|e| panic!("{name}: {e} (regenerate the corpus)"));
        let result = Document::open(&path);
        assert_eq!(std::fs::read(&path).unwrap(), before, "{name} was modified");
        match (expect, result) {
            (Expect::Error(expected_kind, fragment), Err(error)) => {
                let message = error.to_string();
                assert_eq!(kind(&error), *expected_kind, "{name}: {message}");
                assert!(message.contains(fragment), "{name}: '{message}' lacks '{fragment}'");
                assert!(
                    message.contains(name),
                    "{name}: the message does not name the file: {message}"
                );
            }
            (Expect::Warning(fragment), Ok(document)) => {
                assert!(
                    document.warnings.iter().any(|w| w.contains(fragment)),
                    "{name}: {:?}",
                    document.warnings
                );
            }
            (Expect::Opens { lights }, Ok(document)) => assert_eq!(document.scene.lights.len(), *lights, "{name}"),
            (_, Err(error)) => panic!("{name} should open: {error}"),
            (_, Ok(_)) => panic!("{name} should not open"),
        }
    }
}

#[test]
fn a_non_utf8_path_opens() {
    use std::os::unix::ffi::OsStrExt;
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join(std::ffi::OsStr::from_bytes(b"caf\xe9.glb"));
    std::fs::write(&path, triangle_with_light()).unwrap();
    let document = Document::open(&path).expect("a non-UTF-8 file name is fine");
    assert_eq!(document.scene.objects.len(), 1);
}

const TRIANGLE: [Vec3; 3] = [Vec3::ZERO, Vec3::X, Vec3::NEG_Z];

fn sun() -> LightSpec {
    LightSpec::Directional {
        color: [1.0; 3],
        illuminance_lux: 1.0,
    }
}

/// A one-mesh scene with `light` (if any) above it, `edit` applied to its JSON (for broken
/// files), as a .glb.
fn scene_glb(
    positions: &[Vec3],
    normals: Option<&[Vec3]>,
    indices: &[u32],
    light: Option<LightSpec>,
    edit: impl FnOnce(&mut serde_json::Value),
) -> Vec<u8> {
    let mut b = GltfBuilder::new();
    let mesh = b.add_mesh("mesh", positions, normals, None, indices, None);
    b.add_mesh_node("mesh", mesh, Vec3::ZERO, glam::Quat::IDENTITY, Vec3::ONE);
    if let Some(light) = light {
        b.add_light_node("light", &light, Vec3::Y, Vec3::NEG_Y);
    }
    let mut document = b.document(None);
    edit(&mut document);
    lightpaint::scene::gltf_write::glb_bytes(&document, &b.bin())
}

fn triangle_with_light() -> Vec<u8> {
    scene_glb(&TRIANGLE, None, &[0, 1, 2], Some(sun()), |_| {})
}

fn edited_glb(edit: impl FnOnce(&mut serde_json::Value)) -> Vec<u8> {
    scene_glb(&TRIANGLE, None, &[0, 1, 2], Some(sun()), edit)
}

fn mesh_glb(positions: &[Vec3], normals: Option<&[Vec3]>, indices: &[u32]) -> Vec<u8> {
    scene_glb(positions, normals, indices, Some(sun()), |_| {})
}

fn light_glb(light: LightSpec) -> Vec<u8> {
    scene_glb(&TRIANGLE, None, &[0, 1, 2], Some(light), |_| {})
}

#[test]
#[ignore = "rewrites tests/corpus; run on purpose"]
fn regenerate_corpus() {
    let dir = corpus_dir();
    let write = |name: &str, bytes: &[u8]| std::fs::write(dir.join(name), bytes).unwrap();
    let good = triangle_with_light();
    let triangle = TRIANGLE;

    write("scene.glb", &good);
    write("empty.glb", b"");
    write("truncated.glb", &good[..good.len() / 2]);
    let mut wrong_magic = good.clone();
    wrong_magic[..4].copy_from_slice(b"gLTF");
    write("wrong-magic.glb", &wrong_magic);
    write(
        "json-syntax.gltf",
        b"{\"asset\": {\"version\": \"2.0\"}, \"nodes\": [}\n",
    );
    {
        let mut b = GltfBuilder::new();
        let mesh = b.add_mesh("tri", &triangle, None, None, &[0, 1, 2], None);
        b.add_mesh_node("tri", mesh, Vec3::ZERO, glam::Quat::IDENTITY, Vec3::ONE);
        let text = serde_json::to_string_pretty(&b.document(Some("missing-bin.bin"))).unwrap();
        write("missing-bin.gltf", text.as_bytes());
    }
    write(
        "accessor-out-of-range.glb",
        &edited_glb(|doc| doc["accessors"][0]["count"] = serde_json::json!(3000)),
    );
    write(
        "dangling-accessor.glb",
        &edited_glb(|doc| doc["meshes"][0]["primitives"][0]["attributes"]["POSITION"] = serde_json::json!(9)),
    );
    write("index-out-of-range.glb", &mesh_glb(&triangle, None, &[0, 1, 7]));
    write(
        "nan-position.glb",
        &mesh_glb(
            &[Vec3::ZERO, Vec3::new(f32::NAN, 0.0, 0.0), Vec3::NEG_Z],
            None,
            &[0, 1, 2],
        ),
    );
    write(
        "inf-position.glb",
        &mesh_glb(
            &[Vec3::ZERO, Vec3::X, Vec3::new(0.0, f32::INFINITY, 0.0)],
            None,
            &[0, 1, 2],
        ),
    );
    write(
        "huge-coordinates.glb",
        &mesh_glb(&[Vec3::ZERO, Vec3::X * 1e30, Vec3::NEG_Z], None, &[0, 1, 2]),
    );
    write(
        "negative-intensity.glb",
        &light_glb(LightSpec::Point {
            color: [1.0; 3],
            intensity_cd: -1.0,
        }),
    );
    write(
        "cone-over-90.glb",
        &light_glb(LightSpec::Spot {
            color: [1.0; 3],
            intensity_cd: 1.0,
            inner_cone_rad: 0.2,
            outer_cone_rad: 2.0,
        }),
    );
    write("not-a-scene.txt", b"hello\n");
    write(
        "zero-area.glb",
        &mesh_glb(&[Vec3::ZERO, Vec3::X, Vec3::X * 2.0], None, &[0, 1, 2]),
    );
    write(
        "zero-normals.glb",
        &mesh_glb(&triangle, Some(&[Vec3::ZERO; 3]), &[0, 1, 2]),
    );
    write("no-lights.glb", &scene_glb(&TRIANGLE, None, &[0, 1, 2], None, |_| {}));
    {
        let mut b = GltfBuilder::new();
        let mesh = b.add_mesh("tri", &triangle, None, None, &[0, 1, 2], None);
        b.add_mesh_node("tri", mesh, Vec3::ZERO, glam::Quat::IDENTITY, Vec3::ONE);
        for i in 0..5000 {
            let at = Vec3::new((i % 100) as f32 * 0.1, 2.0, (i / 100) as f32 * 0.1);
            b.add_light_node(
                &format!("light {i}"),
                &LightSpec::Point {
                    color: [1.0; 3],
                    intensity_cd: 0.01,
                },
                at,
                Vec3::NEG_Y,
            );
        }
        write("5000-lights.glb", &b.to_glb());
    }
    // Projects on scene.glb.
    let mut document = Document::open(&dir.join("scene.glb")).unwrap();
    document.save(&dir.join("valid.lightpaint")).unwrap();
    let valid = std::fs::read_to_string(dir.join("valid.lightpaint")).unwrap();
    let _ = std::fs::remove_file(dir.join("valid.previous.lightpaint"));
    write(
        "newer-version.lightpaint",
        valid
            .replacen(
                &format!("\"format_version\": {}", lightpaint::project::FORMAT_VERSION),
                // Far ahead, so the file stays newer across format bumps.
                "\"format_version\": 999",
                1,
            )
            .as_bytes(),
    );
    write(
        "missing-gltf.lightpaint",
        valid.replacen("scene.glb", "gone.glb", 1).as_bytes(),
    );
    let zeros = "0".repeat(64);
    let changed = valid.replacen(&document.scene.source_hash.clone().unwrap(), &zeros, 1);
    write("changed-scene.lightpaint", changed.as_bytes());
    write(
        "project-syntax.lightpaint",
        valid.replacen("\"scene\": {", "\"scene\": {{", 1).as_bytes(),
    );
    write(
        "project-wrong-type.lightpaint",
        valid
            .replacen("\"intensity\": 1.0", "\"intensity\": \"bright\"", 1)
            .as_bytes(),
    );
    write(
        "project-bad-values.lightpaint",
        valid
            .replacen("\"intensity\": 1.0", "\"intensity\": -1.0", 1)
            .as_bytes(),
    );
    write("project-not-utf8.lightpaint", &[b'{', 0xff, 0xfe, b'}']);
    write(
        "project-broken-scene.lightpaint",
        valid.replacen("scene.glb", "truncated.glb", 1).as_bytes(),
    );
    let with_environment = |hdr: &str| {
        valid.replacen(
            "\"camera\": null",
            &format!("\"camera\": null,\n  \"environment\": {{ \"hdr\": \"{hdr}\", \"intensity\": 1.0, \"rotation_rad\": 0.0 }}"),
            1,
        )
    };
    write("missing-hdr.lightpaint", with_environment("gone.hdr").as_bytes());
    write(
        "unreadable-hdr.lightpaint",
        with_environment("not-a-scene.txt").as_bytes(),
    );
    let _ = std::fs::remove_file(dir.join("valid.lightpaint"));
    let _ = std::fs::remove_file(Path::new(&dir.join("scene.previous.glb")));
}
