//! Numerical stability at the extremes, in the reduced form CI runs: for each case the f64
//! CPU shading of every visible point is finite, non-negative and never brighter than the
//! unshadowed light (shadows only take light away), and the f32 GPU frame agrees with it.
//! Cases: 10,000 blockers, coincident blockers, a blocker touching the receiver, a receiver
//! inside a blocker, scene scales of 1e-4 and 1e4, intensities 0 and 1e6, a grazing light,
//! and order 8 with HYB in f32.

mod common;

use glam::{DVec3, Vec3};
use lightpaint::blockers::Sphere;
use lightpaint::render::cpu::{self, ShadingInputs};
use lightpaint::render::gpu_types::GpuLight;
use lightpaint::render::{
    GpuContext, RenderSettings, ShadowFrame, ShadowSettings, capture_surfaces, render_logsh_image, shade_surfaces,
};
use lightpaint::scene::{Camera, Light, LightKind, Material, Scene, shapes};
use lightpaint::sh::ExpMethod;

const SIZE: (u32, u32) = (64, 48);

/// A 4 m matte floor under one light, seen from above, everything scaled by `scale`.
struct Case {
    name: String,
    scene: Scene,
    camera: Camera,
    blockers: Vec<Sphere>,
    shadows: ShadowSettings,
}

fn case(name: &str, light: Light, blockers: Vec<Sphere>, scale: f32) -> Case {
    let mut scene = Scene {
        objects: vec![shapes::plane(4.0 * scale, 8, 1.0).into_object("floor")],
        materials: vec![Material {
            metallic: 0.0,
            roughness: 0.5,
            ..Material::default()
        }],
        lights: vec![Light {
            position: light.position * scale,
            // Same irradiance at every scale: candela fall off with the distance squared.
            intensity: if light.kind == LightKind::Directional {
                light.intensity
            } else {
                light.intensity * scale * scale
            },
            ..light
        }],
        ..Default::default()
    };
    scene.lights[0].name = "light".into();
    let position = Vec3::new(0.0, 3.0, 2.5) * scale;
    let forward = (-position).normalize();
    let camera = Camera {
        position,
        forward,
        up: forward.cross(Vec3::Y).cross(forward).normalize(),
        yfov_rad: 0.9,
        znear: 0.01 * scale,
        zfar: None,
    };
    Case {
        name: name.into(),
        scene,
        camera,
        blockers: blockers
            .into_iter()
            .map(|b| Sphere {
                center: b.center * scale,
                radius_m: b.radius_m * scale,
            })
            .collect(),
        shadows: ShadowSettings::default(),
    }
}

fn point_light(position: Vec3, intensity: f32) -> Light {
    Light {
        name: String::new(),
        kind: LightKind::Point,
        color: Vec3::ONE,
        intensity,
        position,
        direction: Vec3::NEG_Y,
        range: None,
    }
}

fn sphere(x: f32, y: f32, z: f32, r: f32) -> Sphere {
    Sphere {
        center: Vec3::new(x, y, z),
        radius_m: r,
    }
}

