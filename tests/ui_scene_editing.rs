//! Editing the scene in the editor under egui_kittest on the real wgpu adapter: selecting
//! lights and objects (outliner and viewport), moving a light with its marker (and
//! re-baking only its maps), hiding objects, soloing a light, exporting the view, File ▸
//! New and the recent files.

mod common;

use common::editor::{drag_through, editor_on, studio_floor_path, viewport_pixels_differing};
use common::snapshot::assert_looks_as_reviewed;
use egui_kittest::Harness;
use egui_kittest::kittest::Queryable;
use lightpaint::project::Document;
use lightpaint::samples::Sample;
use lightpaint::ui::{EditorApp, Selection};

/// The editor on a fresh copy of `sample`, with the pointer parked off the viewport.
fn editor_on_copy(sample: Sample) -> Option<(tempfile::TempDir, std::path::PathBuf, Harness<'static, EditorApp>)> {
    if common::no_gpu_wanted() {
        eprintln!("UI test not run: {}=1", common::NO_GPU_ENV);
        return None;
    }
    let dir = tempfile::tempdir().expect("temp dir");
    let project = sample.write(dir.path()).expect("sample written");
    let mut harness = editor_on(project.clone());
    park_pointer(&mut harness);
    Some((dir, project, harness))
}

/// Moves the pointer to the status bar, where it draws nothing over the viewport.
fn park_pointer(harness: &mut Harness<'static, EditorApp>) {
    harness.hover_at(egui::pos2(5.0, 790.0));
    harness.run();
}

/// A press and release of the left button at `at`, a frame each.
fn click_at(harness: &mut Harness<'static, EditorApp>, at: egui::Pos2) {
    harness.hover_at(at);
    harness.run();
    harness.drag_at(at);
    harness.run();
    harness.drop_at(at);
    harness.run();
}

fn light_index(harness: &Harness<'static, EditorApp>, name: &str) -> usize {
    let document = harness.state().document().expect("open");
    document
        .scene
        .lights
        .iter()
        .position(|l| l.name == name)
        .expect("the light exists")
}

/// Clicking a light in the outliner selects it and the inspector shows its editor;
/// clicking an object in the viewport selects that object.
#[test]
fn lights_and_objects_are_selected_in_the_outliner_and_the_viewport() {
    let Some((_dir, project, mut harness)) = editor_on_copy(Sample::Studio) else {
        return;
    };
    let spheres = lightpaint::project::sphere_cache::cache_path(&project);
    assert!(spheres.exists(), "opening the project cached its sphere fit");
    harness.get_by_label("Key — spot").click();
    harness.run();
    let key = light_index(&harness, "Key");
    assert_eq!(harness.state().selection(), Some(Selection::Light(key)));
    harness.get_by_label("Light: Key");
    // The Shadows section says what the maps take: the studio's five spots and sun at
    // 2048², its three point lights' 18 faces at 1024² (shading::shadow_atlas).
    harness.get_by_label("shadow maps: 6 view(s) at 2048², 18 cube faces at 1024², 176 MiB");
    for row in ["position (m)", "aim", "cone", "colour"] {
        assert!(
            harness.query_all_by_label(row).count() >= 1,
            "the spot's editor has {row}"
        );
    }

    let document = harness.state().document().expect("open");
    let figure = document
        .scene
        .objects
        .iter()
        .position(|o| o.name == "Figure")
        .expect("the studio has a figure");
    let chest = document.scene.objects[figure].bounds().center();
    let at = harness.state().screen_position(chest).expect("the figure is in view");
    click_at(&mut harness, at);
    assert_eq!(harness.state().selection(), Some(Selection::Object(figure)));
    harness.get_by_label("Object: Figure");

    // F frames the selection: the figure's centre comes to the middle of the view.
    park_pointer(&mut harness);
    harness.key_press(egui::Key::F);
    harness.run();
    let centred = harness.state().screen_position(chest).expect("in view");
    let middle = harness.state().viewport_rect().center();
    assert!(centred.distance(middle) < 2.0, "{centred:?} vs {middle:?}");

    // The selected object's bounding box is drawn over the render: its edges' midpoints
    // are lighter than with a light selected instead.
    let selected = harness.render().expect("render");
    let bounds = harness.state().document().expect("open").scene.objects[figure].bounds();
    let corners = bounds.corners();
    let corner = |k: usize| corners[k];
    let midpoints: Vec<egui::Pos2> = (0..8)
        .flat_map(|k| {
            [1, 2, 4]
                .into_iter()
                .filter(move |b| k & b == 0)
                .map(move |b| (k, k | b))
        })
        .filter_map(|(a, b)| harness.state().screen_position(0.5 * (corner(a) + corner(b))))
        .collect();
    harness.get_by_label("Key — spot").click();
    harness.run();
    let other = harness.render().expect("render");
    let brightest = |image: &image::RgbaImage, at: egui::Pos2| {
        let (x, y) = (at.x.round() as i64, at.y.round() as i64);
        (-1..=1)
            .flat_map(|dy| (-1..=1).map(move |dx| (x + dx, y + dy)))
            .filter(|&(x, y)| x >= 0 && y >= 0 && (x as u32) < image.width() && (y as u32) < image.height())
            .map(|(x, y)| {
                let p = image.get_pixel(x as u32, y as u32);
                p[0] as i32 + p[1] as i32 + p[2] as i32
            })
            .max()
            .unwrap_or(0)
    };
    let lighter = midpoints
        .iter()
        .filter(|&&at| brightest(&selected, at) > brightest(&other, at) + 30)
        .count();
    assert!(
        midpoints.len() >= 8 && lighter * 4 >= midpoints.len() * 3,
        "{lighter} of {} box edges drawn",
        midpoints.len()
    );
}

