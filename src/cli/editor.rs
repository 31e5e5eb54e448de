//! The editor, opened on a file or the bundled sample.

use std::path::{Path, PathBuf};

use lightpaint::project::ProjectError;

use super::CliError;

/// The bundled sample project: in the source tree the binary was built from, or in the
/// current directory.
fn bundled_sample() -> PathBuf {
    let in_checkout = Path::new(env!("CARGO_MANIFEST_DIR")).join(lightpaint::samples::SAMPLE_PROJECT);
    if in_checkout.exists() {
        in_checkout
    } else {
        PathBuf::from(lightpaint::samples::SAMPLE_PROJECT)
    }
}

pub fn editor(file: Option<PathBuf>) -> Result<(), CliError> {
    let file = file.unwrap_or_else(bundled_sample);
    // Fail before opening a window when the file is not there at all.
    if !file.exists() {
        return Err(ProjectError::NotFound { path: file }.into());
    }
    let options = lightpaint::ui::EditorOptions {
        file,
        close_when_file_exists: std::env::var_os("LIGHTPAINT_CLOSE_WHEN_FILE_EXISTS").map(PathBuf::from),
        // Screenshots for the docs leave out the numbers that change from run to run.
        hide_frame_timings: std::env::var_os("LIGHTPAINT_HIDE_FRAME_TIMINGS").is_some_and(|v| v == "1"),
        // scripts/editor-frame-rate.sh: the editor's own frame rate.
        measure_frame_rate: match std::env::var("LIGHTPAINT_MEASURE_FRAME_RATE").as_deref() {
            Ok("1") => lightpaint::ui::FrameRateMeasurement::AfterLightEdit,
            Ok("new-view") => lightpaint::ui::FrameRateMeasurement::NewView,
            Ok("interface") => lightpaint::ui::FrameRateMeasurement::InterfaceOnly,
            _ => lightpaint::ui::FrameRateMeasurement::Off,
        },
    };
    lightpaint::ui::run_editor(options).map_err(|e| CliError::Editor(e.to_string()))
}
