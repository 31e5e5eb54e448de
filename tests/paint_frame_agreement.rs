//! What a stroke predicts against what the frame then shows, on the studio with the
//! direct estimate the editor reads before a bake, the painted pixels' luminance read in
//! the rendered frame (tone curve undone):
//! - on the figure's torso, one light at a time (the others locked), a "multiply by 2"
//!   stroke: the frame's change within 5 % of the predicted one for the key, kicker, top
//!   and sky lights (the painting issue's goal). The stroke reads the light at the points
//!   of the surface under the brush (`Transfer::point_shading`); a dab across the
//!   figure's silhouette is measured too and printed (docs/strokes.md): there the frame's
//!   edge filter blends the figure with the backdrop in display values, which no reading
//!   of the light can predict;
//! - the same after a bake, the frame adding the maps' bounced light and strokes reading
//!   it (`shading::frame_transfer`);
//! - on the checkered floor, "direct to a target" above and below what it shows: the
//!   frame reaches the target within 5 %;
//! - on the torso again, the prediction against the path tracer, light by light, before
//!   and after a bake, within 5 %.

mod common;

use common::thin_casters::linear_luma;
use glam::Vec2;
use lightpaint::bake::scene_bvh::SceneBvh;
use lightpaint::paint::{
    BakedTransfer, Brush, BrushKind, Falloff, ModificationStrategy, PaintSettings, Painter, SelectionStrategy,
    StrokeRecord, StrokeReport, Transfer, View, ViewRecord,
};
use lightpaint::project::{Document, sphere_cache};
use lightpaint::render::{AntiAliasing, ShadowFrame, render_logsh_image};
use lightpaint::shading::BakedIndirect;

const WIDTH: u32 = 320;
const HEIGHT: u32 = 240;
const RADIUS_PX: f32 = 6.0;

/// The studio, its camera, blockers and shadow settings as the editor has them, and the
/// stroke's view of it.
struct Studio {
    document: Document,
    blockers: Vec<lightpaint::blockers::Sphere>,
    bvh: SceneBvh,
    view: ViewRecord,
    /// Baked maps: strokes read them, and the frame adds their indirect light.
    maps: Option<lightpaint::bake::ImportanceMaps>,
}

impl Studio {
    fn open() -> Studio {
        let document = Document::open(&common::repo_path("projects/studio/studio.lightpaint")).expect("studio");
        let scene = &document.scene;
        let blockers =
            sphere_cache::cached_or_fitted(scene, &document.settings.blockers, document.project_path.as_deref())
                .shown_spheres(&document.hidden_objects);
        let bvh = SceneBvh::build(scene);
        let view = ViewRecord::of(&View {
            camera: document.view().camera(),
            width_px: WIDTH,
            height_px: HEIGHT,
        });
        Studio {
            document,
            blockers,
            bvh,
            view,
            maps: None,
        }
    }

    /// The studio with maps baked at the default settings.
    fn baked() -> Studio {
        let mut studio = Studio::open();
        let settings = lightpaint::bake::BakeSettings::default();
        studio.maps = Some(lightpaint::bake::bake_maps(&studio.document.scene, &settings));
        studio
    }

    fn object(&self, name: &str) -> usize {
        let objects = &self.document.scene.objects;
        objects.iter().position(|o| o.name == name).expect("the object")
    }

    /// The point `fraction` of the way across `object`'s bounds, projected.
    fn projected(&self, object: usize, fraction: glam::Vec3) -> Vec2 {
        let bounds = self.document.scene.objects[object].bounds();
        let point = bounds.min + (bounds.max - bounds.min) * fraction;
        self.view.view().project(point).expect("in view")
    }

    /// The chest: two thirds up the figure's bounds, on their middle — on the studio
    /// across the torso's edge against the backdrop; and the nearest dab wholly on the
    /// torso.
    fn chest_and_torso(&self) -> (Vec2, Vec2) {
        let figure = self.object("Figure");
        let chest = self.projected(figure, glam::Vec3::new(0.5, 0.66, 0.5));
        (chest, self.dab_wholly_on(figure, chest))
    }

