//! Light edits in the editor: the session's commands, and what follows them in the view —
//! the upload, the heat map, re-baking moved lights and the baked indirect light — applied
//! in one place ([`EditorApp::apply`]).

use super::*;
use crate::session::{Changes, Happened, Outcome};

impl EditorApp {
    /// Applies a session command's outcome: the status bar says what happened, and the
    /// viewport and the editor's caches take up what changed.
    pub(in crate::ui) fn apply(&mut self, outcome: Outcome) {
        if let Some(happened) = &outcome.happened {
            match happened {
                Happened::LightAdded { index, .. } => self.selection = Some(Selection::Light(*index)),
                Happened::LightDeleted { .. } => self.selection = None,
                _ => {}
            }
            let undo_or_redo = matches!(
                happened,
                Happened::Undid(_) | Happened::Redid(_) | Happened::NothingToUndo | Happened::NothingToRedo
            );
            if undo_or_redo {
                // "nothing to undo" twice is still news.
                self.say_again(happened.to_string());
            } else {
                self.message = happened.to_string();
            }
        }
        let Changes {
            lights,
            indirect,
            hidden,
        } = outcome.changes;
        if hidden && let (Some(session), Some(viewport)) = (&self.session, &mut self.viewport) {
            let hidden = &session.document.hidden_objects;
            viewport.set_hidden(hidden);
            viewport.set_blockers(&self.blockers.shown_spheres(hidden));
        }
        if lights {
            self.upload_lights();
        }
        if indirect {
            self.indirect_stale = true;
        }
    }

    /// Shows only `light` in the viewport (None: every light).
    pub fn solo(&mut self, light: Option<usize>) {
        if let Some(outcome) = self.session.as_mut().map(|s| s.solo(light)) {
            self.apply(outcome);
        }
    }

    /// Adds a white 20 cd point light 2 m above the view's pivot and selects it (one
    /// undoable edit). Its maps are baked in the background when the others are baked.
    pub fn add_light(&mut self) {
        let pivot = self.viewport.as_ref().map(|v| v.orbit.target);
        let Some(session) = &mut self.session else { return };
        let pivot = pivot.unwrap_or_else(|| session.document.scene.bounds().center());
        let outcome = session.add_light(pivot);
        self.apply(outcome);
    }

    /// Deletes light `index` (one undoable edit).
    pub fn delete_light(&mut self, index: usize) {
        if let Some(outcome) = self.session.as_mut().map(|s| s.delete_light(index)) {
            self.apply(outcome);
        }
    }

    /// Replaces light `index` (a gizmo drag); values with problems are ignored.
    pub fn set_light(&mut self, index: usize, light: Light) {
        if let Some(outcome) = self.session.as_mut().map(|s| s.set_light(index, light)) {
            self.apply(outcome);
        }
    }

    /// After the inspector edited the lights in place: `moved` when one moved or
    /// changed shape.
    pub(in crate::ui) fn lights_edited(&mut self, moved: bool) {
        if let Some(outcome) = self.session.as_mut().map(|s| s.lights_edited(moved)) {
            self.apply(outcome);
        }
    }

    /// Hides object `index` in the viewport if shown, shows it if hidden.
    pub fn toggle_hidden(&mut self, index: usize) {
        if let Some(outcome) = self.session.as_mut().map(|s| s.toggle_hidden(index)) {
            self.apply(outcome);
        }
    }

    /// Keeps the viewport's heat map in step with the selected light (computing it again
    /// only when the light, its intensity or the transfer's source changed).
    pub(super) fn refresh_heat_map(&mut self) {
        let wanted = match (self.preferences.show_heat_map, self.selection, &self.session) {
            (true, Some(Selection::Light(light)), Some(session)) => {
                let document = &session.document;
                document.scene.lights.get(light).map(|l| HeatMapKey {
                    light,
                    placement: crate::project::bake_cache::light_hash(l),
                    intensity: l.intensity,
                    baked: session.painting.has_fresh_maps(&document.scene) && document.settings.baked_indirect,
                    shadows: document.settings.shadows,
                    blockers: self.fitted_with,
                })
            }
            _ => None,
        };
        if wanted.as_ref() == self.heat_map.as_ref().map(|(key, _)| key) {
            return;
        }
        let Some(viewport) = &mut self.viewport else {
            return;
        };
        let (Some(key), Some(session)) = (wanted, &self.session) else {
            viewport.set_heat_map(None);
            self.heat_map = None;
            return;
        };
        let document = &session.document;
        let spheres = self.blockers.shown_spheres(&document.hidden_objects);
        let transfer = session.painting.transfer(&document.scene, &spheres, &document.settings);
        let eye = viewport.orbit.camera().position;
        let values =
            crate::paint::light_reach::light_reach_per_vertex(&document.scene, transfer.as_ref(), key.light, eye);
        let all: Vec<f32> = values.iter().flatten().copied().collect();
        let scale = crate::render::passes::heat_map::heat_scale(&all);
        viewport.set_heat_map(Some((&values, scale)));
        self.heat_map = Some((key, scale));
    }

    /// The value the heat map's brightest colour stands for (cd/m²), while one is shown.
    pub fn heat_map_scale(&self) -> Option<f32> {
        self.heat_map.as_ref().map(|(_, scale)| *scale)
    }

    /// Sends the displayed lights to the viewport.
    pub(super) fn upload_lights(&mut self) {
        if let (Some(session), Some(viewport)) = (&self.session, &mut self.viewport) {
            viewport.set_lights(&session.displayed_lights());
        }
    }

    /// Once a light is let go after a move, re-bakes only its maps (when there are maps).
    pub(super) fn rebake_moved_lights(&mut self, ctx: &egui::Context) {
        let pointer_down = ctx.input(|i| i.pointer.any_down());
        if self
            .session
            .as_mut()
            .is_some_and(|s| s.rebake_moved_lights(pointer_down))
        {
            self.message = "re-baking the moved light's importance maps…".to_string();
        }
    }

    /// Gives the viewport the baked indirect light of the current lights, when the
    /// setting is on and maps baked for this geometry exist (none otherwise).
    pub(super) fn refresh_baked_indirect(&mut self) {
        let (Some(session), Some(viewport)) = (&self.session, &mut self.viewport) else {
            return;
        };
        viewport.set_baked_indirect(session.baked_indirect().as_ref());
        self.indirect_stale = false;
    }

    /// Records a finished light edit (the pointer let go, no field focused) in the history.
    pub(super) fn settle_light_edits(&mut self, ctx: &egui::Context) {
        let busy = ctx.input(|i| i.pointer.any_down()) || ctx.memory(|m| m.focused().is_some());
        if let (false, Some(session)) = (busy, &mut self.session) {
            session.settle_light_edits();
        }
    }
}
