//! The inspector's section for the selected light: name, kind, colour and colour
//! temperature, intensity in its unit, the painting lock, position, aim (azimuth and elevation), spot cone,
//! emitter size and range. Edits are made in place; the result says what changed, so the
//! app re-uploads the lights and, when the light moved or changed shape, re-bakes only
//! that light's importance maps.

use crate::scene::color_temperature::{TEMPERATURE_RANGE_K, color_of_temperature, temperature_of_color};
use crate::scene::{LIGHT_KINDS, Light, LightKind, direction_angles_deg, direction_from_angles_deg};

/// What an edit of the selected light changed.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct LightEdit {
    /// Anything the renderer shows (colour, intensity, placement, shape).
    pub changed: bool,
    /// Where the light is, where it points, its kind, shape or range: what the bake's
    /// maps depend on.
    pub moved: bool,
}

impl std::ops::BitOrAssign for LightEdit {
    fn bitor_assign(&mut self, other: LightEdit) {
        self.changed |= other.changed;
        self.moved |= other.moved;
    }
}

/// What locking a light does, for the lock's hover text here and in the lights' table.
pub const LOCK_HINT: &str = "Locked: strokes leave this light as it is (they change the other lights that reach the painted area, or say that every one is locked)";

/// Draws the editor of `light`. `reference_distance_m` is how far from the light the
/// scene is, for keeping the brightness when the kind changes (lux ↔ candela).
pub fn light_inspector(ui: &mut egui::Ui, light: &mut Light, reference_distance_m: f32) -> LightEdit {
    let before = light.clone();
    egui::Grid::new("selected light").num_columns(2).show(ui, |ui| {
        let label = ui.label("name");
        ui.text_edit_singleline(&mut light.name).labelled_by(label.id);
        ui.end_row();
        let label = ui.label("type");
        kind_picker(ui, light, reference_distance_m, label.id);
        ui.end_row();
        let label = ui.label("intensity");
        let speed = (light.intensity.abs() * 0.01).max(0.001);
        ui.add(
            egui::DragValue::new(&mut light.intensity)
                .range(0.0..=1.0e7)
                .speed(speed)
                .suffix(format!(" {}", light.kind.intensity_unit())),
        )
        .labelled_by(label.id);
        ui.end_row();
        let label = ui.label("colour");
        color_row(ui, light, label.id);
        ui.end_row();
        let label = ui.label("painting");
        ui.checkbox(&mut light.locked, "locked")
            .on_hover_text(LOCK_HINT)
            .labelled_by(label.id);
        ui.end_row();
        if light.kind.has_position() {
            let label = ui.label("position (m)");
            ui.horizontal(|ui| {
                for value in [&mut light.position.x, &mut light.position.y, &mut light.position.z] {
                    ui.add(egui::DragValue::new(value).speed(0.01).max_decimals(3))
                        .labelled_by(label.id);
                }
            });
            ui.end_row();
        }
        if light.kind.has_direction() {
            let label = ui.label("aim");
            aim_row(ui, light, label.id);
            ui.end_row();
        }
        shape_rows(ui, &mut light.kind);
        if light.kind.has_position() {
            let label = ui.label("range");
            range_row(ui, light, label.id);
            ui.end_row();
        }
    });
    if !light.problems().is_empty() {
        // Widgets keep values in range; anything else (a NaN typed in) is undone.
        *light = before.clone();
    }
    let moved = light.kind != before.kind
        || light.position != before.position
        || light.direction != before.direction
        || light.range != before.range;
    LightEdit {
        changed: *light != before,
        moved,
    }
}

fn kind_picker(ui: &mut egui::Ui, light: &mut Light, reference_distance_m: f32, label: egui::Id) {
    let mut picked = light.kind;
    egui::ComboBox::from_id_salt("light kind")
        .selected_text(light.kind.label())
        .show_ui(ui, |ui| {
            for kind in LIGHT_KINDS {
                let selected = kind.same_kind(&light.kind);
                if ui.selectable_label(selected, kind.label()).clicked() && !selected {
                    picked = kind;
                }
            }
        })
        .response
        .labelled_by(label);
    if picked != light.kind {
        *light = light.converted_to(picked, reference_distance_m);
    }
}

/// The colour swatch, and the colour temperature it is nearest (editable: setting a
/// temperature sets the colour; "–" for colours off the black-body locus).
fn color_row(ui: &mut egui::Ui, light: &mut Light, label: egui::Id) {
    ui.horizontal(|ui| {
        let mut color = light.color.to_array();
        if ui.color_edit_button_rgb(&mut color).labelled_by(label).changed() {
            light.color = glam::Vec3::from(color);
        }
        match temperature_of_color(light.color) {
            Some(mut kelvin) => {
                let response = ui
                    .add(
                        egui::DragValue::new(&mut kelvin)
                            .range(TEMPERATURE_RANGE_K)
                            .speed(20.0)
                            .max_decimals(0)
                            .suffix(" K"),
                    )
                    .labelled_by(label)
                    .on_hover_text("Colour temperature: the black body of this colour (lower is warmer)");
                if response.changed() {
                    // The colour keeps its brightness; the intensity carries the light's.
                    light.color = color_of_temperature(kelvin) * light.color.max_element();
                }
            }
            None => {
                if ui
                    .small_button("– K")
                    .on_hover_text("Not a black-body colour; click for 6500 K daylight")
                    .clicked()
                {
                    light.color = color_of_temperature(6500.0);
                }
            }
        }
    });
}