/// Dragging a light's marker moves the light in the view plane: it lands under the
/// pointer, the render changes, and the project is changed.
#[test]
fn dragging_a_light_marker_moves_the_light() {
    let Some((_dir, _project, mut harness)) = editor_on_copy(Sample::Studio) else {
        return;
    };
    let before = harness.render().expect("render");
    let lights = harness.state().document().expect("open").scene.lights.clone();
    let viewport = harness.state().viewport_rect().shrink(120.0);
    let (index, light, from) = lights
        .iter()
        .enumerate()
        .filter(|(_, l)| l.kind.has_position())
        .find_map(|(i, l)| {
            let at = harness.state().screen_position(l.position)?;
            viewport.contains(at).then(|| (i, l.clone(), at))
        })
        .expect("a light well inside the view");
    let to = from + egui::vec2(-90.0, 40.0);
    drag_through(&mut harness, &[from, to], 6);
    park_pointer(&mut harness);
    let moved = harness.state().document().expect("open").scene.lights[index].clone();
    assert_ne!(moved.position, light.position, "the light moved");
    assert_eq!(moved.direction, light.direction, "a move keeps the aim");
    let landed = harness.state().screen_position(moved.position).expect("in view");
    assert!(
        landed.distance(to) < 1.5,
        "the light is under the pointer: {landed:?} vs {to:?}"
    );
    assert_eq!(harness.state().selection(), Some(Selection::Light(index)));
    assert!(harness.state().has_unsaved_changes());
    let after = harness.render().expect("render");
    let ppp = harness.ctx.pixels_per_point();
    let differing = viewport_pixels_differing(&before, &after, harness.state().viewport_rect(), ppp);
    assert!(
        differing > 1000,
        "the lighting follows the light ({differing} pixels changed)"
    );

    harness.key_press_modifiers(egui::Modifiers::COMMAND, egui::Key::Z);
    harness.run();
    let undone = harness.state().document().expect("open").scene.lights[index].clone();
    assert_eq!(undone, light, "Ctrl+Z puts the light back exactly");
}

