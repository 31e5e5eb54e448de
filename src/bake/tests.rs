//! Unit tests of the bake (`bake::tests`): maps, sparsity, re-baking, bounces.

use std::f64::consts::PI;

use glam::Vec3;

use super::*;
use crate::scene::shapes::{self, ShapeMesh};
use crate::scene::{Light, LightKind, MeshObject};

fn object(name: &str, mesh: ShapeMesh) -> MeshObject {
    mesh.into_object(name)
}

fn point_light(position: Vec3) -> Light {
    Light {
        name: "bulb".into(),
        kind: LightKind::Point,
        color: Vec3::ONE,
        intensity: 5.0,
        position,
        direction: Vec3::NEG_Y,
        range: None,
        locked: false,
    }
}

/// A 2 cm floor patch at the origin (material 0) and a 40 m ceiling 1 m above it facing
/// down (material 1).
fn patch_and_ceiling() -> [MeshObject; 2] {
    let patch = shapes::plane(0.02, 1, 1.0);
    let ceiling = shapes::plane(40.0, 4, 1.0).transformed(glam::Affine3A::from_rotation_translation(
        glam::Quat::from_rotation_x(std::f32::consts::PI),
        Vec3::Y,
    ));
    let mut ceiling_object = object("ceiling", ceiling);
    ceiling_object.material = 1;
    [object("patch", patch), ceiling_object]
}

/// A 4 m floor of 8×8 quads, a 1 m box hovering over its −x half, a light 3 m up.
fn floor_box_light() -> Scene {
    let floor = shapes::plane(4.0, 8, 1.0);
    let block =
        shapes::cuboid(Vec3::splat(0.5)).transformed(glam::Affine3A::from_translation(Vec3::new(-1.0, 1.5, 0.0)));
    Scene {
        objects: vec![object("floor", floor), object("box", block)],
        lights: vec![point_light(Vec3::new(-1.0, 3.0, 0.0))],
        ..Default::default()
    }
}

#[test]
fn lit_vertices_get_the_projected_point_source_and_shadowed_ones_nothing() {
    let scene = floor_box_light();
    let maps = bake_maps(&scene, &BakeSettings::default());
    let floor = &scene.objects[0];
    let mut lit = 0;
    for (v, entries) in maps.objects[0].to_vertices().iter().enumerate() {
        let p = floor.positions[v];
        // Under the box (|x + 1| < 0.5·(3/1.5 − …)): the box's shadow on the floor from
        // a light 1.5 m above its top face covers |x + 1|, |z| < 0.5 · 3/2 = 0.75.
        let in_umbra = (p.x + 1.0).abs() < 0.7 && p.z.abs() < 0.7;
        if in_umbra {
            assert!(entries.is_empty(), "vertex {p} is under the box: {entries:?}");
            continue;
        }
        let Some(entry) = entries.first() else { continue };
        lit += 1;
        let offset = (scene.lights[0].position - p).as_dvec3();
        let d = offset.normalize();
        let e = 1.0 / offset.length_squared();
        // SH of E·δ(ω − d): coefficient i is E·y_i(d); y_0 = 1/(2√π).
        assert!(
            (entry.sh[0] as f64 - e / (2.0 * PI.sqrt())).abs() < 1e-5 * e.max(1.0),
            "{entry:?}"
        );
        let y1 = -0.488_602_511_902_919_9 * d.y;
        assert!((entry.sh[1] as f64 - e * y1).abs() < 1e-5, "{entry:?}");
    }
    assert!(lit > 40, "most of the floor is lit: {lit}");
    // The box's bottom face looks down, away from the light: nothing stored there.
    assert!(maps.entry_count() < scene.vertex_count());
}

