//! A frame after an edit of the lights keeps the surfaces the last frame rasterised (and
//! the shadow maps of the lights that did not move), and
//! the soft layer and the SH path's light at the pixels shaded in full when the edit
//! leaves the SH path's light alone
//! (`render::passes::reduced_shading::FrameInputs`, on lavapipe in CI). Whatever it
//! keeps, the frame must be the one a renderer drawing everything anew gives for the same
//! lights, view, visible objects, environment, blockers and exposure: these tests compare
//! the two byte for byte on the studio sample after each kind of change.

mod common;

use std::collections::BTreeSet;

use lightpaint::blockers::fit_scene;
use lightpaint::project::Document;
use lightpaint::render::{FrameQuality, GpuContext, SceneRenderer};
use lightpaint::scene::{Camera, Light, Scene};
use lightpaint::shading::RenderSettings;

const SIZE: [u32; 2] = [320, 180];

struct Studio {
    document: Document,
    blockers: Vec<lightpaint::blockers::Sphere>,
    camera: Camera,
}

fn studio() -> Studio {
    let document = Document::open(&common::repo_path("projects/studio/studio.lightpaint")).expect("studio opens");
    let camera = document
        .camera
        .map_or_else(|| document.scene.initial_camera(), |o| o.camera());
    let blockers = fit_scene(&document.scene, &document.settings.blockers).spheres();
    Studio {
        document,
        blockers,
        camera,
    }
}

fn renderer(gpu: &GpuContext, studio: &Studio, scene: &Scene) -> SceneRenderer {
    common::renderer_for(gpu, scene, &studio.blockers, &studio.document.settings)
}

fn draw(renderer: &mut SceneRenderer, camera: &Camera, settings: &RenderSettings) -> image::RgbaImage {
    renderer.render(camera, SIZE, settings, FrameQuality::default());
    renderer.read_image().expect("a frame was drawn").expect("readback")
}

/// The frame a new renderer draws of `scene` with `lights` and `hidden` objects.
fn drawn_anew(
    gpu: &GpuContext,
    studio: &Studio,
    lights: &[Light],
    hidden: &BTreeSet<usize>,
    camera: &Camera,
) -> image::RgbaImage {
    let mut scene = studio.document.scene.clone();
    scene.lights = lights.to_vec();
    let mut fresh = renderer(gpu, studio, &scene);
    fresh.set_hidden(hidden);
    draw(&mut fresh, camera, &studio.document.settings)
}

/// The frame a new renderer draws of `scene` with `settings` and `blockers`.
fn scene_drawn_anew(
    gpu: &GpuContext,
    scene: &Scene,
    blockers: &[lightpaint::blockers::Sphere],
    settings: &RenderSettings,
    camera: &Camera,
) -> image::RgbaImage {
    draw(
        &mut common::renderer_for(gpu, scene, blockers, settings),
        camera,
        settings,
    )
}

/// Fails unless the frame drawn `after` a change is byte for byte the one drawn anew.
fn assert_same(after: &image::RgbaImage, anew: &image::RgbaImage, what: &str) {
    let differing = common::differing_pixels(after, anew);
    assert_eq!(
        differing, 0,
        "the frame after {what} differs from the frame drawn anew at {differing} pixels"
    );
}

/// The lights with the first one three times as bright and the last one off.
fn edited(lights: &[Light]) -> Vec<Light> {
    let mut lights = lights.to_vec();
    lights[0].intensity *= 3.0;
    if let Some(last) = lights.last_mut() {
        last.intensity = 0.0;
    }
    lights
}

/// Draws the studio, edits its lights with `edit`, draws again with the same renderer and
/// checks that frame against one drawn anew (and that the edit changed more than
/// `min_changed_share` of the frame's pixels, so that the check means something).
fn check_a_light_edit(what: &str, min_changed_share: f64, edit: impl FnOnce(&mut Vec<Light>)) {
    let Some(gpu) = common::gpu() else { return };
    let studio = studio();
    let settings = &studio.document.settings;
    let mut kept = renderer(&gpu, &studio, &studio.document.scene);
    let before = draw(&mut kept, &studio.camera, settings);

    let mut lights = studio.document.scene.lights.clone();
    edit(&mut lights);
    kept.set_lights(&lights);
    let after = draw(&mut kept, &studio.camera, settings);
    let anew = drawn_anew(&gpu, &studio, &lights, &BTreeSet::new(), &studio.camera);
    let changed = common::differing_pixels(&before, &anew) as f64 / f64::from(SIZE[0] * SIZE[1]);
    assert!(
        changed > min_changed_share,
        "{what} must change the frame to test anything ({changed:.3} of it changed)"
    );
    assert_same(&after, &anew, what);
}

#[test]
fn a_frame_after_a_light_edit_is_the_frame_drawn_anew() {
    check_a_light_edit("an edit of two lights' intensities", 0.25, |lights| {
        *lights = edited(lights)
    });
}

