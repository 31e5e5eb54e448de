//! The stability suite: the shading at the extremes — 10,000 blockers, coincident
//! blockers, a blocker touching the receiver, a receiver inside a blocker, scene scales of
//! 1e-4 and 1e4, intensities 0 and 1e6, a grazing light, order 8 with HYB in f32. Each case
//! is a 4 m matte floor under one light seen from above; for every visible point the f64
//! shading must be finite, non-negative and never brighter than the unshadowed light
//! (shadows only take light away), and the f32 GPU frame must agree with it. The study
//! reports every case ([`measure`]); `tests/stability.rs` holds them to those laws in CI.

use glam::{DVec3, Vec3};

use crate::blockers::Sphere;
use crate::render::{
    AntiAliasing, GpuContext, RenderError, ShadowFrame, capture_surfaces, render_logsh_image, shade_surfaces,
};
use crate::scene::{Camera, Light, LightKind, Material, Scene, shapes};
use crate::sh::ExpMethod;
use crate::shading::cpu::{self, ShadingInputs};
use crate::shading::{RenderSettings, ShadowSettings};

/// One extreme: a floor, its light, the blockers and the shadow settings.
pub struct StabilityCase {
    pub name: String,
    pub scene: Scene,
    pub camera: Camera,
    pub blockers: Vec<Sphere>,
    pub shadows: ShadowSettings,
}

/// What one case measured.
#[derive(Debug, Clone, PartialEq)]
pub struct StabilityResult {
    pub name: String,
    /// Pixels that see the floor (each checked in f64).
    pub visible_pixels: usize,
    /// Points whose f64 shading is NaN or infinite.
    pub non_finite: usize,
    /// Points whose f64 shading is negative in some channel.
    pub negative: usize,
    /// Points whose f64 shading is brighter than the unshadowed light in some channel.
    pub above_unshadowed: usize,
    /// Share of the pixels where the f32 GPU frame is within 2/255 of the f64 one.
    pub gpu_within_2: f64,
    /// The largest GPU–f64 difference of a displayed channel, out of 255.
    pub gpu_worst: u8,
}

impl StabilityResult {
    /// Whether every law held: finite, non-negative, bounded, and ≥ 99 % of the GPU
    /// pixels within 2/255.
    pub fn holds(&self) -> bool {
        self.non_finite == 0 && self.negative == 0 && self.above_unshadowed == 0 && self.gpu_within_2 >= 0.99
    }
}

/// Every case of the suite.
pub fn stability_cases() -> Vec<StabilityCase> {
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
    let grazing = Light {
        kind: LightKind::Directional,
        direction: Vec3::new(1.0, -0.002, 0.0).normalize(),
        intensity: 3.0,
        ..bulb.clone()
    };
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
        case("a grazing light (0.1°)", grazing, ball, 1.0),
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
        ..ShadowSettings::default().every_pixel()
    };
    cases.push(order8);
    cases
}

/// Renders `case` at `width` × `height` on the GPU and in f64 and checks every visible
/// point against the laws.
pub fn measure(
    gpu: &GpuContext,
    case: &StabilityCase,
    width: u32,
    height: u32,
) -> Result<StabilityResult, RenderError> {
    let settings = RenderSettings::default();
    let frame = ShadowFrame {
        scene: &case.scene,
        camera: &case.camera,
        settings: &settings,
        shadows: &case.shadows,
        blockers: &case.blockers,
        baked_indirect: None,
        width,
        height,
    };
    let surfaces = capture_surfaces(gpu, &case.scene, &case.camera, None, width, height)?;
    let lights = frame.shading_lights();
    let no_environment = [[0.0f32; 4]; 9];
    let inputs = ShadingInputs {
        lights: &lights,
        environment_irradiance: &no_environment,
        blockers: &case.blockers,
        terrain: None,
        settings: &case.shadows,
        eye: case.camera.position.as_dvec3(),
        pixel_angle_rad: crate::shading::gpu_types::pixel_angle_rad(&case.camera, height),
        occluders: None,
    };
    let unlit = ShadingInputs {
        blockers: &[],
        terrain: None,
        ..inputs
    };
    let mut result = StabilityResult {
        name: case.name.clone(),
        visible_pixels: 0,
        non_finite: 0,
        negative: 0,
        above_unshadowed: 0,
        gpu_within_2: 0.0,
        gpu_worst: 0,
    };
    for s in surfaces.iter().flatten() {
        result.visible_pixels += 1;
        let (shadowed, unshadowed) = (cpu::shadowed_radiance(s, &inputs), cpu::shadowed_radiance(s, &unlit));
        if !shadowed.is_finite() {
            result.non_finite += 1;
            continue;
        }
        result.negative += usize::from(shadowed.min_element() < 0.0);
        let bound = unshadowed * (1.0 + 1e-9) + DVec3::splat(1e-12);
        result.above_unshadowed += usize::from(!shadowed.cmple(bound).all());
    }
    let cpu_image = shade_surfaces(&surfaces, &frame)?;
    let gpu_image = render_logsh_image(gpu, &frame, AntiAliasing::None)?;
    let differences: Vec<u8> = gpu_image
        .pixels()
        .zip(cpu_image.pixels())
        .map(|(a, b)| (0..3).map(|c| a[c].abs_diff(b[c])).max().unwrap_or(0))
        .collect();
    result.gpu_within_2 = differences.iter().filter(|&&d| d <= 2).count() as f64 / differences.len().max(1) as f64;
    result.gpu_worst = differences.iter().copied().max().unwrap_or(0);
    Ok(result)
}

/// A 4 m matte floor under `light`, seen from above, everything scaled by `scale`.
fn case(name: &str, light: Light, blockers: Vec<Sphere>, scale: f32) -> StabilityCase {
    let scene = Scene {
        objects: vec![shapes::plane(4.0 * scale, 8, 1.0).into_object("floor")],
        materials: vec![Material {
            metallic: 0.0,
            roughness: 0.5,
            ..Material::default()
        }],
        lights: vec![Light {
            name: "light".into(),
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
    StabilityCase {
        name: name.into(),
        scene,
        camera,
        blockers: blockers
            .into_iter()
            .map(|b| Sphere {
                center: b.center * scale,
                radius_m: b.radius_m * scale,
                disc_normal: b.disc_normal,
            })
            .collect(),
        shadows: ShadowSettings::default().every_pixel(),
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
        locked: false,
    }
}

fn sphere(x: f32, y: f32, z: f32, r: f32) -> Sphere {
    Sphere {
        center: Vec3::new(x, y, z),
        radius_m: r,
        disc_normal: glam::Vec3::ZERO,
    }
}
