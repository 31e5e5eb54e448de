//! Light edits in the editor and what follows them: solo, add, delete, hide, the GPU
//! upload, the heat map, re-baking moved lights and the baked indirect light.

use super::*;

impl EditorApp {
    /// The lights as the viewport shows them: all, or only the soloed one.
    pub(super) fn displayed_lights(&self) -> Vec<Light> {
        let Some(document) = &self.document else {
            return Vec::new();
        };
        let mut lights = document.scene.lights.clone();
        if let Some(solo) = self.solo_light {
            for (index, light) in lights.iter_mut().enumerate() {
                if index != solo {
                    light.intensity = 0.0;
                }
            }
        }
        lights
    }

    /// Shows only `light` in the viewport (None: every light). A view setting: painting,
    /// saving and the bake see every light.
    pub fn solo(&mut self, light: Option<usize>) {
        let count = self.document.as_ref().map_or(0, |d| d.scene.lights.len());
        self.solo_light = light.filter(|&l| l < count);
        self.message = match self
            .solo_light
            .and_then(|l| Some(&self.document.as_ref()?.scene.lights[l]))
        {
            Some(light) => format!("showing {} alone", light.name),
            None => "showing every light".to_string(),
        };
        self.upload_lights();
    }

    /// Adds a white 20 cd point light 2 m above the view's pivot and selects it (one
    /// undoable edit). Its maps are baked in the background when the others are baked.
    pub fn add_light(&mut self) {
        let pivot = self.viewport.as_ref().map(|v| v.orbit.target);
        let Some(document) = &mut self.document else { return };
        let pivot = pivot.unwrap_or_else(|| document.scene.bounds().center());
        let taken = |name: &str| document.scene.lights.iter().any(|l| l.name == name);
        let name = (1..)
            .map(|n| format!("Light {n}"))
            .find(|name| !taken(name))
            .unwrap_or_default();
        document.scene.lights.push(Light {
            name: name.clone(),
            kind: crate::scene::LightKind::Point,
            color: glam::Vec3::ONE,
            intensity: 20.0,
            position: pivot + 2.0 * glam::Vec3::Y,
            direction: glam::Vec3::NEG_Y,
            range: None,
            locked: false,
        });
        self.selection = Some(Selection::Light(document.scene.lights.len() - 1));
        self.history.settle(&document.scene.lights);
        self.message = format!("added {name}");
        self.lights_edited(true);
    }

    /// Deletes light `index` (one undoable edit).
    pub fn delete_light(&mut self, index: usize) {
        let Some(document) = &mut self.document else { return };
        if index >= document.scene.lights.len() {
            return;
        }
        // Whatever was still settling is its own edit, before the deletion.
        self.history.settle(&document.scene.lights);
        let light = document.scene.lights.remove(index);
        self.history.settle(&document.scene.lights);
        self.selection = None;
        self.solo_light = match self.solo_light {
            Some(solo) if solo == index => None,
            Some(solo) if solo > index => Some(solo - 1),
            other => other,
        };
        self.message = format!("deleted {} (Ctrl+Z brings it back)", light.name);
        self.lights_edited(true);
    }

    /// Replaces light `index` (a gizmo drag); values with problems are ignored.
    pub fn set_light(&mut self, index: usize, light: Light) {
        let Some(slot) = self.document.as_mut().and_then(|d| d.scene.lights.get_mut(index)) else {
            return;
        };
        if !light.problems().is_empty() || *slot == light {
            return;
        }
        let moved = crate::project::bake_cache::light_hash(slot) != crate::project::bake_cache::light_hash(&light);
        *slot = light;
        self.lights_edited(moved);
    }