#[test]
fn an_unoccluded_sphere_light_lights_like_a_point_at_its_centre() {
    // A uniformly emitting sphere wholly above a receiver's horizon gives E = I/d² at
    // its centre's distance; the sample sum converges to that integral.
    let mut scene = floor_box_light();
    scene.objects.truncate(1);
    scene.lights[0].kind = LightKind::Sphere { radius_m: 0.2 };
    let settings = BakeSettings {
        light_samples: 256,
        ..BakeSettings::default()
    };
    let maps = bake_maps(&scene, &settings);
    let floor = &scene.objects[0];
    for (v, entries) in maps.objects[0].to_vertices().iter().enumerate() {
        let offset = (scene.lights[0].position - floor.positions[v]).as_dvec3();
        let e = 1.0 / offset.length_squared();
        let dc = entries[0].sh[0] as f64 * 2.0 * PI.sqrt();
        assert!((dc / e - 1.0).abs() < 0.005, "vertex {v}: {dc} vs {e}");
    }
}

#[test]
fn a_cancelled_bake_keeps_nothing_and_progress_reaches_the_end() {
    let scene = floor_box_light();
    let cancelled = AtomicBool::new(true);
    assert!(bake_maps_with(&scene, &BakeSettings::default(), &|_, _| {}, &cancelled).is_none());
    let last = std::sync::Mutex::new((0, 0));
    let go = AtomicBool::new(false);
    let maps = bake_maps_with(
        &scene,
        &BakeSettings::default(),
        &|done, total| {
            let mut last = last.lock().unwrap();
            *last = (last.0.max(done), total);
        },
        &go,
    );
    assert!(maps.is_some());
    let (done, total) = *last.lock().unwrap();
    assert_eq!((done, total), (scene.vertex_count(), scene.vertex_count()));
}

/// One bounce under a large lit ceiling: a directional light travelling up lights a
/// 40 m ceiling 1 m above a tiny floor patch with E = 1 lx, so the ceiling reflects a
/// uniform ρ/π; the patch (which the light cannot reach) sees that radiance over the
/// square's solid angle Ω = 4·asin(a²/(a² + h²)), and the DC of its map is
/// ρ/π · Ω · y₀.
#[test]
fn one_bounce_from_a_uniformly_lit_ceiling_matches_the_solid_angle() {
    let albedo = 0.5f32;
    let scene = Scene {
        objects: patch_and_ceiling().into(),
        materials: vec![
            crate::scene::Material::default(),
            crate::scene::Material {
                base_color: glam::Vec4::new(albedo, albedo, albedo, 1.0),
                specular: 0.0,
                metallic: 0.0,
                ..Default::default()
            },
        ],
        lights: vec![Light {
            kind: LightKind::Directional,
            direction: Vec3::Y,
            ..point_light(Vec3::ZERO)
        }],
        ..Default::default()
    };
    let settings = BakeSettings {
        indirect_directions: 512,
        ..BakeSettings::default()
    };
    let maps = bake_maps(&scene, &settings);
    let (a, h) = (20.0f64, 1.0f64);
    let omega = 4.0 * (a * a / (a * a + h * h)).asin();
    let expected = albedo as f64 / PI * omega / (2.0 * PI.sqrt());
    for entries in &maps.objects[0].to_vertices() {
        assert_eq!(entries.len(), 1, "{entries:?}");
        let dc = entries[0].sh[0] as f64;
        assert!((dc / expected - 1.0).abs() < 0.02, "{dc} vs {expected}");
    }
    // The light never reaches the patch directly, and the ceiling gets no bounce back
    // from the dark patch below it beyond its own direct light; the one ceiling vertex
    // right above the patch is in its shadow (the ray meets the patch on its diagonal).
    assert!(maps.objects[1].to_vertices().iter().all(|e| e.len() <= 1));
    let lit = maps.objects[1].to_vertices().iter().filter(|e| e.len() == 1).count();
    assert_eq!(lit, maps.objects[1].vertex_count() - 1);
}