fn checks(gpu: &GpuContext, case: &Case) {
    let settings = RenderSettings::default();
    let (width, height) = SIZE;
    let frame = ShadowFrame {
        baked_indirect: None,
        scene: &case.scene,
        camera: &case.camera,
        settings: &settings,
        shadows: &case.shadows,
        blockers: &case.blockers,
        width,
        height,
    };
    let surfaces = capture_surfaces(gpu, &case.scene, &case.camera, None, width, height).expect("surfaces");
    let lights: Vec<GpuLight> = case.scene.lights.iter().map(GpuLight::new).collect();
    let no_environment = [[0.0f32; 4]; 9];
    let inputs = ShadingInputs {
        lights: &lights,
        environment_irradiance: &no_environment,
        blockers: &case.blockers,
        settings: &case.shadows,
        eye: case.camera.position.as_dvec3(),
    };
    let unlit = ShadingInputs {
        blockers: &[],
        ..inputs
    };
    let mut seen = 0;
    for s in surfaces.iter().flatten() {
        seen += 1;
        let (shadowed, unshadowed) = (cpu::shadowed_radiance(s, &inputs), cpu::shadowed_radiance(s, &unlit));
        assert!(
            shadowed.is_finite() && shadowed.min_element() >= 0.0,
            "{}: {shadowed} at {}",
            case.name,
            s.position
        );
        let bound = unshadowed * (1.0 + 1e-9) + DVec3::splat(1e-12);
        assert!(
            shadowed.cmple(bound).all(),
            "{}: shadowed {shadowed} brighter than unshadowed {unshadowed} at {}",
            case.name,
            s.position
        );
    }
    assert!(
        seen > (width * height / 2) as usize,
        "{}: the floor fills the view ({seen} px)",
        case.name
    );
    let cpu_image = shade_surfaces(&surfaces, &frame).expect("CPU frame");
    let gpu_image = render_logsh_image(gpu, &frame, 1).expect("GPU frame");
    let differences: Vec<u8> = gpu_image
        .pixels()
        .zip(cpu_image.pixels())
        .map(|(a, b)| (0..3).map(|c| a[c].abs_diff(b[c])).max().unwrap_or(0))
        .collect();
    let within = differences.iter().filter(|&&d| d <= 2).count() as f64 / differences.len() as f64;
    let worst = differences.iter().copied().max().unwrap_or(0);
    eprintln!(
        "{}: {:.2} % of pixels within 2/255 of f64, worst {worst}/255",
        case.name,
        100.0 * within
    );
    assert!(
        within >= 0.99,
        "{}: only {:.2} % within 2/255 (worst {worst})",
        case.name,
        100.0 * within
    );
}

#[test]
fn shading_stays_finite_bounded_and_matches_f64_at_the_extremes() {
    let Some(gpu) = common::gpu() else { return };
    let bulb = point_light(Vec3::new(0.3, 2.0, 0.2), 4.0);
    let ball = vec![sphere(0.0, 0.6, 0.0, 0.35)];
    // A fixed low-discrepancy swarm (Weyl sequences), no generator needed.
    let swarm: Vec<Sphere> = (0..10_000)
        .map(|k| {
            let u = |a: f64| ((k as f64 + 0.5) * a).fract() as f32;
            sphere(
                4.0 * u(0.618_034) - 2.0,
                0.3 + 1.2 * u(0.754_878),
                4.0 * u(0.569_840) - 2.0,
                0.01 + 0.03 * u(0.414_214),
            )
        })
        .collect();
    let mut cases = vec![
        case("10,000 blockers", bulb.clone(), swarm, 1.0),
        case(
            "coincident blockers",
            bulb.clone(),
            vec![sphere(0.0, 0.6, 0.0, 0.3); 50],
            1.0,
        ),
        case(
            "a blocker touching the receiver",
            bulb.clone(),
            vec![sphere(0.2, 0.3, 0.0, 0.3)],
            1.0,
        ),
        case(
            "the receiver inside a blocker",
            bulb.clone(),
            vec![sphere(0.0, 0.0, 0.0, 0.8)],
            1.0,
        ),
        case("scale 1e-4", bulb.clone(), ball.clone(), 1e-4),
        case("scale 1e4", bulb.clone(), ball.clone(), 1e4),
        case("intensity 0", point_light(bulb.position, 0.0), ball.clone(), 1.0),
        case("intensity 1e6", point_light(bulb.position, 1e6), ball.clone(), 1.0),
        case(
            "a grazing light",
            Light {
                kind: LightKind::Directional,
                direction: Vec3::new(1.0, -0.002, 0.0).normalize(),
                intensity: 3.0,
                ..bulb.clone()
            },
            ball.clone(),
            1.0,
        ),
    ];
    let mut order8 = case(
        "order 8, HYB, f32",
        bulb,
        vec![
            sphere(0.0, 0.6, 0.0, 0.35),
            sphere(0.5, 0.3, 0.4, 0.25),
            sphere(-0.6, 0.9, -0.2, 0.3),
        ],
        1.0,
    );
    order8.shadows = ShadowSettings {
        order: 8,
        exp: ExpMethod::Hyb,
        ..ShadowSettings::default()
    };
    cases.push(order8);
    for case in &cases {
        checks(&gpu, case);
    }
}
