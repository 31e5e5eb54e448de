//! Per-vertex shading lights a mesh at its vertices only where the light varies nearly
//! linearly across its triangles (`shading::vertex_lighting`), on lavapipe: without
//! blockers (every vertex's visibility 1) a fine floor under a lamp lit at its vertices
//! looks as it does shaded per pixel, while a single-quad floor under the same lamp keeps
//! per-pixel shading (interpolated from its four corners its hot spot would vanish), and
//! a glossy floor too; a floor lit at its vertices by a sky takes a shadow-mapped lamp
//! per pixel.

mod common;

use glam::Vec3;
use lightpaint::render::{AntiAliasing, ShadowFrame, ShadowRenderer};
use lightpaint::scene::{Camera, Light, LightKind, Material, Scene, shapes};
use lightpaint::shading::{LightPaths, RenderSettings, ShadowSettings};

const WIDTH: u32 = 240;
const HEIGHT: u32 = 135;

/// An 8 m floor of `segments` × `segments` quads, of `roughness`, under a lamp 3 m up.
fn floor_under_a_lamp(segments: u32, roughness: f32) -> Scene {
    let mut scene = Scene::default();
    scene.materials.push(Material {
        base_color: glam::Vec4::new(0.7, 0.7, 0.7, 1.0),
        roughness,
        ..Material::default()
    });
    scene
        .objects
        .push(shapes::plane(8.0, segments, 1.0).into_object("floor"));
    scene.lights.push(Light {
        name: "lamp".into(),
        kind: LightKind::Point,
        color: Vec3::ONE,
        intensity: 30.0,
        position: Vec3::new(0.5, 3.0, 0.3),
        direction: Vec3::NEG_Y,
        range: None,
        locked: false,
    });
    scene
}

/// The frame per vertex and per pixel (every pixel shaded, the lamp on the SH path,
/// no blockers), and how many objects the per-vertex frame lit at their vertices.
fn frames(scene: &Scene) -> Option<(image::RgbaImage, image::RgbaImage, usize)> {
    frames_with(scene, LightPaths::Harmonics)
}

/// [`frames`] with the lights on `light_paths`.
fn frames_with(scene: &Scene, light_paths: LightPaths) -> Option<(image::RgbaImage, image::RgbaImage, usize)> {
    let gpu = common::gpu()?;
    let camera = Camera::looking_at(Vec3::new(0.0, 3.5, 5.0), Vec3::ZERO, 50f32.to_radians(), 0.05);
    let settings = RenderSettings::default();
    let render = |per_vertex| {
        let shadows = ShadowSettings {
            per_vertex,
            light_paths,
            ..ShadowSettings::default().every_pixel()
        };
        let frame = ShadowFrame {
            scene,
            camera: &camera,
            settings: &settings,
            shadows: &shadows,
            blockers: &[],
            baked_indirect: None,
            width: WIDTH,
            height: HEIGHT,
        };
        let mut renderer = ShadowRenderer::new(&gpu, &frame, AntiAliasing::None).expect("renderer");
        let image = renderer.read_image().expect("frame");
        (image, renderer.objects_lit_at_vertices())
    };
    let (per_pixel, _) = render(false);
    let (per_vertex, lit) = render(true);
    Some((per_pixel, per_vertex, lit))
}

/// The largest difference of any channel of any pixel, and the share of pixels within
/// `codes` of each other.
fn compare(a: &image::RgbaImage, b: &image::RgbaImage, codes: u8) -> (u8, f64) {
    let mut worst = 0;
    let mut close = 0;
    for (p, q) in a.pixels().zip(b.pixels()) {
        let d = (0..3).map(|c| p[c].abs_diff(q[c])).max().unwrap_or(0);
        worst = worst.max(d);
        close += usize::from(d <= codes);
    }
    (worst, close as f64 / a.pixels().len() as f64)
}

#[test]
fn a_fine_floor_lit_at_its_vertices_looks_as_it_does_per_pixel() {
    let Some((per_pixel, per_vertex, lit)) = frames(&floor_under_a_lamp(96, 1.0)) else {
        return;
    };
    assert_eq!(lit, 1, "the 96 × 96 floor 3 m under the lamp is lit at its vertices");
    let (worst, share) = compare(&per_pixel, &per_vertex, 1);
    eprintln!("fine floor: worst {worst}/255, {:.2} % within 1/255", 100.0 * share);
    // Interpolating E ∝ 1/d² over 12 cm edges 3 m from the lamp errs by under 0.1 %
    // ((3/8)(L/d)²): a code at most where rounding falls differently.
    assert!(worst <= 2, "{worst}");
    assert!(share > 0.99, "{share}");
}

#[test]
fn a_single_quad_floor_under_the_lamp_keeps_its_hot_spot() {
    let scene = floor_under_a_lamp(1, 1.0);
    let Some((per_pixel, per_vertex, lit)) = frames(&scene) else {
        return;
    };
    assert_eq!(lit, 0, "two triangles 8 m across are shaded per pixel");
    let (worst, _) = compare(&per_pixel, &per_vertex, 0);
    assert!(worst <= 1, "{worst}");
    // What lighting it at its corners would lose: the spot under the lamp is far
    // brighter than the floor's corners, which the interpolation would spread.
    let centre = per_pixel.get_pixel(WIDTH / 2, HEIGHT / 2)[0];
    assert!(centre > 100, "the floor under the lamp is lit: {centre}");
}

#[test]
fn a_glossy_floor_is_shaded_per_pixel() {
    // Roughness 0.4: Phong exponent ≈ 76, whose highlight the 12 cm cells would smear.
    let Some((per_pixel, per_vertex, lit)) = frames(&floor_under_a_lamp(96, 0.4)) else {
        return;
    };
    assert_eq!(lit, 0);
    let (worst, _) = compare(&per_pixel, &per_vertex, 0);
    assert!(worst <= 1, "{worst}");
}

#[test]
fn a_floor_lit_at_its_vertices_by_the_sky_takes_a_shadow_mapped_lamp_per_pixel() {
    // Under Auto the lamp takes a shadow map, shaded per pixel; the sky is on the SH path,
    // whose light the floor takes at its vertices (fs_vertex_lit with the varyings the
    // lamp's shading reads, where frames without such lights draw fs_vertex_lit_alone).
    let mut scene = floor_under_a_lamp(96, 1.0);
    scene.environment = Some(lightpaint::scene::Environment::uniform([0.2, 0.25, 0.3]));
    let Some((per_pixel, per_vertex, lit)) = frames_with(&scene, LightPaths::Auto) else {
        return;
    };
    assert_eq!(lit, 1, "the floor is lit at its vertices by the sky");
    let (worst, share) = compare(&per_pixel, &per_vertex, 1);
    eprintln!(
        "sky and mapped lamp: worst {worst}/255, {:.2} % within 1/255",
        100.0 * share
    );
    assert!(worst <= 2, "{worst}");
    assert!(share > 0.99, "{share}");
    // The lamp's hot spot is there: the floor under it far brighter than at its corners.
    let centre = per_vertex.get_pixel(WIDTH / 2, HEIGHT / 2)[0];
    let corner = per_vertex.get_pixel(2, HEIGHT - 3)[0];
    assert!(centre > corner + 30, "{centre} against {corner}");
}