/// A small patch 1 m under a wide matte ceiling lit from below by a directional light,
/// the ceiling's base colour `factor` × `texture` (a uniform one, if any).
fn patch_under_a_ceiling(factor: f32, texture: Option<u8>) -> Scene {
    Scene {
        objects: patch_and_ceiling().into(),
        materials: vec![
            crate::scene::Material::default(),
            crate::scene::Material {
                base_color: glam::Vec4::new(factor, factor, factor, 1.0),
                base_color_texture: texture.map(|_| 0),
                specular: 0.0,
                metallic: 0.0,
                ..Default::default()
            },
        ],
        textures: texture
            .map(|srgb| crate::scene::TextureImage {
                name: "grey".into(),
                width: 2,
                height: 2,
                rgba8: [srgb, srgb, srgb, 255].repeat(4),
            })
            .into_iter()
            .collect(),
        lights: vec![Light {
            kind: LightKind::Directional,
            direction: Vec3::Y,
            ..point_light(Vec3::ZERO)
        }],
        ..Default::default()
    }
}

/// The bounce sees the base-colour texture where it lands, as the path tracer does: a
/// ceiling textured a uniform grey of linear value v bounces what a ceiling of factor v
/// does (one bounce is linear in the albedo), not what its white factor would. (The
/// bake once ignored textures: the studio's checkered floor bounced as if white.)
#[test]
fn a_bounce_sees_the_base_colour_texture_where_it_lands() {
    let srgb = 188u8;
    let c = srgb as f64 / 255.0;
    let linear = ((c + 0.055) / 1.055).powf(2.4);
    let settings = BakeSettings {
        indirect_directions: 64,
        precision: Precision::F32,
        ..BakeSettings::default()
    };
    let patch_bounce = |scene: &Scene| -> Vec<(f64, f64)> {
        let maps = bake_maps(scene, &settings);
        maps.objects[0]
            .to_vertices()
            .iter()
            .map(|e| (e[0].sh[0] as f64, e[0].indirect_irradiance as f64))
            .collect()
    };
    let textured = patch_bounce(&patch_under_a_ceiling(1.0, Some(srgb)));
    let factor = patch_bounce(&patch_under_a_ceiling(linear as f32, None));
    let white = patch_bounce(&patch_under_a_ceiling(1.0, None));
    for ((t, f), w) in textured.iter().zip(&factor).zip(&white) {
        assert!(t.0 > 0.0 && t.1 > 0.0, "{t:?}");
        assert!((t.0 / f.0 - 1.0).abs() < 1e-4, "SH DC {} vs {}", t.0, f.0);
        assert!((t.1 / f.1 - 1.0).abs() < 1e-4, "irradiance {} vs {}", t.1, f.1);
        assert!((t.1 / w.1 - linear).abs() < 1e-3, "{} of white's", t.1 / w.1);
    }
}

