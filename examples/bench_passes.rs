//! The blocker bench's frame (`samples::blocker_bench`, as `cargo bench --bench frame --
//! frame/sphere-count` draws it) pass by pass: where its time goes at a sphere count.
//!
//! `cargo run --release --example bench_passes [SPHERES] [MODE] [FRAMES] [PNG]
//! [DOWNSAMPLE] [LAMPS] [every-light]`: 960 × 540,
//! the shipped defaults with the light on the SH path, SPHERES spheres on the casters
//! (600 by default); MODE `anew` (the default: every frame drawn anew), `per-vertex` (the
//! same, shaded per vertex: the vertices' visibility, computed for the warm-up frame, is
//! kept), `per-vertex-moved` (per vertex, each frame after the light moved a centimetre,
//! which computes the visibility again) or `after-edit` (each frame after the lights were
//! set again, the view kept); prints the mean wall-clock frame and each pass's mean GPU time over
//! FRAMES frames (6) after a warm-up, and how many pixels the upsampling left to be
//! shaded otherwise; PNG: also writes the last frame there; DOWNSAMPLE: shades one pixel
//! in that many squared (1: every pixel, to compare frames with); LAMPS: that many lamps
//! with a range added (`blocker_bench::add_lamps`, the light paths then chosen as the
//! shipped defaults do: as many as the maps' views hold on shadow maps, the rest on the SH
//! path); `every-light`: every point
//! walks every light instead of those of its box of the lights' grid. With BENCH_PANELS=N
//! in the environment the panel is split into N on a ring (`blocker_bench::ring_of_panels`);
//! with BENCH_EXACT=1 every light is on the exact path (the SH path's frame to compare
//! with: exact visibility of the same spheres); with BENCH_SKY=1 a uniform sky lights the
//! set too.

use lightpaint::render::{AntiAliasing, GpuContext, Redraw, ShadowFrame, ShadowRenderer};
use lightpaint::samples::blocker_bench;
use lightpaint::shading::{LightPaths, RenderSettings, ShadowSettings};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let spheres_wanted: usize = args.first().map(|a| a.parse()).transpose()?.unwrap_or(600);
    let (per_vertex, redraw) = match args.get(1).map(String::as_str) {
        None | Some("anew") => (false, Redraw::Everything),
        Some("per-vertex") => (true, Redraw::Everything),
        Some("per-vertex-moved") => (true, Redraw::AfterLightMove),
        Some("after-edit") => (false, Redraw::AfterLightEdit),
        Some(other) => {
            return Err(format!("unknown MODE {other:?}: anew, per-vertex, per-vertex-moved or after-edit").into());
        }
    };
    let frames: u32 = args.get(2).map(|a| a.parse()).transpose()?.unwrap_or(6);
    let gpu = GpuContext::headless()?;
    let mut scene = blocker_bench::thin_casters_scene();
    let lamps: usize = args.get(5).map(|a| a.parse()).transpose()?.unwrap_or(0);
    blocker_bench::add_lamps(&mut scene, lamps);
    let panels: usize = std::env::var("BENCH_PANELS")
        .ok()
        .map(|n| n.parse())
        .transpose()?
        .unwrap_or(1);
    blocker_bench::ring_of_panels(&mut scene, panels);
    if std::env::var("BENCH_SKY").is_ok_and(|v| v == "1") {
        scene.environment = Some(lightpaint::scene::Environment::uniform([0.3, 0.35, 0.4]));
    }
    let every_light = args.get(6).is_some_and(|a| a == "every-light");
    let camera = blocker_bench::thin_casters_camera();
    let png = args.get(3).filter(|path| !path.is_empty());
    let settings = RenderSettings::default();
    let defaults = ShadowSettings::default();
    let shading_downsample: u32 = args
        .get(4)
        .map(|a| a.parse())
        .transpose()?
        .unwrap_or(defaults.shading_downsample);
    let shadows = ShadowSettings {
        light_paths: if std::env::var("BENCH_EXACT").is_ok_and(|v| v == "1") {
            LightPaths::Exact
        } else if lamps > 0 {
            LightPaths::Auto
        } else {
            LightPaths::Harmonics
        },
        per_vertex,
        shading_downsample,
        ..defaults
    };
    let spheres = blocker_bench::spheres_on_casters(&scene, spheres_wanted);
    let frame = ShadowFrame {
        baked_indirect: None,
        scene: &scene,
        camera: &camera,
        settings: &settings,
        shadows: &shadows,
        blockers: &spheres,
        width: 960,
        height: 540,
    };
    let mut renderer = ShadowRenderer::new(&gpu, &frame, AntiAliasing::default())?;
    renderer.set_light_grid(!every_light);
    renderer.draw_and_wait(Redraw::Everything)?;
    let timed = renderer.time_passes();
    let started = std::time::Instant::now();
    for _ in 0..frames {
        renderer.draw_and_wait(redraw)?;
    }
    let mean_ms = started.elapsed().as_secs_f64() * 1000.0 / frames.max(1) as f64;
    println!(
        "{} spheres{}: mean {mean_ms:.1} ms over {frames} frames",
        spheres.len(),
        if per_vertex { ", per vertex" } else { "" }
    );
    if per_vertex {
        println!(
            "vertices whose visibility the last frame computed: {}; objects lit at their vertices: {}",
            renderer.vertices_computed(),
            renderer.objects_lit_at_vertices()
        );
    }
    if let Some(listed) = renderer.listed_pixels() {
        let listed = listed?;
        println!(
            "pixels the upsampling left: {} to the soft layer, {} shaded in full; samples the soft layer left: {}",
            listed.from_soft_layer, listed.in_full, listed.samples_in_full
        );
    }
    if let Some(path) = png {
        renderer.read_image()?.save(path)?;
    }
    if timed {
        let passes: Vec<String> = renderer
            .pass_times_ms()
            .iter()
            .map(|(pass, ms)| format!("{pass} {ms:.1} ms"))
            .collect();
        println!("GPU time per pass: {}", passes.join(", "));
    }
    Ok(())
}
