//! The command line: bad input exits with code 2 and one message naming the file and the
//! cause, never a panic; good input renders a PNG.

mod common;

use std::ffi::OsStr;
use std::path::Path;

use glam::Vec3;

/// Runs `lightpaint render FILE` and checks the failure contract.
fn assert_rejected(file: &Path, cause: &str) {
    let out = common::run_lightpaint(&[
        OsStr::new("render"),
        file.as_os_str(),
        OsStr::new("-o"),
        file.with_extension("png").as_os_str(),
    ]);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(
        out.status.code(),
        Some(2),
        "exit code for {}; stderr: {stderr}",
        file.display()
    );
    assert!(!stderr.contains("panicked"), "panic: {stderr}");
    let lines: Vec<&str> = stderr.lines().collect();
    assert_eq!(lines.len(), 1, "expected one message, got: {stderr}");
    assert!(
        lines[0].contains(&file.display().to_string()),
        "message does not name the file: {stderr}"
    );
    assert!(lines[0].contains(cause), "message does not say '{cause}': {stderr}");
    assert!(!file.with_extension("png").exists(), "no output may be written");
}

#[test]
fn missing_file_is_reported() {
    let dir = tempfile::tempdir().unwrap();
    assert_rejected(&dir.path().join("nowhere.glb"), "file not found");
}

#[test]
fn truncated_glb_is_reported() {
    let dir = tempfile::tempdir().unwrap();
    let sample = std::fs::read(common::repo_path(lightpaint::samples::SAMPLE_SCENE)).unwrap();
    let path = dir.path().join("truncated.glb");
    std::fs::write(&path, &sample[..sample.len() / 2]).unwrap();
    assert_rejected(&path, "truncated");
}

#[test]
fn nan_positions_are_reported() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("nan.glb");
    let glb = common::scenes::triangle([Vec3::ZERO, Vec3::new(f32::NAN, 0.0, 0.0), Vec3::Y]);
    std::fs::write(&path, glb).unwrap();
    assert_rejected(&path, "position 1 is not finite");
}

#[test]
fn out_of_range_accessor_is_reported() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("accessor.glb");
    std::fs::write(&path, common::scenes::out_of_range_accessor()).unwrap();
    assert_rejected(&path, "out of range");
}

#[test]
fn not_a_gltf_is_reported() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("notes.gltf");
    std::fs::write(&path, "{ this is not json").unwrap();
    assert_rejected(&path, "not a valid glTF file");
}

#[test]
fn usage_errors_exit_2() {
    let out = common::run_lightpaint(&[OsStr::new("render"), OsStr::new("scene.glb")]);
    assert_eq!(out.status.code(), Some(2));
    let sample = common::repo_path(lightpaint::samples::SAMPLE_SCENE);
    for exposure in ["nan", "inf", "1e9"] {
        let out = common::run_lightpaint(&[
            OsStr::new("render"),
            sample.as_os_str(),
            OsStr::new("-o"),
            OsStr::new("/nonexistent/out.png"),
            OsStr::new("--exposure"),
            OsStr::new(exposure),
        ]);
        assert_eq!(out.status.code(), Some(2), "--exposure {exposure}");
    }
}

#[test]
fn check_accepts_the_sample() {
    let sample = common::repo_path(lightpaint::samples::SAMPLE_SCENE);
    let out = common::run_lightpaint(&[OsStr::new("check"), sample.as_os_str()]);
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(out.status.success(), "{stdout}{}", String::from_utf8_lossy(&out.stderr));
    assert!(stdout.contains("ok"), "{stdout}");
}

