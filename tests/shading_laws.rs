//! Laws of the log-SH shading that hold independently of how it is implemented, checked on
//! the f64 reference (`shading::cpu`); `gpu_shadows.rs` checks the GPU against it.

mod common;

use std::f64::consts::PI;

use glam::{DVec3, Vec3};
use lightpaint::blockers::Sphere;
use lightpaint::scene::LightKind;
use lightpaint::sh::ExpMethod;
use lightpaint::shading::cpu::{self, ShadingInputs, SurfacePoint};
use lightpaint::shading::gpu_types::GpuLight;
use lightpaint::shading::{BrdfShading, LightPaths, ShadowSettings};

fn white_floor_point(position: DVec3) -> SurfacePoint {
    SurfacePoint {
        position,
        normal: DVec3::Y,
        k_d: DVec3::ONE,
        k_s: DVec3::ZERO,
        phong_exponent: 1.0,
        emissive: DVec3::ZERO,
    }
}

fn light(kind: LightKind, position: Vec3, intensity: f32) -> GpuLight {
    GpuLight::new(&common::scenes::white_light(kind, position, intensity))
}

/// The log-SH path for every light, each blocker's log-visibility ln ε on its cap as Ren
/// et al. state it (these laws are the SH shading's; the exact path for small lights has
/// its own tests in `lightpaint::penumbra`, the scale that keeps a cap's shadow mass its
/// own in `lightpaint::sh` and tests/environment_shadows.rs).
fn sh_path() -> ShadowSettings {
    ShadowSettings {
        light_paths: LightPaths::Harmonics,
        preserve_shadow_mass: false,
        ..ShadowSettings::default()
    }
}

fn shade(p: &SurfacePoint, lights: &[GpuLight], blockers: &[Sphere], settings: &ShadowSettings) -> DVec3 {
    let no_environment = [[0.0f32; 4]; 9];
    cpu::shadowed_radiance(
        p,
        &ShadingInputs {
            lights,
            environment_irradiance: &no_environment,
            blockers,
            terrain: None,
            settings,
            eye: DVec3::new(0.0, 5.0, 0.1),
            pixel_angle_rad: 0.0,
            occluders: None,
        },
    )
}

/// A 0.3 m ball 1.5 m above a white floor point at the origin and a point light of 9 cd
/// 3 m up (irradiance 1 there): the ball's cap, of cos half-angle c = √(1 − 0.2²), is
/// centred on the light, so every function of these laws is zonal about the normal.
struct BallBelowLight {
    blocker: Sphere,
    lights: [GpuLight; 1],
    p: SurfacePoint,
    c: f64,
}

fn ball_below_light() -> BallBelowLight {
    BallBelowLight {
        blocker: Sphere {
            center: Vec3::new(0.0, 1.5, 0.0),
            radius_m: 0.3,
            disc_normal: glam::Vec3::ZERO,
        },
        lights: [light(LightKind::Point, Vec3::new(0.0, 3.0, 0.0), 9.0)],
        p: white_floor_point(DVec3::ZERO),
        c: (1.0f64 - 0.2 * 0.2).sqrt(),
    }
}

impl BallBelowLight {
    /// The point's radiance with `brdf` at `order`, exactly exponentiated, is `expected`
    /// (a value below the clamp at the unshadowed 1/π, so the clamp does not decide it).
    fn assert_reference_shading(&self, brdf: BrdfShading, order: usize, expected: f64) {
        assert!(expected > 0.0 && expected < 0.99 / PI, "not clamped: {expected}");
        let settings = ShadowSettings {
            order,
            exp: ExpMethod::Reference,
            ..with_brdf(brdf)
        };
        let radiance = shade(&self.p, &self.lights, &[self.blocker], &settings).x;
        assert!(
            (radiance - expected).abs() < 1e-6,
            "{brdf:?} order {order}: {radiance} vs {expected}"
        );
    }
}

/// [`ball_below_light`]: the light's visibility at the origin is the zonal exp*(ln ε·cap)
/// evaluated straight up, Σ_l g_l·√((2l+1)/(4π)).
#[test]
fn a_blocker_darkens_the_point_below_by_its_cap_exponential() {
    let BallBelowLight { blocker, lights, p, c } = ball_below_light();
    for order in [2, 3, 4, 6] {
        // The cap axis is world +y while the SH polar axis is +z: the law must not care.
        let g = common::zonal_exp_reference(order, c, 0.1f64.ln());
        let expected: f64 = g
            .iter()
            .enumerate()
            .map(|(l, g)| g * ((2 * l + 1) as f64 / (4.0 * PI)).sqrt())
            .sum();
        let reference = ShadowSettings {
            order,
            exp: ExpMethod::Reference,
            ..sh_path()
        };
        let open = shade(&p, &lights, &[], &reference).x;
        assert!((open - 1.0 / PI).abs() < 1e-12, "unshadowed {open}");
        let visibility = shade(&p, &lights, &[blocker], &reference).x / open;
        assert!(
            (visibility - expected).abs() < 1e-6,
            "order {order}: {visibility} vs {expected}"
        );
        assert!(expected < 0.95, "the ball must shadow visibly: {expected}");
        // HYB approximates the exact exponential (0.5–2 points here, see sh::hyb_threshold).
        let hyb = ShadowSettings { order, ..sh_path() };
        let visibility = shade(&p, &lights, &[blocker], &hyb).x / open;
        assert!(
            (visibility - expected).abs() < 0.03,
            "HYB order {order}: {visibility} vs {expected}"
        );
    }
}

