//! Shadows of the real triangles for lights of no size (shadow maps, the default for point,
//! spot and directional lights), on shapes real scenes have and sphere blockers miss: a
//! single-sided card (one quad), a lattice of thin bars and a helix of thin tubes, each
//! over a one-quad floor, under a point light, a spot and the sun. The GPU is checked
//! against its f64 twin — ray casts on the same triangles, which the maps converge to —
//! and against the path tracer. No sphere blockers are given: every shadow here is the
//! maps'.

mod common;

use common::thin_casters::*;
use glam::Vec3;
use lightpaint::render::{AntiAliasing, ShadowFrame, render_cpu_image, render_logsh_image};
use lightpaint::scene::{Camera, Light, LightKind, Scene};
use lightpaint::shading::{RenderSettings, ShadowSettings};

// Fine enough that the bars' and tubes' shadows are a few pixels wide: a pixel's centre
// ray (the twin) then samples them without aliasing their mass away.
const WIDTH: u32 = 400;
const HEIGHT: u32 = 300;

fn lights() -> [(&'static str, Light); 3] {
    [
        (
            "point",
            light(LightKind::Point, Vec3::new(0.4, 2.6, 0.3), Vec3::NEG_Y, 12.0),
        ),
        (
            "spot",
            light(
                LightKind::Spot {
                    inner_cone_rad: 0.55,
                    outer_cone_rad: 0.7,
                },
                Vec3::new(-0.3, 2.8, 0.5),
                Vec3::new(0.1, -1.0, -0.15),
                14.0,
            ),
        ),
        (
            "sun",
            light(LightKind::Directional, Vec3::ZERO, Vec3::new(0.35, -1.0, 0.2), 2.0),
        ),
    ]
}

fn shadows(map_size: u32) -> ShadowSettings {
    ShadowSettings {
        shadow_map_size: map_size,
        ..ShadowSettings::default().every_pixel()
    }
}

fn frame<'a>(
    scene: &'a Scene,
    camera: &'a Camera,
    settings: &'a RenderSettings,
    shadows: &'a ShadowSettings,
) -> ShadowFrame<'a> {
    frame_of(scene, camera, settings, shadows, (WIDTH, HEIGHT))
}

/// The twin's radiance (linear luma, [`linear_luma`]) at `FACTOR`² rays per pixel,
/// box-filtered: a thin shadow's pixels take the share of their area in shadow, as the
/// path tracer's jittered samples do (a ray through each pixel's centre alone
/// over-counts stripes about a pixel wide).
fn supersampled_twin(gpu: &lightpaint::render::GpuContext, frame: &ShadowFrame) -> Vec<f64> {
    const FACTOR: u32 = 3;
    let fine = render_cpu_image(
        gpu,
        &ShadowFrame {
            width: frame.width * FACTOR,
            height: frame.height * FACTOR,
            ..*frame
        },
    )
    .expect("CPU render");
    let fine = linear_luma(&fine);
    let fine_width = frame.width * FACTOR;
    (0..frame.height)
        .flat_map(|y| (0..frame.width).map(move |x| (x, y)))
        .map(|(x, y)| {
            let mut sum = 0.0;
            for dy in 0..FACTOR {
                for dx in 0..FACTOR {
                    sum += fine[((y * FACTOR + dy) * fine_width + x * FACTOR + dx) as usize];
                }
            }
            sum / (FACTOR * FACTOR) as f64
        })
        .collect()
}