/// `render` writes a PNG of the requested size; with `--time-frames` it also says the
/// frames' mean time and, on a GPU with timestamps (lavapipe has them), each pass's: the
/// reduced-resolution shading, the full-resolution surfaces and the scene pass are named,
/// and their times are positive and within the frame's.
#[test]
fn render_writes_a_png_of_the_requested_size_and_times_its_passes() {
    if common::no_gpu_wanted() {
        eprintln!("GPU test not run: {}=1", common::NO_GPU_ENV);
        return;
    }
    let dir = tempfile::tempdir().unwrap();
    let out_png = dir.path().join("sample.png");
    let sample = common::repo_path(lightpaint::samples::SAMPLE_SCENE);
    let out = common::run_lightpaint(&[
        OsStr::new("render"),
        sample.as_os_str(),
        OsStr::new("-o"),
        out_png.as_os_str(),
        OsStr::new("--width"),
        OsStr::new("160"),
        OsStr::new("--height"),
        OsStr::new("90"),
        OsStr::new("--time-frames"),
        OsStr::new("2"),
    ]);
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(out.status.success(), "{stdout}{}", String::from_utf8_lossy(&out.stderr));
    let image = image::open(&out_png).expect("a PNG was written");
    assert_eq!((image.width(), image.height()), (160, 90));
    let number_after = |text: &str, label: &str| -> f64 {
        let rest = &text[text.find(label).unwrap_or_else(|| panic!("{label:?} in {text}")) + label.len()..];
        let digits: String = rest
            .trim_start()
            .chars()
            .take_while(|c| c.is_ascii_digit() || *c == '.')
            .collect();
        digits
            .parse()
            .unwrap_or_else(|_| panic!("a number after {label:?} in {text}"))
    };
    let frame_ms = number_after(&stdout, "2 frames: mean");
    let passes = stdout
        .lines()
        .find(|l| l.starts_with("GPU time per pass:"))
        .expect("pass times");
    let mut total_ms = 0.0;
    for pass in [
        "low-resolution shading",
        "surfaces",
        "upsampling",
        "frame colours copied",
    ] {
        let ms = number_after(passes, pass);
        assert!(ms > 0.0, "{passes}");
        total_ms += ms;
    }
    assert!(
        total_ms <= frame_ms,
        "passes {total_ms} ms within the frame's {frame_ms} ms: {passes}"
    );
}

/// The flags that change how a frame is shaded change the frame: `--per-vertex` (shadows
/// interpolated from the vertices, under the default automatic light paths) and
/// `--shadow-map-size 0` (the lights of no size on the SH path instead of the real
/// triangles' shadow maps) each give another image than the project's defaults, and
/// `--blockers 0` fits no sphere; the summary says how many blockers a surface point
/// sees on average, and per vertex how many meshes were lit at their vertices.
#[test]
fn render_honours_per_vertex_shadow_maps_and_no_blockers() {
    if common::no_gpu_wanted() {
        eprintln!("GPU test not run: {}=1", common::NO_GPU_ENV);
        return;
    }
    let dir = tempfile::tempdir().unwrap();
    let project = common::repo_path("projects/sample/sample.lightpaint");
    let render_with_summary = |name: &str, extra: &[&str]| {
        let png = dir.path().join(name);
        let mut args: Vec<&OsStr> = vec![
            OsStr::new("render"),
            project.as_os_str(),
            OsStr::new("-o"),
            png.as_os_str(),
            OsStr::new("--width"),
            OsStr::new("160"),
            OsStr::new("--height"),
            OsStr::new("90"),
        ];
        args.extend(extra.iter().map(OsStr::new));
        let out = common::run_lightpaint(&args);
        assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
        (
            image::open(&png).expect("a PNG was written").to_rgb8(),
            String::from_utf8_lossy(&out.stdout).into_owned(),
        )
    };
    let differing =
        |a: &image::RgbImage, b: &image::RgbImage| a.pixels().zip(b.pixels()).filter(|(x, y)| x != y).count();
    let (defaults, summary) = render_with_summary("defaults.png", &[]);
    // The summary says what the SH path's blocker walk visits and finds per surface point:
    // some blockers shadow the sample's surfaces, and no more than are visited.
    let counts: Vec<f64> = summary
        .split("blockers: ")
        .nth(1)
        .and_then(|rest| rest.split(" per surface point").next())
        .map(|words| words.split(' ').filter_map(|w| w.parse().ok()).collect())
        .unwrap_or_default();
    assert!(
        matches!(counts[..], [visited, shadowing] if shadowing > 0.0 && shadowing <= visited),
        "{summary}"
    );
    let pixels = (160 * 90) as usize;
    for (name, flags) in [
        ("per-vertex.png", &["--per-vertex"][..]),
        ("no-maps.png", &["--shadow-map-size", "0"][..]),
    ] {
        let (image, summary) = render_with_summary(name, flags);
        let changed = differing(&image, &defaults);
        assert!(changed > pixels / 100, "{flags:?} changed only {changed} pixels");
        // Per vertex the summary says how many of the sample's seven meshes were lit at
        // their vertices (`shading::vertex_lighting`; tests/vertex_lighting.rs checks
        // which), and only per vertex.
        let lit: Option<usize> = summary
            .split("; per vertex, ")
            .nth(1)
            .and_then(|rest| rest.split_once(" of 7 meshes lit at their vertices"))
            .and_then(|(count, _)| count.parse().ok());
        assert_eq!(lit.is_some_and(|n| n <= 7), flags == ["--per-vertex"], "{summary}");
    }
    let (no_blockers, summary) = render_with_summary("no-blockers.png", &["--blockers", "0"]);
    assert!(summary.contains(", 0 blockers"), "{summary}");
    // Every mesh without spheres is named (the sample has fewer than the eight a reason
    // names), the reason once after them.
    assert!(
        summary.contains("no soft shadows from:") && summary.contains("Floor") && !summary.contains(" more ("),
        "{summary}"
    );
    assert_eq!(summary.matches("a budget of 0").count(), 1, "{summary}");
    assert!(
        differing(&no_blockers, &defaults) > pixels / 100,
        "--blockers 0 shadows as before"
    );
}

