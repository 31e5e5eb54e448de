//! What a stroke predicts against what the frame then shows: on the studio figure's
//! torso, one light at a time (the others locked), a "multiply by 2" stroke read by the
//! direct estimate the editor uses before a bake, and the painted pixels' luminance in
//! the rendered frame before and after (tone curve undone). The painting issue asks for
//! agreement within 5 % for the key, kicker, top and sky lights. Not reached yet, so this
//! is a measurement, not a pass/fail test: `cargo test --test paint_frame_agreement --
//! --ignored --nocapture` prints each light's ratio of the frame's change to the
//! predicted one (docs/strokes.md gives the figures). The dab stays on the chest: the
//! stroke's mean weighs vertices and the frame's weighs pixels, which differ once a dab
//! covers surfaces of different vertex density.

mod common;

use common::thin_casters::linear_luma;
use glam::Vec2;
use lightpaint::bake::scene_bvh::SceneBvh;
use lightpaint::paint::{
    Brush, BrushKind, Falloff, ModificationStrategy, PaintSettings, Painter, SelectionStrategy, StrokeRecord, View,
    ViewRecord,
};
use lightpaint::project::{Document, sphere_cache};
use lightpaint::render::{AntiAliasing, ShadowFrame, render_logsh_image};

const WIDTH: u32 = 320;
const HEIGHT: u32 = 240;
const RADIUS_PX: f32 = 6.0;

/// The frame's change over the predicted one for the stroke on `light_name` alone.
fn frame_over_prediction(document: &Document, gpu: &lightpaint::render::GpuContext, light_name: &str) -> f64 {
    let scene = &document.scene;
    let camera = document.view().camera();
    let blockers = sphere_cache::cached_or_fitted(scene, &document.settings.blockers, document.project_path.as_deref())
        .shown_spheres(&document.hidden_objects);
    let shadows = document.settings.shadows;
    let view = ViewRecord::of(&View {
        camera: camera.clone(),
        width_px: WIDTH,
        height_px: HEIGHT,
    });
    let figure = scene.objects.iter().find(|o| o.name == "Figure").expect("the figure");
    let bounds = figure.bounds();
    // The chest: two thirds of the way up the figure, on its middle.
    let chest = bounds.min + (bounds.max - bounds.min) * glam::Vec3::new(0.5, 0.66, 0.5);
    let dab = view.view().project(chest).expect("the chest is in view");
    let light = scene
        .lights
        .iter()
        .position(|l| l.name == light_name)
        .expect("the light");
    let stroke = StrokeRecord {
        view,
        dabs_px: vec![dab],
        brush: Brush {
            kind: BrushKind::Positive,
            radius_px: RADIUS_PX,
            falloff: Falloff::Hard,
            strength: 1.0,
            target_luminance_nits: 1.0,
        },
        settings: PaintSettings {
            selection: SelectionStrategy::MostImportant,
            modification: ModificationStrategy::Double { factor: 2.0 },
            ..PaintSettings::default()
        },
        seed: 1,
        hidden_objects: Vec::new(),
        locked_lights: (0..scene.lights.len() as u32)
            .filter(|&i| i as usize != light)
            .collect(),
    };
    let transfer = lightpaint::shading::paint_estimate::transfer_for(None, scene, &blockers, &shadows);
    let bvh = SceneBvh::build(scene);
    let before = scene.light_intensities();
    let mut after = before.clone();
    let report = Painter::new().paint(scene, &bvh, transfer.as_ref(), &mut after, stroke);
    assert_eq!(report.changes.len(), 1, "{light_name}: {}", report.message);
    let predicted = report.mean_after - report.mean_before;

    // The frame two stops down so the chest stays below the tone curve's shoulder.
    let mut settings = document.settings;
    settings.exposure_ev = -2.0;
    settings.baked_indirect = false;
    let luma_at = |intensities: &[f32]| {
        let mut lit = scene.clone();
        lit.set_light_intensities(intensities);
        let frame = ShadowFrame {
            baked_indirect: None,
            scene: &lit,
            camera: &camera,
            settings: &settings,
            shadows: &shadows,
            blockers: &blockers,
            width: WIDTH,
            height: HEIGHT,
        };
        let image = render_logsh_image(gpu, &frame, AntiAliasing::default()).expect("frame");
        let luma = linear_luma(&image);
        let (mut sum, mut count) = (0.0, 0.0);
        for y in 0..HEIGHT {
            for x in 0..WIDTH {
                let centre = Vec2::new(x as f32 + 0.5, y as f32 + 0.5);
                if centre.distance(dab) <= RADIUS_PX {
                    sum += luma[(y * WIDTH + x) as usize];
                    count += 1.0;
                }
            }
        }
        4.0 * sum / count
    };
    let shown = luma_at(&after) - luma_at(&before);
    shown / predicted
}

#[test]
#[ignore = "a measurement (docs/strokes.md): the 5 % agreement the painting issue asks for is not reached yet"]
fn measure_a_strokes_predicted_change_against_the_frame() {
    let Some(gpu) = common::gpu() else { return };
    let document = Document::open(&common::repo_path("projects/studio/studio.lightpaint")).expect("studio");
    let mut ratios = Vec::new();
    for name in ["Key", "Kicker", "Top", "Sky"] {
        let ratio = frame_over_prediction(&document, &gpu, name);
        eprintln!("{name}: the frame's change is {ratio:.3} times the predicted one");
        ratios.push((name, ratio));
    }
    assert!(ratios.iter().all(|(_, r)| r.is_finite()), "{ratios:?}");
}