/// With importance maps baked, moving a light re-bakes only that light's maps in the
/// background; strokes use the direct estimate meanwhile and the baked maps after.
#[test]
fn a_moved_light_gets_only_its_maps_re_baked() {
    let Some((_dir, _project, mut harness)) = editor_on_copy(Sample::Sample) else {
        return;
    };
    harness.get_by_label("Bake importance maps").scroll_to_me();
    harness.run();
    harness.get_by_label("Bake importance maps").click();
    harness.run();
    wait_for_label(&mut harness, "Transfer: baked maps");

    let mut light = harness.state().document().expect("open").scene.lights[1].clone();
    light.position.x += 0.5;
    harness.state_mut().set_light(1, light);
    harness.run();
    wait_for_label(&mut harness, "re-baked 1 moved light(s)");
    harness.get_by_label_contains("Transfer: baked maps");
}

fn wait_for_label(harness: &mut Harness<'static, EditorApp>, text: &str) {
    let started = std::time::Instant::now();
    while harness.query_by_label_contains(text).is_none() {
        assert!(
            started.elapsed() < std::time::Duration::from_secs(300),
            "waited 5 minutes for \"{text}\""
        );
        std::thread::sleep(std::time::Duration::from_millis(100));
        harness.run();
    }
}

/// A hidden object is not drawn (the backdrop's pixels change) and stays hidden when the
/// project is saved and reopened; showing it again restores the image exactly.
#[test]
fn hidden_objects_are_not_drawn_and_stay_hidden_after_reopening() {
    let Some((_dir, project, mut harness)) = editor_on_copy(Sample::Studio) else {
        return;
    };
    let before = harness.render().expect("render");
    let backdrop = harness
        .state()
        .document()
        .expect("open")
        .scene
        .objects
        .iter()
        .position(|o| o.name == "Backdrop")
        .expect("the studio has a backdrop");
    harness.get_by_label("show Backdrop").click();
    harness.run();
    park_pointer(&mut harness);
    assert!(
        harness
            .state()
            .document()
            .expect("open")
            .hidden_objects
            .contains(&backdrop)
    );
    let hidden = harness.render().expect("render");
    let ppp = harness.ctx.pixels_per_point();
    let viewport = harness.state().viewport_rect();
    assert!(
        viewport_pixels_differing(&before, &hidden, viewport, ppp) > 10_000,
        "the backdrop is gone"
    );
    assert!(harness.state().has_unsaved_changes());
    harness.key_press_modifiers(egui::Modifiers::COMMAND, egui::Key::S);
    harness.run();
    let reopened = Document::open(&project).expect("reopens");
    assert!(reopened.hidden_objects.contains(&backdrop));

    harness.state_mut().toggle_hidden(backdrop);
    harness.run();
    let shown = harness.render().expect("render");
    assert_eq!(
        viewport_pixels_differing(&before, &shown, viewport, ppp),
        0,
        "shown again exactly"
    );
}

/// Solo shows one light alone (the image changes, intensities and the project do not);
/// un-soloing restores the image exactly.
#[test]
fn a_soloed_light_is_shown_alone_without_changing_the_project() {
    let Some((_dir, _project, mut harness)) = editor_on_copy(Sample::Studio) else {
        return;
    };
    let before = harness.render().expect("render");
    let intensities = harness.state().light_intensities();
    harness
        .get_all_by_label("S")
        .next()
        .expect("a solo toggle per light")
        .click();
    harness.run();
    park_pointer(&mut harness);
    let soloed = harness.render().expect("render");
    let ppp = harness.ctx.pixels_per_point();
    let viewport = harness.state().viewport_rect();
    assert!(viewport_pixels_differing(&before, &soloed, viewport, ppp) > 10_000);
    assert_eq!(harness.state().light_intensities(), intensities);
    assert!(!harness.state().has_unsaved_changes(), "solo is a view setting");
    harness.get_all_by_label("S").next().expect("toggle").click();
    harness.run();
    park_pointer(&mut harness);
    let back = harness.render().expect("render");
    assert_eq!(viewport_pixels_differing(&before, &back, viewport, ppp), 0);
}

