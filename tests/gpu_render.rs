//! The wgpu renderer on a real adapter (lavapipe in CI), checked against values computed
//! here from the documented model: Lambert radiance E·ρ/π, ×2^EV, the ACES-fit tone curve,
//! sRGB encode.

mod common;

use std::f64::consts::PI;

use glam::Vec3;
use lightpaint::render::render_image;
use lightpaint::scene::Scene;
use lightpaint::scene::gltf_write::LightSpec;
use lightpaint::shading::RenderSettings;

fn load_glb(bytes: &[u8]) -> (tempfile::TempDir, Scene) {
    let dir = tempfile::tempdir().expect("temp dir");
    let path = dir.path().join("scene.glb");
    std::fs::write(&path, bytes).expect("write glb");
    let scene = Scene::load(&path).expect("fixture loads");
    (dir, scene)
}

fn assert_close_8bit(actual: u8, expected: f64, what: &str) {
    assert!(
        (actual as f64 - expected).abs() <= 1.0,
        "{what}: pixel {actual}, expected {expected:.2} (within 1/255)"
    );
}

#[test]
fn adapter_is_found_and_named() {
    let Some(gpu) = common::gpu() else { return };
    println!("adapter: {}", gpu.adapter_summary());
    assert!(!gpu.adapter_info.name.is_empty());
}

#[test]
fn plane_under_lights_matches_lambert_through_the_tone_curve() {
    let Some(gpu) = common::gpu() else { return };
    let background = [10u8, 100, 200];
    let white = [1.0, 1.0, 1.0];
    // Directional light of 2 lux straight down: radiance 2/π everywhere on the plane.
    // Point light of 8 cd 2 m above the centre: irradiance 8/2² = 2 lux at the centre.
    let cases = [
        (
            "directional",
            LightSpec::Directional {
                color: white,
                illuminance_lux: 2.0,
            },
            2.0 / PI,
        ),
        (
            "point",
            LightSpec::Point {
                color: white,
                intensity_cd: 8.0,
            },
            2.0 / PI,
        ),
    ];
    for (name, light, radiance) in cases {
        let (_dir, scene) = load_glb(&common::scenes::white_plane(light, Vec3::new(0.0, 2.0, 0.0)));
        for exposure_ev in [0.0f32, 1.5] {
            let settings = RenderSettings {
                exposure_ev,
                background_srgb8: background,
                ..RenderSettings::default()
            };
            let image = render_image(&gpu, &scene, &scene.initial_camera(), &settings, 64, 48).expect("render");
            let centre = image.get_pixel(32, 24);
            let expected = common::expected_8bit(radiance, exposure_ev as f64);
            for channel in 0..3 {
                assert_close_8bit(
                    centre[channel],
                    expected,
                    &format!("{name} light, EV {exposure_ev}, centre"),
                );
            }
            // The plane spans ±1 m; at 5 m with a 40° field the corners look past it.
            let corner = image.get_pixel(0, 0);
            for channel in 0..3 {
                assert_close_8bit(corner[channel], background[channel] as f64, "background corner");
            }
        }
    }
}

#[test]
fn point_light_falls_off_with_the_inverse_square_and_cosine() {
    let Some(gpu) = common::gpu() else { return };
    let white = [1.0, 1.0, 1.0];
    let intensity_cd = 2.0f64;
    let height = 1.0f64;
    let (_dir, scene) = load_glb(&common::scenes::white_plane(
        LightSpec::Point {
            color: white,
            intensity_cd: intensity_cd as f32,
        },
        Vec3::new(0.0, height as f32, 0.0),
    ));
    let (width, pixels_high) = (200u32, 200u32);
    let image = render_image(
        &gpu,
        &scene,
        &scene.initial_camera(),
        &RenderSettings::default(),
        width,
        pixels_high,
    )
    .expect("render");
    // A pixel's world position on the plane: the camera looks straight down from y = 5 with
    // a 40° vertical field; image right is +x.
    let half_extent = 5.0 * (20f64.to_radians()).tan();
    for px in [100u32, 110, 120, 130] {
        let x = ((px as f64 + 0.5) / width as f64 * 2.0 - 1.0) * half_extent;
        let distance2 = x * x + height * height;
        let cos_incidence = height / distance2.sqrt();
        let radiance = intensity_cd / distance2 * cos_incidence / PI;
        let expected = common::expected_8bit(radiance, 0.0);
        assert_close_8bit(image.get_pixel(px, 100)[0], expected, &format!("x = {x:.3} m"));
    }
}