#[test]
fn blockers_below_the_horizon_or_beyond_influence_leave_points_unshadowed() {
    let lights = [light(LightKind::Point, Vec3::new(0.0, 3.0, 0.0), 9.0)];
    let settings = sh_path();
    let p = white_floor_point(DVec3::ZERO);
    let open = shade(&p, &lights, &[], &settings);
    let below = Sphere {
        center: Vec3::new(0.5, -0.6, 0.0),
        radius_m: 0.5,
        disc_normal: glam::Vec3::ZERO,
    };
    // r/d = 0.3/20 is below the influence cut-off of 0.03.
    let far = Sphere {
        center: Vec3::new(20.0, 0.5, 0.0),
        radius_m: 0.3,
        disc_normal: glam::Vec3::ZERO,
    };
    assert_eq!(shade(&p, &lights, &[below, far], &settings), open);
}

#[test]
fn an_unoccluded_plane_under_a_sphere_light_gets_the_exact_irradiance() {
    // A uniformly emitting sphere wholly above a receiver's horizon lights it as a point
    // source of the same intensity at its centre: E = I·cos θ/d².
    let centre = Vec3::new(0.7, 2.0, -0.4);
    let lights = [light(LightKind::Sphere { radius_m: 0.5 }, centre, 40.0)];
    for (x, z) in [(0.0, 0.0), (1.5, 0.3), (-2.0, 1.0)] {
        let p = white_floor_point(DVec3::new(x, 0.0, z));
        let offset = centre.as_dvec3() - p.position;
        let expected = 40.0 * (offset.y / offset.length()) / offset.length_squared() / PI;
        for order in [2, 4, 8] {
            let settings = ShadowSettings { order, ..sh_path() };
            let radiance = shade(&p, &lights, &[], &settings);
            assert!(
                (radiance.x / expected - 1.0).abs() < 1e-6,
                "order {order}: {radiance} vs {expected}"
            );
        }
    }
}

#[test]
fn white_furnace_shades_to_one() {
    // A uniform environment of radiance 1 on a white Lambertian surface: L = 1, whatever
    // the normal, at every order (the environment's order-3 irradiance is exact here).
    let environment = lightpaint::scene::Environment::uniform([1.0; 3]);
    let irradiance = lightpaint::shading::gpu_types::environment_irradiance(Some(&environment));
    for normal in [DVec3::Y, DVec3::new(1.0, 1.0, 0.0).normalize(), DVec3::NEG_Z] {
        let p = SurfacePoint {
            normal,
            ..white_floor_point(DVec3::ZERO)
        };
        for order in [2, 3, 4, 8] {
            // The product's diffuse lobe against a uniform environment is exact too: the
            // constant visibility times the lobe is the lobe, whose integral is 1.
            for brdf in [BrdfShading::Separate, BrdfShading::Product] {
                let settings = ShadowSettings {
                    order,
                    ..with_brdf(brdf)
                };
                let inputs = ShadingInputs {
                    lights: &[],
                    environment_irradiance: &irradiance,
                    blockers: &[],
                    terrain: None,
                    settings: &settings,
                    eye: DVec3::new(0.0, 5.0, 0.0),
                    pixel_angle_rad: 0.0,
                    occluders: None,
                };
                let radiance = cpu::shadowed_radiance(&p, &inputs);
                assert!(
                    (radiance - DVec3::ONE).abs().max_element() < 1e-6,
                    "{brdf:?}: {radiance}"
                );
            }
        }
    }
}

fn scattered_blockers() -> Vec<Sphere> {
    (0..7)
        .map(|i| {
            let t = i as f32 * 1.7;
            Sphere {
                center: Vec3::new(t.cos() * 0.8, 0.6 + 0.2 * (i % 3) as f32, t.sin() * 0.8),
                radius_m: 0.15 + 0.03 * i as f32,
                disc_normal: glam::Vec3::ZERO,
            }
        })
        .collect()
}

