//! The exact shadow path for small lights (`lightpaint::penumbra`, `exact_batch_visibility`
//! in logsh.wgsl) on the GPU: parity with the f64 CPU reference on the sample scenes with
//! every light exact, and a ball over a plane under a sphere light whose penumbra, pixel by
//! pixel, is the visible share of the light computed here by integration over its disc.

mod common;

use std::f64::consts::PI;

use glam::{DVec3, Vec3, Vec4};
use lightpaint::blockers::{BlockerSettings, Sphere, fit_scene};
use lightpaint::penumbra::{Emitter, LightDisc, light_visibility};
use lightpaint::project::Document;
use lightpaint::render::{
    AntiAliasing, GpuContext, ShadowFrame, capture_surfaces, render_cpu_image, render_logsh_image,
};
use lightpaint::scene::{Camera, Light, LightKind, Material, Scene, shapes};
use lightpaint::shading::{LightPaths, RenderSettings, ShadowSettings};

/// A white Lambertian floor `size_m` wide at y = 0 under `lights`.
fn white_floor(size_m: f32, lights: Vec<Light>) -> Scene {
    Scene {
        objects: vec![shapes::plane(size_m, 4, 1.0).into_object("floor")],
        materials: vec![Material {
            base_color: Vec4::ONE,
            metallic: 0.0,
            specular: 0.0,
            ..Material::default()
        }],
        lights,
        ..Scene::default()
    }
}

/// The GPU frame agrees with the f64 CPU shading of the same surfaces: at least 99.5 %
/// of pixels within 1/255 (hard shadow edges may fall on the other side of a pixel
/// centre in f32).
fn assert_gpu_matches_cpu(gpu: &GpuContext, frame: &ShadowFrame, what: &str) {
    let gpu_image = render_logsh_image(gpu, frame, AntiAliasing::None).expect("GPU frame");
    let cpu_image = render_cpu_image(gpu, frame).expect("CPU frame");
    let (within, worst) = agreement(&gpu_image, &cpu_image, 1);
    eprintln!("{what}: {:.3} % within 1/255, worst {worst}/255", 100.0 * within);
    assert!(within >= 0.995, "{what}: {:.3} % within 1/255", 100.0 * within);
}

/// Share of the pixels whose channels lie within `tolerance`/255 of the other image, and
/// the largest difference.
fn agreement(a: &image::RgbaImage, b: &image::RgbaImage, tolerance: u8) -> (f64, u8) {
    let differences: Vec<u8> = a
        .pixels()
        .zip(b.pixels())
        .map(|(p, q)| (0..3).map(|c| p[c].abs_diff(q[c])).max().unwrap_or(0))
        .collect();
    let within = differences.iter().filter(|&&d| d <= tolerance).count();
    (
        within as f64 / differences.len() as f64,
        differences.into_iter().max().unwrap_or(0),
    )
}

/// Every light of the samples exact — point and spot lights with hard shadows, and the
/// same lights as 0.3 m spheres with penumbrae: the f32 GPU agrees with the f64 CPU.
#[test]
fn the_exact_path_matches_the_cpu_reference_on_the_samples() {
    let Some(gpu) = common::gpu() else { return };
    for path in ["projects/studio/studio.lightpaint", "projects/sample/sample.lightpaint"] {
        let document = Document::open(&common::repo_path(path)).expect("sample opens");
        let camera = document
            .camera
            .map_or_else(|| document.scene.initial_camera(), |o| o.camera());
        let blockers = fit_scene(&document.scene, &BlockerSettings::default()).spheres();
        let mut spheres = document.scene.clone();
        for light in &mut spheres.lights {
            if light.kind == LightKind::Point {
                light.kind = LightKind::Sphere { radius_m: 0.3 };
            }
        }
        let exact = ShadowSettings {
            light_paths: LightPaths::Exact,
            ..document.settings.shadows.every_pixel()
        };
        // The spot lights without shadow maps, on the SH path (their maps' twin is a ray
        // cast: tests/shadow_maps.rs).
        let auto = ShadowSettings {
            light_paths: LightPaths::Auto,
            shadow_map_size: 0,
            ..document.settings.shadows.every_pixel()
        };
        // A budget of one exact light: the sphere light whose shadows matter most goes
        // exact, the others stay on the SH, on the GPU and the CPU alike.
        let one_exact = ShadowSettings {
            exact_light_budget: 1,
            ..auto
        };
        for (scene, shadows, what) in [
            (&document.scene, &exact, "exact"),
            (&spheres, &auto, "sphere lights, auto"),
            (&spheres, &one_exact, "sphere lights, auto, one exact"),
        ] {
            let frame = ShadowFrame {
                scene,
                camera: &camera,
                settings: &document.settings,
                shadows,
                blockers: &blockers,
                baked_indirect: None,
                width: 240,
                height: 135,
            };
            assert_gpu_matches_cpu(&gpu, &frame, &format!("{path}, {what}"));
        }
    }
}

