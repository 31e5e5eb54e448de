//! The session's commands: a stroke, undo and redo, light edits (add, delete, replace,
//! an inspector's edit in place), hiding objects, solo, and what runs between frames (the
//! saved strokes taken up, a finished bake, a moved light's re-bake, the baked indirect
//! light). Each says what happened and what changed; none touches a view.

use super::history::{EntryKind, History};
use super::{Changes, EditorSession, Happened, Outcome, ScreenStroke, Tool};
use crate::blockers::{SceneBlockers, Sphere};
use crate::paint::Painter;
use crate::project::bake_cache::light_hash;
use crate::scene::{Camera, Light, LightKind, Scene};
use crate::shading::BakedIndirect;

impl EditorSession {
    /// Paints a stroke taken in a view seen by `camera`, with the painting's tool and
    /// brush, through the blockers `spheres`; nothing when the tool is not a brush.
    pub fn paint_stroke(&mut self, camera: Camera, stroke: &ScreenStroke, spheres: &[Sphere]) -> Outcome {
        if self.painting.tool == Tool::Navigate {
            return Outcome::NOTHING;
        }
        let document = &mut self.document;
        // A light edit still settling belongs before the stroke in the history.
        self.history.settle(&document.scene.lights);
        let strokes_before = self.painting.stroke_count();
        let settings = document.settings;
        let hidden = &document.hidden_objects;
        // The saved strokes are taken up before the first stroke if the frames have not
        // done it yet (the picking BVH is built by then).
        self.painting.picking_bvh(&document.scene);
        let taken_up = self
            .painting
            .take_up_saved_strokes(&document.scene, || spheres.to_vec(), &settings);
        let Some(mut report) = self
            .painting
            .paint(&mut document.scene, camera, stroke, spheres, &settings, hidden)
        else {
            return Outcome::NOTHING;
        };
        if let Some(keeps) = taken_up.filter(|&keeps| keeps > 0) {
            report.message = format!("{} ({})", report.message, Happened::SavedKeepsHold(keeps));
        }
        if self.painting.stroke_count() > strokes_before {
            self.history.stroke_done(&document.scene.lights);
        } else {
            self.history.resettle(&document.scene.lights);
        }
        Outcome::new(Happened::Painted(report), Changes::LIGHTS)
    }

    /// Takes back the last stroke or light edit (Ctrl+Z).
    pub fn undo(&mut self) -> Outcome {
        self.history.settle(&self.document.scene.lights);
        self.step_through_history(History::undo, Happened::Undid, Happened::NothingToUndo)
    }

    /// Carries out again what was undone last (Ctrl+Shift+Z or Ctrl+Y).
    pub fn redo(&mut self) -> Outcome {
        self.step_through_history(History::redo, Happened::Redid, Happened::NothingToRedo)
    }

    /// One step of `step` (undo or redo) on the scene and the strokes: `done` with the
    /// entry's kind where there was one, else `nothing`.
    fn step_through_history(
        &mut self,
        step: fn(&mut History, &mut Painter, &mut Scene) -> Option<EntryKind>,
        done: fn(EntryKind) -> Happened,
        nothing: Happened,
    ) -> Outcome {
        let before = self.document.scene.lights.clone();
        match step(&mut self.history, &mut self.painting.painter, &mut self.document.scene) {
            Some(kind) => {
                self.note_moves(&before);
                Outcome::new(done(kind), Changes::LIGHTS)
            }
            None => Outcome::new(nothing, Changes::NONE),
        }
    }

    /// Remembers that a light's maps need a re-bake when it moved or changed shape since
    /// `before`.
    fn note_moves(&mut self, before: &[Light]) {
        let now = &self.document.scene.lights;
        self.lights_moved |=
            now.len() != before.len() || now.iter().zip(before).any(|(a, b)| light_hash(a) != light_hash(b));
    }

    /// Adds a white 20 cd point light 2 m above `pivot` (one undoable edit).
    pub fn add_light(&mut self, pivot: glam::Vec3) -> Outcome {
        let lights = &mut self.document.scene.lights;
        let taken = |name: &str| lights.iter().any(|l| l.name == name);
        let name = (1..)
            .map(|n| format!("Light {n}"))
            .find(|name| !taken(name))
            .unwrap_or_default();
        lights.push(Light {
            name: name.clone(),
            kind: LightKind::Point,
            color: glam::Vec3::ONE,
            intensity: 20.0,
            position: pivot + 2.0 * glam::Vec3::Y,
            direction: glam::Vec3::NEG_Y,
            range: None,
            locked: false,
        });
        let index = lights.len() - 1;
        self.history.settle(&self.document.scene.lights);
        self.lights_moved = true;
        Outcome::new(Happened::LightAdded { index, name }, Changes::LIGHTS)
    }