#[test]
fn a_camera_move_or_a_hidden_object_draws_the_surfaces_again() {
    let Some(gpu) = common::gpu() else { return };
    let studio = studio();
    let settings = &studio.document.settings;
    let lights = studio.document.scene.lights.clone();
    let mut kept = renderer(&gpu, &studio, &studio.document.scene);
    draw(&mut kept, &studio.camera, settings);

    // Half a metre to the side: every surface moves on the screen.
    let mut moved = studio.camera.clone();
    let side = moved.forward.cross(glam::Vec3::Y).normalize() * 0.5;
    moved.position += side;
    let after_move = draw(&mut kept, &moved, settings);
    let none = BTreeSet::new();
    assert_same(
        &after_move,
        &drawn_anew(&gpu, &studio, &lights, &none, &moved),
        "the camera moved",
    );

    // The largest object hidden, the view as before.
    let largest = (0..studio.document.scene.objects.len())
        .max_by_key(|&i| studio.document.scene.objects[i].indices.len())
        .expect("the studio has objects");
    let hidden = BTreeSet::from([largest]);
    kept.set_hidden(&hidden);
    let after_hiding = draw(&mut kept, &moved, settings);
    let anew = drawn_anew(&gpu, &studio, &lights, &hidden, &moved);
    assert!(
        common::differing_pixels(&after_move, &anew) > 0,
        "hiding must change the frame"
    );
    assert_same(&after_hiding, &anew, "hiding an object");
}

#[test]
fn a_change_the_soft_layer_reads_draws_it_again() {
    let Some(gpu) = common::gpu() else { return };
    let studio = studio();
    let camera = &studio.camera;
    let mut scene = studio.document.scene.clone();
    assert!(scene.environment.is_some(), "the studio has an environment to change");
    // A sphere light too large for maps or the exact path (56° seen from the centre):
    // the SH carries it with the environment, in the soft layer, while the maps carry
    // the studio's own lights.
    let centre = scene.bounds().center();
    scene.lights.push(Light {
        name: "dome".into(),
        kind: lightpaint::scene::LightKind::Sphere { radius_m: 2.5 },
        position: centre + glam::Vec3::new(0.0, 3.0, 0.0),
        ..scene.lights[0].clone()
    });
    let settings = &mut studio.document.settings.clone();
    let mut blockers = studio.blockers.clone();
    let mut kept = common::renderer_for(&gpu, &scene, &blockers, settings);
    let paths = kept.light_paths_at(&scene.lights, centre, &settings.shadows);
    assert_eq!(
        paths.last().map(|p| p.0),
        Some(lightpaint::shading::ShadowPath::Harmonics)
    );
    assert_eq!(paths[0].0, lightpaint::shading::ShadowPath::Map);
    let mut last = draw(&mut kept, camera, settings);
    let mut check = |what: &str,
                     kept: &mut SceneRenderer,
                     scene: &Scene,
                     blockers: &[lightpaint::blockers::Sphere],
                     settings: &RenderSettings| {
        let after = draw(kept, camera, settings);
        let anew = scene_drawn_anew(&gpu, scene, blockers, settings, camera);
        assert!(
            common::differing_pixels(&last, &anew) > 0,
            "{what} must change the frame"
        );
        assert_same(&after, &anew, what);
        last = after;
    };

    // The light on the maps alone: the soft layer, and the SH path's light kept at the
    // pixels shaded in full (full_resolution.wgsl's kept_harmonic_light), are read again.
    scene.lights[0].intensity *= 3.0;
    kept.set_lights(&scene.lights);
    check(
        "an edit of a light on the maps alone",
        &mut kept,
        &scene,
        &blockers,
        settings,
    );

    scene.lights = edited(&scene.lights);
    kept.set_lights(&scene.lights);
    check(
        "an edit of lights on the SH path",
        &mut kept,
        &scene,
        &blockers,
        settings,
    );

    if let Some(environment) = &mut scene.environment {
        environment.intensity *= 4.0;
    }
    kept.set_environment(scene.environment.as_ref());
    check("a brighter environment", &mut kept, &scene, &blockers, settings);

    blockers.truncate(blockers.len() / 2);
    kept.set_blockers(&blockers);
    check("fewer blockers", &mut kept, &scene, &blockers, settings);

    settings.exposure_ev += 1.0;
    check("a brighter exposure", &mut kept, &scene, &blockers, settings);
}

#[test]
fn a_frame_after_a_light_moved_is_the_frame_drawn_anew() {
    // The key spot (a shadow map of its own) moved 30 cm and turned; the others' maps
    // are kept.
    check_a_light_edit("the key light's move", 0.0, |lights| {
        let key = lights.iter().position(|l| l.name == "Key").expect("the key light");
        lights[key].position += glam::Vec3::new(0.3, 0.0, -0.2);
        lights[key].direction = (lights[key].direction + glam::Vec3::new(0.1, 0.0, 0.0)).normalize();
    });
}

