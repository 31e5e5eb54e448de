//! Objects outside the camera's frustum are left out of the passes drawn from it
//! (`scene::Frustum`, `GpuScene::write_frame`), on lavapipe: the frame must be byte for
//! byte the one drawn with every object, in the default (deferred) mode and per vertex,
//! and the culling must have left something out for the comparison to mean anything.
//! Each shadow-map view culls the same way against its own frustum, and the maps' frame
//! must be the same too.

mod common;

use lightpaint::blockers::fit_scene;
use lightpaint::project::Document;
use lightpaint::render::{FrameQuality, GpuContext, SceneRenderer};
use lightpaint::scene::Camera;
use lightpaint::shading::RenderSettings;

const SIZE: [u32; 2] = [320, 180];

/// The frame `settings` give of the sample from `camera`, with or without culling, and the
/// triangles drawn from the camera against those shown.
fn frame(
    gpu: &GpuContext,
    document: &Document,
    settings: &RenderSettings,
    camera: &Camera,
    culling: bool,
) -> (image::RgbaImage, (u64, u64)) {
    let blockers = fit_scene(&document.scene, &settings.blockers).spheres();
    let (image, renderer) = common::drawn_with(gpu, (&document.scene, &blockers), settings, (camera, SIZE), |r| {
        r.set_view_culling(culling)
    });
    (image, renderer.triangles_in_view())
}

/// The sample's whole view, and one close to its smallest object, from the side the
/// sample's camera sees it from, turned 50° to the side: some objects leave the view, the
/// floor and the wall stay.
fn whole_and_close_views(document: &Document) -> (Camera, Camera) {
    let whole = document
        .camera
        .map_or_else(|| document.scene.initial_camera(), |o| o.camera());
    let smallest = document
        .scene
        .objects
        .iter()
        .map(|o| o.bounds())
        .min_by(|a, b| a.radius().total_cmp(&b.radius()))
        .expect("the sample has objects");
    let toward_camera = (whole.position - smallest.center()).normalize();
    let position = smallest.center() + toward_camera * 3.0 * smallest.radius();
    let turn = glam::Quat::from_rotation_y(50f32.to_radians());
    let close = Camera::looking_at(
        position,
        position + turn * (smallest.center() - position),
        whole.yfov_rad,
        whole.znear,
    );
    (whole, close)
}

#[test]
fn culling_what_the_camera_cannot_see_leaves_the_frame_unchanged() {
    let Some(gpu) = common::gpu() else { return };
    let document = Document::open(&common::repo_path("projects/sample/sample.lightpaint")).expect("sample opens");
    let (_, close) = whole_and_close_views(&document);
    for per_vertex in [false, true] {
        let mut settings = document.settings;
        settings.shadows.per_vertex = per_vertex;
        let (culled, (in_view, shown)) = frame(&gpu, &document, &settings, &close, true);
        let (every_object, (all_drawn, _)) = frame(&gpu, &document, &settings, &close, false);
        assert!(
            in_view < shown,
            "the close view must cull something ({in_view} of {shown} triangles)"
        );
        assert_eq!(all_drawn, shown, "without culling every shown triangle is drawn");
        let differing = common::differing_pixels(&culled, &every_object);
        assert_eq!(
            differing, 0,
            "per vertex {per_vertex}: the culled frame differs from the whole one at {differing} pixels"
        );
    }
}

/// Each shadow-map view leaves out the objects outside its frustum (`ShadowMaps::draw`):
/// a point light among a ring of posts and cards on a floor, and a spot aimed at one post,
/// cast the same shadows with and without the culling — the frames byte for byte alike
/// — while the cube's faces, each seeing a quarter of the ring or less, and the spot's
/// narrow cone draw well under every object into each view.
#[test]
fn shadow_maps_culled_per_view_cast_the_same_shadows() {
    use common::scenes::white_light;
    use glam::Vec3;
    use lightpaint::scene::LightKind;
    let Some(gpu) = common::gpu() else { return };
    let mut scene = common::scenes::ring_of_posts_and_cards();
    scene
        .lights
        .push(white_light(LightKind::Point, Vec3::new(0.0, 1.2, 0.0), 8.0));
    let spot = LightKind::Spot {
        inner_cone_rad: 0.15,
        outer_cone_rad: 0.25,
    };
    let mut aimed = white_light(spot, Vec3::new(-4.5, 3.0, 0.5), 30.0);
    aimed.direction = (Vec3::new(3.0, 0.9, 0.0) - aimed.position).normalize();
    scene.lights.push(aimed);
    let settings = RenderSettings::default();
    let camera = common::scenes::ring_camera();
    let blockers = fit_scene(&scene, &settings.blockers).spheres();
    let draw = |culling: bool| {
        let (image, renderer) = common::drawn_with(&gpu, (&scene, &blockers), &settings, (&camera, SIZE), |r| {
            r.set_view_culling(culling)
        });
        (image, renderer.shadow_map_triangles(), renderer.triangles_in_view().1)
    };
    let (culled, (views, culled_triangles), shown) = draw(true);
    let (whole, (whole_views, whole_triangles), _) = draw(false);
    assert_eq!(views, 7, "the point light's six faces and the spot's view");
    assert_eq!(whole_views, views);
    assert_eq!(
        whole_triangles,
        views * shown,
        "without culling every view draws every object"
    );
    assert!(
        culled_triangles * 2 < whole_triangles,
        "the views drew {culled_triangles} of {whole_triangles} triangles"
    );
    let differing = common::differing_pixels(&culled, &whole);
    assert_eq!(
        differing, 0,
        "the culled maps' frame differs from the whole one at {differing} pixels"
    );
    common::thin_casters::save_for_review("shadow-maps-culled-per-view", &culled);
}

