//! The editor's session without a window or a GPU: the open document, its painting state
//! (one owner: [`Painting`]), the one undo history of strokes and light edits
//! ([`history`]), and the commands that change them (`commands.rs`). Each command returns
//! an [`Outcome`]: what happened, in an enum the status bar words, and which [`Changes`]
//! the editor must apply to the viewport and its caches — in one place
//! (`ui::app::EditorApp::apply`).

pub mod bake_job;
mod commands;
pub mod history;
pub mod painting;

use std::fmt;
use std::path::Path;

pub use history::EntryKind;
pub use painting::{Painting, ScreenStroke, Tool};

use crate::paint::StrokeReport;
use crate::project::{Document, PaintingState, ProjectError, ProjectFile};
use crate::scene::Light;
use history::History;

/// What a command changed that the views of the document must take up.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct Changes {
    /// The lights shown (intensities, placement, the solo): upload them.
    pub lights: bool,
    /// The baked indirect light no longer matches the lights or maps: work it out again.
    pub indirect: bool,
    /// Objects were hidden or shown: the drawn objects and their blockers.
    pub hidden: bool,
}

impl Changes {
    pub const NONE: Changes = Changes {
        lights: false,
        indirect: false,
        hidden: false,
    };
    /// The lights changed, and with them the light they bounce.
    pub const LIGHTS: Changes = Changes {
        lights: true,
        indirect: true,
        hidden: false,
    };
}

/// What a command did, for the status bar.
#[derive(Debug, Clone, PartialEq)]
pub enum Happened {
    /// A stroke was painted (or changed nothing); the painter's report says how.
    Painted(StrokeReport),
    Undid(EntryKind),
    Redid(EntryKind),
    NothingToUndo,
    NothingToRedo,
    LightAdded {
        index: usize,
        name: String,
    },
    LightDeleted {
        name: String,
    },
    ObjectHidden {
        name: String,
    },
    ObjectShown {
        name: String,
    },
    /// Only this light is shown (None: every light).
    Solo(Option<String>),
    /// The strokes of earlier sessions were taken up, with this many Keep areas.
    SavedKeepsHold(usize),
}

impl fmt::Display for Happened {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Happened::Painted(report) => f.write_str(&report.message),
            Happened::Undid(kind) => write!(f, "undid {kind}"),
            Happened::Redid(kind) => write!(f, "redid {kind}"),
            Happened::NothingToUndo => f.write_str("nothing to undo"),
            Happened::NothingToRedo => f.write_str("nothing to redo"),
            Happened::LightAdded { name, .. } => write!(f, "added {name}"),
            Happened::LightDeleted { name } => write!(f, "deleted {name} (Ctrl+Z brings it back)"),
            Happened::ObjectHidden { name } => write!(f, "{name} hidden"),
            Happened::ObjectShown { name } => write!(f, "{name} shown"),
            Happened::Solo(Some(name)) => write!(f, "showing {name} alone"),
            Happened::Solo(None) => f.write_str("showing every light"),
            Happened::SavedKeepsHold(keeps) => write!(f, "{keeps} Keep area(s) of earlier sessions hold"),
        }
    }
}

/// A command's result: what happened (None: nothing worth saying) and what changed.
#[derive(Debug, Clone, PartialEq)]
pub struct Outcome {
    pub happened: Option<Happened>,
    pub changes: Changes,
}

impl Outcome {
    /// Nothing happened.
    pub const NOTHING: Outcome = Outcome {
        happened: None,
        changes: Changes::NONE,
    };

    pub fn new(happened: Happened, changes: Changes) -> Outcome {
        Outcome {
            happened: Some(happened),
            changes,
        }
    }
}

/// An open document and what the editor keeps of it besides the view.
pub struct EditorSession {
    /// The scene, settings and file. Its `painting` field is the file's form of the
    /// painting state only as the document came in ([`EditorSession::new`] hands it to
    /// [`Painting`], which owns it from then on; [`EditorSession::into_document`] and the
    /// project file write the current state back).
    pub document: Document,
    pub painting: Painting,
    history: History,
    /// The light shown alone (a view setting, not saved).
    solo_light: Option<usize>,
    /// A light moved or changed shape: its maps are re-baked once the edit ends.
    lights_moved: bool,
}

impl EditorSession {
    /// A session on `document`, its painting state taken from it; a bake cache beside its
    /// project is loaded in the background.
    pub fn new(document: Document) -> EditorSession {
        let painting = Painting::for_document(&document);
        let mut session = EditorSession {
            history: History::new(&document.scene.lights),
            document,
            painting,
            solo_light: None,
            lights_moved: false,
        };
        let project = session.document.project_path.clone();
        session
            .painting
            .resume_cached_bake(&session.document.scene, project.as_deref());
        session
    }

    /// The document with the painting state as it is now (to install it again, or to
    /// take it elsewhere).
    pub fn into_document(self) -> Document {
        let mut document = self.document;
        document.painting = self.painting.state();
        document
    }

    /// The painting state as the project saves it: every stroke applied, brush, settings.
    pub fn painting_state(&self) -> PaintingState {
        self.painting.state()
    }

    /// The project file for saving at `project_path`.
    pub fn project_file(&self, project_path: &Path) -> ProjectFile {
        self.document.to_project_file_with(project_path, self.painting.state())
    }

    /// Saves atomically to `project_path`, which becomes the document's file.
    pub fn save(&mut self, project_path: &Path) -> Result<(), ProjectError> {
        let file = self.project_file(project_path);
        self.document.save_file(project_path, &file)
    }

    pub fn can_undo(&self) -> bool {
        self.history.can_undo()
    }

    pub fn can_redo(&self) -> bool {
        self.history.can_redo()
    }

    /// The light shown alone, if any.
    pub fn solo_light(&self) -> Option<usize> {
        self.solo_light
    }

    /// The lights as the viewport shows them: all, or only the soloed one.
    pub fn displayed_lights(&self) -> Vec<Light> {
        let mut lights = self.document.scene.lights.clone();
        if let Some(solo) = self.solo_light {
            for (index, light) in lights.iter_mut().enumerate() {
                if index != solo {
                    light.intensity = 0.0;
                }
            }
        }
        lights
    }
}

#[cfg(test)]
mod tests;