/// Ten exact lights of every kind over a tight cluster of small balls: the GPU takes the
/// lights eight at a time and, under the cluster, finds more blockers cutting a disc than
/// its list of eight holds, and must still agree with the f64 CPU, which takes every light
/// and blocker one by one.
#[test]
fn many_lights_over_a_crowd_of_blockers_match_the_cpu_reference() {
    let Some(gpu) = common::gpu() else { return };
    let light = |name: &str, kind, position: Vec3, intensity| Light {
        name: name.into(),
        kind,
        color: Vec3::ONE,
        intensity,
        position,
        direction: Vec3::new(0.2, -1.0, 0.1).normalize(),
        range: None,
        locked: false,
    };
    let spot = LightKind::Spot {
        inner_cone_rad: 0.4,
        outer_cone_rad: 0.7,
    };
    let mut lights: Vec<Light> = [0.05f32, 0.2, 0.4, 0.8, 1.2, 0.1]
        .iter()
        .enumerate()
        .map(|(k, &radius_m)| {
            let turn = k as f32 * 1.1;
            let position = Vec3::new(1.5 * turn.cos(), 3.0 + 0.3 * k as f32, 1.5 * turn.sin());
            light(&format!("sphere {k}"), LightKind::Sphere { radius_m }, position, 12.0)
        })
        .collect();
    lights.push(light("point", LightKind::Point, Vec3::new(-0.4, 2.5, 0.3), 8.0));
    lights.push(light("spot", spot, Vec3::new(0.5, 3.0, -0.2), 20.0));
    lights.push(light("sun", LightKind::Directional, Vec3::ZERO, 0.5));
    lights.push(light(
        "far sphere",
        LightKind::Sphere { radius_m: 0.3 },
        Vec3::new(0.0, 6.0, 0.0),
        30.0,
    ));
    let scene = white_floor(4.0, lights);
    // Thirty 6 cm balls 10 cm apart, 0.8 m up: under them a light's disc meets many.
    let blockers: Vec<Sphere> = (0..30)
        .map(|k| Sphere {
            center: Vec3::new(-0.25 + 0.1 * (k % 6) as f32, 0.8, -0.2 + 0.1 * (k / 6) as f32),
            radius_m: 0.06,
            disc_normal: glam::Vec3::ZERO,
        })
        .collect();
    let camera = Camera {
        position: Vec3::new(0.0, 4.0, 0.01),
        forward: Vec3::NEG_Y,
        up: Vec3::NEG_Z,
        yfov_rad: 40f32.to_radians(),
        znear: 0.1,
        zfar: None,
    };
    let settings = RenderSettings::default();
    let shadows = ShadowSettings {
        light_paths: LightPaths::Exact,
        ..ShadowSettings::default().every_pixel()
    };
    let frame = ShadowFrame {
        scene: &scene,
        camera: &camera,
        settings: &settings,
        shadows: &shadows,
        blockers: &blockers,
        baked_indirect: None,
        width: 160,
        height: 160,
    };
    assert_gpu_matches_cpu(&gpu, &frame, "ten lights over a crowd");
    // The crowd is there: under its middle, the largest sphere light's disc meets more
    // than eight balls.
    let under = DVec3::new(0.0, 0.0, 0.0);
    let big = &scene.lights[4];
    let to_light = (big.position.as_dvec3() - under).normalize();
    let disc = (1.2 / (big.position.as_dvec3() - under).length()).asin();
    let cutting = blockers
        .iter()
        .filter(|b| {
            let offset = b.center.as_dvec3() - under;
            let cap = (b.radius_m as f64 / offset.length()).asin();
            offset.normalize().angle_between(to_light) < disc + cap
        })
        .count();
    assert!(cutting > 8, "{cutting} balls cut the disc");
}