    /// The dab centre nearest `near` whose disc, and a pixel around it, shows `object`
    /// alone.
    fn dab_wholly_on(&self, object: usize, near: Vec2) -> Vec2 {
        let view = self.view.view();
        let on_object = |pixel: Vec2| {
            view.ray_through(pixel)
                .and_then(|(origin, direction)| self.bvh.closest_hit_ignoring(origin, direction, f32::INFINITY, &[]))
                .is_some_and(|hit| hit.object == object && hit.front_facing)
        };
        let reach = RADIUS_PX.ceil() as i32 + 1;
        let wholly_on = |centre: Vec2| {
            (-reach..=reach).all(|dy| {
                (-reach..=reach).all(|dx| {
                    let offset = Vec2::new(dx as f32, dy as f32);
                    offset.length() > RADIUS_PX + 1.0 || on_object(centre + offset)
                })
            })
        };
        let mut candidates: Vec<Vec2> = (-30..=30)
            .flat_map(|dy| (-30..=30).map(move |dx| near.round() + Vec2::new(dx as f32, dy as f32)))
            .collect();
        candidates.sort_by(|a, b| a.distance(near).total_cmp(&b.distance(near)));
        candidates
            .into_iter()
            .find(|&c| wholly_on(c))
            .expect("a dab's disc wholly on the object")
    }

    /// The transfer strokes read: the direct estimate the editor reads before a bake, and
    /// after one the maps' bounce with it (the frame the prediction is checked against
    /// adds the baked light when there are maps: frame_luminance).
    fn transfer(&self) -> Box<dyn Transfer + '_> {
        let mut frame_settings = self.document.settings;
        frame_settings.baked_indirect = self.maps.is_some();
        lightpaint::shading::frame_transfer::transfer_for(
            self.maps.as_ref(),
            &self.document.scene,
            &self.blockers,
            &frame_settings,
        )
    }

    /// A one-dab stroke at `dab`, painted with [`Studio::transfer`]: its report and the
    /// intensities after it.
    fn paint(
        &self,
        dab: Vec2,
        brush: Brush,
        settings: PaintSettings,
        locked_lights: Vec<u32>,
    ) -> (StrokeReport, Vec<f32>) {
        self.paint_with(self.transfer().as_ref(), dab, brush, settings, locked_lights)
    }

    /// A one-dab stroke at `dab`, painted with `transfer`.
    fn paint_with(
        &self,
        transfer: &dyn Transfer,
        dab: Vec2,
        brush: Brush,
        settings: PaintSettings,
        locked_lights: Vec<u32>,
    ) -> (StrokeReport, Vec<f32>) {
        let scene = &self.document.scene;
        let stroke = StrokeRecord {
            view: self.view,
            dabs_px: vec![dab],
            brush,
            settings,
            seed: 1,
            hidden_objects: Vec::new(),
            locked_lights,
        };
        let mut after = scene.light_intensities();
        let report = Painter::new().paint(scene, &self.bvh, transfer, &mut after, stroke);
        (report, after)
    }

    /// The mean luminance (cd/m², linear) the path tracer shows at the surfaces seen
    /// through the dab's pixel centres (the points a stroke reads), with light `light`
    /// alone at `intensity` (no other light, no environment), after `bounces` (0: direct
    /// light, what the estimate models; 1: the maps' bounce too), `spp` paths each.
    fn path_traced_luminance(&self, light: usize, intensity: f32, dab: Vec2, bounces: u32, spp: u32) -> f64 {
        let mut alone = self.document.scene.clone();
        for (index, l) in alone.lights.iter_mut().enumerate() {
            l.intensity = if index == light { intensity } else { 0.0 };
        }
        alone.environment = None;
        let view = self.view.view();
        let mut hits = Vec::new();
        for y in 0..HEIGHT {
            for x in 0..WIDTH {
                let centre = Vec2::new(x as f32 + 0.5, y as f32 + 0.5);
                if centre.distance(dab) > RADIUS_PX {
                    continue;
                }
                let (origin, direction) = view.ray_through(centre).expect("a ray");
                let hit = self.bvh.closest_hit(origin, direction, 0.0, f32::INFINITY);
                hits.push(hit.map(|hit| lightpaint::reference::surface_at(&alone, &hit, origin, direction)));
            }
        }
        let count = hits.len() as u32;
        let eye = view.camera.position;
        let mut render = lightpaint::reference::ProgressiveRender::from_surfaces(&alone, hits, eye, count, bounces, 7);
        for _ in 0..spp {
            render.run_pass();
        }
        let radiance = render.image().radiance;
        radiance.iter().map(|&r| lightpaint::scene::luminance(r)).sum::<f64>() / count as f64
    }

    /// The mean luminance (cd/m², tone curve undone) of the frame's pixels within the
    /// dab, the lights at `intensities`, two stops down so the painted surfaces stay below
    /// the tone curve's shoulder, without baked indirect light (the estimate is direct).
    fn frame_luminance(
        &self,
        gpu: &lightpaint::render::GpuContext,
        intensities: &[f32],
        dab: Vec2,
        anti_aliasing: AntiAliasing,
    ) -> f64 {
        let mut settings = self.document.settings;
        settings.exposure_ev = -2.0;
        settings.baked_indirect = self.maps.is_some();
        let mut lit = self.document.scene.clone();
        lit.set_light_intensities(intensities);
        let indirect = self.maps.as_ref().map(|maps| BakedIndirect::from_maps(&lit, maps));
        let camera = self.document.view().camera();
        let frame = ShadowFrame {
            baked_indirect: indirect.as_ref(),
            scene: &lit,
            camera: &camera,
            settings: &settings,
            shadows: &self.document.settings.shadows,
            blockers: &self.blockers,
            width: WIDTH,
            height: HEIGHT,
        };
        let image = render_logsh_image(gpu, &frame, anti_aliasing).expect("frame");
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
    }
}

