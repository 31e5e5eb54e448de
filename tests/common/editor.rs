//! The editor under egui_kittest on the real wgpu adapter: building it on a project,
//! dragging like a hand, and reading the rendered viewport.

use egui_kittest::Harness;
use lightpaint::ui::{EditorApp, EditorOptions};

/// The editor on `project`, in a 1280 × 800 window on the real wgpu adapter.
pub fn editor_on(project: std::path::PathBuf) -> Harness<'static, EditorApp> {
    let options = EditorOptions {
        file: project,
        close_when_file_exists: None,
        hide_frame_timings: true,
        measure_frame_rate: lightpaint::ui::FrameRateMeasurement::Off,
    };
    Harness::builder()
        .with_size(egui::vec2(1280.0, 800.0))
        .wgpu()
        .build_eframe(|cc| EditorApp::new(cc, options))
}

/// Four points across the studio's floor in front of the figure, on screen: a stroke's
/// path there.
#[allow(dead_code)] // Not every test binary that shares this module paints.
pub fn studio_floor_path(harness: &Harness<'static, EditorApp>) -> Vec<egui::Pos2> {
    [[-0.6f32, 1.2], [-0.2, 1.3], [0.2, 1.3], [0.6, 1.2]]
        .iter()
        .map(|&[x, z]| {
            harness
                .state()
                .screen_position(glam::Vec3::new(x, 0.0, z))
                .expect("the floor in front of the figure is in view")
        })
        .collect()
}

/// How many points the open document's Keep areas hold now.
#[allow(dead_code)]
pub fn kept_point_count(harness: &mut Harness<'static, EditorApp>) -> usize {
    let scene = harness.state().document().expect("open").scene.clone();
    harness
        .state_mut()
        .painting_mut()
        .expect("painting")
        .kept_points(&scene)
        .len()
}

/// Presses the left button at `path[0]`, moves along the polyline in `steps` moves per
/// segment (a frame each) and releases at its end: a stroke as a hand paints it.
pub fn drag_through(harness: &mut Harness<'static, EditorApp>, path: &[egui::Pos2], steps: usize) {
    harness.hover_at(path[0]);
    harness.run();
    harness.drag_at(path[0]);
    harness.run();
    for pair in path.windows(2) {
        for k in 1..=steps {
            harness.hover_at(pair[0] + (pair[1] - pair[0]) * (k as f32 / steps as f32));
            harness.run();
        }
    }
    harness.drop_at(path[path.len() - 1]);
    harness.run();
}

/// The editor on a fresh copy of one of the bundled samples (None when the run wants no
/// GPU: see `common::gpu`), with the copy's directory and project file.
pub fn editor_on_written_sample(
    sample: lightpaint::samples::Sample,
) -> Option<(tempfile::TempDir, std::path::PathBuf, Harness<'static, EditorApp>)> {
    if super::no_gpu_wanted() {
        eprintln!("UI test not run: {}=1", super::NO_GPU_ENV);
        return None;
    }
    let dir = tempfile::tempdir().unwrap();
    let project = sample.write(dir.path()).unwrap();
    let harness = editor_on(project.clone());
    Some((dir, project, harness))
}

/// The editor on a fresh copy of the sample project.
pub fn editor_on_sample_copy() -> Option<(tempfile::TempDir, std::path::PathBuf, Harness<'static, EditorApp>)> {
    editor_on_written_sample(lightpaint::samples::Sample::Sample)
}

/// Mean Rec. 709 luma (0–255) of `image`'s pixels within `radius` points of `centre`.
pub fn mean_luma_near(image: &image::RgbaImage, centre: egui::Pos2, radius: f32, pixels_per_point: f32) -> f64 {
    let (cx, cy, r) = (
        centre.x * pixels_per_point,
        centre.y * pixels_per_point,
        radius * pixels_per_point,
    );
    let (mut sum, mut count) = (0.0, 0usize);
    for (x, y, p) in image.enumerate_pixels() {
        if (x as f32 - cx).hypot(y as f32 - cy) <= r {
            sum += 0.2126 * p[0] as f64 + 0.7152 * p[1] as f64 + 0.0722 * p[2] as f64;
            count += 1;
        }
    }
    sum / count.max(1) as f64
}

/// How many pixels of `a` and `b` differ inside `viewport` (points).
pub fn viewport_pixels_differing(
    a: &image::RgbaImage,
    b: &image::RgbaImage,
    viewport: egui::Rect,
    pixels_per_point: f32,
) -> usize {
    a.enumerate_pixels()
        .filter(|(x, y, _)| viewport.contains(egui::pos2(*x as f32 / pixels_per_point, *y as f32 / pixels_per_point)))
        .filter(|(x, y, p)| b.get_pixel(*x, *y) != *p)
        .count()
}

/// Scrolls the widget labelled `label` into view (the inspector is taller than the
/// window), then clicks it.
pub fn scroll_and_click(harness: &mut Harness<'static, EditorApp>, label: &str) {
    use egui_kittest::kittest::Queryable;
    harness.get_by_label(label).scroll_to_me();
    harness.run();
    harness.get_by_label(label).click();
    harness.run();
}