/// Per vertex, each object's visibility is computed when it first comes into view and kept
/// while the blockers, settings and — where their windows on the blockers apply — the SH
/// path's lights hold: a frame of the close view computes the objects it sees, the whole
/// view then only those the close one culled, the same view again none, and under the
/// sample's environment (no windows) a moved light none; without the environment the
/// windows apply and a moved light computes every object in view again, a brightened one
/// none. Each frame must be byte for byte the one a new renderer draws.
#[test]
fn per_vertex_visibility_is_computed_once_per_object_in_view() {
    let Some(gpu) = common::gpu() else { return };
    let document = Document::open(&common::repo_path("projects/sample/sample.lightpaint")).expect("sample opens");
    assert!(document.scene.environment.is_some(), "the sample has an environment");
    let (whole, close) = whole_and_close_views(&document);
    let mut settings = document.settings;
    settings.shadows.per_vertex = true;
    // Every light on the SH path, so that without the environment their windows apply.
    settings.shadows.light_paths = lightpaint::shading::LightPaths::Harmonics;
    let blockers = fit_scene(&document.scene, &settings.blockers).spheres();
    let new_renderer = |scene: &lightpaint::scene::Scene| common::renderer_for(&gpu, scene, &blockers, &settings);
    let draw = |renderer: &mut SceneRenderer, camera: &Camera| {
        renderer.render(camera, SIZE, &settings, FrameQuality::default());
        let image = renderer.read_image().expect("a frame was drawn").expect("readback");
        (image, renderer.vertices_computed())
    };
    let drawn_anew = |scene: &lightpaint::scene::Scene, camera: &Camera| draw(&mut new_renderer(scene), camera);
    let all_vertices: u64 = document.scene.objects.iter().map(|o| o.positions.len() as u64).sum();
    let mut kept = new_renderer(&document.scene);

    let (_, close_vertices) = draw(&mut kept, &close);
    assert!(
        close_vertices > 0 && close_vertices < all_vertices,
        "the close view computes what it sees: {close_vertices} of {all_vertices} vertices"
    );
    let (whole_frame, whole_vertices) = draw(&mut kept, &whole);
    let (anew, anew_vertices) = drawn_anew(&document.scene, &whole);
    assert_eq!(
        common::differing_pixels(&whole_frame, &anew),
        0,
        "the whole view after the close one"
    );
    assert_eq!(
        whole_vertices,
        anew_vertices - close_vertices,
        "the whole view computes only what the close one did not"
    );
    let (again, again_vertices) = draw(&mut kept, &whole);
    assert_eq!(common::differing_pixels(&again, &anew), 0, "the whole view drawn again");
    assert_eq!(again_vertices, 0, "the same view again computes nothing");

    let moved_light = |scene: &lightpaint::scene::Scene| {
        let mut moved = scene.clone();
        moved.lights[0].position += glam::Vec3::new(0.8, 0.3, -0.5);
        moved
    };
    let moved = moved_light(&document.scene);
    kept.set_lights(&moved.lights);
    let (after_move, move_vertices) = draw(&mut kept, &whole);
    let (move_anew, _) = drawn_anew(&moved, &whole);
    assert!(
        common::differing_pixels(&anew, &move_anew) > 1000,
        "the light's move must show"
    );
    assert_eq!(
        common::differing_pixels(&after_move, &move_anew),
        0,
        "the view after a light moved"
    );
    assert_eq!(
        move_vertices, 0,
        "under the environment no light is read: nothing computed"
    );

    let mut unlit = document.scene.clone();
    unlit.environment = None;
    let mut kept = new_renderer(&unlit);
    let (_, first_vertices) = draw(&mut kept, &whole);
    let moved = moved_light(&unlit);
    kept.set_lights(&moved.lights);
    let (after_move, move_vertices) = draw(&mut kept, &whole);
    let (move_anew, _) = drawn_anew(&moved, &whole);
    assert_eq!(
        common::differing_pixels(&after_move, &move_anew),
        0,
        "the view after a windowed light moved"
    );
    assert_eq!(
        move_vertices, first_vertices,
        "a moved light whose window applies computes every vertex in view again"
    );

    // A stroke changes how bright a light is, not where its window is.
    let mut brighter = moved.clone();
    brighter.lights[0].intensity *= 2.0;
    kept.set_lights(&brighter.lights);
    let (after_stroke, stroke_vertices) = draw(&mut kept, &whole);
    let (stroke_anew, _) = drawn_anew(&brighter, &whole);
    assert!(
        common::differing_pixels(&move_anew, &stroke_anew) > 1000,
        "the brighter light must show"
    );
    assert_eq!(
        common::differing_pixels(&after_stroke, &stroke_anew),
        0,
        "the view after a windowed light was brightened"
    );
    assert_eq!(
        stroke_vertices, 0,
        "a brighter light leaves its window: nothing computed"
    );
}