/// Export writes the viewport's image as a PNG of the viewport's size.
#[test]
fn the_view_is_exported_as_png() {
    let Some((dir, _project, mut harness)) = editor_on_copy(Sample::Sample) else {
        return;
    };
    let path = dir.path().join("export.png");
    harness.state_mut().export_png(&path);
    harness.run();
    let image = image::open(&path).expect("a PNG was written").to_rgb8();
    let viewport = harness.state().viewport_rect();
    let ppp = harness.ctx.pixels_per_point();
    assert_eq!(image.width(), (viewport.width() * ppp).round() as u32);
    assert_eq!(image.height(), (viewport.height() * ppp).round() as u32);
    let lit = image.pixels().filter(|p| p.0.iter().any(|&c| c > 40)).count();
    assert!(lit > image.pixels().len() / 4, "the export shows the lit scene");
}

/// File ▸ New closes the document (after asking about unsaved changes); the start page
/// lists the recent files, and clicking one opens it again.
#[test]
fn new_closes_the_document_and_the_start_page_reopens_a_recent_file() {
    let Some((_dir, _project, mut harness)) = editor_on_copy(Sample::Sample) else {
        return;
    };
    harness.get_by_label("show Floor").click();
    harness.run();
    assert!(harness.state().has_unsaved_changes(), "hiding the floor is a change");
    harness.key_press_modifiers(egui::Modifiers::COMMAND, egui::Key::N);
    harness.run();
    harness.get_by_label_contains("before starting anew");
    harness.get_by_label("Discard").click();
    harness.run();
    assert!(harness.state().document().is_none());
    harness.get_by_label("Nothing open");
    harness.get_by_label("sample.lightpaint").click();
    harness.run();
    assert!(harness.state().document().is_some(), "the recent file reopened");
    harness.get_by_label("Lights (4)");
}

/// The heat map colours the scene by how much of the selected light reaches each vertex:
/// the image changes, the scale is positive, and turning it off restores the image.
#[test]
fn the_heat_map_shows_where_the_selected_light_reaches() {
    let Some((_dir, _project, mut harness)) = editor_on_copy(Sample::Studio) else {
        return;
    };
    let before = harness.render().expect("render");
    harness.get_by_label("Key — spot").click();
    harness.run();
    harness.get_by_label("heat map of where it reaches").click();
    harness.run();
    park_pointer(&mut harness);
    let scale = harness.state().heat_map_scale().expect("a heat map is shown");
    assert!(
        scale.is_finite() && scale > 1e-3,
        "the key light reaches the scene: {scale}"
    );
    let heat = harness.render().expect("render");
    let ppp = harness.ctx.pixels_per_point();
    let viewport = harness.state().viewport_rect();
    assert!(viewport_pixels_differing(&before, &heat, viewport, ppp) > 10_000);
    harness.get_by_label("heat map of where it reaches").click();
    harness.run();
    park_pointer(&mut harness);
    assert!(harness.state().heat_map_scale().is_none());
    let back = harness.render().expect("render");
    // The key light stays selected, so its gizmo is drawn over the viewport now.
    harness.state_mut().select(None);
    harness.run();
    park_pointer(&mut harness);
    let back_unselected = harness.render().expect("render");
    assert!(viewport_pixels_differing(&heat, &back, viewport, ppp) > 10_000);
    assert_eq!(viewport_pixels_differing(&before, &back_unselected, viewport, ppp), 0);
}