/// Azimuth (about +y, from +z towards +x) and elevation of the direction the light
/// travels, in degrees.
fn aim_row(ui: &mut egui::Ui, light: &mut Light, label: egui::Id) {
    let (mut azimuth, mut elevation) = direction_angles_deg(light.direction);
    let changed = ui
        .horizontal(|ui| {
            let a = ui
                .add(
                    egui::DragValue::new(&mut azimuth)
                        .range(-180.0..=180.0)
                        .speed(0.5)
                        .max_decimals(1)
                        .suffix("°"),
                )
                .labelled_by(label)
                .on_hover_text("Azimuth of the direction the light shines: 0° towards +z, 90° towards +x");
            let e = ui
                .add(
                    egui::DragValue::new(&mut elevation)
                        .range(-90.0..=90.0)
                        .speed(0.5)
                        .max_decimals(1)
                        .suffix("°"),
                )
                .labelled_by(label)
                .on_hover_text("Elevation of the direction the light shines: −90° straight down");
            a.changed() || e.changed()
        })
        .inner;
    if changed {
        light.direction = direction_from_angles_deg(azimuth, elevation);
    }
}

/// The spot cone in degrees, or the emitter's size in metres.
fn shape_rows(ui: &mut egui::Ui, kind: &mut LightKind) {
    match kind {
        LightKind::Spot {
            inner_cone_rad,
            outer_cone_rad,
        } => {
            let label = ui.label("cone").id;
            ui.horizontal(|ui| {
                let mut outer_deg = outer_cone_rad.to_degrees();
                let mut inner_deg = inner_cone_rad.to_degrees();
                ui.add(
                    egui::DragValue::new(&mut inner_deg)
                        .range(0.0..=89.0)
                        .speed(0.25)
                        .max_decimals(1)
                        .prefix("inner ")
                        .suffix("°"),
                )
                .labelled_by(label);
                ui.add(
                    egui::DragValue::new(&mut outer_deg)
                        .range(0.5..=90.0)
                        .speed(0.25)
                        .max_decimals(1)
                        .prefix("outer ")
                        .suffix("°"),
                )
                .labelled_by(label);
                // The falloff needs inner < outer: the edited angle pushes the other.
                let outer = outer_deg.to_radians();
                let inner = inner_deg.to_radians().min(outer * 0.999);
                *outer_cone_rad = outer;
                *inner_cone_rad = inner;
            });
            ui.end_row();
        }
        LightKind::Sphere { radius_m } | LightKind::Disk { radius_m } => {
            let label = ui.label("radius").id;
            size_value(ui, radius_m, label);
            ui.end_row();
        }
        LightKind::Rect {
            width_m,
            height_m,
            turn_rad,
        } => {
            let label = ui.label("size").id;
            ui.horizontal(|ui| {
                size_value(ui, width_m, label);
                ui.label("×");
                size_value(ui, height_m, label);
            });
            ui.end_row();
            let label = ui.label("turn").id;
            let mut turn_deg = turn_rad.to_degrees();
            let response = ui
                .add(
                    egui::DragValue::new(&mut turn_deg)
                        .range(-180.0..=180.0)
                        .speed(0.5)
                        .max_decimals(1)
                        .suffix("°"),
                )
                .labelled_by(label)
                .on_hover_text("Turns the rectangle about its normal (the way it faces stays)");
            if response.changed() {
                *turn_rad = turn_deg.to_radians();
            }
            ui.end_row();
        }
        LightKind::Point | LightKind::Directional => {}
    }
}

fn size_value(ui: &mut egui::Ui, metres: &mut f32, label: egui::Id) {
    let speed = (*metres * 0.01).max(0.0005);
    ui.add(
        egui::DragValue::new(metres)
            .range(0.001..=100.0)
            .speed(speed)
            .max_decimals(3)
            .suffix(" m"),
    )
    .labelled_by(label);
}

/// glTF's range: beyond it the light has no effect (off: unlimited).
fn range_row(ui: &mut egui::Ui, light: &mut Light, label: egui::Id) {
    ui.horizontal(|ui| {
        let mut limited = light.range.is_some();
        if ui
            .checkbox(&mut limited, "")
            .labelled_by(label)
            .on_hover_text("Limit the light's reach (glTF range)")
            .changed()
        {
            light.range = limited.then_some(10.0);
        }
        if let Some(range) = &mut light.range {
            let speed = (*range * 0.01).max(0.001);
            ui.add(
                egui::DragValue::new(range)
                    .range(0.01..=1.0e5)
                    .speed(speed)
                    .max_decimals(2)
                    .suffix(" m"),
            )
            .labelled_by(label);
        } else {
            ui.weak("unlimited");
        }
    });
}