/// A glossy metal ceiling (k_d = 0, k_s = 1, Phong exponent 30: glTF roughness 0.5)
/// 1 m above a tiny floor patch, and a 1 cd point light 0.5 m up and 1 m aside: the
/// patch's one-bounce light is the ceiling's glossy reflection of the light, whose DC
/// is y₀·∫ L(q → p) dω_p with L = I/|ℓ − q|²·(r + 1)/(2π)·max(m·l, 0)^r, integrated here
/// over the ceiling by a midpoint rule (dω_p = dA·cos θ_q/|p − q|²). A diffuse-only
/// bounce would give nothing.
#[test]
fn a_glossy_ceiling_bounces_the_light_in_its_mirror_direction() {
    let light_position = Vec3::new(1.0, 0.5, 0.0);
    let scene = Scene {
        objects: patch_and_ceiling().into(),
        materials: vec![
            crate::scene::Material::default(),
            crate::scene::Material {
                base_color: glam::Vec4::ONE,
                metallic: 1.0,
                roughness: 0.5,
                ..Default::default()
            },
        ],
        lights: vec![point_light(light_position)],
        ..Default::default()
    };
    let dc_of = |bounces: usize| -> Vec<f64> {
        let settings = BakeSettings {
            bounces,
            indirect_directions: 4096,
            ..BakeSettings::default()
        };
        let maps = bake_maps(&scene, &settings);
        maps.objects[0]
            .to_vertices()
            .iter()
            .map(|e| e.first().map_or(0.0, |c| c.sh[0] as f64))
            .collect()
    };
    let (direct, bounced) = (dc_of(0), dc_of(1));

    let exponent = 30.0f64;
    let light = light_position.as_dvec3();
    let normal = glam::DVec3::NEG_Y;
    let expected_dc = |p: glam::DVec3| -> f64 {
        let (cells, x0, z0, side) = (1200, -4.0, -6.0, 12.0);
        let step = side / cells as f64;
        let mut integral = 0.0;
        for i in 0..cells {
            for j in 0..cells {
                let q = glam::DVec3::new(x0 + (i as f64 + 0.5) * step, 1.0, z0 + (j as f64 + 0.5) * step);
                let (to_light, to_patch) = (light - q, p - q);
                let (l, v) = (to_light.normalize(), to_patch.normalize());
                let mirror = 2.0 * normal.dot(v) * normal - v;
                let lobe = (exponent + 1.0) / (2.0 * PI) * mirror.dot(l).max(0.0).powf(exponent);
                let radiance = lobe / to_light.length_squared();
                integral += radiance * step * step * normal.dot(v) / to_patch.length_squared();
            }
        }
        integral / (2.0 * PI.sqrt())
    };
    let vertices = &scene.objects[0].positions;
    for (v, (with, without)) in bounced.iter().zip(&direct).enumerate() {
        let expected = expected_dc(vertices[v].as_dvec3());
        let indirect = with - without;
        assert!(
            (indirect / expected - 1.0).abs() < 0.05,
            "vertex {v}: baked {indirect} vs {expected}"
        );
    }
}

/// Inside a closed 2 m box of albedo ρ = 0.5 with a unit point light at its centre:
/// each extra bounce adds light, and the indirect light stays under the geometric
/// bound: after the first bounce no radiance exceeds ρ·E_max/π, each further bounce at
/// most ρ times the last, so ∫L_ind dω ≤ 2π·ρ·E_max/(π(1 − ρ)) over the hemisphere
/// (E_max = 1/(1 m)² at the middle of a wall); the DC is that integral / (2√π).
#[test]
fn indirect_light_in_a_closed_box_grows_with_bounces_within_the_albedo_bound() {
    let rho = 0.5f32;
    // Six 2 m walls of 6×6 quads facing in (a plane faces +y; turn it onto each face).
    use glam::{Affine3A, Quat};
    use std::f32::consts::{FRAC_PI_2, PI as PI32};
    let turns = [
        Quat::IDENTITY,
        Quat::from_rotation_x(PI32),
        Quat::from_rotation_x(FRAC_PI_2),
        Quat::from_rotation_x(-FRAC_PI_2),
        Quat::from_rotation_z(FRAC_PI_2),
        Quat::from_rotation_z(-FRAC_PI_2),
    ];
    let walls: Vec<MeshObject> = turns
        .iter()
        .map(|&turn| {
            let wall = shapes::plane(2.0, 6, 1.0).transformed(Affine3A::from_translation(Vec3::NEG_Y));
            object("wall", wall.transformed(Affine3A::from_quat(turn)))
        })
        .collect();
    let scene = Scene {
        objects: walls,
        materials: vec![crate::scene::Material {
            base_color: glam::Vec4::new(rho, rho, rho, 1.0),
            specular: 0.0,
            metallic: 0.0,
            ..Default::default()
        }],
        lights: vec![Light {
            intensity: 1.0,
            ..point_light(Vec3::ZERO)
        }],
        ..Default::default()
    };
    let dc = |bounces: usize| -> Vec<f64> {
        let settings = BakeSettings {
            bounces,
            indirect_directions: 512,
            ..BakeSettings::default()
        };
        let maps = bake_maps(&scene, &settings);
        maps.objects
            .iter()
            .flat_map(ObjectMaps::to_vertices)
            .map(|e| e.first().map_or(0.0, |c| c.sh[0] as f64))
            .collect()
    };
    let direct = dc(0);
    let levels: Vec<Vec<f64>> = [1, 2, 4].into_iter().map(dc).collect();
    let total = |v: &[f64]| v.iter().sum::<f64>();
    assert!(total(&levels[0]) > total(&direct) * 1.05, "one bounce adds light");
    assert!(
        total(&levels[1]) > total(&levels[0]) * 1.02,
        "a second bounce adds more"
    );
    assert!(total(&levels[2]) > total(&levels[1]), "and more bounces more still");
    let bound = 2.0 * PI * rho as f64 / (PI * (1.0 - rho as f64)) / (2.0 * PI.sqrt());
    for (v, (with, without)) in levels[2].iter().zip(&direct).enumerate() {
        let indirect = with - without;
        assert!(indirect >= 0.0 && indirect <= bound, "vertex {v}: {indirect} > {bound}");
    }
}