/// Each thin caster casts its shadow under each light, where the ray casts put it: the
/// shadows' mass (in linear light) on the GPU from 0.8 to 1.3 times the twin's (measured
/// at the default 1024²: 0.98–1.05 for the card and under the point light and the spot,
/// up to 1.11 for the lattice and 1.24 for the helix under the sun, whose one view spans
/// the scene in 8 mm texels that the bars and tubes are only a few of; a missing or
/// doubled shadow is far outside), and the images agree within
/// 2/255 at 98 % of the pixels or more (measured 99.4–99.9 %: the rest is the maps'
/// texel-wide, filtered edges).
#[test]
fn every_thin_caster_shadows_the_floor_under_every_light_of_no_size() {
    let Some(gpu) = common::gpu() else { return };
    let camera = camera();
    let settings = RenderSettings::default();
    let mapped = shadows(lightpaint::shading::SUGGESTED_SHADOW_MAP_SIZE);
    let no_maps = shadows(0);
    for (caster_name, caster) in casters() {
        for (light_name, light) in lights() {
            let scene = scene_with(caster.clone(), light);
            let name = format!("{caster_name}-{light_name}");
            let gpu_image = render_logsh_image(&gpu, &frame(&scene, &camera, &settings, &mapped), AntiAliasing::None)
                .expect("GPU render");
            let cpu_image = render_cpu_image(&gpu, &frame(&scene, &camera, &settings, &mapped)).expect("CPU render");
            // Without maps and without blockers nothing shadows the floor: the lit frame.
            let lit = render_cpu_image(&gpu, &frame(&scene, &camera, &settings, &no_maps)).expect("CPU render");
            let floor = floor_only(scene.lights[0].clone());
            let gpu_floor = render_logsh_image(&gpu, &frame(&floor, &camera, &settings, &mapped), AntiAliasing::None)
                .expect("GPU render");
            let cpu_floor = render_cpu_image(&gpu, &frame(&floor, &camera, &settings, &mapped)).expect("CPU render");
            let on_floor = floor_pixels(&lit, &cpu_floor);
            save_for_review(&format!("{name}-gpu"), &gpu_image);
            save_for_review(&format!("{name}-cpu"), &cpu_image);
            let mask = shadow_mask(&cpu_image, &lit);
            let shadowed = mask.iter().filter(|m| **m).count();
            let (gpu_mean, cpu_mean, lit_mean) = (
                mean_over(&gpu_image, &mask),
                mean_over(&cpu_image, &mask),
                mean_over(&lit, &mask),
            );
            let agreement = within(&gpu_image, &cpu_image, 2);
            let area_twin = supersampled_twin(&gpu, &frame(&scene, &camera, &settings, &mapped));
            let mass = darkening(&linear_luma(&gpu_image), &linear_luma(&gpu_floor), &on_floor)
                / darkening(&area_twin, &linear_luma(&cpu_floor), &on_floor);
            eprintln!(
                "{name}: {shadowed} shadowed pixels, mean luma GPU {gpu_mean:.1} twin {cpu_mean:.1} lit {lit_mean:.1}; \
                 shadow mass GPU/twin {mass:.3}; {:.2} % within 2/255",
                100.0 * agreement
            );
            assert!(
                shadowed > 100,
                "{name}: the caster casts (only {shadowed} shadowed pixels)"
            );
            assert!((0.8..=1.3).contains(&mass), "{name}: shadow mass GPU/twin {mass:.3}");
            assert!(
                agreement >= 0.98,
                "{name}: only {:.2} % within 2/255",
                100.0 * agreement
            );
        }
    }
}

/// The maps converge to the ray casts: the share of pixels that differ from the twin by
/// more than 2/255 shrinks as the maps grow (the lattice under the point light, whose
/// thin bars are a few texels wide in a small map).
#[test]
fn shadow_maps_converge_to_the_ray_casts_as_they_grow() {
    let Some(gpu) = common::gpu() else { return };
    let camera = camera();
    let settings = RenderSettings::default();
    let [(_, point), _, _] = lights();
    let scene = scene_with(lattice(), point);
    let cpu_image = render_cpu_image(&gpu, &frame(&scene, &camera, &settings, &shadows(1024))).expect("CPU render");
    let mut previous = f64::INFINITY;
    for size in [128, 512, 2048] {
        let shadows = shadows(size);
        let image =
            render_logsh_image(&gpu, &frame(&scene, &camera, &settings, &shadows), AntiAliasing::None).expect("render");
        let off = 1.0 - within(&image, &cpu_image, 2);
        eprintln!(
            "lattice, point light, maps of {size}²: {:.3} % of pixels off by more than 2/255",
            100.0 * off
        );
        assert!(off < previous, "{size}²: {off} not below {previous}");
        previous = off;
    }
    assert!(previous < 0.01, "2048²: {:.3} % off", 100.0 * previous);
}

/// Against the path tracer (direct light, 32 samples per pixel): the spot's shadows of the
/// card and the helix are where the reference shows them, with the same mass (within
/// 10 %: the darkening summed over the image, which its noise and its jittered pixel
/// samples leave unbiased).
#[test]
fn the_spots_shadows_match_the_path_tracer() {
    let Some(gpu) = common::gpu() else { return };
    let camera = camera();
    let settings = RenderSettings::default();
    let mapped = shadows(lightpaint::shading::SUGGESTED_SHADOW_MAP_SIZE);
    let no_maps = shadows(0);
    let [_, (_, spot), _] = lights();
    for (name, caster) in [("card", card()), ("helix", helix())] {
        let scene = scene_with(caster, spot.clone());
        let gpu_image =
            render_logsh_image(&gpu, &frame(&scene, &camera, &settings, &mapped), AntiAliasing::None).expect("render");
        let lit = render_cpu_image(&gpu, &frame(&scene, &camera, &settings, &no_maps)).expect("CPU render");
        let trace = |scene: &Scene| path_traced(scene, &camera, &settings, (WIDTH, HEIGHT), 32);
        let reference = trace(&scene);
        let floor = floor_only(spot.clone());
        let reference_floor = trace(&floor);
        let gpu_floor =
            render_logsh_image(&gpu, &frame(&floor, &camera, &settings, &mapped), AntiAliasing::None).expect("render");
        let cpu_floor = render_cpu_image(&gpu, &frame(&floor, &camera, &settings, &mapped)).expect("CPU render");
        let on_floor = floor_pixels(&lit, &cpu_floor);
        save_for_review(&format!("{name}-spot-reference"), &reference);
        let mask = shadow_mask(&reference, &lit);
        let (gpu_mean, reference_mean, lit_mean) = (
            mean_over(&gpu_image, &mask),
            mean_over(&reference, &mask),
            mean_over(&lit, &mask),
        );
        let agreement = within(&gpu_image, &reference, 6);
        let mass = darkening(&linear_luma(&gpu_image), &linear_luma(&gpu_floor), &on_floor)
            / darkening(&linear_luma(&reference), &linear_luma(&reference_floor), &on_floor);
        eprintln!(
            "{name} under the spot: shadow mean luma GPU {gpu_mean:.1}, path tracer {reference_mean:.1}, lit \
             {lit_mean:.1}; shadow mass GPU/path tracer {mass:.3}; {:.2} % within 6/255",
            100.0 * agreement
        );
        assert!(
            (0.9..=1.1).contains(&mass),
            "{name}: shadow mass GPU/path tracer {mass:.3}"
        );
        assert!(agreement >= 0.9, "{name}: only {:.2} % within 6/255", 100.0 * agreement);
    }
}

