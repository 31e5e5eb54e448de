//! glTF's `doubleSided`: when every material of a scene is single-sided the renderer culls
//! back faces (glTF 2.0, "Double Sided"), so a single-sided floor seen from below shows
//! the background; a double-sided one shows its lit underside.

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