/// A hard brush of the test's radius.
fn hard_brush(kind: BrushKind, target_luminance_nits: f32) -> Brush {
    Brush {
        kind,
        radius_px: RADIUS_PX,
        falloff: Falloff::Hard,
        strength: 1.0,
        target_luminance_nits,
    }
}

/// A "× 2" stroke at `dab` on `light_name` alone (the other lights locked), read through
/// `transfer`: the light's index, the predicted change of the painted luminance, and the
/// intensities after it.
fn double_alone(studio: &Studio, transfer: &dyn Transfer, light_name: &str, dab: Vec2) -> (usize, f64, Vec<f32>) {
    let scene = &studio.document.scene;
    let light = scene
        .lights
        .iter()
        .position(|l| l.name == light_name)
        .expect("the light");
    let settings = PaintSettings {
        selection: SelectionStrategy::MostImportant,
        modification: ModificationStrategy::Double { factor: 2.0 },
        ..PaintSettings::default()
    };
    let locked = (0..scene.lights.len() as u32)
        .filter(|&i| i as usize != light)
        .collect();
    let (report, after) = studio.paint_with(transfer, dab, hard_brush(BrushKind::Positive, 1.0), settings, locked);
    assert_eq!(report.changes.len(), 1, "{light_name}: {}", report.message);
    (light, report.mean_after - report.mean_before, after)
}

/// The frame's change over the predicted one for a "× 2" stroke at `dab` on
/// `light_name` alone, read through the studio's transfer.
fn frame_over_prediction(
    studio: &Studio,
    gpu: &lightpaint::render::GpuContext,
    light_name: &str,
    dab: Vec2,
    anti_aliasing: AntiAliasing,
) -> f64 {
    let (_, predicted, after) = double_alone(studio, studio.transfer().as_ref(), light_name, dab);
    let before = studio.document.scene.light_intensities();
    let shown = studio.frame_luminance(gpu, &after, dab, anti_aliasing)
        - studio.frame_luminance(gpu, &before, dab, anti_aliasing);
    shown / predicted
}

#[test]
fn a_strokes_predicted_change_shows_in_the_frame_within_five_percent() {
    let Some(gpu) = common::gpu() else { return };
    let studio = Studio::open();
    let (chest, torso) = studio.chest_and_torso();
    let mut misses = Vec::new();
    for name in ["Key", "Kicker", "Top", "Sky"] {
        let shipped = AntiAliasing::default();
        let ratio = frame_over_prediction(&studio, &gpu, name, torso, shipped);
        let across_edge = frame_over_prediction(&studio, &gpu, name, chest, shipped);
        // The same without the edge filter, which blends the torso with the backdrop.
        let unfiltered = frame_over_prediction(&studio, &gpu, name, chest, AntiAliasing::None);
        eprintln!(
            "{name}: the frame's change is {ratio:.3} times the predicted one on the torso, \
             {across_edge:.3} across its edge ({unfiltered:.3} without the edge filter)"
        );
        if !((0.95..=1.05).contains(&ratio)) {
            misses.push((name, ratio));
        }
    }
    assert!(misses.is_empty(), "frame/prediction outside 5 %: {misses:?}");
}