/// `render` checks where it writes before it renders: a format it cannot write or a
/// folder that does not exist is a usage error (exit 2) that leaves no file; a .jpg is
/// written as JPEG.
#[test]
fn render_checks_its_output_before_rendering_and_writes_jpeg() {
    let dir = tempfile::tempdir().unwrap();
    let project = common::repo_path("projects/sample/sample.lightpaint");
    let render = |output: &Path| {
        common::run_lightpaint(&[
            OsStr::new("render"),
            project.as_os_str(),
            OsStr::new("-o"),
            output.as_os_str(),
            OsStr::new("--width"),
            OsStr::new("64"),
            OsStr::new("--height"),
            OsStr::new("36"),
        ])
    };
    for bad in [dir.path().join("frame.bmp"), dir.path().join("missing/frame.png")] {
        let out = render(&bad);
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{stderr}");
        assert!(stderr.contains(&bad.display().to_string()), "{stderr}");
        assert!(!bad.exists(), "no file is left at {}", bad.display());
    }
    if common::no_gpu_wanted() {
        eprintln!("GPU part not run: {}=1", common::NO_GPU_ENV);
        return;
    }
    let jpeg = dir.path().join("frame.JPG");
    let out = render(&jpeg);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let bytes = std::fs::read(&jpeg).expect("written");
    assert_eq!(image::guess_format(&bytes).ok(), Some(image::ImageFormat::Jpeg));
    let image = image::load_from_memory(&bytes).expect("decodes");
    assert_eq!((image.width(), image.height()), (64, 36));
}