/// Dragging the selected light's intensity in the inspector changes the render; Ctrl+Z
/// takes the edit back exactly (intensity and image), Ctrl+Shift+Z brings it again.
#[test]
fn an_intensity_dragged_in_the_inspector_changes_the_render_and_undoes() {
    let Some((_dir, _project, mut harness)) = editor_on_copy(Sample::Studio) else {
        return;
    };
    harness.get_by_label("Key — spot").click();
    harness.run();
    harness.state_mut().select(None);
    harness.run();
    park_pointer(&mut harness);
    let before = harness.render().expect("render");
    harness.get_by_label("Key — spot").click();
    harness.run();
    let key = light_index(&harness, "Key");
    let intensity = harness.state().light_intensities()[key];
    let field = harness
        .get_by_role_and_label(egui::accesskit::Role::SpinButton, "intensity")
        .rect()
        .center();
    drag_through(&mut harness, &[field, field + egui::vec2(60.0, 0.0)], 4);
    park_pointer(&mut harness);
    let raised = harness.state().light_intensities()[key];
    assert!(raised > intensity, "{intensity} → {raised} cd");
    harness.state_mut().select(None);
    harness.run();
    park_pointer(&mut harness);
    let brighter = harness.render().expect("render");
    let ppp = harness.ctx.pixels_per_point();
    let viewport = harness.state().viewport_rect();
    assert!(viewport_pixels_differing(&before, &brighter, viewport, ppp) > 1000);

    harness.key_press_modifiers(egui::Modifiers::COMMAND, egui::Key::Z);
    harness.run();
    park_pointer(&mut harness);
    assert_eq!(
        harness.state().light_intensities()[key],
        intensity,
        "undo restores it exactly"
    );
    let undone = harness.render().expect("render");
    assert_eq!(viewport_pixels_differing(&before, &undone, viewport, ppp), 0);
    harness.key_press_modifiers(egui::Modifiers::COMMAND | egui::Modifiers::SHIFT, egui::Key::Z);
    harness.run();
    assert_eq!(harness.state().light_intensities()[key], raised, "redo brings it back");
}

/// An object renamed in the inspector keeps its name in the saved project.
#[test]
fn a_renamed_object_keeps_its_name_after_reopening() {
    let Some((_dir, project, mut harness)) = editor_on_copy(Sample::Studio) else {
        return;
    };
    harness.get_by_label("Figure").click();
    harness.run();
    harness.get_by_label("Object: Figure");
    let field = harness.get_by_role_and_label(egui::accesskit::Role::TextInput, "name");
    field.focus();
    harness.run();
    harness
        .get_by_role_and_label(egui::accesskit::Role::TextInput, "name")
        .type_text(" (hero)");
    harness.run();
    harness.key_press(egui::Key::Enter);
    harness.run();
    let document = harness.state().document().expect("open");
    let figure = document
        .scene
        .objects
        .iter()
        .position(|o| o.name.contains("(hero)"))
        .expect("the figure was renamed");
    let name = document.scene.objects[figure].name.clone();
    harness.key_press_modifiers(egui::Modifiers::COMMAND, egui::Key::S);
    harness.run();
    let reopened = Document::open(&project).expect("reopens");
    assert_eq!(reopened.scene.objects[figure].name, name);
}

/// The main editing states look as reviewed: a light selected with its gizmo and
/// inspector, and its heat map.
#[test]
fn selected_light_and_heat_map_look_as_reviewed() {
    let Some((_dir, _project, mut harness)) = editor_on_copy(Sample::Studio) else {
        return;
    };
    harness.get_by_label("Rim left — spot").click();
    harness.run();
    park_pointer(&mut harness);
    let image = harness.render().expect("the editor renders");
    assert_looks_as_reviewed(&image, "editor_light_selected");
    harness.get_by_label("heat map of where it reaches").click();
    harness.run();
    park_pointer(&mut harness);
    let image = harness.render().expect("the editor renders");
    assert_looks_as_reviewed(&image, "editor_heat_map");
}

