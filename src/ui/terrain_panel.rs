//! The inspector's "Terrain" section: what the terrain is, its editable height scale and
//! colour, adding generated hills or a height map, removing it. Edits come back as a
//! [`TerrainEdit`] for the app to apply (a new terrain is a new mesh: the scene is
//! reinstalled, as when another glTF scene is shown).

use std::path::PathBuf;

use crate::scene::{Scene, TerrainSource, TerrainSpec};

/// A change to the scene's terrain asked for in the panel.
#[derive(Debug, Clone, PartialEq)]
pub enum TerrainEdit {
    /// Replace (or add) the terrain with this spec.
    Set(TerrainSpec),
    /// Ask for a height-map image, then use it with the current placement.
    PickImage,
    Remove,
}

/// Draws the section; `editing` holds the spec being edited, so a dragged height scale or
/// colour is applied once the drag ends (each applied change rebuilds the terrain mesh).
pub fn terrain_section(ui: &mut egui::Ui, scene: &Scene, editing: &mut Option<TerrainSpec>) -> Option<TerrainEdit> {
    let Some(terrain) = &scene.terrain else {
        let mut edit = None;
        ui.horizontal(|ui| {
            if ui
                .button("Add hills")
                .on_hover_text("Generated rolling hills under the scene, sized to its footprint.")
                .clicked()
            {
                edit = Some(TerrainEdit::Set(hills_for(scene)));
            }
            if ui
                .button("Import height map…")
                .on_hover_text("A grayscale PNG or JPEG (8 or 16 bit) or a float .hdr.")
                .clicked()
            {
                edit = Some(TerrainEdit::PickImage);
            }
        });
        return edit;
    };
    let field = &terrain.field;
    let source = match &terrain.spec.source {
        TerrainSource::Image { path } => path
            .file_name()
            .map_or_else(|| path.display().to_string(), |n| n.to_string_lossy().into_owned()),
        TerrainSource::Hills { seed, .. } => format!("hills (seed {seed})"),
    };
    let (low, high) = field.height_range_m();
    let [width, depth] = terrain.spec.size_m;
    ui.label(format!(
        "{source}: {}×{} samples over {width:.0}×{depth:.0} m, heights {low:.2}–{high:.2} m",
        field.columns, field.rows
    ));
    let spec = editing.get_or_insert_with(|| terrain.spec.clone());
    let mut typing = false;
    ui.horizontal(|ui| {
        ui.label("height scale");
        let response = ui.add(
            egui::DragValue::new(&mut spec.height_scale_m)
                .range(-1000.0..=1000.0)
                .speed(0.05)
                .suffix(" m"),
        );
        typing = response.has_focus();
    })
    .response
    .on_hover_text("World height of a full-scale (white) sample.");
    ui.horizontal(|ui| {
        ui.label("colour");
        // The picker round-trips the colour through HSVA, which moves its last bits: only a
        // change by the user is written back (else opening a project would edit it).
        let mut color = spec.color;
        if ui.color_edit_button_rgb(&mut color).changed() {
            spec.color = color;
        }
    });
    // Applied once the drag or the typing ends: each change rebuilds the mesh and marches
    // the terrain's surface cache.
    let settled = !typing && !ui.input(|i| i.pointer.any_down());
    let mut edit = None;
    if settled && *spec != terrain.spec && spec.problems().is_empty() {
        edit = Some(TerrainEdit::Set(spec.clone()));
    }
    if ui.button("Remove terrain").clicked() {
        edit = Some(TerrainEdit::Remove);
    }
    if edit.is_some() {
        *editing = None;
    }
    edit
}

/// Hills under the scene: the footprint of its bounds (at least 10 m, with a margin), top
/// at the lowest point of the scene, relief a tenth of the width.
pub fn hills_for(scene: &Scene) -> TerrainSpec {
    let bounds = scene.bounds();
    let (center, size, floor) = if bounds.is_empty() {
        (glam::Vec3::ZERO, 10.0, 0.0)
    } else {
        let extent = bounds.max - bounds.min;
        (bounds.center(), (1.5 * extent.x.max(extent.z)).max(10.0), bounds.min.y)
    };
    let relief = 0.1 * size;
    TerrainSpec {
        center_m: [center.x, floor - relief, center.z],
        ..TerrainSpec::hills(1, 129, size, relief)
    }
}

/// A spec on the image at `path`, placed like `like` (or under the scene).
pub fn image_terrain(path: PathBuf, like: Option<&TerrainSpec>, scene: &Scene) -> TerrainSpec {
    TerrainSpec {
        source: TerrainSource::Image { path },
        ..like.cloned().unwrap_or_else(|| hills_for(scene))
    }
}