/// One pixel of a frame row over the floor: the GPU's 8-bit value, and what a light of
/// irradiance `irradiance` (unshadowed) and visible share `visible` would give.
struct RowPixel {
    x_m: f64,
    got: f64,
    irradiance: f64,
    visible: f64,
}

/// A white Lambertian floor under a 0.5 m sphere light 3 m above the origin (40 cd) and
/// `balls`, drawn from above on the exact path; along the frame's middle row (x ≥ 0 when
/// `right_half_only`) each floor pixel with the unshadowed irradiance I·cos θ/d² (the
/// renderer's unshadowed sphere light) and the share of the light's disc whose rays miss
/// every ball, integrated over the disc.
fn floor_row_under_a_sphere_light(gpu: &GpuContext, balls: &[Sphere], right_half_only: bool) -> Vec<RowPixel> {
    let light_position = DVec3::new(0.0, 3.0, 0.0);
    let scene = white_floor(
        6.0,
        vec![Light {
            name: "globe".into(),
            kind: LightKind::Sphere { radius_m: 0.5 },
            color: Vec3::ONE,
            intensity: 40.0,
            position: light_position.as_vec3(),
            direction: Vec3::NEG_Y,
            range: None,
            locked: false,
        }],
    );
    let camera = Camera {
        position: Vec3::new(0.0, 6.0, 0.0),
        forward: Vec3::NEG_Y,
        up: Vec3::NEG_Z,
        yfov_rad: 40f32.to_radians(),
        znear: 0.1,
        zfar: None,
    };
    let settings = RenderSettings {
        exposure_ev: -2.0,
        ..RenderSettings::default()
    };
    // Auto without shadow maps (which would take a 9.6° light): the exact path.
    let shadows = ShadowSettings {
        shadow_map_size: 0,
        ..ShadowSettings::default().every_pixel()
    };
    let (width, height) = (160, 160);
    let frame = ShadowFrame {
        scene: &scene,
        camera: &camera,
        settings: &settings,
        shadows: &shadows,
        blockers: balls,
        baked_indirect: None,
        width,
        height,
    };
    let image = render_logsh_image(gpu, &frame, AntiAliasing::None).expect("GPU frame");
    let surfaces = capture_surfaces(gpu, &scene, &camera, None, width, height).expect("surfaces");
    let row = height / 2;
    let balls: Vec<(DVec3, f64)> = balls.iter().map(|b| (b.center.as_dvec3(), b.radius_m as f64)).collect();
    let first = if right_half_only { width / 2 } else { 0 };
    (first..width)
        .filter_map(|x| {
            let p = surfaces[(row * width + x) as usize].as_ref()?.position;
            let offset = light_position - p;
            Some(RowPixel {
                x_m: p.x,
                got: image.get_pixel(x, row)[0] as f64,
                irradiance: 40.0 * offset.normalize().y / offset.length_squared(),
                visible: 1.0 - hidden_share(p, light_position, 0.5, &balls),
            })
        })
        .collect()
}

/// A ball of 0.3 m at 1 m over the floor under the sphere light: pixel by pixel its
/// penumbra is the share of the light it leaves visible.
#[test]
fn a_ball_under_a_sphere_light_casts_the_exact_penumbra_on_the_gpu() {
    let Some(gpu) = common::gpu() else { return };
    let ball = Sphere::ball(Vec3::new(0.0, 1.0, 0.0), 0.3);
    let row = floor_row_under_a_sphere_light(&gpu, &[ball], true);
    for pixel in &row {
        let expected = common::expected_8bit(pixel.irradiance / PI * pixel.visible, -2.0);
        assert!(
            (pixel.got - expected).abs() <= 1.5,
            "x = {:.3} m: pixel {}, expected {expected:.2} (visible share {:.4})",
            pixel.x_m,
            pixel.got,
            pixel.visible
        );
    }
    let penumbra = row.iter().filter(|p| p.visible > 0.02 && p.visible < 0.98).count();
    assert!(
        row.len() > 60 && penumbra > 5,
        "{} pixels, {penumbra} in the penumbra",
        row.len()
    );
}