    /// Deletes light `index` (one undoable edit).
    pub fn delete_light(&mut self, index: usize) -> Outcome {
        if index >= self.document.scene.lights.len() {
            return Outcome::NOTHING;
        }
        // Whatever was still settling is its own edit, before the deletion.
        self.history.settle(&self.document.scene.lights);
        let light = self.document.scene.lights.remove(index);
        self.history.settle(&self.document.scene.lights);
        self.solo_light = match self.solo_light {
            Some(solo) if solo == index => None,
            Some(solo) if solo > index => Some(solo - 1),
            other => other,
        };
        self.lights_moved = true;
        Outcome::new(Happened::LightDeleted { name: light.name }, Changes::LIGHTS)
    }

    /// Replaces light `index` (a gizmo drag); a light with problems is ignored. Recorded
    /// in the history once the edit settles ([`EditorSession::settle_light_edits`]).
    pub fn set_light(&mut self, index: usize, light: Light) -> Outcome {
        let Some(slot) = self.document.scene.lights.get_mut(index) else {
            return Outcome::NOTHING;
        };
        if !light.problems().is_empty() || *slot == light {
            return Outcome::NOTHING;
        }
        let moved = light_hash(slot) != light_hash(&light);
        *slot = light;
        self.lights_edited(moved)
    }

    /// After the lights were edited in place (the inspector's fields): `moved` when a
    /// light moved or changed shape, so that its maps are re-baked once the edit ends.
    pub fn lights_edited(&mut self, moved: bool) -> Outcome {
        self.lights_moved |= moved;
        Outcome {
            happened: None,
            changes: Changes::LIGHTS,
        }
    }

    /// Records a finished light edit in the history (call once the pointer is let go and
    /// no field is focused).
    pub fn settle_light_edits(&mut self) {
        self.history.settle(&self.document.scene.lights);
    }

    /// Hides object `index` if shown, shows it if hidden.
    pub fn toggle_hidden(&mut self, index: usize) -> Outcome {
        let Some(object) = self.document.scene.objects.get(index) else {
            return Outcome::NOTHING;
        };
        let name = object.name.clone();
        let hidden = &mut self.document.hidden_objects;
        let now_hidden = !hidden.remove(&index);
        if now_hidden {
            hidden.insert(index);
        }
        let happened = if now_hidden {
            Happened::ObjectHidden { name }
        } else {
            Happened::ObjectShown { name }
        };
        Outcome::new(
            happened,
            Changes {
                hidden: true,
                ..Changes::NONE
            },
        )
    }

    /// Shows only `light` (None: every light). A view setting: painting, saving and the
    /// bake see every light.
    pub fn solo(&mut self, light: Option<usize>) -> Outcome {
        let lights = &self.document.scene.lights;
        self.solo_light = light.filter(|&l| l < lights.len());
        let name = self.solo_light.map(|l| lights[l].name.clone());
        Outcome::new(
            Happened::Solo(name),
            Changes {
                lights: true,
                ..Changes::NONE
            },
        )
    }

    /// Takes up the saved strokes' Keep areas and equations once the picking BVH is ready
    /// (`Painting::take_up_saved_strokes`); cheap until then and once done (the editor
    /// calls it every frame). The view's blockers are `blockers` less the hidden
    /// objects', worked out only when the strokes are taken up.
    pub fn take_up_saved_strokes(&mut self, blockers: &SceneBlockers) -> Outcome {
        let document = &self.document;
        let spheres = || blockers.shown_spheres(&document.hidden_objects);
        match self
            .painting
            .take_up_saved_strokes(&document.scene, spheres, &document.settings)
        {
            Some(keeps) if keeps > 0 => Outcome::new(Happened::SavedKeepsHold(keeps), Changes::NONE),
            _ => Outcome::NOTHING,
        }
    }

    /// Once a light was let go after a move (`pointer_down` false), re-bakes only its
    /// maps, in the background, when there are maps; true if it started.
    pub fn rebake_moved_lights(&mut self, pointer_down: bool) -> bool {
        if !self.lights_moved || pointer_down || self.painting.bake.is_some() {
            // After a running bake: its maps are for the lights as they were.
            return false;
        }
        self.lights_moved = false;
        self.painting.rebake_moved_lights(&self.document.scene)
    }

    /// The baked indirect light of the current lights, when the setting is on and maps
    /// baked for this geometry and these lights exist.
    pub fn baked_indirect(&self) -> Option<BakedIndirect> {
        let document = &self.document;
        if !document.settings.baked_indirect {
            return None;
        }
        let maps = self.painting.maps_for(&document.scene)?;
        Some(BakedIndirect::from_maps(&document.scene, maps))
    }
}
