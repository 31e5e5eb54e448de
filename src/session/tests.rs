//! The session's commands on a real scene (a lit floor), its BVH and its painter: one
//! history of strokes and light edits, outcomes that say what changed, and the painting
//! state written back where the document leaves the session.

use glam::{Vec2, Vec3};

use super::*;
use crate::paint::BrushKind;
use crate::scene::{Camera, Scene};

fn session() -> EditorSession {
    let scene = Scene::lambert_floor_under_point_light(16, Vec3::new(0.0, 1.0, 0.0), 10.0);
    let document = Document {
        scene,
        scene_path: "floor.gltf".into(),
        settings: Default::default(),
        camera: None,
        project_path: None,
        warnings: Vec::new(),
        notes: Vec::new(),
        painting: Default::default(),
        hidden_objects: Default::default(),
        object_names: Default::default(),
    };
    let mut session = EditorSession::new(document);
    session.painting.tool = Tool::Brush(BrushKind::Positive);
    session
}

fn camera() -> Camera {
    Camera::looking_at(Vec3::new(0.0, 2.0, 1.5), Vec3::ZERO, 0.8, 0.05)
}

/// A dab at the middle of a 200 × 200 px view: on the floor.
fn dab() -> ScreenStroke {
    ScreenStroke {
        points_px: vec![Vec2::new(100.0, 100.0)],
        viewport_size_px: Vec2::new(200.0, 200.0),
    }
}

fn intensity(session: &EditorSession) -> f32 {
    session.document.scene.lights[0].intensity
}

#[test]
fn strokes_and_light_edits_undo_and_redo_in_one_order() {
    let mut session = session();
    let start = session.document.scene.lights.clone();
    let painted = session.paint_stroke(camera(), &dab(), &[]);
    assert!(matches!(painted.happened, Some(Happened::Painted(_))), "{painted:?}");
    assert_eq!(painted.changes, Changes::LIGHTS);
    let brightened = intensity(&session);
    assert!(brightened > 10.0, "the brighten stroke raised the bulb: {brightened}");

    // A light edit after the stroke: moved, then settled as one entry.
    let mut moved = session.document.scene.lights[0].clone();
    moved.position.x += 0.5;
    assert_eq!(session.set_light(0, moved.clone()).changes, Changes::LIGHTS);
    session.settle_light_edits();

    assert_eq!(session.undo().happened, Some(Happened::Undid(EntryKind::LightEdit)));
    assert_eq!(session.document.scene.lights[0].position, start[0].position);
    assert_eq!(intensity(&session), brightened, "the stroke is still applied");
    assert_eq!(session.undo().happened, Some(Happened::Undid(EntryKind::Stroke)));
    assert_eq!(
        session.document.scene.lights, start,
        "exactly the lights before the stroke"
    );
    assert_eq!(session.painting_state().strokes.len(), 0);
    assert_eq!(session.undo().happened, Some(Happened::NothingToUndo));

    assert_eq!(session.redo().happened, Some(Happened::Redid(EntryKind::Stroke)));
    assert_eq!(intensity(&session), brightened);
    assert_eq!(session.painting_state().strokes.len(), 1);
    assert_eq!(session.redo().happened, Some(Happened::Redid(EntryKind::LightEdit)));
    assert_eq!(session.document.scene.lights[0], moved);
    assert_eq!(session.redo().happened, Some(Happened::NothingToRedo));
}

#[test]
fn a_new_stroke_drops_what_was_undone() {
    let mut session = session();
    session.paint_stroke(camera(), &dab(), &[]);
    session.undo();
    assert!(session.can_redo());
    session.paint_stroke(camera(), &dab(), &[]);
    assert!(!session.can_redo());
    assert_eq!(session.painting_state().strokes.len(), 1);
}

#[test]
fn the_painting_state_goes_with_the_document_when_it_leaves() {
    let mut session = session();
    session.paint_stroke(camera(), &dab(), &[]);
    session.painting.brush.radius_px = 31.0;
    let state = session.painting_state();
    let file = session.project_file(std::path::Path::new("floor.lightpaint"));
    assert_eq!(file.painting, state);
    let document = session.into_document();
    assert_eq!(document.painting, state);
    assert_eq!(document.painting.strokes.len(), 1);
    // A session on it takes the strokes up as earlier ones: not undoable there.
    let again = EditorSession::new(document);
    assert_eq!(again.painting_state(), state);
    assert!(!again.can_undo());
}

#[test]
fn light_commands_say_what_they_did_and_what_changed() {
    let mut session = session();
    let added = session.add_light(Vec3::ZERO);
    assert_eq!(
        added.happened,
        Some(Happened::LightAdded {
            index: 1,
            name: "Light 1".into()
        })
    );
    assert_eq!(
        session.solo(Some(1)).happened,
        Some(Happened::Solo(Some("Light 1".into())))
    );
    assert_eq!(session.displayed_lights()[0].intensity, 0.0, "the bulb is not shown");
    assert_eq!(intensity(&session), 10.0, "but keeps its intensity");
    let deleted = session.delete_light(1);
    assert_eq!(
        deleted.happened.map(|h| h.to_string()).as_deref(),
        Some("deleted Light 1 (Ctrl+Z brings it back)")
    );
    assert_eq!(session.solo_light(), None, "the soloed light is gone");
    assert_eq!(session.undo().happened, Some(Happened::Undid(EntryKind::LightEdit)));
    assert_eq!(session.document.scene.lights.len(), 2);
    let hidden = session.toggle_hidden(0);
    assert!(hidden.changes.hidden && !hidden.changes.lights);
    assert_eq!(hidden.happened, Some(Happened::ObjectHidden { name: "floor".into() }));
    assert_eq!(session.delete_light(7), Outcome::NOTHING, "no such light");
    let mut bad = session.document.scene.lights[0].clone();
    bad.intensity = f32::NAN;
    assert_eq!(
        session.set_light(0, bad),
        Outcome::NOTHING,
        "a light with problems is ignored"
    );
}