/// A new SH order compiles its shaders in the background: the editor keeps drawing the
/// previous shadows (and says so), then switches to the new order.
#[test]
fn a_new_order_compiles_in_the_background_while_the_editor_draws() {
    let Some((_dir, _project, mut harness)) = editor_on_copy(Sample::Sample) else {
        return;
    };
    let before = harness.render().expect("render");
    harness.state_mut().render_settings_mut().expect("open").shadows.order = 6;
    // One frame: it starts the compile and returns long before the compile can finish.
    harness.step();
    assert!(
        harness.state().is_compiling_shaders(),
        "order 6 compiles on its own thread"
    );
    let meanwhile = harness.render().expect("render");
    let ppp = harness.ctx.pixels_per_point();
    let viewport = harness.state().viewport_rect();
    let shadows = viewport.shrink(40.0); // the notice sits in the bottom-left corner
    assert_eq!(
        viewport_pixels_differing(&before, &meanwhile, shadows, ppp),
        0,
        "the previous shadows are drawn while compiling"
    );
    let started = std::time::Instant::now();
    while harness.state().is_compiling_shaders() {
        assert!(started.elapsed().as_secs() < 300, "order 6 compiled within 5 minutes");
        std::thread::sleep(std::time::Duration::from_millis(200));
        harness.run();
    }
    harness.run();
    let after = harness.render().expect("render");
    assert!(
        viewport_pixels_differing(&before, &after, viewport, ppp) > 100,
        "order 6 shadows are drawn"
    );
}

/// Add light puts a point light in the scene (selected, drawn, saved); Delete light takes
/// it out; each is one undoable edit.
#[test]
fn lights_are_added_and_deleted_with_undo() {
    let Some((_dir, project, mut harness)) = editor_on_copy(Sample::Sample) else {
        return;
    };
    let before = harness.render().expect("render");
    let count = harness.state().light_intensities().len();
    harness.get_by_label("Add light").click();
    harness.run();
    park_pointer(&mut harness);
    assert_eq!(harness.state().light_intensities().len(), count + 1);
    assert_eq!(harness.state().selection(), Some(Selection::Light(count)));
    harness.get_by_label("Light: Light 1");
    harness.state_mut().select(None);
    harness.run();
    park_pointer(&mut harness);
    let added = harness.render().expect("render");
    let ppp = harness.ctx.pixels_per_point();
    let viewport = harness.state().viewport_rect();
    assert!(
        viewport_pixels_differing(&before, &added, viewport, ppp) > 1000,
        "the new light lights the scene"
    );
    harness.key_press_modifiers(egui::Modifiers::COMMAND, egui::Key::S);
    harness.run();
    assert_eq!(Document::open(&project).expect("reopens").scene.lights.len(), count + 1);

    harness.get_by_label("Light 1 — point").click();
    harness.run();
    harness.get_by_label("Delete light").scroll_to_me();
    harness.run();
    harness.get_by_label("Delete light").click();
    harness.run();
    assert_eq!(harness.state().light_intensities().len(), count);
    harness.key_press_modifiers(egui::Modifiers::COMMAND, egui::Key::Z);
    harness.run();
    assert_eq!(
        harness.state().light_intensities().len(),
        count + 1,
        "undo brings it back"
    );
    harness.key_press_modifiers(egui::Modifiers::COMMAND, egui::Key::Z);
    harness.run();
    assert_eq!(
        harness.state().light_intensities().len(),
        count,
        "undo takes the addition back"
    );
    park_pointer(&mut harness);
    let undone = harness.render().expect("render");
    assert_eq!(viewport_pixels_differing(&before, &undone, viewport, ppp), 0);
}

