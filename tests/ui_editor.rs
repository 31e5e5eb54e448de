//! The editor driven headlessly with egui_kittest on a real wgpu adapter: it opens the
//! sample project, shows its scene, saves with Ctrl+S, and looks as reviewed.

mod common;

use egui_kittest::Harness;
use egui_kittest::kittest::Queryable;
use lightpaint::project::Document;
use lightpaint::ui::{EditorApp, EditorOptions};

fn editor_on_sample_copy() -> Option<(tempfile::TempDir, std::path::PathBuf, Harness<'static, EditorApp>)> {
    if common::no_gpu_wanted() {
        eprintln!("UI test not run: {}=1", common::NO_GPU_ENV);
        return None;
    }
    let dir = tempfile::tempdir().unwrap();
    lightpaint::samples::write_sample_project(dir.path()).unwrap();
    let project = dir.path().join("sample.lightpaint");
    let options = EditorOptions {
        file: project.clone(),
        close_when_file_exists: None,
        hide_frame_timings: true,
    };
    let harness = Harness::builder()
        .with_size(egui::vec2(1280.0, 800.0))
        .wgpu()
        .build_eframe(|cc| EditorApp::new(cc, options));
    Some((dir, project, harness))
}

#[test]
fn editor_shows_the_sample_and_saves_with_ctrl_s() {
    let Some((_dir, project, mut harness)) = editor_on_sample_copy() else {
        return;
    };
    harness.run();
    harness.get_by_label("Lights (4)");
    harness.get_by_label("Key (warm spot)");
    assert!(
        !harness.state().has_unsaved_changes(),
        "a freshly opened project has no changes"
    );

    let before = std::fs::read_to_string(&project).unwrap();
    harness.key_press_modifiers(egui::Modifiers::COMMAND, egui::Key::S);
    harness.run();
    let after = std::fs::read_to_string(&project).unwrap();
    assert_ne!(before, after, "Ctrl+S saved the view");
    let reopened = Document::open(&project).unwrap();
    assert!(reopened.camera.is_some(), "the saved project keeps the camera");
    assert!(!harness.state().has_unsaved_changes());
}

#[test]
fn editor_looks_as_reviewed() {
    let Some((_dir, _project, mut harness)) = editor_on_sample_copy() else {
        return;
    };
    harness.run();
    harness.snapshot("editor_sample");
}

/// Shadow settings changed in the inspector are drawn, marked unsaved, and saved into the
/// project (format 2 keeps them).
#[test]
fn shadow_settings_edited_in_the_inspector_are_saved() {
    let Some((_dir, project, mut harness)) = editor_on_sample_copy() else {
        return;
    };
    harness.run();
    harness.get_by_label("per vertex").click();
    harness.run();
    harness.get_by_label("log-SH soft shadows").click();
    harness.run();
    assert!(harness.state().has_unsaved_changes(), "shadow edits are changes");
    harness.key_press_modifiers(egui::Modifiers::COMMAND, egui::Key::S);
    harness.run();
    let reopened = Document::open(&project).unwrap();
    assert!(reopened.settings.shadows.per_vertex, "per vertex was saved");
    assert!(!reopened.settings.shadows.enabled, "shadows off was saved");
}