#[test]
fn render_reference_path_traces_without_a_gpu_and_is_repeatable() {
    let dir = tempfile::tempdir().unwrap();
    let sample = common::repo_path(lightpaint::samples::SAMPLE_SCENE);
    let render = |name: &str, seed: &str| {
        let png = dir.path().join(name);
        let out = common::run_lightpaint(&[
            OsStr::new("render"),
            sample.as_os_str(),
            OsStr::new("-o"),
            png.as_os_str(),
            OsStr::new("--reference"),
            OsStr::new("--spp"),
            OsStr::new("2"),
            OsStr::new("--bounces"),
            OsStr::new("1"),
            OsStr::new("--seed"),
            OsStr::new(seed),
            OsStr::new("--width"),
            OsStr::new("64"),
            OsStr::new("--height"),
            OsStr::new("36"),
        ]);
        let stdout = String::from_utf8_lossy(&out.stdout).to_string();
        assert!(out.status.success(), "{stdout}{}", String::from_utf8_lossy(&out.stderr));
        assert!(
            stdout.contains("reference path tracer, 2 spp, 1 bounces, seed"),
            "{stdout}"
        );
        image::open(&png).expect("a PNG was written").to_rgba8()
    };
    let (first, again, other) = (render("a.png", "7"), render("b.png", "7"), render("c.png", "8"));
    assert_eq!((first.width(), first.height()), (64, 36));
    assert_eq!(first, again, "the same seed renders the same image");
    assert_ne!(first, other, "another seed draws other paths");
    let usage = common::run_lightpaint(&[
        OsStr::new("render"),
        sample.as_os_str(),
        OsStr::new("-o"),
        dir.path().join("d.png").as_os_str(),
        OsStr::new("--reference"),
        OsStr::new("--spp"),
        OsStr::new("0"),
    ]);
    assert_eq!(usage.status.code(), Some(2), "0 samples per pixel is a usage error");
}

#[test]
fn a_file_that_crashes_the_gltf_validator_is_reported_not_panicked() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("dangling.glb");
    std::fs::write(&path, common::scenes::dangling_position_accessor()).unwrap();
    assert_rejected(&path, "structure is inconsistent");
}

#[test]
fn a_closed_stdout_is_not_a_crash() {
    // `lightpaint check FILE | head -c 0`: the reader is gone before anything is printed.
    let sample = common::repo_path(lightpaint::samples::SAMPLE_PROJECT);
    let runtime = tempfile::tempdir().expect("temp dir");
    let mut child = std::process::Command::new(env!("CARGO_BIN_EXE_lightpaint"))
        .args([OsStr::new("check"), sample.as_os_str()])
        .env("XDG_RUNTIME_DIR", runtime.path())
        .stdout(std::process::Stdio::piped())
        .stderr(std::process::Stdio::piped())
        .spawn()
        .expect("the binary starts");
    drop(child.stdout.take());
    let out = child.wait_with_output().expect("the binary ends");
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(0), "{stderr}");
    assert!(!stderr.contains("panicked"), "{stderr}");
}

/// A glTF without lights is no problem for `check` (it opens lit by the default rig):
/// exit 0, with a note that says so; `render` draws it lit and says so too.
#[test]
fn a_scene_without_lights_opens_lit_by_the_default_rig() {
    let file = common::repo_path("tests/corpus/no-lights.glb");
    let out = common::run_lightpaint(&[OsStr::new("check"), file.as_os_str()]);
    let stdout = String::from_utf8_lossy(&out.stdout);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(0), "{stdout}{stderr}");
    assert!(stdout.contains("note:") && stdout.contains("default rig"), "{stdout}");
    assert!(stdout.contains("2 lights"), "{stdout}");
    assert!(stdout.contains(": ok"), "{stdout}");
    if common::no_gpu_wanted() {
        return;
    }
    let dir = tempfile::tempdir().unwrap();
    let image = dir.path().join("lit.png");
    let out = common::run_lightpaint(&[
        OsStr::new("render"),
        file.as_os_str(),
        OsStr::new("-o"),
        image.as_os_str(),
        OsStr::new("--width"),
        OsStr::new("64"),
        OsStr::new("--height"),
        OsStr::new("64"),
    ]);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "{stderr}");
    assert!(stderr.contains("default rig"), "{stderr}");
    // The triangle is lit: some pixel is well above the background's grey.
    let brightest = image::open(&image)
        .expect("a PNG")
        .to_luma8()
        .pixels()
        .map(|p| p[0])
        .max()
        .unwrap_or(0);
    assert!(brightest > 100, "brightest pixel {brightest}");
}