#[test]
fn moving_blockers_lights_and_receiver_together_changes_nothing() {
    let blockers = scattered_blockers();
    let lights = [
        light(LightKind::Point, Vec3::new(0.3, 3.0, 0.2), 9.0),
        light(LightKind::Sphere { radius_m: 0.4 }, Vec3::new(-1.0, 2.0, 0.5), 20.0),
    ];
    let shift = Vec3::new(3.0, -2.0, 5.5);
    let moved_blockers: Vec<Sphere> = blockers
        .iter()
        .map(|b| Sphere {
            center: b.center + shift,
            ..*b
        })
        .collect();
    let moved_lights = lights.map(|l| GpuLight {
        position: (Vec3::from_slice(&l.position[..3]) + shift).extend(1.0).to_array(),
        ..l
    });
    let no_environment = [[0.0f32; 4]; 9];
    let eye = DVec3::new(0.0, 5.0, 0.1);
    let exact = ShadowSettings {
        light_paths: LightPaths::Exact,
        ..sh_path()
    };
    for ((x, z), settings) in [(0.0, 0.0), (0.4, -0.3), (-0.7, 0.6)].into_iter().flat_map(|at| {
        [
            (at, sh_path()),
            (at, exact),
            (at, with_brdf(BrdfShading::Log)),
            (at, with_brdf(BrdfShading::Product)),
        ]
    }) {
        let p = white_floor_point(DVec3::new(x, 0.0, z));
        let moved_p = SurfacePoint {
            position: p.position + shift.as_dvec3(),
            ..p
        };
        let here = cpu::shadowed_radiance(
            &p,
            &ShadingInputs {
                lights: &lights,
                environment_irradiance: &no_environment,
                blockers: &blockers,
                terrain: None,
                settings: &settings,
                eye,
                pixel_angle_rad: 0.0,
                occluders: None,
            },
        );
        let there = cpu::shadowed_radiance(
            &moved_p,
            &ShadingInputs {
                lights: &moved_lights,
                environment_irradiance: &no_environment,
                blockers: &moved_blockers,
                terrain: None,
                settings: &settings,
                eye: eye + shift.as_dvec3(),
                pixel_angle_rad: 0.0,
                occluders: None,
            },
        );
        // f32 positions moved by metres round at ~1e-7 relative.
        assert!(
            (here - there).abs().max_element() < 1e-5 * here.max_element().max(1e-3),
            "{here} vs {there}"
        );
        assert!(
            settings.light_paths == LightPaths::Exact || here.x < 0.95 * shade(&p, &lights, &[], &settings).x,
            "the blockers must shadow here"
        );
    }
}

#[test]
fn permuting_blockers_changes_nothing() {
    let blockers = scattered_blockers();
    let mut reversed = blockers.clone();
    reversed.reverse();
    let lights = [light(LightKind::Point, Vec3::new(0.3, 3.0, 0.2), 9.0)];
    for method in [ExpMethod::Dc, ExpMethod::Ol, ExpMethod::Hyb, ExpMethod::Ps(8)] {
        for brdf in BrdfShading::ALL {
            let settings = ShadowSettings {
                exp: method,
                ..with_brdf(brdf)
            };
            let p = white_floor_point(DVec3::new(0.2, 0.0, 0.1));
            let a = shade(&p, &lights, &blockers, &settings);
            let b = shade(&p, &lights, &reversed, &settings);
            assert!((a - b).abs().max_element() < 1e-12, "{method:?} {brdf:?}: {a} vs {b}");
        }
    }
}

fn with_brdf(brdf: BrdfShading) -> ShadowSettings {
    ShadowSettings { brdf, ..sh_path() }
}

/// [`ball_below_light`] with the log-BRDF: the light reads
/// exp(ln ε·cap + ln max(cos θ/π, ε)) straight up, exponentiated exactly, computed here
/// from the functions themselves (`common::zonal_exp`).
#[test]
fn the_log_brdf_shades_through_the_exponential_of_the_summed_logs() {
    let scene = ball_below_light();
    let c = scene.c;
    let ln_epsilon = 0.1f64.ln();
    let kink = PI * 0.1;
    let log_diffuse = |t: f64| {
        if t > 0.0 {
            (t / PI).ln().max(ln_epsilon)
        } else {
            ln_epsilon
        }
    };
    for order in [3, 4, 6] {
        let f = common::zonal_projection(
            order,
            |t| log_diffuse(t) + if t > c { ln_epsilon } else { 0.0 },
            &[(-1.0, 0.0), (0.0, kink), (kink, c), (c, 1.0)],
        );
        let expected = common::zonal_value(&common::zonal_exp(&f), 1.0);
        scene.assert_reference_shading(BrdfShading::Log, order, expected);
    }
}

/// [`ball_below_light`] with the BRDF by product: the light reads (exp(ln ε·cap) ∗ cos⁺/π)
/// straight up, both factors and their product computed here from the functions.
#[test]
fn the_product_brdf_shades_through_the_product_of_visibility_and_cosine() {
    let scene = ball_below_light();
    let c = scene.c;
    for order in [3, 4, 6] {
        let visibility = common::zonal_exp_reference(order, c, 0.1f64.ln());
        let cosine = common::zonal_projection(order, |t| t / PI, &[(0.0, 1.0)]);
        let expected = common::zonal_value(&common::zonal_product(&visibility, &cosine), 1.0);
        scene.assert_reference_shading(BrdfShading::Product, order, expected);
    }
}
