//! The scene outliner (left panel): the glTF scene picker, the objects and the lights.
//! A click selects (the inspector then edits the selection); each object has a
//! show/hide toggle, each light a solo toggle that shows it alone in the viewport.

use crate::scene::Scene;

/// What is selected in the outliner and the viewport.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Selection {
    Object(usize),
    Light(usize),
}

/// What the user asked for in the outliner this frame.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum OutlinerAction {
    Select(Selection),
    /// Show object `index` if hidden, hide it if shown.
    ToggleHidden(usize),
    /// Show only this light in the viewport (None: all lights again).
    Solo(Option<usize>),
    AddLight,
    ShowGltfScene(usize),
}

/// The view state the outliner shows and changes.
pub struct OutlinerState<'a> {
    pub selection: Option<Selection>,
    pub hidden: &'a [bool],
    pub solo: Option<usize>,
}

/// Draws the outliner's contents; the action the user took, if any.
pub fn outliner(ui: &mut egui::Ui, scene: &Scene, state: &OutlinerState) -> Option<OutlinerAction> {
    let mut action = gltf_scene_picker(ui, scene).map(OutlinerAction::ShowGltfScene);
    egui::ScrollArea::vertical().show(ui, |ui| {
        egui::CollapsingHeader::new(format!("Objects ({})", scene.objects.len()))
            .default_open(true)
            .show(ui, |ui| {
                for (index, object) in scene.objects.iter().enumerate() {
                    let hidden = state.hidden.get(index).copied().unwrap_or(false);
                    ui.horizontal(|ui| {
                        let mut shown = !hidden;
                        let toggle = ui.add(egui::Checkbox::without_text(&mut shown));
                        toggle.widget_info(|| {
                            egui::WidgetInfo::selected(
                                egui::Role::CheckBox,
                                true,
                                shown,
                                format!("show {}", object.name),
                            )
                        });
                        if toggle
                            .on_hover_text(if hidden {
                                "Hidden: tick to show"
                            } else {
                                "Shown: untick to hide it (a hidden object is neither drawn nor casts shadows)"
                            })
                            .changed()
                        {
                            action = Some(OutlinerAction::ToggleHidden(index));
                        }
                        let material = scene.materials.get(object.material);
                        let summary = material.map_or_else(|| "default material".to_string(), |m| m.summary());
                        let selected = state.selection == Some(Selection::Object(index));
                        let text = if hidden {
                            egui::RichText::new(&object.name).weak()
                        } else {
                            egui::RichText::new(&object.name)
                        };
                        if ui
                            .selectable_label(selected, text)
                            .on_hover_text(format!("{} vertices; {summary}", object.positions.len()))
                            .clicked()
                        {
                            action = Some(OutlinerAction::Select(Selection::Object(index)));
                        }
                    });
                }
            });
        egui::CollapsingHeader::new(format!("Lights ({})", scene.lights.len()))
            .default_open(true)
            .show(ui, |ui| {
                for (index, light) in scene.lights.iter().enumerate() {
                    ui.horizontal(|ui| {
                        let soloed = state.solo == Some(index);
                        if ui
                            .selectable_label(soloed, "S")
                            .on_hover_text(if soloed {
                                "Show all lights again"
                            } else {
                                "Solo: show this light alone in the viewport (not saved, painting unaffected)"
                            })
                            .clicked()
                        {
                            action = Some(OutlinerAction::Solo((!soloed).then_some(index)));
                        }
                        let selected = state.selection == Some(Selection::Light(index));
                        let dimmed = state.solo.is_some_and(|s| s != index);
                        // A lock says painting leaves the light as it is.
                        let lock = if light.locked { " (locked)" } else { "" };
                        let label = format!("{} — {}{lock}", light.name, light.kind.label());
                        let text = if dimmed {
                            egui::RichText::new(label).weak()
                        } else {
                            egui::RichText::new(label)
                        };
                        if ui.selectable_label(selected, text).clicked() {
                            action = Some(OutlinerAction::Select(Selection::Light(index)));
                        }
                    });
                }
                if ui
                    .button("Add light")
                    .on_hover_text("A point light above the view's pivot; the inspector changes its kind")
                    .clicked()
                {
                    action = Some(OutlinerAction::AddLight);
                }
            });
    });
    action
}

/// A choice of the glTF file's scenes, when it has several; the index picked, if the user
/// picked another.
fn gltf_scene_picker(ui: &mut egui::Ui, scene: &Scene) -> Option<usize> {
    if scene.gltf_scenes.len() < 2 {
        return None;
    }
    let shown = scene.gltf_scene.unwrap_or(0);
    let mut picked = shown;
    egui::ComboBox::from_label("glTF scene")
        .selected_text(scene.gltf_scene_label(shown))
        .show_ui(ui, |ui| {
            for index in 0..scene.gltf_scenes.len() {
                ui.selectable_value(&mut picked, index, scene.gltf_scene_label(index));
            }
        })
        .response
        .on_hover_text("The file holds several scenes; the project remembers which one it shows");
    (picked != shown).then_some(picked)
}