/// "Direct to a target" on the studio's checkered (textured) floor in front of the figure:
/// the frame's mean luminance over the dab, tone curve undone, reaches the target within
/// 5 %, for a target above and one below what the floor shows.
#[test]
fn a_target_on_the_textured_floor_is_reached_in_the_frame() {
    let Some(gpu) = common::gpu() else { return };
    let studio = Studio::open();
    let floor = studio.object("Floor");
    assert!(
        studio.document.scene.materials[studio.document.scene.objects[floor].material]
            .base_color_texture
            .is_some(),
        "the floor is textured"
    );
    let near = studio.projected(floor, glam::Vec3::new(0.5, 0.0, 0.6));
    let dab = studio.dab_wholly_on(floor, near);
    let inside = RADIUS_PX..(WIDTH as f32 - RADIUS_PX);
    assert!(
        inside.contains(&dab.x) && (RADIUS_PX..HEIGHT as f32 - RADIUS_PX).contains(&dab.y),
        "{dab}"
    );
    let before = studio.document.scene.light_intensities();
    let shown_before = studio.frame_luminance(&gpu, &before, dab, AntiAliasing::default());
    let settings = PaintSettings {
        modification: ModificationStrategy::Direct,
        ..PaintSettings::default()
    };
    for (kind, scale) in [(BrushKind::Positive, 1.5), (BrushKind::Negative, 0.7)] {
        let target = (scale * shown_before) as f32;
        let (report, after) = studio.paint(dab, hard_brush(kind, target), settings, Vec::new());
        assert!(!report.changes.is_empty(), "{}", report.message);
        let shown = studio.frame_luminance(&gpu, &after, dab, AntiAliasing::default());
        eprintln!(
            "floor at {shown_before:.4} cd/m², target {target:.4}: the frame shows {shown:.4} ({})",
            report.message
        );
        assert!(
            (shown / target as f64 - 1.0).abs() <= 0.05,
            "target {target}: the frame shows {shown} ({})",
            report.message
        );
    }
}

/// Once maps are baked, strokes read them for the bounced light and the frame adds it:
/// the same "× 2" strokes on the torso, with maps baked at the default settings, agree
/// with the frame (with the maps' indirect light) within 5 % too.
#[test]
fn after_a_bake_a_strokes_predicted_change_shows_in_the_frame_within_five_percent() {
    let Some(gpu) = common::gpu() else { return };
    let studio = Studio::baked();
    let (_, torso) = studio.chest_and_torso();
    let mut misses = Vec::new();
    for name in ["Key", "Kicker", "Top", "Sky"] {
        let ratio = frame_over_prediction(&studio, &gpu, name, torso, AntiAliasing::default());
        eprintln!("{name}, baked: the frame's change is {ratio:.3} times the predicted one on the torso");
        if !((0.95..=1.05).contains(&ratio)) {
            misses.push((name, ratio));
        }
    }
    assert!(misses.is_empty(), "frame/prediction outside 5 %: {misses:?}");
}

/// The change the path tracer shows (that light alone at the intensity added, with
/// `bounces`) over the predicted one for a "× 2" stroke on `light_name` alone at `dab`,
/// read through `transfer`.
fn path_tracer_over_prediction(
    studio: &Studio,
    transfer: &dyn Transfer,
    light_name: &str,
    dab: Vec2,
    bounces: u32,
) -> f64 {
    let (light, predicted, after) = double_alone(studio, transfer, light_name, dab);
    let added = after[light] - studio.document.scene.lights[light].intensity;
    studio.path_traced_luminance(light, added, dab, bounces, 1024) / predicted
}

/// The representation strokes read, chosen against the path tracer (the painting issue's
/// item 8): on the studio torso, one light at a time, the change a "× 2" stroke predicts
/// against the change the path tracer shows for that light alone (1,024 paths at each
/// point under the dab) — before a bake the direct estimate against direct light; after
/// a bake the estimate plus the maps' bounce against one bounce: within 5 % for the key,
/// kicker, top and sky lights. The maps' order-3 SH of the incident light (what strokes
/// read before) is printed beside it; it was up to 8 % off (docs/strokes.md).
#[test]
fn the_transfer_strokes_read_agrees_with_the_path_tracer_per_light() {
    let direct = Studio::open();
    let baked = Studio::baked();
    let (_, torso) = direct.chest_and_torso();
    let maps = baked.maps.as_ref().expect("maps");
    let harmonics = BakedTransfer::new(&baked.document.scene, maps);
    let mut misses = Vec::new();
    for name in ["Key", "Kicker", "Top", "Sky"] {
        let estimate = path_tracer_over_prediction(&direct, direct.transfer().as_ref(), name, torso, 0);
        let frame_transfer = path_tracer_over_prediction(&baked, baked.transfer().as_ref(), name, torso, 1);
        let sh = path_tracer_over_prediction(&baked, &harmonics, name, torso, 1);
        eprintln!(
            "{name}: path tracer / prediction — estimate (direct) {estimate:.3}, \
             estimate + maps' bounce {frame_transfer:.3}, maps' order-3 SH {sh:.3}"
        );
        for (what, ratio) in [("direct", estimate), ("after a bake", frame_transfer)] {
            if !(0.95..=1.05).contains(&ratio) {
                misses.push((name, what, ratio));
            }
        }
    }
    assert!(misses.is_empty(), "path tracer / prediction outside 5 %: {misses:?}");
}
