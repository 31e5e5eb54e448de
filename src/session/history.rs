//! The editor's one undo history: strokes and light edits in the order they were made, so
//! Ctrl+Z takes back whichever came last. An applied stroke lives in the `Painter` (its
//! Keep areas and equations are part of what later strokes honour); this history keeps
//! the order, and holds a stroke once it is undone until it is redone or dropped. A light
//! edit — an inspector drag, a gizmo move, a typed name — is one entry from the lights
//! before it began to the lights once it settled (the pointer let go and no field focused).

use std::fmt;

use crate::paint::{Edit, Painter};
use crate::scene::{Light, Scene};

/// What was done, newest last.
#[derive(Debug, Clone, PartialEq)]
enum Done {
    /// The painter's last applied stroke.
    Stroke,
    Lights {
        before: Vec<Light>,
        after: Vec<Light>,
    },
}

/// What was undone, most recently undone last.
#[derive(Debug, Clone)]
enum Undone {
    Stroke(Box<Edit>),
    Lights { before: Vec<Light>, after: Vec<Light> },
}

/// Which kind of entry an undo or redo carried out.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum EntryKind {
    Stroke,
    LightEdit,
}

impl fmt::Display for EntryKind {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            EntryKind::Stroke => "the stroke",
            EntryKind::LightEdit => "the light edit",
        })
    }
}

#[derive(Debug, Clone, Default)]
pub struct History {
    done: Vec<Done>,
    undone: Vec<Undone>,
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

    /// Records a stroke the painter applied, which left the lights as `lights`.
    pub fn stroke_done(&mut self, lights: &[Light]) {
        self.done.push(Done::Stroke);
        self.undone.clear();
        self.settled = lights.to_vec();
    }

    /// Records the lights as one edit if they differ from the settled ones; true if so.
    pub fn settle(&mut self, lights: &[Light]) -> bool {
        if lights == self.settled.as_slice() {
            return false;
        }
        let before = std::mem::replace(&mut self.settled, lights.to_vec());
        self.done.push(Done::Lights {
            before,
            after: lights.to_vec(),
        });
        self.undone.clear();
        true
    }

    /// The lights as they are now, without an entry (a stroke that changed nothing).
    pub fn resettle(&mut self, lights: &[Light]) {
        self.settled = lights.to_vec();
    }

    /// Takes back the last entry on `scene`'s lights and `painter`; which kind it was, if
    /// any.
    pub fn undo(&mut self, painter: &mut Painter, scene: &mut Scene) -> Option<EntryKind> {
        let entry = self.done.pop()?;
        let (undone, kind) = match entry {
            Done::Stroke => {
                let mut intensities = scene.light_intensities();
                let edit = painter.undo(&mut intensities)?;
                scene.set_light_intensities(&intensities);
                (Undone::Stroke(Box::new(edit)), EntryKind::Stroke)
            }
            Done::Lights { before, after } => {
                scene.lights = before.clone();
                (Undone::Lights { before, after }, EntryKind::LightEdit)
            }
        };
        self.undone.push(undone);
        self.settled = scene.lights.clone();
        Some(kind)
    }

    /// Carries out again the entry undone last; which kind it was, if any.
    pub fn redo(&mut self, painter: &mut Painter, scene: &mut Scene) -> Option<EntryKind> {
        let entry = self.undone.pop()?;
        let (done, kind) = match entry {
            Undone::Stroke(edit) => {
                let mut intensities = scene.light_intensities();
                painter.redo(*edit, &mut intensities);
                scene.set_light_intensities(&intensities);
                (Done::Stroke, EntryKind::Stroke)
            }
            Undone::Lights { before, after } => {
                scene.lights = after.clone();
                (Done::Lights { before, after }, EntryKind::LightEdit)
            }
        };
        self.done.push(done);
        self.settled = scene.lights.clone();
        Some(kind)
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

    fn scene_with(lights: Vec<Light>) -> Scene {
        Scene {
            lights,
            ..Scene::default()
        }
    }

    #[test]
    fn light_edits_undo_last_first_and_redo_in_order() {
        let mut painter = Painter::new();
        let mut now = scene_with(lights(10.0, 0.0));
        let mut history = History::new(&now.lights);
        assert!(!history.settle(&now.lights), "nothing changed");
        now.lights = lights(12.0, 0.0);
        assert!(history.settle(&now.lights));
        now.lights = lights(12.0, 1.5);
        assert!(history.settle(&now.lights), "the light moved");
        assert_eq!(history.undo(&mut painter, &mut now), Some(EntryKind::LightEdit));
        assert_eq!(now.lights, lights(12.0, 0.0));
        assert_eq!(history.undo(&mut painter, &mut now), Some(EntryKind::LightEdit));
        assert_eq!(now.lights, lights(10.0, 0.0));
        assert_eq!(history.undo(&mut painter, &mut now), None);
        assert_eq!(history.redo(&mut painter, &mut now), Some(EntryKind::LightEdit));
        assert_eq!(now.lights, lights(12.0, 0.0));
        assert_eq!(history.redo(&mut painter, &mut now), Some(EntryKind::LightEdit));
        assert_eq!(now.lights, lights(12.0, 1.5));
        assert!(!history.can_redo());
    }

    #[test]
    fn a_new_edit_drops_what_was_undone() {
        let mut painter = Painter::new();
        let mut now = scene_with(lights(10.0, 0.0));
        let mut history = History::new(&now.lights);
        history.settle(&lights(12.0, 0.0));
        now.lights = lights(12.0, 0.0);
        history.undo(&mut painter, &mut now);
        assert!(history.can_redo());
        history.settle(&lights(10.0, 3.0));
        assert!(!history.can_redo());
        now.lights = lights(10.0, 3.0);
        assert_eq!(history.undo(&mut painter, &mut now), Some(EntryKind::LightEdit));
        assert_eq!(now.lights, lights(10.0, 0.0));
    }
}
