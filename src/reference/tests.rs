//! The path tracer against closed forms: a point light's irradiance, a white furnace, a
//! uniform sky, a sphere light whose error falls like 1/√spp; and its determinism.

use std::f64::consts::PI;

use glam::{DVec3, Vec3, Vec4};

use super::*;
use crate::scene::{Environment, LightKind, Material, shapes};

/// A Lambertian material of albedo `rho` (no specular) emitting `emissive`.
fn lambert(rho: f32, emissive: f32) -> Material {
    Material {
        base_color: Vec4::new(rho, rho, rho, 1.0),
        metallic: 0.0,
        specular: 0.0,
        emissive: Vec3::splat(emissive),
        ..Material::default()
    }
}

/// Mean radiance of `n` paths straight down from (x, 1, z) onto the floor point (x, 0, z).
fn mean_radiance_below(tracer: &PathTracer, x: f32, z: f32, n: usize, seed: u64) -> f64 {
    let mut random = SplitMix64(seed);
    let sum: f64 = (0..n)
        .map(|_| {
            tracer
                .radiance(Vec3::new(x, 1.0, z), Vec3::NEG_Y, 0.0, f32::INFINITY, &mut random)
                .expect("the ray meets the floor")
                .x
        })
        .sum();
    sum / n as f64
}

#[test]
fn a_point_light_over_a_lambertian_floor_gives_rho_over_pi_times_its_irradiance() {
    let scene = Scene::lambert_floor_under_point_light(4, Vec3::new(0.3, 1.5, -0.2), 7.0);
    let tracer = PathTracer::new(&scene, 0);
    for (x, z) in [(0.0f32, 0.0f32), (0.6, 0.4), (-0.7, -0.5)] {
        let offset = (Vec3::new(0.3, 1.5, -0.2) - Vec3::new(x, 0.0, z)).as_dvec3();
        let irradiance = 7.0 * (offset.y / offset.length()) / offset.length_squared();
        let expected = irradiance / PI;
        // A delta light and a direct-only path: every sample is the exact value.
        let l = mean_radiance_below(&tracer, x, z, 8, 1);
        assert!((l - expected).abs() < 1e-5 * expected, "({x}, {z}): {l} vs {expected}");
    }
}

/// A closed box of albedo `rho` emitting `emissive`, its floor at y = 0 (seen from inside).
fn furnace(rho: f32, emissive: f32) -> Scene {
    let centre_up = glam::Affine3A::from_translation(Vec3::new(0.0, 2.0, 0.0));
    Scene {
        objects: vec![
            shapes::cuboid(Vec3::splat(2.0))
                .transformed(centre_up)
                .into_object("box"),
        ],
        materials: vec![lambert(rho, emissive)],
        ..Default::default()
    }
}

#[test]
fn a_white_furnace_sums_the_neumann_series_of_its_bounces() {
    // Inside a closed emitter of radiance Le and albedo ρ the radiance is uniform:
    // L = Le·Σ_{k=0}^{B+1} ρ^k with B bounces (B + 1 reflections at most).
    let (rho, le) = (0.6f32 as f64, 1.0f64);
    let scene = furnace(rho as f32, le as f32);
    for bounces in [0u32, 1, 2, 8] {
        let tracer = PathTracer::new(&scene, bounces);
        let expected: f64 = (0..=bounces + 1).map(|k| le * rho.powi(k as i32)).sum();
        let l = mean_radiance_below(&tracer, 0.2, 0.1, 20_000, 3);
        // Zero variance until Russian roulette starts at the third reflection.
        let tolerance = if bounces < 2 { 1e-9 } else { 0.01 };
        assert!(
            (l - expected).abs() <= tolerance * expected,
            "B = {bounces}: {l} vs {expected}"
        );
    }
    let converged = mean_radiance_below(&PathTracer::new(&scene, MAX_BOUNCES), 0.2, 0.1, 20_000, 4);
    let limit = le / (1.0 - rho);
    assert!(
        (converged - limit).abs() < 0.01 * limit,
        "{converged} vs Le/(1 − ρ) = {limit}"
    );
}

#[test]
fn a_floor_under_a_uniform_sky_reflects_rho_times_the_sky() {
    let scene = Scene {
        objects: vec![shapes::plane(2.0, 1, 1.0).into_object("floor")],
        materials: vec![lambert(0.5, 0.0)],
        environment: Some(Environment::uniform([2.0, 2.0, 2.0])),
        ..Default::default()
    };
    let l = mean_radiance_below(&PathTracer::new(&scene, 0), 0.1, 0.2, 64, 2);
    assert!((l - 1.0).abs() < 1e-5, "{l}");
}

