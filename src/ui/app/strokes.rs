//! The painting tool, strokes, and undo and redo through the session's one history of
//! strokes and light edits.

use super::*;
use crate::session::{Changes, Happened, Outcome};

impl EditorApp {
    /// The current tool (what a left drag in the viewport does).
    pub fn tool(&self) -> Tool {
        self.session.as_ref().map_or(Tool::Navigate, |s| s.painting.tool)
    }

    pub fn set_tool(&mut self, tool: Tool) {
        if let Some(session) = &mut self.session {
            session.painting.tool = tool;
        }
    }

    /// The painting state (brush, strategies, stroke history), if a document is open.
    pub fn painting_mut(&mut self) -> Option<&mut Painting> {
        self.session.as_mut().map(|s| &mut s.painting)
    }

    /// The painting state as the project would save it now, if a document is open.
    pub fn painting_state(&self) -> Option<crate::project::PaintingState> {
        self.session.as_ref().map(EditorSession::painting_state)
    }

    /// Applies a stroke painted in the viewport with the current tool and brush.
    pub fn paint_stroke(&mut self, stroke: &ScreenStroke) {
        let (Some(session), Some(viewport)) = (&mut self.session, &self.viewport) else {
            return;
        };
        let spheres = self.blockers.shown_spheres(&session.document.hidden_objects);
        let outcome = session.paint_stroke(viewport.orbit.camera(), stroke, &spheres);
        self.apply(outcome);
    }

    /// Undoes the last stroke or light edit (Ctrl+Z).
    pub fn undo(&mut self) {
        let nothing = Outcome::new(Happened::NothingToUndo, Changes::NONE);
        let outcome = self.session.as_mut().map_or(nothing, EditorSession::undo);
        self.apply(outcome);
    }

    /// Redoes the last undone stroke or light edit (Ctrl+Shift+Z or Ctrl+Y).
    pub fn redo(&mut self) {
        let nothing = Outcome::new(Happened::NothingToRedo, Changes::NONE);
        let outcome = self.session.as_mut().map_or(nothing, EditorSession::redo);
        self.apply(outcome);
    }

    /// Shows `message` as news even when it reads as the last one did ("nothing to undo"
    /// twice): the status bar times it afresh.
    pub(super) fn say_again(&mut self, message: String) {
        self.message = message;
        self.message_seen.text.clear();
    }

    /// Whether Edit ▸ Undo and Redo have anything to do.
    pub fn can_undo(&self) -> bool {
        self.session.as_ref().is_some_and(EditorSession::can_undo)
    }

    pub fn can_redo(&self) -> bool {
        self.session.as_ref().is_some_and(EditorSession::can_redo)
    }

    /// Takes up the saved strokes' Keep areas once the picking BVH is ready, saying so in
    /// the status bar.
    pub(super) fn take_up_saved_strokes(&mut self) {
        let Some(session) = &mut self.session else { return };
        let outcome = session.take_up_saved_strokes(&self.blockers);
        self.apply(outcome);
    }
}
