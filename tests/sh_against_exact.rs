//! The SH path against exact visibility of the same spheres on the blocker bench scene
//! (`samples::blocker_bench`: thin casters over a floor under one rect light, spheres
//! spread over the casters): how far hundreds of small caps summed in log space drag the
//! light down where nothing hides it. A measurement (ignored in the suite), for
//! docs/performance.md and the issue on the blocker hierarchy.

mod common;

use lightpaint::blockers::Sphere;
use lightpaint::sh::ExpMethod;
use lightpaint::shading::{LightPaths, ShadowSettings};

/// The SH path's visibility against the exact path's visibility of the same spheres, over
/// the blocker bench scene's floor with 600 spheres (f64 twin, order 4 and 8, and order 4
/// with the exact exponential): penumbra RMS, umbra RMS and the lit floor's bias (where
/// no sphere hides the light). A measurement for docs/performance.md:
/// `cargo nextest run --test sh_against_exact --run-ignored only --no-capture`.
#[test]
#[ignore = "a measurement: run it with --run-ignored only --no-capture"]
fn measure_the_sh_path_against_exact_visibility_with_600_spheres() {
    use lightpaint::scene::luminance;
    use lightpaint::shading::cpu::{ShadingInputs, shadowed_radiance};
    use rayon::prelude::*;
    let Some(gpu) = common::gpu() else { return };
    let scene = lightpaint::samples::blocker_bench::thin_casters_scene();
    let camera = lightpaint::samples::blocker_bench::thin_casters_camera();
    let surfaces = lightpaint::render::capture_surfaces(&gpu, &scene, &camera, None, 240, 135).expect("surfaces");
    let spheres = lightpaint::samples::blocker_bench::spheres_on_casters(&scene, 600);
    // The shipped exponentiation (HYB) at orders 4 and 8, and the exact exponential at 4.
    let defaults = ShadowSettings::default();
    for (order, exp) in [(4, defaults.exp), (8, defaults.exp), (4, ExpMethod::Reference)] {
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
                    Some(luminance(shadowed_radiance(s, &inputs)))
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
        eprintln!(
            "order {order}, {exp:?}: penumbra RMS {:.4} ({} px), umbra RMS {:.4} ({} px), lit floor bias {:+.4} ({} px)",
            rms(&penumbra),
            penumbra.len(),
            rms(&umbra),
            umbra.len(),
            mean(&lit),
            lit.len()
        );
    }
}