#[test]
fn the_error_under_a_sphere_light_falls_like_one_over_root_spp() {
    let mut scene = Scene::lambert_floor_under_point_light(1, Vec3::new(0.0, 1.0, 0.0), 3.0);
    scene.lights[0].kind = LightKind::Sphere { radius_m: 0.9 };
    // Wholly above the floor at (0.4, 0, 0): E = I·cos θ/d².
    let offset = DVec3::new(-0.4, 1.0, 0.0);
    let expected = 3.0 * (offset.y / offset.length()) / offset.length_squared() / PI;
    let tracer = PathTracer::new(&scene, 0);
    let rms_error = |spp: usize| {
        let trials = 400;
        let squares: f64 = (0..trials)
            .map(|t| (mean_radiance_below(&tracer, 0.4, 0.0, spp, 100 + t as u64) - expected).powi(2))
            .sum();
        (squares / trials as f64).sqrt()
    };
    let (coarse, fine) = (rms_error(4), rms_error(64));
    let ratio = coarse / fine;
    // 16× the samples: 4× less error (the trials' own noise allows ±20 %).
    assert!(
        (3.2..4.8).contains(&ratio),
        "rms {coarse} at 4 spp, {fine} at 64 spp: ratio {ratio}"
    );
    assert!(fine < 0.05 * expected, "{fine} vs {expected}");
}

fn small_scene() -> (Scene, Camera) {
    let mut scene = Scene::lambert_floor_under_point_light(2, Vec3::new(0.2, 1.0, 0.1), 4.0);
    scene.lights[0].kind = LightKind::Sphere { radius_m: 0.2 };
    scene.objects.push(
        shapes::uv_sphere(0.3, 12, 6)
            .transformed(glam::Affine3A::from_translation(Vec3::new(0.0, 0.3, 0.0)))
            .into_object("ball"),
    );
    let camera = Camera::framing(&scene.bounds());
    (scene, camera)
}

#[test]
fn the_same_seed_gives_the_same_image_on_any_number_of_threads() {
    let (scene, camera) = small_scene();
    let settings = ReferenceSettings {
        samples_per_pixel: 3,
        bounces: 2,
        seed: 9,
    };
    let render_on = |threads: usize| {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .expect("a pool");
        pool.install(|| render_reference(&scene, &camera, 24, 16, &settings, |_| {}))
    };
    let (one, two) = (render_on(1), render_on(2));
    assert_eq!(one, two);
    assert_eq!(one.samples_per_pixel, 3);
    assert_eq!(one.discarded_samples, 0);
    assert!(one.coverage.contains(&1.0) && one.radiance.iter().all(|r| r.is_finite()));
    let other = render_reference(
        &scene,
        &camera,
        24,
        16,
        &ReferenceSettings { seed: 10, ..settings },
        |_| {},
    );
    assert_ne!(one.radiance, other.radiance, "another seed draws other paths");
}

/// A captured floor point that lies inside a box standing on the floor (as where a depth
/// test kept the wrong side of a crack) is lit by nothing as captured; as the eye sees it
/// it becomes the box's face in front of it, lit by the point light. A point the eye sees
/// keeps its place and takes the face normal of its triangle.
#[test]
fn captured_points_are_taken_as_the_eye_sees_them() {
    let mut scene = Scene::lambert_floor_under_point_light(4, Vec3::new(0.0, 1.5, 1.5), 7.0);
    scene.objects.push(
        shapes::cuboid(Vec3::splat(0.25))
            .transformed(glam::Affine3A::from_translation(Vec3::new(0.0, 0.25, 0.0)))
            .into_object("box"),
    );
    let tracer = PathTracer::new(&scene, 0);
    let eye = Vec3::new(0.0, 0.3, 2.0);
    let floor_point = |position: Vec3| SurfaceHit {
        position,
        geometric_normal: Vec3::Y,
        normal: Vec3::Y,
        reflectance: crate::scene::Reflectance {
            k_d: DVec3::splat(0.5),
            k_s: DVec3::ZERO,
            phong_exponent: 1.0,
        },
        emissive: DVec3::ZERO,
    };
    let radiance = |surface: SurfaceHit| {
        let mut random = SplitMix64(3);
        tracer.radiance_leaving(surface, (eye - surface.position).normalize(), &mut random)
    };
    // 1 cm inside the box's front face (z = 0.25).
    let hidden = floor_point(Vec3::new(0.0, 0.0, 0.24));
    assert_eq!(radiance(hidden), DVec3::ZERO);
    let seen = tracer.as_seen_from(eye, hidden);
    assert!((seen.position.z - 0.25).abs() < 1e-4, "{:?}", seen.position);
    assert!(seen.geometric_normal.z > 0.99, "{:?}", seen.geometric_normal);
    assert!(radiance(seen).x > 0.0);
    // In front of the box: kept where it is, with the floor's face normal.
    let visible = SurfaceHit {
        normal: Vec3::new(0.3, 0.95, 0.0).normalize(),
        ..floor_point(Vec3::new(0.0, 0.0, 0.6))
    };
    let kept = tracer.as_seen_from(eye, visible);
    assert_eq!(kept.position, visible.position);
    assert_eq!(kept.normal, visible.normal);
    assert!((kept.geometric_normal - Vec3::Y).length() < 1e-5);
}