/// A headless session without XDG_RUNTIME_DIR (CI, ssh): `render` prints no complaint
/// about it (the binary gives itself a private one) and leaves none behind.
#[test]
fn a_render_without_a_runtime_dir_says_nothing_about_it() {
    if common::no_gpu_wanted() {
        return;
    }
    let sample = common::repo_path(lightpaint::samples::SAMPLE_PROJECT);
    let out_dir = tempfile::tempdir().expect("temp dir");
    let image = out_dir.path().join("frame.png");
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_lightpaint"))
        .args([
            OsStr::new("render"),
            sample.as_os_str(),
            OsStr::new("-o"),
            image.as_os_str(),
            OsStr::new("--width"),
            OsStr::new("64"),
            OsStr::new("--height"),
            OsStr::new("36"),
        ])
        .env_remove("XDG_RUNTIME_DIR")
        .output()
        .expect("the binary runs");
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(0), "{stderr}");
    assert!(image.is_file());
    assert!(!stderr.contains("XDG_RUNTIME_DIR"), "{stderr}");
}

#[test]
fn render_rejects_bad_shadow_settings_with_exit_code_2() {
    let sample = common::repo_path(lightpaint::samples::SAMPLE_PROJECT);
    let dir = tempfile::tempdir().expect("temp dir");
    let out_png = dir.path().join("out.png");
    for args in [
        &["--order", "9"][..],
        &["--eps", "0"][..],
        &["--exp", "ref"][..],
        &["--exp", "fast"][..],
        &["--order", "8", "--per-vertex"][..],
        &["--blockers", "many"][..],
        &["--aa", "4x"][..],
    ] {
        let mut all: Vec<&OsStr> = vec![
            OsStr::new("render"),
            sample.as_os_str(),
            OsStr::new("-o"),
            out_png.as_os_str(),
        ];
        all.extend(args.iter().map(OsStr::new));
        let out = common::run_lightpaint(&all);
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{args:?}: {stderr}");
        assert!(!stderr.contains("panicked"), "{args:?}: {stderr}");
        assert!(!out_png.exists(), "{args:?} wrote an image");
    }
}

#[test]
fn bake_reports_the_maps_of_the_sample() {
    // A copy: baking a project writes its cache beside it.
    let dir = tempfile::tempdir().expect("temp dir");
    let sample = lightpaint::samples::Sample::Sample.write(dir.path()).expect("sample");
    let out = common::run_lightpaint(&[OsStr::new("bake"), sample.as_os_str()]);
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert_eq!(out.status.code(), Some(0), "{}", String::from_utf8_lossy(&out.stderr));
    assert!(stdout.contains("(vertex, light) pairs stored"), "{stdout}");
    assert!(
        stdout.contains("MiB in memory") && stdout.contains("M rays/s"),
        "{stdout}"
    );
    let bad = common::run_lightpaint(&[
        OsStr::new("bake"),
        sample.as_os_str(),
        OsStr::new("--order"),
        OsStr::new("0"),
    ]);
    assert_eq!(bad.status.code(), Some(2));
}

/// `paint` reads a project's bake cache baked in half precision rather than baking again
/// in full precision, and leaves the input's cache as it was (writing the output's).
#[test]
fn paint_reads_a_half_precision_bake_cache_instead_of_baking_again() {
    let dir = tempfile::tempdir().expect("temp dir");
    let sample = lightpaint::samples::Sample::Sample.write(dir.path()).expect("sample");
    let baked = common::run_lightpaint(&[OsStr::new("bake"), sample.as_os_str(), OsStr::new("--f16")]);
    assert_eq!(
        baked.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&baked.stderr)
    );
    let cache = lightpaint::project::bake_cache::cache_path(&sample);
    let cached = std::fs::read(&cache).expect("the bake wrote its cache");
    let script = r#"{"strokes": [{"brush": {"kind": "positive", "radius_px": 60}, "world": [[0.0, 0.5, 0.0]]}]}"#;
    let out_dir = tempfile::tempdir().expect("temp dir");
    let (stdout, output) = run_paint_ok(&sample, script, out_dir.path(), &["--bounces", "1"]);
    assert!(stdout.contains("read the bake cache"), "{stdout}");
    assert!(!stdout.contains("baked ("), "baked again: {stdout}");
    assert_eq!(
        std::fs::read(&cache).expect("cache"),
        cached,
        "the input's cache is untouched"
    );
    assert!(lightpaint::project::bake_cache::cache_path(&output).is_file());
}

