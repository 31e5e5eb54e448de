//! The lamp room (samples' `lamp-room`, read through its glTF and project files): single-quad
//! walls, an open shelf and card, a lattice of 2 cm bars, a box, a thin pole and a
//! 100k-triangle ball under 30 lamps of 1.5 m range. On the defaults the live view must be
//! closer to the path tracer than the same frame without shadows: every lamp's shadows
//! come from the real triangles, none from the walls' disc blockers, which hid the lamps
//! that hang in front of them when half the lamps went to the SH path.

mod common;

use lightpaint::blockers::fit_scene;
use lightpaint::project::Document;
use lightpaint::render::{AntiAliasing, ShadowFrame, render_logsh_image};
use lightpaint::samples::Sample;
use lightpaint::scene::Scene;
use lightpaint::shading::gpu_types::SHADOW_PATH_MAP;
use lightpaint::shading::{LightPathContext, ShadowSettings, shading_lights};

const WIDTH: u32 = 240;
const HEIGHT: u32 = 135;

fn lamp_room() -> (tempfile::TempDir, Document) {
    let dir = tempfile::tempdir().expect("temporary directory");
    let project = Sample::LampRoom.write(dir.path()).expect("the lamp room is written");
    let document = Document::open(&project).expect("the lamp room opens");
    (dir, document)
}

/// The displayed (8-bit sRGB) values in [0, 1], as the artist sees them, each averaged
/// over the 3 × 3 pixels around it (edges clamped): a shadow's outline placed half a pixel
/// apart, the checkered floor's aliasing and the path tracer's noise then weigh as little
/// as they change what the eye sees.
fn blurred(image: &image::RgbaImage) -> Vec<[f64; 3]> {
    let (w, h) = (image.width() as i64, image.height() as i64);
    let mut out = Vec::with_capacity((w * h) as usize);
    for y in 0..h {
        for x in 0..w {
            let mut sum = [0.0; 3];
            for (dx, dy) in (-1..=1).flat_map(|dy| (-1..=1).map(move |dx| (dx, dy))) {
                let p = image.get_pixel((x + dx).clamp(0, w - 1) as u32, (y + dy).clamp(0, h - 1) as u32);
                for c in 0..3 {
                    sum[c] += p[c] as f64 / 255.0 / 9.0;
                }
            }
            out.push(sum);
        }
    }
    out
}

/// RMSE over the pixels `mask` keeps (all when None) of two images' values.
fn rmse(a: &[[f64; 3]], b: &[[f64; 3]], mask: Option<&[bool]>) -> f64 {
    let (sum, count) = a
        .iter()
        .zip(b)
        .enumerate()
        .filter(|(k, _)| mask.is_none_or(|m| m[*k]))
        .fold((0.0, 0usize), |(sum, n), (_, (p, q))| {
            (sum + (0..3).map(|c| (p[c] - q[c]).powi(2)).sum::<f64>(), n + 3)
        });
    (sum / count.max(1) as f64).sqrt()
}

/// The displayed values of every pixel, unblurred.
fn displayed(image: &image::RgbaImage) -> Vec<[f64; 3]> {
    image.pixels().map(|p| [0, 1, 2].map(|c| p[c] as f64 / 255.0)).collect()
}

#[test]
fn every_lamp_of_the_room_casts_from_the_real_triangles() {
    let (_dir, document) = lamp_room();
    let scene: &Scene = &document.scene;
    assert_eq!(scene.lights.len(), 30);
    let shadows = document.settings.shadows;
    let blockers = fit_scene(scene, &document.settings.blockers).spheres();
    let context = LightPathContext::of_scene(scene, &blockers);
    let lights = shading_lights(&scene.lights, &shadows, &context);
    let mapped = lights
        .iter()
        .filter(|light| light.shadow_path == SHADOW_PATH_MAP)
        .count();
    assert_eq!(mapped, 30, "lamps on shadow maps");
}

