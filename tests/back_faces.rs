//! Back faces on lavapipe. glTF's `doubleSided`: when every material of a scene is
//! single-sided the renderer culls back faces (glTF 2.0, "Double Sided"), so a
//! single-sided floor seen from below shows the background; a double-sided one shows its
//! lit underside. Closed meshes: per-vertex frames cull the back faces of those the
//! camera sees from outside, which changes nothing but ties at silhouettes, and keep them
//! where the camera is inside or the near plane cuts in.

mod common;

use glam::{Vec3, Vec4};
use lightpaint::render::{AntiAliasing, ShadowFrame, render_logsh_image};
use lightpaint::scene::{Camera, LightKind, Material, Scene, shapes};
use lightpaint::shading::{RenderSettings, ShadowSettings};

/// A white 4 m floor at y = 0, lit from above and from below by point lights.
fn floor(double_sided: bool) -> Scene {
    let light = |y: f32| common::scenes::white_light(LightKind::Point, Vec3::new(0.0, y, 0.0), 20.0);
    Scene {
        objects: vec![shapes::plane(4.0, 4, 1.0).into_object("floor")],
        materials: vec![Material {
            base_color: Vec4::ONE,
            metallic: 0.0,
            double_sided,
            ..Material::default()
        }],
        lights: vec![light(2.0), light(-2.0)],
        ..Scene::default()
    }
}

/// The camera 3 m above (`from_above`) or below the floor's centre, looking at it.
fn camera(from_above: bool) -> Camera {
    let side = if from_above { 1.0 } else { -1.0 };
    Camera {
        position: Vec3::new(0.0, 3.0 * side, 0.01),
        forward: Vec3::new(0.0, -side, 0.0),
        up: Vec3::NEG_Z,
        yfov_rad: 40f32.to_radians(),
        znear: 0.1,
        zfar: None,
    }
}

/// The centre pixel of a 64 × 64 frame, and the frame's background colour.
fn centre_pixel(scene: &Scene, camera: &Camera) -> ([u8; 3], [u8; 3]) {
    let gpu = common::gpu().expect("a GPU adapter");
    let settings = RenderSettings::default();
    let shadows = ShadowSettings::default();
    let frame = ShadowFrame {
        scene,
        camera,
        settings: &settings,
        shadows: &shadows,
        blockers: &[],
        baked_indirect: None,
        width: 64,
        height: 64,
    };
    let image = render_logsh_image(&gpu, &frame, AntiAliasing::None).expect("frame");
    let p = image.get_pixel(32, 32);
    ([p[0], p[1], p[2]], settings.background_srgb8)
}

#[test]
fn a_single_sided_floor_is_seen_from_above_only() {
    let scene = floor(false);
    assert!(scene.every_material_single_sided());
    let (above, background) = centre_pixel(&scene, &camera(true));
    assert!(above.iter().all(|&c| c > 100), "lit floor from above: {above:?}");
    let (below, background_below) = centre_pixel(&scene, &camera(false));
    assert_eq!(
        below, background_below,
        "a back face was drawn: {below:?} (background {background:?})"
    );
}

#[test]
fn a_double_sided_floor_shows_its_lit_underside() {
    let scene = floor(true);
    assert!(!scene.every_material_single_sided());
    let (below, background) = centre_pixel(&scene, &camera(false));
    assert!(
        below.iter().all(|&c| c > 100),
        "lit underside: {below:?} (background {background:?})"
    );
}

// Closed meshes: per-vertex frames cull the back faces of meshes that enclose volume with
// their faces turned outward (`scene::encloses_outward`) when the camera is outside their
// bounds and the near plane's reach, whatever their materials say. From outside nothing
// changes but ties at silhouettes; from inside, or through a cut of the near plane, the
// back faces are what shows and must stay.

/// `scene`'s frame per vertex at 160 × 90 from `camera` (back faces of closed meshes
/// culled where hidden, or never), and how many objects the renderer saw from outside.
fn per_vertex_frame(scene: &Scene, camera: &Camera, culling: bool) -> (image::RgbaImage, usize, [u8; 3]) {
    let gpu = common::gpu().expect("a GPU adapter");
    let mut settings = RenderSettings::default();
    settings.shadows.per_vertex = true;
    let (image, renderer) = common::drawn_with(&gpu, (scene, &[]), &settings, (camera, [160, 90]), |r| {
        r.set_back_face_culling(culling)
    });
    (image, renderer.objects_seen_from_outside(), settings.background_srgb8)
}

