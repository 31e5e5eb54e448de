//! The baked importance maps against the reference path tracer: light transport is linear
//! in the intensities, so Σ_i P_i·t_{i,v} (the maps' shading of every light at unit
//! intensity, scaled by its intensity) must equal the path-traced luminance of the vertex
//! with all lights on — direct light through exact visibility and one bounce — within the
//! path tracer's sampling noise and the maps' SH truncation.

use std::f64::consts::PI;

use glam::{Affine3A, DVec3, Quat, Vec3, Vec4};
use lightpaint::bake::{BakeSettings, bake_maps};
use lightpaint::paint::{BakedTransfer, Transfer, VertexRef};
use lightpaint::random::SplitMix64;
use lightpaint::reference::{PathTracer, SurfaceHit};
use lightpaint::scene::{Light, LightKind, Material, Reflectance, Scene, luminance, shapes};

const ORDER: usize = 8;
const FLOOR_ALBEDO: f32 = 0.8;

/// A Lambertian floor (4 m, 8 × 8 quads) beside a white wall that bounces light back onto
/// it, a box hovering over it that casts shadows, under a coloured point light and a
/// sphere light of different intensities.
fn scene() -> Scene {
    let lambert = |value: f32| Material {
        name: format!("lambert {value}"),
        base_color: Vec4::new(value, value, value, 1.0),
        metallic: 0.0,
        specular: 0.0,
        ..Material::default()
    };
    let floor = shapes::plane(4.0, 8, 1.0).into_object("floor");
    let mut wall = shapes::plane(4.0, 8, 1.0)
        .transformed(Affine3A::from_rotation_translation(
            Quat::from_rotation_z(-std::f32::consts::FRAC_PI_2),
            Vec3::new(-2.0, 2.0, 0.0),
        ))
        .into_object("wall");
    wall.material = 1;
    let mut block = shapes::cuboid(Vec3::new(0.4, 0.2, 0.4))
        .transformed(Affine3A::from_translation(Vec3::new(0.3, 1.0, 0.2)))
        .into_object("block");
    block.material = 1;
    let light = |name: &str, kind: LightKind, color: Vec3, intensity: f32, position: Vec3| Light {
        name: name.into(),
        kind,
        color,
        intensity,
        position,
        direction: Vec3::NEG_Y,
        range: None,
        locked: false,
    };
    Scene {
        objects: vec![floor, wall, block],
        materials: vec![lambert(FLOOR_ALBEDO), lambert(0.9)],
        lights: vec![
            light(
                "bulb",
                LightKind::Point,
                Vec3::new(1.0, 0.85, 0.7),
                6.0,
                Vec3::new(0.6, 2.4, 0.5),
            ),
            light(
                "globe",
                LightKind::Sphere { radius_m: 0.25 },
                Vec3::new(0.6, 0.8, 1.0),
                3.0,
                Vec3::new(-0.8, 1.8, -0.6),
            ),
        ],
        ..Scene::default()
    }
}

/// The largest error of the order-`order` Legendre truncation of max(t, 0) on [−1, 1]:
/// max(t, 0) = Σ_l (2l + 1)/2·a_l·P_l(t), a_l = ∫₀¹ x·P_l(x) dx. A map is exact for the
/// light it holds up to that order, so shading it errs by at most this share of the
/// light's ∫ L dω (lights and radiance are non-negative).
fn clamped_cosine_truncation_error(order: usize) -> f64 {
    let legendre = |t: f64| -> Vec<f64> {
        let mut p = vec![1.0, t];
        for l in 1..order {
            p.push(((2 * l + 1) as f64 * t * p[l] - l as f64 * p[l - 1]) / (l + 1) as f64);
        }
        p
    };
    // a_l by the midpoint rule on [0, 1] (polynomials of degree ≤ order: 20k points is plenty).
    let nodes = 20_000;
    let mut a = vec![0.0; order];
    for k in 0..nodes {
        let x = (k as f64 + 0.5) / nodes as f64;
        for (l, p) in legendre(x).iter().take(order).enumerate() {
            a[l] += x * p / nodes as f64;
        }
    }
    (0..=2000)
        .map(|k| {
            let t = -1.0 + 2.0 * k as f64 / 2000.0;
            let series: f64 = legendre(t)
                .iter()
                .take(order)
                .enumerate()
                .map(|(l, p)| (2 * l + 1) as f64 / 2.0 * a[l] * p)
                .sum();
            (series - t.max(0.0)).abs()
        })
        .fold(0.0, f64::max)
}

