//! The SH path against exact visibility of the same spheres on the blocker bench scene
//! (`samples::blocker_bench`: thin casters over a floor under one rect light, spheres
//! spread over the casters): how far hundreds of small caps summed in log space drag the
//! light down where nothing hides it: a test of the SH lights' windows on the blockers
//! (`shading::light_windows`), and a measurement (ignored in the suite) for
//! docs/performance.md.

mod common;

use lightpaint::blockers::Sphere;
use lightpaint::sh::ExpMethod;
use lightpaint::shading::{LightPaths, ShadowSettings};

/// How the SH path's visibility departs from the exact path's over the same spheres, on
/// the blocker bench's floor: RMS and mean in the penumbra (exact visibility 0.05–0.999)
/// and the umbra (below 0.05), and the mean where nothing hides the light (the lit floor).
struct Departure {
    penumbra_rms: f64,
    penumbra_bias: f64,
    umbra_rms: f64,
    umbra_bias: f64,
    lit_bias: f64,
    pixels: [usize; 3],
}

/// The SH path (order `order`, exponentiation `exp`) against the exact path with
/// `spheres` spheres spread over the bench's casters, its panel split into `panels` on a
/// ring (`blocker_bench::ring_of_panels`; 1: as it is) and `lamps` lamps of 1 m range
/// added (`blocker_bench::add_lamps`), on the f64 twin at `width` × `height` surfaces;
/// None without a GPU (the surfaces are rasterised on it). With `sky` a uniform
/// environment lights the set too, and the lights' light alone is compared (the
/// environment's, through the same SH visibility on both paths, taken off).
fn departure(
    order: usize,
    exp: ExpMethod,
    spheres: usize,
    [panels, lamps]: [usize; 2],
    sky: bool,
    (width, height): (u32, u32),
) -> Option<Departure> {
    use lightpaint::scene::luminance;
    use lightpaint::shading::cpu::{ShadingInputs, shadowed_radiance};
    use rayon::prelude::*;
    let gpu = common::gpu()?;
    let mut scene = lightpaint::samples::blocker_bench::thin_casters_scene();
    lightpaint::samples::blocker_bench::ring_of_panels(&mut scene, panels);
    lightpaint::samples::blocker_bench::add_lamps(&mut scene, lamps);
    if sky {
        scene.environment = Some(lightpaint::scene::Environment::uniform([0.3, 0.35, 0.4]));
    }
    let camera = lightpaint::samples::blocker_bench::thin_casters_camera();
    let surfaces = lightpaint::render::capture_surfaces(&gpu, &scene, &camera, None, width, height).expect("surfaces");
    let spheres = lightpaint::samples::blocker_bench::spheres_on_casters(&scene, spheres);
    let shade = |paths: LightPaths, blockers: &[Sphere]| -> Vec<Option<f64>> {
        let shadows = ShadowSettings {
            light_paths: paths,
            order,
            exp,
            ..ShadowSettings::default()
        };
        let context = lightpaint::shading::LightPathContext::of_scene(&scene, blockers);
        let lights = lightpaint::shading::shading_lights(&scene.lights, &shadows, &context);
        let environment = lightpaint::shading::gpu_types::environment_irradiance(scene.environment.as_ref());
        let inputs = ShadingInputs {
            lights: &lights,
            environment_irradiance: &environment,
            blockers,
            terrain: None,
            settings: &shadows,
            eye: camera.position.as_dvec3(),
            pixel_angle_rad: 0.0,
            occluders: None,
        };
        surfaces
            .par_iter()
            .map(|s| {
                let s = s.as_ref().filter(|s| s.position.y.abs() < 1e-3)?;
                let environment_alone = ShadingInputs { lights: &[], ..inputs };
                let sky_light = if sky {
                    shadowed_radiance(s, &environment_alone)
                } else {
                    glam::DVec3::ZERO
                };
                Some(luminance(shadowed_radiance(s, &inputs) - sky_light))
            })
            .collect()
    };
    let open = shade(LightPaths::Harmonics, &[]);
    let exact = shade(LightPaths::Exact, &spheres);
    let harmonics = shade(LightPaths::Harmonics, &spheres);
    let (mut penumbra, mut umbra, mut lit) = (Vec::new(), Vec::new(), Vec::new());
    for ((open, exact), harmonics) in open.iter().zip(&exact).zip(&harmonics) {
        let (Some(open), Some(exact), Some(harmonics)) = (open, exact, harmonics) else {
            continue;
        };
        if *open <= 1e-9 {
            continue;
        }
        let (v_exact, v_sh) = (exact / open, harmonics / open);
        if v_exact >= 0.999 {
            lit.push(v_sh - 1.0);
        } else if v_exact > 0.05 {
            penumbra.push(v_sh - v_exact);
        } else {
            umbra.push(v_sh - v_exact);
        }
    }
    let rms = |v: &[f64]| (v.iter().map(|e| e * e).sum::<f64>() / v.len().max(1) as f64).sqrt();
    let mean = |v: &[f64]| v.iter().sum::<f64>() / v.len().max(1) as f64;
    Some(Departure {
        penumbra_rms: rms(&penumbra),
        penumbra_bias: mean(&penumbra),
        umbra_rms: rms(&umbra),
        umbra_bias: mean(&umbra),
        lit_bias: mean(&lit),
        pixels: [penumbra.len(), umbra.len(), lit.len()],
    })
}

