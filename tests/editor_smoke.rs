//! Smoke test of the real editor binary in a real window: start it under Xvfb on the
//! bundled sample, wait for its first frame, screenshot the screen, check the picture is
//! not blank, and close the window cleanly.

mod common;

use std::process::Command;

fn have(program: &str) -> bool {
    Command::new("sh")
        .args(["-c", &format!("command -v {program}")])
        .output()
        .is_ok_and(|o| o.status.success())
}

/// Starts the editor (on `$PROJECT` when set) and waits up to 2 minutes for its first
/// frame; the scripts below go on from there.
const START_EDITOR: &str = r#"
timeout 300 "$LIGHTPAINT" ${PROJECT:+"$PROJECT"} > "$LOG" 2>&1 &
pid=$!
for _ in $(seq 1 1200); do
    grep -q "first frame drawn" "$LOG" && break
    kill -0 "$pid" 2>/dev/null || break
    sleep 0.1
done
"#;

const SCRIPT: &str = r#"
# Let the viewport draw a few frames after the first; on a loaded machine the window can
# take longer to show them, so look again (up to 30 s) while the screen is still blank.
sleep 3
for _ in $(seq 1 30); do
    import -window root "$SHOT"
    [ "$(identify -format %k "$SHOT" 2>/dev/null || echo 0)" -gt 500 ] && break
    sleep 1
done
touch "$CLOSE"
wait "$pid"
"#;

/// Whether the Xvfb tests run: not when GPU tests are opted out (said on stderr); else
/// every one of `programs` must be installed (the README's test command installs them).
fn xvfb_tools_present(programs: &[&str]) -> bool {
    if common::no_gpu_wanted() {
        eprintln!("editor smoke test not run: {}=1", common::NO_GPU_ENV);
        return false;
    }
    for program in programs {
        assert!(
            have(program),
            "{program} is missing: the README's test command installs it (xvfb, imagemagick, xdotool, zenity)"
        );
    }
    true
}

/// `xvfb-run` on a 1280 × 800 screen starting the editor (START_EDITOR) and then `script`,
/// with its log in `dir`/editor.log, its screenshot to `shot`, closing once `dir`/close
/// exists, and a private runtime, data and home directory under `dir` (no persisted
/// window state or settings leak in or out).
fn editor_under_xvfb(script: &str, dir: &std::path::Path, shot: &std::path::Path) -> Command {
    let mut command = Command::new("xvfb-run");
    command
        .args([
            "-a",
            "-s",
            "-screen 0 1280x800x24",
            "bash",
            "-c",
            &format!("{START_EDITOR}{script}"),
        ])
        .env("LIGHTPAINT", env!("CARGO_BIN_EXE_lightpaint"))
        .env("LOG", dir.join("editor.log"))
        .env("SHOT", shot)
        .env("CLOSE", dir.join("close"))
        .env("LIGHTPAINT_CLOSE_WHEN_FILE_EXISTS", dir.join("close"))
        .env("XDG_RUNTIME_DIR", dir)
        .env("XDG_DATA_HOME", dir.join("data"))
        .env("HOME", dir);
    command
}

#[test]
fn editor_opens_the_sample_draws_and_closes_under_xvfb() {
    if !xvfb_tools_present(&["xvfb-run", "import"]) {
        return;
    }
    let dir = tempfile::tempdir().unwrap();
    let log = dir.path().join("editor.log");
    let shot = std::path::Path::new(env!("CARGO_TARGET_TMPDIR")).join("editor-smoke.png");
    let _ = std::fs::remove_file(&shot);
    let status = editor_under_xvfb(SCRIPT, dir.path(), &shot)
        .status()
        .expect("xvfb-run runs");
    let log_text = std::fs::read_to_string(&log).unwrap_or_default();
    assert!(status.success(), "editor exited with {status}; log:\n{log_text}");
    assert!(
        log_text.contains(lightpaint::ui::FIRST_FRAME_LINE),
        "no first frame; log:\n{log_text}"
    );
    assert!(!log_text.contains("panicked"), "{log_text}");

    let image = image::open(&shot).expect("screenshot taken").to_rgb8();
    let distinct: std::collections::HashSet<[u8; 3]> = image.pixels().map(|p| p.0).collect();
    let mean = image.pixels().map(|p| p[1] as f64).sum::<f64>() / (image.width() * image.height()) as f64;
    assert!(
        distinct.len() > 500,
        "screenshot looks blank: {} colours",
        distinct.len()
    );
    assert!((10.0..245.0).contains(&mean), "screenshot mean {mean}");
    eprintln!("screenshot: {}", shot.display());
}

const SAVE_AS_SCRIPT: &str = r#"
sleep 2
# File ▸ Save As… (the menu bar's first entry; the sixth item of its menu).
xdotool mousemove 20 12 click 1
sleep 1
xdotool mousemove 45 163 click 1
# The system's dialog (zenity under Xvfb): its name field holds the project's name.
for _ in $(seq 1 100); do
    xdotool search --onlyvisible --class zenity >/dev/null 2>&1 && break
    sleep 0.2
done
sleep 1
import -window root "$SHOT"
xdotool key --clearmodifiers ctrl+a
xdotool type --delay 20 "$TARGET"
xdotool key Return
for _ in $(seq 1 100); do
    [ -f "$TARGET" ] && break
    sleep 0.2
done
touch "$CLOSE"
wait "$pid"
"#;

/// File ▸ Save As through the system's file dialog, driven as a user would (xdotool under
/// Xvfb, the README's set-up installing zenity): the dialog opens on the project's folder
/// under its name, and the name typed there gets a project that opens.
#[test]
fn save_as_through_the_file_dialog_writes_the_project_under_xvfb() {
    if !xvfb_tools_present(&["xvfb-run", "import", "xdotool", "zenity"]) {
        return;
    }
    let dir = tempfile::tempdir().unwrap();
    let studio = dir.path().join("studio");
    std::fs::create_dir(&studio).unwrap();
    for entry in std::fs::read_dir(common::repo_path("projects/studio")).unwrap() {
        let path = entry.unwrap().path();
        if path.is_file() {
            std::fs::copy(&path, studio.join(path.file_name().unwrap())).unwrap();
        }
    }
    let target = dir.path().join("saved as.lightpaint");
    let log = dir.path().join("editor.log");
    let shot = std::path::Path::new(env!("CARGO_TARGET_TMPDIR")).join("editor-save-as.png");
    let status = editor_under_xvfb(SAVE_AS_SCRIPT, dir.path(), &shot)
        .env("PROJECT", studio.join("studio.lightpaint"))
        .env("TARGET", &target)
        .env_remove("DBUS_SESSION_BUS_ADDRESS")
        .status()
        .expect("xvfb-run runs");
    let log_text = std::fs::read_to_string(&log).unwrap_or_default();
    assert!(status.success(), "editor exited with {status}; log:\n{log_text}");
    assert!(!log_text.contains("panicked"), "{log_text}");
    assert!(
        target.is_file(),
        "Save As wrote nothing (screenshot of the dialog: {}); log:\n{log_text}",
        shot.display()
    );
    let saved = lightpaint::project::Document::open(&target).expect("the saved project opens");
    let original = lightpaint::project::Document::open(&studio.join("studio.lightpaint")).expect("studio");
    assert_eq!(saved.scene.lights, original.scene.lights);
}