#[test]
fn the_maps_scaled_by_the_intensities_match_the_path_traced_vertices() {
    let scene = scene();
    let settings = BakeSettings {
        order: ORDER,
        bounces: 1,
        light_samples: 64,
        indirect_directions: 1024,
        relative_threshold: 0.0,
        ..BakeSettings::default()
    };
    let maps = bake_maps(&scene, &settings);
    let transfer = BakedTransfer::new(&scene, &maps);
    let tracer = PathTracer::new(&scene, 1);
    let truncation = clamped_cosine_truncation_error(ORDER);
    let intensities = scene.light_intensities();
    let light_luminance: Vec<f64> = scene.lights.iter().map(|l| luminance(l.color.as_dvec3())).collect();
    let floor = &scene.objects[0];
    let reflectance = Reflectance::of_material(&scene.materials[0], DVec3::ONE);
    let eye = Vec3::new(0.0, 6.0, 4.0);

    let (mut sum_baked, mut sum_traced, mut checked, mut worst) = (0.0, 0.0, 0, 0.0f64);
    for v in 0..floor.positions.len() {
        let vertex = VertexRef {
            object: 0,
            vertex: v as u32,
        };
        let baked: f64 = transfer
            .vertex_transfer(vertex, eye)
            .iter()
            .map(|&(i, t)| intensities[i as usize] as f64 * t)
            .sum();
        // The light each map holds, ∫ L dω = DC·2√π, bounds what truncation can move.
        let incident: f64 = maps.objects[0]
            .entries(v)
            .map(|e| {
                let i = e.light as usize;
                intensities[i] as f64 * light_luminance[i] * e.sh.dc() as f64 * 2.0 * PI.sqrt()
            })
            .sum();
        let bias = truncation * FLOOR_ALBEDO as f64 / PI * incident;

        let p = floor.positions[v];
        let surface = SurfaceHit {
            position: p,
            geometric_normal: Vec3::Y,
            normal: Vec3::Y,
            reflectance,
            emissive: DVec3::ZERO,
        };
        let to_eye = (eye - p).normalize();
        let samples = 4096;
        let mut random = SplitMix64(v as u64 + 1);
        let (mut sum, mut sum_sq) = (0.0, 0.0);
        for _ in 0..samples {
            let y = luminance(tracer.radiance_leaving(surface, to_eye, &mut random));
            sum += y;
            sum_sq += y * y;
        }
        let traced = sum / samples as f64;
        let standard_error = ((sum_sq / samples as f64 - traced * traced).max(0.0) / samples as f64).sqrt();
        // 4 σ of the path tracer, the truncation bound, and 2 % for the bake's own finite
        // emitter samples and bounce directions.
        let tolerance = 4.0 * standard_error + bias + 0.02 * baked;
        assert!(
            (baked - traced).abs() <= tolerance,
            "vertex {v} at {p}: maps {baked:.5} vs path tracer {traced:.5} (σ {standard_error:.5}, truncation ≤ {bias:.5})"
        );
        worst = worst.max((baked - traced).abs() / tolerance);
        sum_baked += baked;
        sum_traced += traced;
        checked += 1;
    }
    assert_eq!(checked, 81);
    eprintln!(
        "81 floor vertices: maps {sum_baked:.4} vs path tracer {sum_traced:.4} in all; worst vertex used {:.0} % of its tolerance",
        worst * 100.0
    );
    // Over the whole floor the noise averages out: the totals agree far more closely.
    assert!(
        (sum_baked / sum_traced - 1.0).abs() < 0.01,
        "floor total: maps {sum_baked} vs path tracer {sum_traced}"
    );
}