/// A closed box's shadow lies where the ray casts put it under each light of no size
/// (and a wide spot low at the side, whose texels are large on the floor it grazes): per
/// well-lit floor pixel the visibility (shadowed over floor-alone linear luma) on the GPU
/// and in the twin's 3 × 3 ray casts per pixel, and the light the GPU misplaces over the
/// shadow and its outline, Σ|v_gpu − v_twin| over the shadow's mass Σ(1 − v_twin), under
/// 0.023 (measured on lavapipe 2026-12-04 at the default 1024² maps: 0.013–0.018).
/// Receivers pushed a texel and a half along their normal before reading the maps, as
/// until then, had moved the outlines by as much: 0.026 under the sun, 0.029 under the
/// low spot (0.016 and 0.018 under the point and the spot, whose light meets the floor
/// more steeply).
#[test]
fn a_boxs_shadow_outline_lies_where_the_ray_casts_put_it() {
    let Some(gpu) = common::gpu() else { return };
    let camera = camera();
    let settings = RenderSettings::default();
    let mapped = shadows(lightpaint::shading::SUGGESTED_SHADOW_MAP_SIZE);
    let no_maps = shadows(0);
    // Besides the three lights above, a wide spot low at the side, whose texels are
    // large on the floor and whose light grazes it.
    let low_spot = light(
        LightKind::Spot {
            inner_cone_rad: 0.8,
            outer_cone_rad: 0.95,
        },
        Vec3::new(-2.6, 1.4, 0.4),
        Vec3::new(2.6, -0.9, -0.4),
        40.0,
    );
    let mut all = lights().to_vec();
    all.push(("low wide spot", low_spot));
    for (light_name, light) in all {
        let scene = scene_with(closed_box(), light);
        let floor = floor_only(scene.lights[0].clone());
        let gpu_image = render_logsh_image(&gpu, &frame(&scene, &camera, &settings, &mapped), AntiAliasing::None)
            .expect("GPU render");
        let gpu_floor = render_logsh_image(&gpu, &frame(&floor, &camera, &settings, &mapped), AntiAliasing::None)
            .expect("GPU render");
        let lit = render_cpu_image(&gpu, &frame(&scene, &camera, &settings, &no_maps)).expect("CPU render");
        let cpu_floor = render_cpu_image(&gpu, &frame(&floor, &camera, &settings, &mapped)).expect("CPU render");
        let on_floor = floor_pixels(&lit, &cpu_floor);
        let twin = supersampled_twin(&gpu, &frame(&scene, &camera, &settings, &mapped));
        let twin_floor_linear = supersampled_twin(&gpu, &frame(&floor, &camera, &settings, &mapped));
        let (gpu_linear, gpu_floor_linear) = (linear_luma(&gpu_image), linear_luma(&gpu_floor));
        let (mut misplaced, mut mass, mut gpu_mass) = (0.0, 0.0, 0.0);
        // The floor well inside the light (the cone's rim and the floor's own edge, where a
        // pixel's centre and its 3 × 3 rays see different shares of light, left out).
        let lit_floor = |i: usize| on_floor[i] && twin_floor_linear[i].min(gpu_floor_linear[i]) > 0.02;
        for i in (0..on_floor.len()).filter(|&i| lit_floor(i)) {
            let v_twin = (twin[i] / twin_floor_linear[i]).min(1.0);
            let v_gpu = (gpu_linear[i] / gpu_floor_linear[i].max(1e-6)).min(1.0);
            // The shadow and its outline: elsewhere both see the whole light.
            if v_gpu.min(v_twin) > 0.98 {
                continue;
            }
            misplaced += (v_gpu - v_twin).abs();
            mass += 1.0 - v_twin;
            gpu_mass += 1.0 - v_gpu;
        }
        save_for_review(&format!("box-{light_name}-gpu"), &gpu_image);
        let share = misplaced / mass.max(1e-9);
        eprintln!(
            "box under the {light_name}: shadow mass {mass:.1} pixels (GPU {gpu_mass:.1}), misplaced share {share:.3}"
        );
        assert!(mass > 200.0, "{light_name}: the box casts (mass {mass:.1} pixels)");
        assert!(share < 0.023, "{light_name}: {share:.3} of the shadow misplaced");
    }
}