/// The editor and `lightpaint render` draw through the same renderer: the viewport of a
/// project and `render` of the same project at the viewport's size give the same pixels —
/// also with an object hidden (saved in the project), which neither draws nor shadows.
#[test]
fn the_editor_and_render_draw_the_same_pixels() {
    for (sample, hide_first) in [(Sample::Sample, false), (Sample::Studio, false), (Sample::Sample, true)] {
        let Some((dir, project, mut harness)) = editor_on_copy(sample) else {
            return;
        };
        if hide_first {
            let pillar = harness
                .state()
                .document()
                .and_then(|d| d.scene.objects.iter().position(|o| o.name.contains("Pillar")))
                .expect("the sample has a pillar");
            harness.state_mut().toggle_hidden(pillar);
            harness.run();
            harness.state_mut().save_to(&project);
            harness.run();
            let saved = lightpaint::project::Document::open(&project).expect("reopens");
            assert!(saved.hidden_objects.contains(&pillar), "the hidden pillar is saved");
        }
        let exported = dir.path().join("viewport.png");
        harness.state_mut().export_png(&exported);
        harness.run();
        let viewport = image::open(&exported).expect("the viewport was exported").to_rgba8();
        let rendered = rendered_by_cli(&project, &dir.path().join("render.png"), viewport.dimensions());
        assert_eq!(rendered.dimensions(), viewport.dimensions());
        let differing = common::differing_pixels(&viewport, &rendered);
        assert_eq!(
            differing, 0,
            "{sample:?}: {differing} pixels differ between the editor and render"
        );
    }
}

/// A status message that no longer holds fades: "nothing to undo" once an edit has given
/// something to undo. Long messages are cut at the window's edge, whole on hover.
#[test]
fn a_status_message_fades_once_it_no_longer_holds() {
    let Some((_dir, _project, mut harness)) = editor_on_copy(Sample::Sample) else {
        return;
    };
    harness.run();
    harness.key_press_modifiers(egui::Modifiers::COMMAND, egui::Key::Z);
    harness.run();
    assert_eq!(harness.state().status_message(), "nothing to undo");
    assert!(!harness.state().status_message_is_stale(), "fresh when said");
    let mut light = harness.state().document().expect("open").scene.lights[0].clone();
    light.intensity *= 1.5;
    harness.state_mut().set_light(0, light);
    harness.run();
    assert!(harness.state().can_undo());
    assert!(
        harness.state().status_message() != "nothing to undo" || harness.state().status_message_is_stale(),
        "\"nothing to undo\" no longer reads as news"
    );
}

/// File ▸ Export render as PNG asks the size: the window offers the viewport's and
/// presets, and an export at another size than the viewport's is the frame `render`
/// draws at that size, pixel for pixel; the viewport goes on at its own size.
#[test]
fn an_export_at_any_size_is_the_frame_render_draws() {
    let Some((dir, project, mut harness)) = editor_on_copy(Sample::Sample) else {
        return;
    };
    harness.run();
    harness.get_by_label("File").click();
    harness.run();
    harness.get_by_label("Export render as PNG…").click();
    harness.run();
    assert!(harness.state().is_export_window_open());
    harness.get_by_label("Full HD 1920 × 1080").click();
    harness.run();
    harness.get_by_label("as the viewport");

    let (width, height) = (400u32, 240u32);
    let exported = dir.path().join("export.png");
    harness.state_mut().export_png_sized(&exported, [width, height]);
    harness.run();
    let exported = image::open(&exported).expect("exported").to_rgba8();
    assert_eq!(exported.dimensions(), (width, height));
    let rendered = rendered_by_cli(&project, &dir.path().join("render.png"), (width, height));
    let differing = common::differing_pixels(&exported, &rendered);
    assert_eq!(differing, 0, "{differing} pixels differ between the export and render");

    // The viewport draws at its own size again.
    harness.run();
    let viewport = dir.path().join("viewport.png");
    harness.state_mut().export_png(&viewport);
    let viewport = image::open(&viewport).expect("exported").to_rgba8();
    let rect = harness.state().viewport_rect();
    let ppp = harness.ctx.pixels_per_point();
    assert_eq!(
        viewport.dimensions(),
        (
            (rect.width() * ppp).round() as u32,
            (rect.height() * ppp).round() as u32
        )
    );
}

/// `lightpaint render PROJECT -o OUT --width W --height H`, read back.
fn rendered_by_cli(project: &std::path::Path, out: &std::path::Path, (width, height): (u32, u32)) -> image::RgbaImage {
    let output = common::run_lightpaint(&[
        "render".as_ref(),
        project.as_os_str(),
        "-o".as_ref(),
        out.as_os_str(),
        "--width".as_ref(),
        width.to_string().as_ref(),
        "--height".as_ref(),
        height.to_string().as_ref(),
    ]);
    assert!(output.status.success(), "{}", String::from_utf8_lossy(&output.stderr));
    image::open(out).expect("render wrote a PNG").to_rgba8()
}

