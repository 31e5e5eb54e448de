//! "Unsaved changes" before closing the window or opening another file: Save, Discard or
//! Cancel, so nothing is lost by a stray click.

use std::path::PathBuf;

/// What waits for the answer.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Pending {
    Close,
    /// File ▸ New: closing the document.
    New,
    Open(PathBuf),
    /// Showing another scene of the document's glTF file (its index).
    ShowGltfScene(usize),
}

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Answer {
    Save,
    Discard,
    Cancel,
}

/// Shows the question for `pending`; the answer once a button is clicked.
pub fn ask(ctx: &egui::Context, pending: &Pending) -> Option<Answer> {
    let question = match pending {
        Pending::Close => "Save the changes before closing?".to_string(),
        Pending::New => "Save the changes before starting anew?".to_string(),
        Pending::Open(path) => format!(
            "Save the changes before opening {}?",
            path.file_name()
                .map_or_else(|| path.display().to_string(), |n| n.to_string_lossy().into_owned())
        ),
        Pending::ShowGltfScene(index) => format!(
            "Save the changes before showing glTF scene {index}? (Its lights replace these, and the stroke log starts afresh.)"
        ),
    };
    let mut answer = None;
    egui::Window::new("Unsaved changes")
        .collapsible(false)
        .resizable(false)
        .anchor(egui::Align2::CENTER_CENTER, egui::Vec2::ZERO)
        .show(ctx, |ui| {
            ui.label(question);
            ui.horizontal(|ui| {
                if ui.button("Save").clicked() {
                    answer = Some(Answer::Save);
                }
                if ui.button("Discard").clicked() {
                    answer = Some(Answer::Discard);
                }
                if ui.button("Cancel").clicked() {
                    answer = Some(Answer::Cancel);
                }
            });
        });
    answer
}