impl Departure {
    /// One line: the lit floor's bias, the penumbra's and the umbra's RMS, with pixel counts.
    fn summary(&self) -> String {
        format!(
            "lit floor bias {:+.4} ({} px), penumbra RMS {:.4} ({} px), umbra RMS {:.4} ({} px)",
            self.lit_bias, self.pixels[2], self.penumbra_rms, self.pixels[0], self.umbra_rms, self.pixels[1]
        )
    }
}

/// [`departure`] at order 4 (the default exponentiation, 600 spheres, 120 × 68), printed.
fn departure_at_order_4(lights: [usize; 2], sky: bool) -> Option<Departure> {
    let d = departure(4, ShadowSettings::default().exp, 600, lights, sky, (120, 68))?;
    eprintln!("{}", d.summary());
    Some(d)
}

/// The bar for the lit floor with 600 spheres at order 4 (HYB): within 5 % of
/// exact visibility (it was −23 % before the SH lights' windows on the blockers, −72 %
/// when the issue was filed), with no more penumbra error than before the windows (RMS
/// 0.397 at 240 × 135, the measurement below) — on the f64 twin, which the GPU matches
/// (tests/gpu_shadows.rs), at a quarter of the measurement's surfaces.
#[test]
fn six_hundred_spheres_leave_the_lit_floor_lit_at_order_4() {
    let Some(d) = departure_at_order_4([1, 0], false) else {
        return;
    };
    assert!(
        d.pixels.iter().all(|&n| n > 100),
        "the floor has lit, penumbra and umbra pixels: {:?}",
        d.pixels
    );
    assert!(d.lit_bias.abs() <= 0.05, "lit floor bias {:+.4}", d.lit_bias);
    assert!(d.penumbra_rms <= 0.397, "penumbra RMS {:.4}", d.penumbra_rms);
}

/// The SH path's visibility against the exact path's visibility of the same spheres, over
/// the blocker bench scene's floor with 600 spheres (f64 twin, order 4 and 8, and order 4
/// with the exact exponential): penumbra RMS, umbra RMS and the lit floor's bias (where
/// no sphere hides the light). A measurement for docs/performance.md:
/// `cargo nextest run --test sh_against_exact --run-ignored only --no-capture`.
#[test]
#[ignore = "a measurement: run it with --run-ignored only --no-capture"]
fn measure_the_sh_path_against_exact_visibility_with_600_spheres() {
    // The shipped exponentiation (HYB) at orders 4 and 8, and the exact exponential at 4.
    let defaults = ShadowSettings::default();
    for (order, exp) in [(4, defaults.exp), (8, defaults.exp), (4, ExpMethod::Reference)] {
        let Some(d) = departure(order, exp, 600, [1, 0], false, (240, 135)) else {
            return;
        };
        eprintln!(
            "order {order}, {exp:?}: penumbra RMS {:.4} (bias {:+.4}, {} px), umbra RMS {:.4} (bias {:+.4}, {} px), lit floor bias {:+.4} ({} px)",
            d.penumbra_rms,
            d.penumbra_bias,
            d.pixels[0],
            d.umbra_rms,
            d.umbra_bias,
            d.pixels[1],
            d.lit_bias,
            d.pixels[2]
        );
    }
}