/// Balls whose caps share the light: two side by side that touch (under them each hides
/// one side of the light, together all of it), and one above the left that hides much of
/// what it hides. Pixel by pixel the frame shows the share of the light their union
/// leaves, within 0.03 of it; taking the balls' shares as independent, Π(1 − fᵢ), is off
/// by more than 0.1 somewhere on the row (so the test tells the two apart).
#[test]
fn overlapping_and_adjacent_balls_hide_the_union_of_their_shares_on_the_gpu() {
    let Some(gpu) = common::gpu() else { return };
    let balls = [
        Sphere::ball(Vec3::new(-0.25, 1.0, 0.0), 0.25),
        Sphere::ball(Vec3::new(0.25, 1.0, 0.0), 0.25),
        Sphere::ball(Vec3::new(-0.3, 1.6, 0.0), 0.2),
    ];
    let row = floor_row_under_a_sphere_light(&gpu, &balls, false);
    let mut independent_worst: f64 = 0.0;
    for pixel in &row {
        let level = |visible: f64| common::expected_8bit(pixel.irradiance / PI * visible, -2.0);
        let (low, high) = (
            level((pixel.visible - 0.03).max(0.0)),
            level((pixel.visible + 0.03).min(1.0)),
        );
        assert!(
            (low - 1.0..=high + 1.0).contains(&pixel.got),
            "x = {:.3} m: pixel {}, expected {low:.1}–{high:.1} (visible share {:.4})",
            pixel.x_m,
            pixel.got,
            pixel.visible
        );
        let p = DVec3::new(pixel.x_m, 0.0, 0.0);
        let light = DVec3::new(0.0, 3.0, 0.0);
        let independent: f64 = balls
            .iter()
            .map(|b| 1.0 - hidden_share(p, light, 0.5, &[(b.center.as_dvec3(), b.radius_m as f64)]))
            .product();
        independent_worst = independent_worst.max((independent - pixel.visible).abs());
    }
    let penumbra = row.iter().filter(|p| p.visible > 0.02 && p.visible < 0.98).count();
    assert!(
        row.len() > 120 && penumbra > 20,
        "{} pixels, {penumbra} in the penumbra",
        row.len()
    );
    assert!(
        independent_worst > 0.1,
        "independent shares are off by at most {independent_worst}"
    );
}

/// The f64 path alone: a ball of 0.3 m at 1 m over the origin under a 0.5 m sphere light
/// 3 m up; along a line through the penumbra the visibility is the share of the light's
/// disc whose rays miss the ball, and it rises away from the ball to the whole light.
#[test]
fn the_f64_path_draws_the_exact_penumbra_of_a_ball() {
    let ball = [Sphere {
        center: Vec3::new(0.0, 1.0, 0.0),
        radius_m: 0.3,
        disc_normal: glam::Vec3::ZERO,
    }];
    let light = DVec3::new(0.0, 3.0, 0.0);
    let mut last = 0.0;
    for k in 0..=40 {
        let p = DVec3::new(k as f64 * 0.05, 0.0, 0.0);
        let offset = light - p;
        let d = offset.length();
        let disc = LightDisc {
            to_light: offset / d,
            distance_m: d,
            cap_ratio: 0.5 / d,
            emitter: Emitter::Sphere { radius_m: 0.5 },
        };
        let v = light_visibility(p, DVec3::Y, &disc, &ball, &[], 0.0, 0.0);
        let expected = 1.0 - hidden_share(p, light, 0.5, &[(DVec3::new(0.0, 1.0, 0.0), 0.3)]);
        assert!((v - expected).abs() < 3e-3, "x = {:.2}: {v} vs {expected}", p.x);
        assert!(v >= last - 1e-9, "visibility rises away from the ball");
        last = v;
    }
    assert!(last > 0.999, "far points see the whole light");
}

