//! The reference path tracer in direct-light mode against the real-time log-SH renderer
//! on the GPU, on scenes where nothing casts a shadow: with no blockers the log-visibility
//! is 0 and exp*(0) is exactly the unoccluded visibility at every SH order, so the two
//! must agree up to the path tracer's noise and the pixel footprint (the GPU shades pixel
//! centres, the path tracer averages each pixel).

mod common;

use glam::{Vec3, Vec4};
use lightpaint::reference::{ReferenceSettings, render_reference};
use lightpaint::render::{AntiAliasing, ShadowFrame, render_logsh_image};
use lightpaint::scene::{Camera, Environment, Light, LightKind, Material, Scene, shapes};
use lightpaint::shading::{RenderSettings, ShadowSettings};

const WIDTH: u32 = 96;
const HEIGHT: u32 = 64;

fn light(name: &str, kind: LightKind, position: Vec3, direction: Vec3, intensity: f32, color: Vec3) -> Light {
    Light {
        name: name.into(),
        kind,
        color,
        intensity,
        position,
        direction,
        range: None,
        locked: false,
    }
}

/// A 40 m floor that fills the view of a camera looking down at it.
fn floor_scene(material: Material, lights: Vec<Light>, environment: Option<Environment>) -> (Scene, Camera) {
    let scene = Scene {
        objects: vec![shapes::plane(40.0, 8, 4.0).into_object("floor")],
        materials: vec![material],
        lights,
        environment,
        ..Default::default()
    };
    let position = Vec3::new(0.0, 4.0, 3.0);
    let forward = (Vec3::new(0.0, 0.0, -1.0) - position).normalize();
    let camera = Camera {
        position,
        forward,
        up: forward.cross(Vec3::Y).cross(forward).normalize(),
        yfov_rad: 0.9,
        znear: 0.05,
        zfar: None,
    };
    (scene, camera)
}

/// Mean and 99th percentile of the largest per-channel difference of two images, in
/// 8-bit codes.
fn differences(a: &image::RgbaImage, b: &image::RgbaImage) -> (f64, u8) {
    let mut largest: Vec<u8> = a
        .pixels()
        .zip(b.pixels())
        .map(|(p, q)| (0..3).map(|c| p[c].abs_diff(q[c])).max().unwrap_or(0))
        .collect();
    let mean = largest.iter().map(|&d| d as f64).sum::<f64>() / largest.len() as f64;
    largest.sort_unstable();
    (mean, largest[largest.len() * 99 / 100])
}

fn assert_direct_parity(name: &str, scene: &Scene, camera: &Camera, orders: &[usize]) {
    let Some(gpu) = common::gpu() else { return };
    let settings = RenderSettings::default();
    let reference = render_reference(
        scene,
        camera,
        WIDTH,
        HEIGHT,
        &ReferenceSettings {
            samples_per_pixel: 64,
            bounces: 0,
            seed: 3,
        },
        |_| {},
    );
    assert_eq!(reference.discarded_samples, 0);
    assert!(
        reference.coverage.iter().all(|&c| c == 1.0),
        "{name}: the floor fills the view"
    );
    let reference_image = reference.to_srgb8(0.0, settings.background_srgb8);
    let dir = std::path::Path::new(env!("CARGO_TARGET_TMPDIR")).join("reference_parity");
    let _ = std::fs::create_dir_all(&dir);
    let _ = reference_image.save(dir.join(format!("{name}-reference.png")));
    for &order in orders {
        let shadows = ShadowSettings {
            order,
            ..ShadowSettings::default().every_pixel()
        };
        let frame = ShadowFrame {
            baked_indirect: None,
            scene,
            camera,
            settings: &settings,
            shadows: &shadows,
            blockers: &[],
            width: WIDTH,
            height: HEIGHT,
        };
        let real_time = render_logsh_image(&gpu, &frame, AntiAliasing::Multisample).expect("GPU render");
        let _ = real_time.save(dir.join(format!("{name}-order{order}.png")));
        let (mean, p99) = differences(&real_time, &reference_image);
        eprintln!("{name}, order {order}: mean difference {mean:.2}/255, 99th percentile {p99}/255");
        assert!(
            mean <= 1.0 && p99 <= 4,
            "{name}, order {order}: mean {mean:.2}/255, 99th percentile {p99}/255"
        );
    }
}

#[test]
fn direct_light_of_every_light_type_on_a_glossy_floor_matches_the_real_time_renderer() {
    let glossy = Material {
        base_color: Vec4::new(0.8, 0.7, 0.6, 1.0),
        metallic: 0.0,
        roughness: 0.6,
        ..Material::default()
    };
    let lights = vec![
        light(
            "bulb",
            LightKind::Point,
            Vec3::new(-1.5, 1.2, -1.0),
            Vec3::NEG_Y,
            3.0,
            Vec3::new(1.0, 0.9, 0.8),
        ),
        light(
            "spot",
            LightKind::Spot {
                inner_cone_rad: 0.3,
                outer_cone_rad: 0.6,
            },
            Vec3::new(1.5, 2.0, -1.5),
            Vec3::new(0.0, -1.0, 0.3).normalize(),
            12.0,
            Vec3::new(0.6, 0.8, 1.0),
        ),
        light(
            "globe",
            LightKind::Sphere { radius_m: 0.1 },
            Vec3::new(0.0, 0.8, 0.5),
            Vec3::NEG_Y,
            0.8,
            Vec3::ONE,
        ),
        light(
            "sun",
            LightKind::Directional,
            Vec3::ZERO,
            Vec3::new(0.3, -1.0, -0.2).normalize(),
            0.15,
            Vec3::ONE,
        ),
    ];
    let (scene, camera) = floor_scene(glossy, lights, None);
    assert_direct_parity("lights", &scene, &camera, &[2, 4, 6]);
}

#[test]
fn direct_light_of_the_sky_on_a_matte_floor_matches_the_real_time_renderer() {
    // The real-time renderer reflects the environment diffusely only, so the floor is
    // Lambertian here.
    let matte = Material {
        base_color: Vec4::new(0.7, 0.7, 0.7, 1.0),
        metallic: 0.0,
        specular: 0.0,
        ..Material::default()
    };
    let sky = Environment::load(&common::repo_path("projects/sample/sky.hdr"), 1.0, 0.4).expect("the sample sky");
    let (scene, camera) = floor_scene(matte, vec![], Some(sky));
    assert_direct_parity("sky", &scene, &camera, &[4]);
}