/// A light locked in its inspector ("painting: locked") shows a lock in the outliner, is
/// left as it is by a brighten stroke that raises another light, stays locked in the saved
/// project, and Ctrl+Z unlocks it again (the lock is a light edit like any other).
#[test]
fn a_locked_light_is_left_as_it_is_by_strokes_and_stays_locked() {
    let Some((_dir, project, mut harness)) = editor_on_copy(Sample::Studio) else {
        return;
    };
    let key = light_index(&harness, "Key");
    harness.get_by_label("Key — spot").click();
    harness.run();
    harness
        .get_by_role_and_label(egui::accesskit::Role::CheckBox, "painting")
        .click();
    harness.run();
    assert!(harness.state().document().expect("open").scene.lights[key].locked);
    harness.get_by_label("Key — spot (locked)");
    harness.state_mut().select(None);
    harness.run();
    park_pointer(&mut harness);

    let before = harness.state().light_intensities();
    harness.key_press(egui::Key::B);
    harness.run();
    let path = studio_floor_path(&harness);
    drag_through(&mut harness, &path, 6);
    park_pointer(&mut harness);
    let after = harness.state().light_intensities();
    assert_eq!(after[key], before[key], "the locked key is left as it is");
    assert!(
        after.iter().zip(&before).any(|(a, b)| a > b),
        "another light rose: {before:?} → {after:?}"
    );
    let painting = harness.state().painting_state().expect("open");
    assert_eq!(
        painting.strokes.last().map(|s| s.locked_lights.clone()),
        Some(vec![key as u32])
    );

    harness.key_press(egui::Key::Escape);
    harness.key_press_modifiers(egui::Modifiers::COMMAND, egui::Key::S);
    harness.run();
    let reopened = Document::open(&project).expect("reopens");
    assert_eq!(reopened.scene.locked_lights(), vec![key as u32]);

    // Undo the stroke, then the lock.
    for _ in 0..2 {
        harness.key_press_modifiers(egui::Modifiers::COMMAND, egui::Key::Z);
        harness.run();
    }
    assert!(!harness.state().document().expect("open").scene.lights[key].locked);
    assert_eq!(harness.state().light_intensities(), before);
}

/// A project lit by lamps with a range: the Shadows section says the frames walk the
/// lights' grid, and how many lamps a box lists (`shading::light_grid`).
#[test]
fn the_shadows_section_tells_of_the_lights_grid() {
    if common::no_gpu_wanted() {
        eprintln!("UI test not run: {}=1", common::NO_GPU_ENV);
        return;
    }
    let dir = tempfile::tempdir().unwrap();
    let project = Sample::Sample.write(dir.path()).unwrap();
    let mut document = Document::open(&project).expect("the sample opens");
    for k in 0..12 {
        document.scene.lights.push(lightpaint::scene::Light {
            name: format!("lamp {k}"),
            kind: lightpaint::scene::LightKind::Point,
            color: glam::Vec3::ONE,
            intensity: 0.2,
            position: glam::Vec3::new(-1.5 + 0.3 * k as f32, 0.3, 0.5),
            direction: glam::Vec3::NEG_Y,
            range: Some(0.8),
            locked: false,
        });
    }
    document.save(&project).expect("saved with its lamps");
    let mut harness = editor_on(project);
    harness.run();
    // A label keeps its text as its value (AccessKit's Role::Label).
    let label = egui_kittest::kittest::NodeT::accesskit_node(&harness.get_by_label_contains("lights' grid: "))
        .value()
        .unwrap_or_default();
    assert!(
        label.contains("boxes of") && label.contains("lights listed a box on average"),
        "{label}"
    );
}