/// Runs `lightpaint paint INPUT --strokes S -o DIR/painted.lightpaint EXTRA…` with the
/// script text `script` written to DIR/strokes.json; the output and the project path.
fn run_paint(input: &Path, script: &str, dir: &Path, extra: &[&str]) -> (std::process::Output, std::path::PathBuf) {
    let script_path = dir.join("strokes.json");
    std::fs::write(&script_path, script).expect("script");
    let output = dir.join("painted.lightpaint");
    let mut args = vec![
        OsStr::new("paint"),
        input.as_os_str(),
        OsStr::new("--strokes"),
        script_path.as_os_str(),
        OsStr::new("-o"),
        output.as_os_str(),
    ];
    args.extend(extra.iter().map(OsStr::new));
    (common::run_lightpaint(&args), output)
}

/// As [`run_paint`], checking that it succeeded; its standard output and the project path.
fn run_paint_ok(input: &Path, script: &str, dir: &Path, extra: &[&str]) -> (String, std::path::PathBuf) {
    let (out, output) = run_paint(input, script, dir, extra);
    let stdout = String::from_utf8_lossy(&out.stdout).into_owned();
    assert_eq!(
        out.status.code(),
        Some(0),
        "{stdout}{}",
        String::from_utf8_lossy(&out.stderr)
    );
    (stdout, output)
}

/// `paint` applies a script to the studio and writes a project whose log holds the
/// strokes that changed something, with the positive stroke's lights brighter; the
/// original project is untouched.
#[test]
fn paint_applies_scripted_strokes_and_saves_them_in_the_project_log() {
    let studio = common::repo_path("projects/studio/studio.lightpaint");
    let original = std::fs::read(&studio).expect("studio project");
    let dir = tempfile::tempdir().expect("temp dir");
    let script = r#"{"seed": 3, "strokes": [
            {"brush": {"kind": "positive", "radius_px": 60}, "world": [[0.0, 1.0, 0.3]]},
            {"brush": {"kind": "constraint", "radius_px": 30}, "world": [[1.0, 0.0, 1.0]]}
        ]}"#;
    let (stdout, output) = run_paint_ok(&studio, script, dir.path(), &["--bounces", "0"]);
    assert!(stdout.contains("stroke 0: Changed"), "{stdout}");
    assert_eq!(
        std::fs::read(&studio).expect("studio"),
        original,
        "the input is untouched"
    );
    let before = lightpaint::project::Document::open(&studio).expect("studio opens");
    let after = lightpaint::project::Document::open(&output).expect("the painted project opens");
    assert_eq!(after.painting.strokes.len(), 2);
    let raised = before
        .scene
        .lights
        .iter()
        .zip(&after.scene.lights)
        .filter(|(b, a)| a.intensity > b.intensity)
        .count();
    assert!(raised >= 1, "a positive stroke raises a light");
    assert!(
        before
            .scene
            .lights
            .iter()
            .zip(&after.scene.lights)
            .all(|(b, a)| a.intensity >= b.intensity)
    );
}