/// Two bakes of the same scene and settings are identical, bit for bit (per-vertex
/// seeds, no shared random state between threads).
#[test]
fn the_same_inputs_bake_the_same_maps() {
    let mut scene = floor_box_light();
    scene.lights[0].kind = LightKind::Sphere { radius_m: 0.3 };
    let settings = BakeSettings {
        bounces: 3,
        ..BakeSettings::default()
    };
    assert_eq!(bake_maps(&scene, &settings), bake_maps(&scene, &settings));
}

/// A sphere light half hidden behind a box edge: the error of the sampled direct light
/// (against 4096 samples) falls at least like 1/√N from 16 to 256 samples.
#[test]
fn direct_light_error_falls_with_the_sample_count() {
    let mut scene = floor_box_light();
    scene.lights[0].kind = LightKind::Sphere { radius_m: 0.6 };
    scene.lights[0].position = Vec3::new(-0.5, 3.0, 0.0);
    let dc = |samples: usize| -> Vec<f64> {
        let settings = BakeSettings {
            light_samples: samples,
            bounces: 0,
            relative_threshold: 0.0,
            ..BakeSettings::default()
        };
        bake_maps(&scene, &settings).objects[0]
            .to_vertices()
            .iter()
            .map(|e| e.first().map_or(0.0, |c| c.sh[0] as f64))
            .collect()
    };
    let reference = dc(4096);
    let rms = |estimate: Vec<f64>| -> f64 {
        let n = estimate.len() as f64;
        (estimate
            .iter()
            .zip(&reference)
            .map(|(a, b)| (a - b).powi(2))
            .sum::<f64>()
            / n)
            .sqrt()
    };
    let (coarse, fine) = (rms(dc(16)), rms(dc(256)));
    assert!(coarse > 0.0, "the penumbra is not resolved exactly by 16 samples");
    // 16× the samples: 1/√N predicts a 4× smaller error; allow for noise down to 3×.
    assert!(fine < coarse / 3.0, "rms {coarse} at 16 samples, {fine} at 256");
}

#[test]
fn re_baking_a_moved_light_equals_a_full_bake() {
    let mut scene = floor_box_light();
    scene.lights.push(Light {
        position: Vec3::new(1.5, 2.0, 1.0),
        ..point_light(Vec3::ZERO)
    });
    let settings = BakeSettings::default();
    let before = bake_maps(&scene, &settings);
    scene.lights[1].position = Vec3::new(-1.5, 2.5, -1.0);
    let never = AtomicBool::new(false);
    let rebaked = rebake_lights(&scene, &settings, &before, &[1], &|_, _| {}, &never).expect("not cancelled");
    assert_eq!(rebaked, bake_maps(&scene, &settings));
    assert_ne!(rebaked, before, "the moved light changed its maps");
}

#[test]
fn no_lights_or_no_geometry_bake_to_empty_maps() {
    let mut scene = floor_box_light();
    scene.lights.clear();
    assert_eq!(bake_maps(&scene, &BakeSettings::default()).entry_count(), 0);
    let empty = Scene {
        lights: vec![point_light(Vec3::Y)],
        ..Default::default()
    };
    assert!(bake_maps(&empty, &BakeSettings::default()).objects.is_empty());
}
