//! The editor's undo history: strokes and light edits in the order they were made, so
//! Ctrl+Z takes back whichever came last. Strokes keep their intensities in the
//! `Painter` (this only remembers that one happened); a light edit — an inspector drag,
//! a gizmo move, a typed name — is one entry from the lights before it began to the
//! lights once it settled (the pointer let go and no field focused).

use crate::scene::Light;

#[derive(Debug, Clone, PartialEq)]
enum Entry {
    Stroke,
    Lights { before: Vec<Light>, after: Vec<Light> },
}

/// What undoing or redoing an entry asks of the editor.
#[derive(Debug, Clone, PartialEq)]
pub enum Step {
    /// Undo (or redo) the Painter's last stroke.
    Stroke,
    /// Put these lights in place.
    SetLights(Vec<Light>),
}

#[derive(Debug, Clone, Default)]
pub struct History {
    done: Vec<Entry>,
    undone: Vec<Entry>,
    /// The lights as the last entry (or the document's opening) left them.
    settled: Vec<Light>,
}

impl History {
    /// A fresh history for a document whose lights are `lights`.
    pub fn new(lights: &[Light]) -> History {
        History {
            settled: lights.to_vec(),
            ..History::default()
        }
    }

    pub fn can_undo(&self) -> bool {
        !self.done.is_empty()
    }

    pub fn can_redo(&self) -> bool {
        !self.undone.is_empty()
    }

    /// Records a stroke that left the lights as `lights`.
    pub fn stroke_done(&mut self, lights: &[Light]) {
        self.done.push(Entry::Stroke);
        self.undone.clear();
        self.settled = lights.to_vec();
    }

    /// Records the lights as one edit if they differ from the settled ones; true if so.
    pub fn settle(&mut self, lights: &[Light]) -> bool {
        if lights == self.settled.as_slice() {
            return false;
        }
        let before = std::mem::replace(&mut self.settled, lights.to_vec());
        self.done.push(Entry::Lights {
            before,
            after: lights.to_vec(),
        });
        self.undone.clear();
        true
    }

    /// Takes back the last entry; the caller carries out the step, then tells the
    /// history where the lights ended up ([`History::resettle`]).
    pub fn undo(&mut self) -> Option<Step> {
        let entry = self.done.pop()?;
        let step = match &entry {
            Entry::Stroke => Step::Stroke,
            Entry::Lights { before, .. } => Step::SetLights(before.clone()),
        };
        self.undone.push(entry);
        Some(step)
    }

    pub fn redo(&mut self) -> Option<Step> {
        let entry = self.undone.pop()?;
        let step = match &entry {
            Entry::Stroke => Step::Stroke,
            Entry::Lights { after, .. } => Step::SetLights(after.clone()),
        };
        self.done.push(entry);
        Some(step)
    }

    /// The lights after an undo or redo was carried out.
    pub fn resettle(&mut self, lights: &[Light]) {
        self.settled = lights.to_vec();
    }
}

#[cfg(test)]
mod tests {
    use glam::Vec3;

    use super::*;
    use crate::scene::LightKind;

    fn lights(intensity: f32, x: f32) -> Vec<Light> {
        vec![Light {
            name: "key".into(),
            kind: LightKind::Point,
            color: Vec3::ONE,
            intensity,
            position: Vec3::new(x, 2.0, 0.0),
            direction: Vec3::NEG_Y,
            range: None,
            locked: false,
        }]
    }

    #[test]
    fn strokes_and_light_edits_undo_last_first_and_redo_in_order() {
        let mut history = History::new(&lights(10.0, 0.0));
        assert!(!history.settle(&lights(10.0, 0.0)), "nothing changed");
        history.stroke_done(&lights(20.0, 0.0));
        assert!(history.settle(&lights(20.0, 1.5)), "the light moved");
        assert_eq!(history.undo(), Some(Step::SetLights(lights(20.0, 0.0))));
        history.resettle(&lights(20.0, 0.0));
        assert_eq!(history.undo(), Some(Step::Stroke));
        history.resettle(&lights(10.0, 0.0));
        assert_eq!(history.undo(), None);
        assert_eq!(history.redo(), Some(Step::Stroke));
        history.resettle(&lights(20.0, 0.0));
        assert_eq!(history.redo(), Some(Step::SetLights(lights(20.0, 1.5))));
        assert!(!history.can_redo());
    }

    #[test]
    fn a_new_edit_drops_what_was_undone() {
        let mut history = History::new(&lights(10.0, 0.0));
        history.settle(&lights(12.0, 0.0));
        history.undo();
        history.resettle(&lights(10.0, 0.0));
        assert!(history.can_redo());
        history.settle(&lights(10.0, 3.0));
        assert!(!history.can_redo());
        assert_eq!(history.undo(), Some(Step::SetLights(lights(10.0, 0.0))));
    }
}