/// A scene of `objects` (double-sided, white) lit by a lamp at `lamp`.
fn lit_objects(objects: Vec<lightpaint::scene::MeshObject>, lamp: Vec3) -> Scene {
    Scene {
        objects,
        materials: vec![Material {
            base_color: Vec4::new(0.8, 0.8, 0.8, 1.0),
            metallic: 0.0,
            ..Material::default()
        }],
        lights: vec![common::scenes::white_light(LightKind::Point, lamp, 20.0)],
        ..Scene::default()
    }
}

fn pixels_of(image: &image::RgbaImage, colour: [u8; 3]) -> usize {
    image.pixels().filter(|p| [p[0], p[1], p[2]] == colour).count()
}

#[test]
fn a_closed_room_seen_from_inside_keeps_its_walls() {
    let room = shapes::cuboid(Vec3::new(2.0, 1.5, 2.0)).into_object("room");
    let scene = lit_objects(vec![room], Vec3::new(0.0, 1.0, 0.0));
    let camera = Camera::looking_at(Vec3::new(0.3, 0.2, 1.2), Vec3::new(-0.5, -0.3, -2.0), 1.2, 0.05);
    let (image, outside, background) = per_vertex_frame(&scene, &camera, true);
    assert_eq!(outside, 0, "the camera is inside the room");
    assert_eq!(pixels_of(&image, background), 0, "a wall went missing");
}

#[test]
fn a_box_cut_by_the_near_plane_shows_its_inside() {
    let crate_box = shapes::cuboid(Vec3::splat(0.5)).into_object("box");
    // A lamp inside (outside, the box would shadow its own inside).
    let scene = lit_objects(vec![crate_box], Vec3::new(0.1, 0.2, -0.1));
    // 5 cm in front of the box's face, with the near plane 20 cm out: the face is clipped
    // away and the far walls' insides show through the cut.
    let camera = Camera::looking_at(Vec3::new(0.0, 0.0, 0.55), Vec3::ZERO, 0.8, 0.2);
    let (image, outside, background) = per_vertex_frame(&scene, &camera, true);
    assert_eq!(outside, 0, "the near plane reaches into the box");
    let centre = image.get_pixel(80, 45);
    assert_ne!(
        [centre[0], centre[1], centre[2]],
        background,
        "the box's inside went missing"
    );
    assert!(centre[0] > 40, "the far wall's inside is lit: {centre:?}");
}

#[test]
fn closed_meshes_seen_from_outside_draw_as_with_their_back_faces() {
    let tube = shapes::tube_along(
        |t| Vec3::new(-1.0 + 2.0 * t, 0.6 + 0.3 * (6.0 * t).sin(), 0.0),
        12,
        0.05,
        6,
    );
    let objects = vec![
        shapes::plane(6.0, 24, 1.0).into_object("floor"),
        shapes::torus(0.5, 0.1, 48, 12)
            .transformed(glam::Affine3A::from_translation(Vec3::new(1.2, 0.6, -0.8)))
            .into_object("torus"),
        tube.into_object("tube"),
        shapes::cuboid(Vec3::splat(0.3))
            .transformed(glam::Affine3A::from_translation(Vec3::new(-1.2, 0.3, -0.6)))
            .into_object("box"),
    ];
    let scene = lit_objects(objects, Vec3::new(0.5, 3.0, 1.0));
    let camera = Camera::looking_at(Vec3::new(0.0, 2.0, 4.0), Vec3::new(0.0, 0.4, 0.0), 0.9, 0.05);
    let (culled, outside, _) = per_vertex_frame(&scene, &camera, true);
    let (drawn, none, _) = per_vertex_frame(&scene, &camera, false);
    assert_eq!(
        (outside, none),
        (3, 0),
        "the torus, the tube and the box are closed; the floor is not"
    );
    // Where a back face meets a front face along a silhouette their depths tie, and the
    // one drawn later may win the pixel: a few pixels of the outlines, no more.
    let differing = culled
        .pixels()
        .zip(drawn.pixels())
        .filter(|(p, q)| (0..3).any(|c| p[c].abs_diff(q[c]) > 2))
        .count();
    assert!(
        differing * 500 <= (160 * 90) as usize,
        "{differing} of {} pixels differ",
        160 * 90
    );
}