/// A point light's hard shadow is anti-aliased: along a line across the edge of a ball's
/// shadow, the visibility ramps from 5 % to 95 % over about one pixel footprint, centred
/// on the geometric edge (the cone from the light tangent to the ball, in closed form), and
/// is exactly 0 and 1 a pixel and a half inside and outside it.
#[test]
fn a_point_lights_shadow_edge_ramps_over_about_one_pixel() {
    let (centre, radius) = (DVec3::new(0.0, 1.0, 0.0), 0.3);
    let ball = [Sphere {
        center: centre.as_vec3(),
        radius_m: radius as f32,
        disc_normal: glam::Vec3::ZERO,
    }];
    let light = DVec3::new(0.0, 3.0, 0.0);
    // The cone from the light tangent to the ball meets the floor at this radius.
    let half_angle = (radius / (light - centre).length()).asin();
    let edge = light.y * half_angle.tan();
    let visibility = |x: f64, footprint: f64| {
        let p = DVec3::new(x, 0.0, 0.0);
        let offset = light - p;
        let disc = LightDisc {
            to_light: offset.normalize(),
            distance_m: offset.length(),
            cap_ratio: 0.0,
            emitter: Emitter::Sphere { radius_m: 0.0 },
        };
        light_visibility(p, DVec3::Y, &disc, &ball, &[], 0.0, footprint)
    };
    // Without a footprint the edge is a step.
    assert_eq!(visibility(edge - 1e-4, 0.0), 0.0);
    assert_eq!(visibility(edge + 1e-4, 0.0), 1.0);
    for footprint in [0.004, 0.01, 0.03] {
        let xs: Vec<f64> = (-60..=60).map(|k| edge + k as f64 * footprint / 20.0).collect();
        let vs: Vec<f64> = xs.iter().map(|&x| visibility(x, footprint)).collect();
        assert!(vs.windows(2).all(|w| w[1] >= w[0] - 1e-12), "monotonic across the edge");
        let crossing = |level: f64| xs[vs.iter().position(|&v| v >= level).expect("crosses")];
        let width = crossing(0.95) - crossing(0.05);
        assert!(
            (0.5 * footprint..=2.0 * footprint).contains(&width),
            "footprint {footprint}: 5-95 % over {width}"
        );
        assert!(
            (crossing(0.5) - edge).abs() <= 0.25 * footprint,
            "footprint {footprint}: centred at {} vs the edge at {edge}",
            crossing(0.5)
        );
        assert_eq!(visibility(edge - 1.5 * footprint, footprint), 0.0, "umbra stays dark");
        assert_eq!(visibility(edge + 1.5 * footprint, footprint), 1.0, "lit stays lit");
    }
}

/// Share of the light's cap, seen from p, whose rays meet the ball (a fine polar grid of
/// equal solid-angle cells over the cap).
fn hidden_share(p: DVec3, light: DVec3, light_radius: f64, balls: &[(DVec3, f64)]) -> f64 {
    let axis = (light - p).normalize();
    let half_angle = (light_radius / (light - p).length()).asin();
    let (t, b) = axis.any_orthonormal_pair();
    let (rings, sectors) = (600, 600);
    let mut hidden = 0usize;
    for i in 0..rings {
        let cos_t = 1.0 - (i as f64 + 0.5) / rings as f64 * (1.0 - half_angle.cos());
        let sin_t = (1.0 - cos_t * cos_t).sqrt();
        for j in 0..sectors {
            let phi = (j as f64 + 0.5) / sectors as f64 * std::f64::consts::TAU;
            let d = axis * cos_t + (t * phi.cos() + b * phi.sin()) * sin_t;
            let hits = balls.iter().any(|&(centre, radius)| {
                let oc = p - centre;
                let half_b = oc.dot(d);
                let c = oc.length_squared() - radius * radius;
                half_b < 0.0 && half_b * half_b >= c
            });
            hidden += usize::from(hits);
        }
    }
    hidden as f64 / (rings * sectors) as f64
}