#[test]
fn bundled_sample_renders_lit_and_varied() {
    let Some(gpu) = common::gpu() else { return };
    let scene = Scene::load(&common::repo_path(lightpaint::samples::SAMPLE_SCENE)).expect("sample loads");
    let image = render_image(
        &gpu,
        &scene,
        &scene.initial_camera(),
        &RenderSettings::default(),
        320,
        180,
    )
    .expect("render");
    let luminance: Vec<f64> = image
        .pixels()
        .map(|p| 0.2126 * p[0] as f64 + 0.7152 * p[1] as f64 + 0.0722 * p[2] as f64)
        .collect();
    let mean = luminance.iter().sum::<f64>() / luminance.len() as f64;
    let distinct: std::collections::HashSet<[u8; 4]> = image.pixels().map(|p| p.0).collect();
    assert!((40.0..200.0).contains(&mean), "mean luminance {mean}");
    assert!(distinct.len() > 1000, "only {} distinct colours", distinct.len());
}

/// Sphere and disk lights, saved in a project and reopened, against closed forms: a sphere
/// wholly above the horizon irradiates like a point, E = I/h²; a Lambertian disk of
/// luminance L and radius R at height h gives E = π·L·R²/(h² + R²) on its axis (the
/// renderer's far-field model differs by R²/h², 0.25 % here).
#[test]
fn sphere_and_disk_lights_match_their_closed_forms() {
    use lightpaint::project::Document;
    use lightpaint::scene::{Light, LightKind};
    let Some(gpu) = common::gpu() else { return };
    let dir = tempfile::tempdir().unwrap();
    let scene_path = dir.path().join("plane.glb");
    let white = [1.0, 1.0, 1.0];
    let glb = common::scenes::white_plane(
        LightSpec::Directional {
            color: white,
            illuminance_lux: 0.0,
        },
        Vec3::Y,
    );
    std::fs::write(&scene_path, glb).unwrap();
    let height = 2.0f64;
    let (radius, luminance_nt) = (0.1f64, 60.0f64);
    let light = |kind, intensity: f64| Light {
        name: "test".into(),
        kind,
        color: glam::Vec3::ONE,
        intensity: intensity as f32,
        position: glam::Vec3::new(0.0, height as f32, 0.0),
        direction: glam::Vec3::NEG_Y,
        range: None,
    };
    let cases = [
        (
            light(LightKind::Sphere { radius_m: 0.3 }, 2.5),
            2.5 / (height * height) / PI,
        ),
        (
            light(
                LightKind::Disk {
                    radius_m: radius as f32,
                },
                luminance_nt,
            ),
            PI * luminance_nt * radius * radius / (height * height + radius * radius) / PI,
        ),
    ];
    for (light, radiance) in cases {
        let mut document = Document::open(&scene_path).unwrap();
        document.scene.lights = vec![light.clone()];
        let project = dir.path().join("lights.lightpaint");
        document.save(&project).unwrap();
        let reopened = Document::open(&project).unwrap();
        assert_eq!(reopened.scene.lights, vec![light.clone()]);
        let image = render_image(
            &gpu,
            &reopened.scene,
            &reopened.scene.initial_camera(),
            &reopened.settings,
            64,
            48,
        )
        .expect("render");
        let expected = common::expected_8bit(radiance, 0.0);
        assert_close_8bit(image.get_pixel(32, 24)[0], expected, light.kind.label());
    }
}

/// A uniform environment of radiance L₀ irradiates any surface with E = π·L₀, so a white
/// Lambertian plane shows L₀ itself.
#[test]
fn a_uniform_environment_lights_a_white_plane_with_its_radiance() {
    let Some(gpu) = common::gpu() else { return };
    let white = [1.0, 1.0, 1.0];
    let (_dir, mut scene) = load_glb(&common::scenes::white_plane(
        LightSpec::Directional {
            color: white,
            illuminance_lux: 0.0,
        },
        Vec3::Y,
    ));
    let radiance = 0.35;
    scene.environment = Some(lightpaint::scene::Environment::uniform([radiance; 3]));
    let image = render_image(
        &gpu,
        &scene,
        &scene.initial_camera(),
        &RenderSettings::default(),
        64,
        48,
    )
    .expect("render");
    assert_close_8bit(
        image.get_pixel(32, 24)[1],
        common::expected_8bit(radiance, 0.0),
        "uniform environment",
    );
}