/// The default frame (sphere blockers fitted at the project's budget, Auto light paths,
/// reduced shading, the edge filter) against the path tracer's direct light (64 samples
/// per pixel), beside the same frame with no shadows at all (no blockers, no maps; same
/// shading and antialiasing):
/// - where shadows change what the artist sees (the 3 × 3-averaged displayed values of
///   the frame without shadows more than 4/255 from the path tracer's: 6 % of the
///   pixels), the frame with shadows at most 0.75 of the other's RMSE there (measured
///   0.0284 against 0.0442: 0.64; while 14 of the 30 lamps went to the SH path, whose
///   walls' disc blockers hid the sconces in front of them, 0.0756: worse than none);
/// - over the whole frame, where lit areas count too, at most 0.92 of it (measured
///   0.0153 against 0.0181; with the SH lamps 0.0541).
///
/// The same at 480 × 270 against 512 samples (`render`, `render --reference`): 0.0234
/// against 0.0483 where shadows matter, 0.0106 against 0.0139 over the frame.
#[test]
fn the_default_frame_is_closer_to_the_path_tracer_than_no_shadows() {
    let Some(gpu) = common::gpu() else { return };
    let (_dir, document) = lamp_room();
    let scene = &document.scene;
    let camera = scene.initial_camera();
    let settings = &document.settings;
    let blockers = fit_scene(scene, &settings.blockers).spheres();
    let frame = |shadows: &ShadowSettings, blockers: &[lightpaint::blockers::Sphere]| {
        let frame = ShadowFrame {
            scene,
            camera: &camera,
            settings,
            shadows,
            blockers,
            baked_indirect: None,
            width: WIDTH,
            height: HEIGHT,
        };
        render_logsh_image(&gpu, &frame, AntiAliasing::EdgeFilter).expect("GPU frame")
    };
    let shaded = frame(&settings.shadows, &blockers);
    let unshadowed = frame(
        &ShadowSettings {
            shadow_map_size: 0,
            ..settings.shadows
        },
        &[],
    );
    let reference = lightpaint::reference::render_reference(
        scene,
        &camera,
        WIDTH,
        HEIGHT,
        &lightpaint::reference::ReferenceSettings {
            samples_per_pixel: 64,
            bounces: 0,
            seed: 7,
        },
        |_| {},
    )
    .to_srgb8(settings.exposure_ev as f64, settings.background_srgb8);
    let dir = std::path::Path::new(env!("CARGO_TARGET_TMPDIR")).join("lamp_room");
    let _ = std::fs::create_dir_all(&dir);
    for (name, image) in [
        ("default", &shaded),
        ("unshadowed", &unshadowed),
        ("reference", &reference),
    ] {
        let _ = image.save(dir.join(format!("{name}.png")));
    }
    let (shaded_blurred, unshadowed_blurred, reference_blurred) =
        (blurred(&shaded), blurred(&unshadowed), blurred(&reference));
    let shadows_matter: Vec<bool> = unshadowed_blurred
        .iter()
        .zip(&reference_blurred)
        .map(|(p, q)| (0..3).any(|c| (p[c] - q[c]).abs() > 4.0 / 255.0))
        .collect();
    let share = shadows_matter.iter().filter(|m| **m).count() as f64 / shadows_matter.len() as f64;
    assert!(
        share > 0.02,
        "only {:.1} % of the pixels have shadows to get right",
        100.0 * share
    );
    let (with, without) = (
        rmse(&shaded_blurred, &reference_blurred, Some(&shadows_matter)),
        rmse(&unshadowed_blurred, &reference_blurred, Some(&shadows_matter)),
    );
    let reference_displayed = displayed(&reference);
    let (whole_with, whole_without) = (
        rmse(&displayed(&shaded), &reference_displayed, None),
        rmse(&displayed(&unshadowed), &reference_displayed, None),
    );
    eprintln!(
        "lamp room against the path tracer, where shadows matter ({:.1} % of pixels): default {with:.4}, \
         no shadows {without:.4}; whole frame: {whole_with:.4}, {whole_without:.4}",
        100.0 * share
    );
    assert!(
        with <= 0.75 * without,
        "where shadows matter the default frame ({with:.4}) is not clearly closer to the path tracer than no shadows ({without:.4})"
    );
    assert!(
        whole_with <= 0.92 * whole_without,
        "over the frame the default ({whole_with:.4}) is not closer to the path tracer than no shadows ({whole_without:.4})"
    );
}
