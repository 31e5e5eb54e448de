//! The painting tool, strokes, and undo and redo through the editor's one history of
//! strokes and light edits.

use super::*;

impl EditorApp {
    /// The current tool (what a left drag in the viewport does).
    pub fn tool(&self) -> Tool {
        self.painting.as_ref().map_or(Tool::Navigate, |p| p.tool)
    }

    pub fn set_tool(&mut self, tool: Tool) {
        if let Some(painting) = &mut self.painting {
            painting.tool = tool;
        }
    }

    /// The painting state (brush, strategies, stroke history), if a document is open.
    pub fn painting_mut(&mut self) -> Option<&mut Painting> {
        self.painting.as_mut()
    }

    /// Applies a stroke painted in the viewport with the current tool and brush.
    pub fn paint_stroke(&mut self, stroke: &FinishedStroke) {
        let (Some(document), Some(painting), Some(viewport)) = (&mut self.document, &mut self.painting, &self.viewport)
        else {
            return;
        };
        let spheres = self.blockers.shown_spheres(&document.hidden_objects);
        let camera = viewport.orbit.camera();
        let shadows = document.settings.shadows;
        let hidden = &document.hidden_objects;
        // A light edit still settling belongs before the stroke in the history.
        self.history.settle(&document.scene.lights);
        let strokes_before = painting.stroke_count();
        if let Some(report) = painting.paint(&mut document.scene, camera, stroke, &spheres, &shadows, hidden) {
            if painting.stroke_count() > strokes_before {
                self.history.stroke_done(&document.scene.lights);
            } else {
                self.history.resettle(&document.scene.lights);
            }
            self.message = report.message;
            self.lights_changed();
        }
    }

    /// Undoes the last stroke or light edit (Ctrl+Z).
    pub fn undo(&mut self) {
        if let Some(document) = &self.document {
            self.history.settle(&document.scene.lights);
        }
        let step = self.history.undo();
        let message = self.carry_out(step, Direction::Undo);
        self.say_again(message);
    }

    /// Redoes the last undone stroke or light edit (Ctrl+Shift+Z or Ctrl+Y).
    pub fn redo(&mut self) {
        let step = self.history.redo();
        let message = self.carry_out(step, Direction::Redo);
        self.say_again(message);
    }

    /// Shows `message` as news even when it reads as the last one did ("nothing to undo"
    /// twice): the status bar times it afresh.
    pub(super) fn say_again(&mut self, message: String) {
        self.message = message;
        self.message_seen.text.clear();
    }

    /// Whether Edit ▸ Undo and Redo have anything to do.
    pub fn can_undo(&self) -> bool {
        self.history.can_undo()
    }

    pub fn can_redo(&self) -> bool {
        self.history.can_redo()
    }

    /// Carries out an undo or redo step; the message to show.
    pub(super) fn carry_out(&mut self, step: Option<Step>, direction: Direction) -> String {
        let (verb, nothing) = match direction {
            Direction::Undo => ("undid", "nothing to undo"),
            Direction::Redo => ("redid", "nothing to redo"),
        };
        let (Some(document), Some(painting), Some(step)) = (&mut self.document, &mut self.painting, step) else {
            return nothing.to_string();
        };
        let message = match step {
            Step::Stroke => {
                let done = match direction {
                    Direction::Undo => painting.undo(&mut document.scene),
                    Direction::Redo => painting.redo(&mut document.scene),
                };
                if done {
                    format!("{verb} the stroke")
                } else {
                    nothing.to_string()
                }
            }
            Step::SetLights(lights) => {
                let moved = lights.iter().zip(&document.scene.lights).any(|(a, b)| {
                    crate::project::bake_cache::light_hash(a) != crate::project::bake_cache::light_hash(b)
                });
                document.scene.lights = lights;
                self.lights_moved |= moved;
                format!("{verb} the light edit")
            }
        };
        self.history.resettle(&document.scene.lights);
        self.indirect_stale = true;
        self.lights_changed();
        message
    }

    /// Takes up the saved strokes' Keep areas once the picking BVH is ready (see
    /// `Painting::take_up_saved_strokes`), saying so in the status bar.
    pub(super) fn take_up_saved_strokes(&mut self) {
        let (Some(document), Some(painting)) = (&self.document, &mut self.painting) else {
            return;
        };
        let blockers = &self.blockers;
        let hidden = &document.hidden_objects;
        if let Some(message) = painting.take_up_saved_strokes(
            &document.scene,
            || blockers.shown_spheres(hidden),
            &document.settings.shadows,
        ) {
            self.message = message;
        }
    }
}