    /// Hides object `index` in the viewport if shown, shows it if hidden.
    pub fn toggle_hidden(&mut self, index: usize) {
        let Some(document) = &mut self.document else { return };
        let Some(object) = document.scene.objects.get(index) else {
            return;
        };
        let now_hidden = !document.hidden_objects.remove(&index);
        if now_hidden {
            document.hidden_objects.insert(index);
        }
        self.message = format!("{} {}", object.name, if now_hidden { "hidden" } else { "shown" });
        if let Some(viewport) = &mut self.viewport {
            viewport.set_hidden(&document.hidden_objects);
            viewport.set_blockers(&self.blockers.shown_spheres(&document.hidden_objects));
        }
    }

    /// Keeps the viewport's heat map in step with the selected light (computing it again
    /// only when the light, its intensity or the transfer's source changed).
    pub(super) fn refresh_heat_map(&mut self) {
        let wanted = match (
            self.preferences.show_heat_map,
            self.selection,
            &self.document,
            &self.painting,
        ) {
            (true, Some(Selection::Light(light)), Some(document), Some(painting)) => {
                document.scene.lights.get(light).map(|l| HeatMapKey {
                    light,
                    placement: crate::project::bake_cache::light_hash(l),
                    intensity: l.intensity,
                    baked: painting.has_fresh_maps(&document.scene),
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
        let (Some(key), Some(document), Some(painting)) = (wanted, &self.document, &self.painting) else {
            viewport.set_heat_map(None);
            self.heat_map = None;
            return;
        };
        let spheres = self.blockers.shown_spheres(&document.hidden_objects);
        let transfer = painting.transfer(&document.scene, &spheres, &document.settings.shadows);
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
        let lights = self.displayed_lights();
        if let Some(viewport) = &mut self.viewport {
            viewport.set_lights(&lights);
        }
    }

    /// After an edit of lights in the inspector: the viewport shows them, the baked
    /// indirect light follows, and `moved` lights get their maps re-baked once the edit ends.
    pub(in crate::ui) fn lights_edited(&mut self, moved: bool) {
        self.upload_lights();
        self.indirect_stale = true;
        self.lights_moved |= moved;
    }

    /// Once a light is let go after a move, re-bakes only its maps (when there are maps).
    pub(super) fn rebake_moved_lights(&mut self, ctx: &egui::Context) {
        if !self.lights_moved || ctx.input(|i| i.pointer.any_down()) {
            return;
        }
        let (Some(document), Some(painting)) = (&self.document, &mut self.painting) else {
            return;
        };
        if painting.bake.is_some() {
            // After the running bake: its maps are for the lights as they were.
            return;
        }
        self.lights_moved = false;
        if painting.rebake_moved_lights(&document.scene) {
            self.message = "re-baking the moved light's importance maps…".to_string();
        }
    }

    /// Gives the viewport the baked indirect light of the current lights, when the
    /// setting is on and maps baked for this geometry exist (none otherwise).
    pub(super) fn refresh_baked_indirect(&mut self) {
        let (Some(document), Some(viewport)) = (&self.document, &mut self.viewport) else {
            return;
        };
        let maps = document
            .settings
            .baked_indirect
            .then(|| self.painting.as_ref()?.maps_for(&document.scene))
            .flatten();
        let indirect = maps.map(|maps| crate::shading::BakedIndirect::from_maps(&document.scene, maps));
        viewport.set_baked_indirect(indirect.as_ref());
        self.indirect_stale = false;
    }

    /// Records a finished light edit (the pointer let go, no field focused) in the history.
    pub(super) fn settle_light_edits(&mut self, ctx: &egui::Context) {
        let busy = ctx.input(|i| i.pointer.any_down()) || ctx.memory(|m| m.focused().is_some());
        if let (false, Some(document)) = (busy, &self.document) {
            self.history.settle(&document.scene.lights);
        }
    }

    pub(super) fn lights_changed(&mut self) {
        if let (Some(document), Some(painting)) = (&mut self.document, &self.painting) {
            document.painting = painting.state();
        }
        self.upload_lights();
        self.refresh_baked_indirect();
    }
}