/// A script's `locked_lights` lock the lights it names: the strokes leave the key as it
/// is while raising another light, the saved project keeps the key locked and its strokes
/// record the lock; a name no light has is refused, naming it, and nothing is written.
#[test]
fn paint_leaves_the_lights_a_script_locks_as_they_are() {
    let studio = common::repo_path("projects/studio/studio.lightpaint");
    let dir = tempfile::tempdir().expect("temp dir");
    let script = r#"{"seed": 3, "locked_lights": ["Key"], "strokes": [
            {"brush": {"kind": "positive", "radius_px": 60}, "world": [[0.0, 1.0, 0.3]]}
        ]}"#;
    let (stdout, output) = run_paint_ok(&studio, script, dir.path(), &["--bounces", "0"]);
    assert!(stdout.contains("stroke 0: Changed"), "{stdout}");
    let before = lightpaint::project::Document::open(&studio).expect("studio opens");
    let after = lightpaint::project::Document::open(&output).expect("the painted project opens");
    let key = before
        .scene
        .lights
        .iter()
        .position(|l| l.name == "Key")
        .expect("a key light");
    assert_eq!(after.scene.lights[key].intensity, before.scene.lights[key].intensity);
    assert_eq!(after.scene.locked_lights(), vec![key as u32]);
    assert_eq!(after.painting.strokes[0].locked_lights, vec![key as u32]);
    assert!(
        (before.scene.lights.iter().zip(&after.scene.lights)).any(|(b, a)| a.intensity > b.intensity),
        "another light is raised instead"
    );
    let unknown = r#"{"locked_lights": ["Nobody"], "strokes": []}"#;
    let elsewhere = dir.path().join("unknown");
    std::fs::create_dir(&elsewhere).expect("dir");
    let (out, output) = run_paint(&studio, unknown, &elsewhere, &[]);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{stderr}");
    assert!(
        stderr.contains("locked_lights[0]") && stderr.contains("\"Nobody\""),
        "{stderr}"
    );
    assert!(!output.exists(), "nothing is written");
}

#[test]
fn paint_rejects_a_bad_script_naming_the_file_and_the_field() {
    let studio = common::repo_path("projects/studio/studio.lightpaint");
    let dir = tempfile::tempdir().expect("temp dir");
    let script = dir.path().join("bad.json");
    std::fs::write(
        &script,
        r#"{"strokes": [{"brush": {"kind": "positive", "radius_px": "big"}, "world": []}]}"#,
    )
    .expect("script");
    let output = dir.path().join("out.lightpaint");
    let run = |script: &Path, output: &Path| {
        common::run_lightpaint(&[
            OsStr::new("paint"),
            studio.as_os_str(),
            OsStr::new("--strokes"),
            script.as_os_str(),
            OsStr::new("-o"),
            output.as_os_str(),
        ])
    };
    let out = run(&script, &output);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{stderr}");
    assert!(
        stderr.contains("bad.json") && stderr.contains("strokes[0].brush.radius_px"),
        "{stderr}"
    );
    assert!(!output.exists(), "nothing is written for a bad script");
    let png = dir.path().join("out.png");
    std::fs::write(&script, r#"{"strokes": []}"#).expect("script");
    let out = run(&script, &png);
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains(".lightpaint"));
}

/// Without a bake, `paint --no-bake` reads the transfer from the real-time log-SH shading
/// and still finds and raises a light.
#[test]
fn paint_without_a_bake_uses_the_direct_estimate() {
    let sample = common::repo_path(lightpaint::samples::SAMPLE_PROJECT);
    let dir = tempfile::tempdir().expect("temp dir");
    let script = r#"{"strokes": [{"brush": {"kind": "positive", "radius_px": 80}, "screen_px": [[640, 500]]}]}"#;
    let (out, _) = run_paint(&sample, script, dir.path(), &["--no-bake"]);
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert_eq!(
        out.status.code(),
        Some(0),
        "{stdout}{}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert!(
        stdout.contains("estimated") && stdout.contains("stroke 0: Changed"),
        "{stdout}"
    );
}