/// Past eight SH lights each point opens the windows of those that reach it
/// (`light_windows::light_window_indices`) when at most eight do: with the panel and 24 lamps of
/// 1 m range all on the SH path, a floor point sees the panel and at most a few lamps,
/// and the lit floor stays lit as with the panel alone.
#[test]
fn twenty_four_lamps_leave_the_lit_floor_lit_at_order_4() {
    let Some(d) = departure_at_order_4([1, 24], false) else {
        return;
    };
    assert!(d.pixels[2] > 100, "the floor has lit pixels: {:?}", d.pixels);
    assert!(d.lit_bias.abs() <= 0.05, "lit floor bias {:+.4}", d.lit_bias);
    // Walking without windows wherever more than four SH lights lit the frame gave
    // −0.204 and a penumbra RMS of 0.364 here.
    assert!(d.penumbra_rms < 0.364, "penumbra RMS {:.4}", d.penumbra_rms);
}

/// Under three panels spread over a ring, each reads a log-visibility of its own (its
/// blockers weighed by its window alone: `cpu::harmonic_log_visibility`): the lit floor
/// stays lit and the penumbrae keep their light, where one log-visibility weighed by the
/// largest window's weight, read by all three, gave −4.0 % and a penumbra RMS of 0.324
/// (and without windows −15.0 % and 0.268; docs/performance.md).
#[test]
fn three_panels_each_read_their_own_visibility_at_order_4() {
    assert_panels_read_their_own_visibility(3);
}

/// Six panels (past the four windows one shared visibility may have) each read a
/// log-visibility of their own too: the lit floor stays lit, where walking without
/// windows past four SH lights gave −14.6 % with five panels and a penumbra RMS of 0.272
/// (docs/performance.md).
#[test]
fn six_panels_each_read_their_own_visibility_at_order_4() {
    assert_panels_read_their_own_visibility(6);
}

/// Under `panels` panels on the ring, at order 4: lit floor within 3 %, penumbra RMS
/// below 0.22, umbra RMS below 0.06.
fn assert_panels_read_their_own_visibility(panels: usize) {
    let Some(d) = departure_at_order_4([panels, 0], false) else {
        return;
    };
    assert!(
        d.pixels[2] > 100 && d.pixels[0] > 100,
        "lit and penumbra pixels: {:?}",
        d.pixels
    );
    assert!(d.lit_bias.abs() <= 0.03, "lit floor bias {:+.4}", d.lit_bias);
    assert!(d.penumbra_rms < 0.22, "penumbra RMS {:.4}", d.penumbra_rms);
    assert!(d.umbra_rms < 0.06, "umbra RMS {:.4}", d.umbra_rms);
}

/// Under a sky the panel still reads its own windowed visibility (the sky reads every
/// blocker at k(s)): its lit floor stays lit. With the sky taking the windows away from
/// the lights, as before, the panel's light alone came out −21.0 % on the lit floor, as
/// without windows (docs/performance.md).
#[test]
fn under_a_sky_the_panel_leaves_the_lit_floor_lit_at_order_4() {
    let Some(d) = departure_at_order_4([1, 0], true) else {
        return;
    };
    assert!(d.pixels[2] > 100, "the floor has lit pixels: {:?}", d.pixels);
    assert!(d.lit_bias.abs() <= 0.05, "lit floor bias {:+.4}", d.lit_bias);
}

/// The SH path against exact visibility under the bench's panel split into 1 to 9 panels
/// on a ring (order 4, HYB, 600 spheres, 120 × 68): how the windows of several lights
/// spread over the sky weigh the lit floor against the penumbrae (docs/performance.md).
/// `cargo nextest run --test sh_against_exact --run-ignored only --no-capture`.
#[test]
#[ignore = "a measurement: run it with --run-ignored only --no-capture"]
fn measure_the_sh_path_against_exact_visibility_under_several_panels() {
    for panels in [1, 2, 3, 4, 5, 6, 8, 9] {
        let Some(d) = departure(4, ShadowSettings::default().exp, 600, [panels, 0], false, (120, 68)) else {
            return;
        };
        eprintln!("{panels} panels: {}", d.summary());
    }
}
