//! The lights' grid (`shading::light_grid`) leaves out of a point's walk only lights that
//! add nothing there: frames of a scene lit by many lamps with a range — around a ring
//! of posts and open cards, some on shadow maps and the rest on the SH path through the
//! fitted blockers, beside spots and an unbounded sun — must be byte for byte those drawn
//! walking every light, deferred (one pixel in 3 × 3 shaded), with every pixel shaded,
//! and per vertex; and the frames must walk the grid for the comparison to mean anything.

mod common;

use glam::Vec3;
use lightpaint::blockers::fit_scene;
use lightpaint::scene::{Light, LightKind, Scene};
use lightpaint::shading::{RenderSettings, ShadowSettings};

const SIZE: [u32; 2] = [320, 180];

fn light(name: String, kind: LightKind, position: Vec3, intensity: f32, range: Option<f32>) -> Light {
    Light {
        name,
        kind,
        color: Vec3::new(1.0, 0.85, 0.7),
        intensity,
        position,
        direction: Vec3::NEG_Y,
        range,
        locked: false,
    }
}

/// The ring with 40 lamps of 1.5 m range in two rings about it (the first 16 take shadow
/// maps, the rest the SH path), four spots of 4 m range aimed into the ring, and a dim sun.
fn lamplit_ring() -> Scene {
    let mut scene = common::scenes::ring_of_posts_and_cards();
    for k in 0..40 {
        let angle = k as f32 * std::f32::consts::TAU / 20.0;
        let radius_m = if k < 20 { 2.2 } else { 4.0 };
        let at = Vec3::new(
            radius_m * angle.cos(),
            0.5 + 0.04 * (k % 7) as f32,
            radius_m * angle.sin(),
        );
        scene
            .lights
            .push(light(format!("lamp {k}"), LightKind::Point, at, 0.6, Some(1.5)));
    }
    for k in 0..4 {
        let angle = k as f32 * std::f32::consts::FRAC_PI_2 + 0.4;
        let at = Vec3::new(5.0 * angle.cos(), 2.5, 5.0 * angle.sin());
        let mut spot = light(
            format!("spot {k}"),
            LightKind::Spot {
                inner_cone_rad: 0.2,
                outer_cone_rad: 0.35,
            },
            at,
            12.0,
            Some(4.0),
        );
        spot.direction = (Vec3::new(0.0, 0.0, 0.0) - at).normalize();
        scene.lights.push(spot);
    }
    let mut sun = light("sun".into(), LightKind::Directional, Vec3::ZERO, 0.05, None);
    sun.direction = Vec3::new(0.3, -1.0, 0.2).normalize();
    scene.lights.push(sun);
    scene
}

#[test]
fn frames_walking_the_lights_grid_are_those_walking_every_light() {
    let Some(gpu) = common::gpu() else { return };
    let scene = lamplit_ring();
    let camera = common::scenes::ring_camera();
    let defaults = RenderSettings::default();
    let blockers = fit_scene(&scene, &defaults.blockers).spheres();
    assert!(!blockers.is_empty(), "the SH path's lamps walk blockers");
    for (what, shadows) in [
        ("deferred", defaults.shadows),
        (
            "every pixel",
            ShadowSettings {
                shading_downsample: 1,
                ..defaults.shadows
            },
        ),
        (
            "per vertex",
            ShadowSettings {
                per_vertex: true,
                ..defaults.shadows
            },
        ),
    ] {
        let settings = RenderSettings { shadows, ..defaults };
        let draw = |grid: bool| {
            let (image, renderer) = common::drawn_with(&gpu, (&scene, &blockers), &settings, (&camera, SIZE), |r| {
                r.set_light_grid(grid)
            });
            (image, renderer.walks_light_grid())
        };
        let (gridded, walked) = draw(true);
        let (every, walked_without) = draw(false);
        assert!(walked, "{what}: 40 lamps with a range are worth a grid");
        assert!(!walked_without, "{what}: the grid was turned off");
        let lit = gridded.pixels().filter(|p| p[0] > 40).count();
        assert!(
            lit > (SIZE[0] * SIZE[1] / 10) as usize,
            "{what}: the lamps light the floor ({lit} pixels)"
        );
        let differing = common::differing_pixels(&gridded, &every);
        assert_eq!(differing, 0, "{what}: {differing} pixels differ with the grid");
    }
}