/// `bake` on a project fills the cache beside it; a second run reads it instead of
/// baking; a moved light re-bakes only that light; a corrupt cache is rebuilt.
#[test]
fn bake_uses_the_cache_beside_the_project_and_never_trusts_a_bad_one() {
    let dir = tempfile::tempdir().expect("temp dir");
    let project = lightpaint::samples::Sample::Sample.write(dir.path()).expect("sample");
    let bake = || {
        let out = common::run_lightpaint(&[OsStr::new("bake"), project.as_os_str()]);
        assert_eq!(out.status.code(), Some(0), "{}", String::from_utf8_lossy(&out.stderr));
        String::from_utf8_lossy(&out.stdout).into_owned()
    };
    let first = bake();
    assert!(
        first.contains("baked (") && first.contains("rays/s); cache written"),
        "{first}"
    );
    let cache = lightpaint::project::bake_cache::cache_path(&project);
    let second = bake();
    assert!(second.contains("read the bake cache"), "{second}");

    let mut document = lightpaint::project::Document::open(&project).expect("opens");
    document.scene.lights[1].position += Vec3::new(0.3, 0.0, 0.0);
    document.scene.lights[2].intensity *= 2.0;
    document.save(&project).expect("save");
    let third = bake();
    assert!(third.contains("re-baked 1 changed light(s)"), "{third}");

    let mut bytes = std::fs::read(&cache).expect("cache");
    let middle = bytes.len() / 2;
    bytes[middle] ^= 1;
    std::fs::write(&cache, &bytes).expect("corrupt it");
    let fourth = bake();
    assert!(
        fourth.contains("baked again") && fourth.contains("checksum"),
        "{fourth}"
    );
    assert!(bake().contains("read the bake cache"));
}

/// The painted luminance a stroke of `paint` started from ("painted luminance from X"),
/// as it printed it.
fn painted_luminance_before(stdout: &str) -> f64 {
    let after = stdout
        .split("painted luminance from ")
        .nth(1)
        .unwrap_or_else(|| panic!("no painted luminance in: {stdout}"));
    after
        .split_whitespace()
        .next()
        .and_then(|v| v.parse().ok())
        .unwrap_or_else(|| panic!("unreadable luminance in: {stdout}"))
}

/// After a bake a stroke reads the light the frame shows: the direct light through the
/// view's shadows (as without a bake) plus the maps' bounced light only where the frame
/// adds it. A bake without bounces, or a project whose frame adds no baked light, reads
/// exactly what the estimate reads; with the baked light shown it reads more. (`paint`
/// once read the direct light without any shadow after a bake.)
#[test]
fn paint_after_a_bake_reads_the_view_s_shadows_and_the_bounce_the_frame_shows() {
    let dir = tempfile::tempdir().expect("temp dir");
    let sample = lightpaint::samples::Sample::Sample.write(dir.path()).expect("sample");
    // A dab on the floor under the ball at (1.4, 0.55, 0.9), which hides much of the
    // sky there (the environment's light is shadowed by the sphere blockers).
    let script = r#"{"strokes": [{"brush": {"kind": "positive", "radius_px": 20}, "world": [[1.4, 0.0, 0.9]]}]}"#;
    let read = |project: &Path, extra: &[&str]| {
        let out_dir = tempfile::tempdir().expect("temp dir");
        let (stdout, _) = run_paint_ok(project, script, out_dir.path(), extra);
        painted_luminance_before(&stdout)
    };
    let estimate = read(&sample, &["--no-bake"]);
    let without_bounces = read(&sample, &["--bounces", "0"]);
    assert_eq!(
        without_bounces, estimate,
        "a bake of direct light adds nothing to the estimate"
    );
    let bounced = read(&sample, &["--bounces", "1"]);
    assert!(bounced > estimate, "the frame adds the bounce: {bounced} vs {estimate}");
    let mut document = lightpaint::project::Document::open(&sample).expect("sample");
    document.settings.baked_indirect = false;
    let no_baked_light = dir.path().join("no_baked_light.lightpaint");
    document.save(&no_baked_light).expect("save");
    assert_eq!(
        read(&no_baked_light, &["--bounces", "1"]),
        estimate,
        "the frame adds no baked light, so neither do strokes"
    );
}