#[test]
fn a_moved_point_light_redraws_its_own_faces_alone() {
    // Two point lights' twelve cube faces fill three layers of four quadrants, and the
    // middle layer holds two faces of each: moving one light redraws its six faces, each
    // quadrant cleared alone, and keeps the other light's two beside them. The frame
    // must be the one drawn anew.
    use common::scenes::{ring_camera, ring_of_posts_and_cards, white_light};
    use lightpaint::scene::LightKind;
    let Some(gpu) = common::gpu() else { return };
    let mut scene = ring_of_posts_and_cards();
    scene
        .lights
        .push(white_light(LightKind::Point, glam::Vec3::new(0.0, 1.2, 0.0), 8.0));
    scene
        .lights
        .push(white_light(LightKind::Point, glam::Vec3::new(1.2, 1.6, 1.0), 6.0));
    let settings = RenderSettings::default();
    let blockers = fit_scene(&scene, &settings.blockers).spheres();
    let camera = ring_camera();
    let mut kept = common::renderer_for(&gpu, &scene, &blockers, &settings);
    let before = draw(&mut kept, &camera, &settings);
    assert_eq!(kept.shadow_map_triangles().0, 12, "both lights' cubes drawn");
    let mut moved = scene.clone();
    moved.lights[1].position += glam::Vec3::new(0.5, 0.0, -0.4);
    kept.set_lights(&moved.lights);
    let after = draw(&mut kept, &camera, &settings);
    assert_eq!(
        kept.shadow_map_triangles().0,
        6,
        "the moved light's faces alone redrawn"
    );
    let anew = scene_drawn_anew(&gpu, &moved, &blockers, &settings, &camera);
    assert!(
        common::differing_pixels(&before, &anew) > 1000,
        "the move must change the shadows to test anything"
    );
    assert_same(&after, &anew, "the second point light's move");
}

#[test]
fn a_dragged_lights_drafted_map_is_drawn_in_full_once_the_drag_ends() {
    // While the key spot is dragged its map is drawn at half resolution (a draft); the
    // first frame drawn without drafting must be the frame drawn anew, and the drafted
    // frame must differ from it (else the draft was never drawn and nothing is tested).
    let Some(gpu) = common::gpu() else { return };
    let studio = studio();
    let settings = &studio.document.settings;
    let mut kept = renderer(&gpu, &studio, &studio.document.scene);
    draw(&mut kept, &studio.camera, settings);
    let mut lights = studio.document.scene.lights.clone();
    let key = lights.iter().position(|l| l.name == "Key").expect("the key light");
    let dragging = FrameQuality {
        draft_moved_maps: true,
        ..FrameQuality::default()
    };
    for step in 1..=3 {
        lights[key].position += glam::Vec3::new(0.1, 0.0, -0.05);
        kept.set_lights(&lights);
        kept.render(&studio.camera, SIZE, settings, dragging);
        assert!(
            kept.maps_drafted(),
            "step {step} of the drag drew the moved map as a draft"
        );
    }
    let drafted = kept.read_image().expect("a frame was drawn").expect("readback");
    let anew = drawn_anew(&gpu, &studio, &lights, &BTreeSet::new(), &studio.camera);
    assert!(
        common::differing_pixels(&drafted, &anew) > 0,
        "a half-resolution map must change some shadow edge"
    );
    let released = draw(&mut kept, &studio.camera, settings);
    assert!(!kept.maps_drafted());
    assert_same(&released, &anew, "the key light's drag ended");
}

/// A device whose storage bindings are too small for the samples' kept visibility of the
/// mapped lights (the studio's nine at 960 × 540: 320 × 180 samples × 9 × 4 bytes, 2.1 MB;
/// the limit here 1 MiB, which every other buffer of the frame fits) shades them from
/// their maps every frame instead: its frames, drawn anew and after a light edit, are
/// byte for byte those of a device that keeps them (and the light edit changes the
/// frame, so the comparison means something).
#[test]
fn without_room_for_the_kept_visibility_the_frames_read_the_maps_alike() {
    let Some(gpu) = common::gpu() else { return };
    let small = GpuContext::headless_with_limits(|limits| wgpu::Limits {
        max_storage_buffer_binding_size: 1 << 20,
        ..limits
    })
    .expect("a device with a lower storage binding limit");
    let studio = studio();
    let settings = &studio.document.settings;
    let lights = edited(&studio.document.scene.lights);
    let size = [960, 540];
    let frames = |gpu: &GpuContext| {
        let mut renderer = renderer(gpu, &studio, &studio.document.scene);
        let draw = |renderer: &mut SceneRenderer| {
            renderer.render(&studio.camera, size, settings, FrameQuality::default());
            renderer.read_image().expect("a frame was drawn").expect("readback")
        };
        let anew = draw(&mut renderer);
        renderer.set_lights(&lights);
        (anew, draw(&mut renderer))
    };
    let (kept_anew, kept_after) = frames(&gpu);
    let (read_anew, read_after) = frames(&small);
    assert!(
        common::differing_pixels(&kept_anew, &kept_after) > 1000,
        "the edit changes the frame"
    );
    assert_same(&read_anew, &kept_anew, "drawing anew without the kept visibility");
    assert_same(&read_after, &kept_after, "a light edit without the kept visibility");
}
