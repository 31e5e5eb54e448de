//! Reduced-resolution shading (`render::passes::reduced_shading`, on lavapipe in CI) against
//! shading every pixel: on the sample scenes the frames look alike, and texture detail
//! finer than the shading blocks survives because only the lighting is interpolated.

mod common;

use glam::{Vec2, Vec3};
use lightpaint::blockers::{Sphere, fit_scene};
use lightpaint::project::Document;
use lightpaint::render::{AntiAliasing, GpuContext, ShadowFrame, render_logsh_image};
use lightpaint::scene::gltf_write::LightSpec;
use lightpaint::scene::{Camera, Scene};
use lightpaint::shading::{RenderSettings, SUGGESTED_SHADOW_MAP_SIZE, ShadowSettings};

/// Shares of pixels whose channels all lie within 2/255 and within 8/255 of `full`, and
/// the largest channel difference.
fn agreement(reduced: &image::RgbaImage, full: &image::RgbaImage) -> (f64, f64, u8) {
    let (mut within_2, mut within_8, mut worst) = (0usize, 0usize, 0u8);
    for (a, b) in reduced.pixels().zip(full.pixels()) {
        let d = (0..3).map(|c| a[c].abs_diff(b[c])).max().unwrap_or(0);
        worst = worst.max(d);
        within_2 += usize::from(d <= 2);
        within_8 += usize::from(d <= 8);
    }
    let n = (full.width() * full.height()) as f64;
    (within_2 as f64 / n, within_8 as f64 / n, worst)
}

fn save_for_review(name: &str, image: &image::RgbaImage) {
    let dir = std::path::Path::new(env!("CARGO_TARGET_TMPDIR")).join("reduced_shading");
    let _ = std::fs::create_dir_all(&dir);
    let _ = image.save(dir.join(format!("{name}.png")));
}

/// The frame shaded at every pixel and with one shaded pixel per `downsample`², with
/// `samples` per pixel (1, where unmatched pixels are shaded in full, or 4, where they
/// take the best sample nearby).
#[allow(clippy::too_many_arguments)]
fn full_and_reduced(
    gpu: &GpuContext,
    scene: &Scene,
    camera: &Camera,
    settings: &RenderSettings,
    blockers: &[Sphere],
    downsample: u32,
    samples: u32,
    [width, height]: [u32; 2],
) -> (image::RgbaImage, image::RgbaImage) {
    let render = |shading_downsample| {
        let shadows = ShadowSettings {
            shading_downsample,
            ..settings.shadows
        };
        let frame = ShadowFrame {
            baked_indirect: None,
            scene,
            camera,
            settings,
            shadows: &shadows,
            blockers,
            width,
            height,
        };
        render_logsh_image(gpu, &frame, AntiAliasing::with_samples(samples)).expect("render")
    };
    (render(1), render(downsample))
}

#[test]
fn shading_one_pixel_per_block_looks_like_shading_every_pixel_on_the_samples() {
    let Some(gpu) = common::gpu() else { return };
    for (name, project) in [
        ("sample", "projects/sample/sample.lightpaint"),
        ("studio", "projects/studio/studio.lightpaint"),
    ] {
        let document = Document::open(&common::repo_path(project)).expect("sample opens");
        let camera = document
            .camera
            .map_or_else(|| document.scene.initial_camera(), |o| o.camera());
        let blockers = fit_scene(&document.scene, &document.settings.blockers).spheres();
        // 2 × 2 blocks with and without multisampling, and the default 3 × 3; the soft
        // shadows alone (no shadow maps) and with the maps' hard edges, which are
        // interpolated across the blocks too and held to their own measured bounds.
        for (downsample, samples, map_size) in [
            (2, 1, 0),
            (2, 4, 0),
            (3, 1, 0),
            (2, 1, SUGGESTED_SHADOW_MAP_SIZE),
            (3, 1, SUGGESTED_SHADOW_MAP_SIZE),
        ] {
            let settings = RenderSettings {
                shadows: ShadowSettings {
                    shadow_map_size: map_size,
                    ..document.settings.shadows
                },
                ..document.settings
            };
            let (full, reduced) = full_and_reduced(
                &gpu,
                &document.scene,
                &camera,
                &settings,
                &blockers,
                downsample,
                samples,
                [480, 270],
            );
            let label = format!("{name}, 1 in {downsample}², {samples} sample(s) per pixel, maps {map_size}");
            save_for_review(&format!("{name}-msaa{samples}-maps{map_size}-every-pixel"), &full);
            save_for_review(
                &format!("{name}-msaa{samples}-maps{map_size}-one-in-{downsample}x{downsample}"),
                &reduced,
            );
            let (within_2, within_8, worst) = agreement(&reduced, &full);
            eprintln!(
                "{label}: {:.3} % within 2/255, {:.3} % within 8/255, worst {worst}/255",
                100.0 * within_2,
                100.0 * within_8
            );
            // What differs lies where the lighting changes within a block: specular
            // highlights (interpolated, slightly blurred) and what of rims and hard
            // shadow edges the samples' disagreement does not catch (measured with 1024²
            // maps at 480 × 270: 96.6–97.8 % within 2/255 and 99.2–99.6 % within 8/255 on
            // the sample and the studio — with the soft layer at half the samples'
            // resolution, which two-level shading adds here — against 95.4–96.4 and
            // 98.3–98.9 % when those pixels were interpolated too; without maps 97.4–99.1
            // and 99.0–99.8 %, the lowest with 4 samples per pixel, where no pixel is
            // shaded in full: 97.7 and 99.1 % before base colour textures were filtered
            // over their footprint's area, which sharpens the sample's grazing checker
            // floor, so the material a sample divides out, taken over its own coarser
            // footprint, differs more from its pixels', and before the discs stopped
            // fading toward their receivers' horizon, which deepens the sky's shadows
            // beside the objects).
            let (least_2, least_8) = if map_size == 0 { (0.97, 0.985) } else { (0.96, 0.99) };
            assert!(
                within_2 >= least_2,
                "{label}: only {:.3} % within 2/255",
                100.0 * within_2
            );
            assert!(
                within_8 >= least_8,
                "{label}: only {:.3} % within 8/255",
                100.0 * within_8
            );
        }
    }
}

/// A checker of cells about five pixels wide — about the size of the 4 × 4 shading blocks,
/// which interpolating the shaded colour would smear — on a plane under a light high
/// above: the lighting is smooth, so after dividing the material out and back in the
/// checker must come through pixel for pixel.
#[test]
fn texture_detail_the_size_of_the_shading_blocks_survives() {
    let Some(gpu) = common::gpu() else { return };
    let dir = tempfile::tempdir().expect("temp dir");
    let path = dir.path().join("plane.glb");
    let light = LightSpec::Point {
        color: [1.0; 3],
        intensity_cd: 80.0,
    };
    std::fs::write(&path, common::scenes::white_plane(light, Vec3::new(0.3, 6.0, -0.2))).expect("write");
    let mut scene = Scene::load(&path).expect("plane loads");
    // The plane spans about 120 of the image's 216 pixels, so 24 cells span 5 pixels each.
    let cells = 24;
    // Eight texels a cell, so that linear filtering keeps the cells' edges sharp.
    scene
        .textures
        .push(common::scenes::texture("checker", cells * 8, |x, y| {
            if (x / 8 + y / 8) % 2 == 0 {
                [40, 60, 90, 255]
            } else {
                [230, 220, 200, 255]
            }
        }));
    let object = &mut scene.objects[0];
    object.uvs = object
        .positions
        .iter()
        .map(|p| Vec2::new((p.x + 1.0) / 2.0, (p.z + 1.0) / 2.0))
        .collect();
    let material = object.material;
    scene.materials[material].base_color_texture = Some(scene.textures.len() - 1);
    let camera = scene.initial_camera();
    let settings = RenderSettings::default();
    let (full, reduced) = full_and_reduced(&gpu, &scene, &camera, &settings, &[], 4, 1, [216, 216]);
    save_for_review("checker-every-pixel", &full);
    save_for_review("checker-one-in-sixteen", &reduced);
    let (within_2, _, worst) = agreement(&reduced, &full);
    eprintln!("checker: {:.3} % within 2/255, worst {worst}/255", 100.0 * within_2);
    assert!(worst <= 2, "the checker changed by up to {worst}/255");
    // The checker is really there: neighbouring pixels differ by far more than that.
    let step = (90..126)
        .map(|x| full.get_pixel(x, 108)[0].abs_diff(full.get_pixel(x + 1, 108)[0]))
        .max();
    assert!(step > Some(40), "no checker seen: largest step {step:?}");
}

/// Hard shadow-map edges stay where shading every pixel puts them: a box and a thin wall
/// (4 cm: two pixels of the image, under a shading block) over a floor under a low sun,
/// seen from above. Pixels whose nearest samples disagree are shaded in full, so along the edges
/// the reduced frame is the full one; interpolating across the 3 × 3 blocks instead
/// had blurred every edge over a block (measured on lavapipe: 738 pixels off by more
/// than 16/255 that way, none with the disagreeing pixels shaded in full).
#[test]
fn hard_shadow_edges_stay_where_shading_every_pixel_puts_them() {
    use lightpaint::scene::{Light, LightKind, Material, shapes};
    let Some(gpu) = common::gpu() else { return };
    let placed = |shape: shapes::ShapeMesh, at: Vec3, name: &str| {
        shape
            .transformed(glam::Affine3A::from_translation(at))
            .into_object(name)
    };
    let scene = Scene {
        objects: vec![
            shapes::plane(6.0, 1, 1.0).into_object("floor"),
            placed(
                shapes::cuboid(Vec3::new(0.5, 0.6, 0.4)),
                Vec3::new(-1.0, 0.6, 0.0),
                "box",
            ),
            placed(
                shapes::cuboid(Vec3::new(0.02, 0.8, 1.2)),
                Vec3::new(1.2, 0.8, 0.0),
                "bar",
            ),
        ],
        materials: vec![Material {
            base_color: glam::Vec4::new(0.7, 0.7, 0.7, 1.0),
            metallic: 0.0,
            ..Material::default()
        }],
        lights: vec![Light {
            name: "sun".into(),
            kind: LightKind::Directional,
            color: Vec3::ONE,
            intensity: 3.0,
            position: Vec3::new(0.0, 5.0, 0.0),
            direction: Vec3::new(0.8, -0.6, 0.1).normalize(),
            range: None,
            locked: false,
        }],
        ..Scene::default()
    };
    let camera = Camera {
        position: Vec3::new(0.0, 6.0, 0.01),
        forward: Vec3::NEG_Y,
        up: Vec3::NEG_Z,
        yfov_rad: 60f32.to_radians(),
        znear: 0.1,
        zfar: None,
    };
    let settings = RenderSettings {
        shadows: ShadowSettings {
            shadow_map_size: SUGGESTED_SHADOW_MAP_SIZE,
            ..ShadowSettings::default()
        },
        ..RenderSettings::default()
    };
    let (full, reduced) = full_and_reduced(&gpu, &scene, &camera, &settings, &[], 3, 1, [360, 360]);
    save_for_review("hard-edges-every-pixel", &full);
    save_for_review("hard-edges-one-in-3x3", &reduced);
    let off = full
        .pixels()
        .zip(reduced.pixels())
        .filter(|(a, b)| (0..3).any(|c| a[c].abs_diff(b[c]) > 16))
        .count();
    // The shadows are there, with hard edges: the floor goes from lit to shadowed.
    let darkest = full.pixels().map(|p| p[1]).min().unwrap_or(255);
    let brightest = full.pixels().map(|p| p[1]).max().unwrap_or(0);
    eprintln!("hard edges: {off} pixels off by more than 16/255 (floor {darkest}..{brightest})");
    assert!(brightest - darkest > 80, "no shadow seen: {darkest}..{brightest}");
    assert!(
        off <= 100,
        "{off} pixels off by more than 16/255 along the shadows' edges"
    );
}

/// The studio at `size` with every pixel shaded and with its settings (one pixel in 3 × 3
/// shaded, single-sampled).
fn studio_every_pixel_and_defaults(gpu: &GpuContext, size: [u32; 2]) -> (image::RgbaImage, image::RgbaImage) {
    let document = Document::open(&common::repo_path("projects/studio/studio.lightpaint")).expect("studio opens");
    let camera = document
        .camera
        .map_or_else(|| document.scene.initial_camera(), |o| o.camera());
    let blockers = fit_scene(&document.scene, &document.settings.blockers).spheres();
    full_and_reduced(gpu, &document.scene, &camera, &document.settings, &blockers, 3, 1, size)
}

/// At 960 × 540 the studio's frame leaves more pixels to its listed passes than one row
/// of their dispatches holds (full_resolution.wgsl, LISTED_WORKGROUPS_PER_ROW): every one
/// must still be shaded. A listed pixel left unshaded keeps the background's colour,
/// far from its surface's; shading every pixel is the reference.
#[test]
fn every_pixel_a_full_size_frame_leaves_to_its_lists_is_shaded() {
    let Some(gpu) = common::gpu() else { return };
    let (full, reduced) = studio_every_pixel_and_defaults(&gpu, [960, 540]);
    let far_off = reduced
        .pixels()
        .zip(full.pixels())
        .filter(|(a, b)| (0..3).any(|c| a[c].abs_diff(b[c]) > 64))
        .count();
    eprintln!("pixels more than 64/255 off shading every pixel: {far_off}");
    // Measured on lavapipe: 6 such pixels (where interpolation misses an edge by a pixel);
    // with the dispatch's second row of workgroups dropped, 6,896.
    assert!(far_off <= 60, "{far_off} pixels far off shading every pixel");
}

/// A frame whose colours take more than one band of the copy into the frame's image
/// (full_resolution.rs: bands of 16 MiB, 2,048 rows at 2,048 pixels wide; this frame has
/// 2,112 rows, so its last 64 rows go in a second band) is whole: a band copied to the
/// wrong rows, or not at all, would leave thousands of pixels far from shading every
/// pixel (the lowest rows hold the studio's floor, not its background).
#[test]
fn a_frame_taller_than_one_copy_band_is_copied_whole() {
    let Some(gpu) = common::gpu() else { return };
    let (full, reduced) = studio_every_pixel_and_defaults(&gpu, [2048, 2112]);
    let far_off_in_rows = |rows: std::ops::Range<u32>| {
        rows.flat_map(|y| (0..full.width()).map(move |x| (x, y)))
            .filter(|&(x, y)| (0..3).any(|c| reduced.get_pixel(x, y)[c].abs_diff(full.get_pixel(x, y)[c]) > 64))
            .count()
    };
    let (first_band, second_band) = (far_off_in_rows(0..2048), far_off_in_rows(2048..2112));
    eprintln!(
        "pixels more than 64/255 off shading every pixel: {first_band} in the first band, {second_band} in the second"
    );
    assert!(first_band <= 200, "{first_band} pixels far off in the first band");
    assert!(second_band <= 20, "{second_band} pixels far off in the second band");
}

/// Curved objects of a few dozen pixels — upright tori and balls over a floor, the large
/// sample's kind — under a bluish sky (the SH path) and a lamp (a shadow map), so that
/// the frame goes in two levels: their normals turn tens of degrees between the samples,
/// and the soft light is interpolated as its share of the unshadowed light, each pixel
/// multiplying its own back in (low_resolution.wgsl's soft_share).
fn curved_objects_under_a_sky(lamp_intensity: f32) -> Scene {
    use common::thin_casters::{light, scene_with};
    use glam::{Affine3A, Quat};
    use lightpaint::scene::LightKind;
    use lightpaint::scene::shapes::{torus, uv_sphere};
    let mut objects = lightpaint::scene::shapes::ShapeMesh::default();
    for (k, x) in [-1.8f32, -0.6, 0.6, 1.8].into_iter().enumerate() {
        let depth = -0.9 + 0.6 * (k % 2) as f32;
        let upright = Affine3A::from_rotation_translation(Quat::from_rotation_x(1.2), Vec3::new(x, 0.42, depth));
        objects = objects.merged(torus(0.3, 0.1, 48, 24).transformed(upright));
        let ball = Affine3A::from_translation(Vec3::new(x + 0.5, 0.22, depth + 0.9));
        objects = objects.merged(uv_sphere(0.22, 32, 16).transformed(ball));
    }
    let mut scene = scene_with(
        objects,
        light(LightKind::Point, Vec3::new(1.0, 3.0, 1.5), Vec3::NEG_Y, lamp_intensity),
    );
    scene.environment = Some(lightpaint::scene::Environment::uniform([0.35, 0.45, 0.7]));
    scene
}

/// The two-level frame of curved objects looks like shading every pixel, under the sky
/// alone (the lamp at 0, its map still drawn, so the frame is the soft light through the
/// two levels and nothing else) and with the lamp. Measured on lavapipe at 480 × 270:
/// under the sky 98.31 % of pixels within 2/255 and 99.76 % within 8/255, with the lamp
/// 98.17 % and 99.72 % (before the rims' pixels shared their blocker walks, 98.41 / 99.77
/// and 98.26 / 99.73 %; interpolating the soft light itself rather than its share, the
/// sky's were 98.38 % and 99.77 %; its share with samples weighed by (n·n')⁴ rather than
/// (n·n')¹⁶, 97.69 % and 99.64 %). What differs lies along the tori's inner rims and
/// under the balls, where the visibility turns with the normal.
#[test]
fn curved_objects_under_a_sky_look_like_every_pixel_shaded_in_two_levels() {
    let Some(gpu) = common::gpu() else { return };
    let camera = Camera::looking_at(Vec3::new(0.0, 2.2, 3.4), Vec3::new(0.0, 0.3, -0.3), 0.8, 0.05);
    for (name, lamp_intensity, least_2, least_8) in [("sky", 0.0, 0.979, 0.996), ("sky-and-lamp", 6.0, 0.978, 0.995)] {
        let scene = curved_objects_under_a_sky(lamp_intensity);
        let settings = RenderSettings::default();
        let blockers = fit_scene(&scene, &lightpaint::blockers::BlockerSettings::default()).spheres();
        let (full, reduced) = full_and_reduced(&gpu, &scene, &camera, &settings, &blockers, 3, 1, [480, 270]);
        save_for_review(&format!("curved-{name}-every-pixel"), &full);
        save_for_review(&format!("curved-{name}-two-levels"), &reduced);
        let (within_2, within_8, worst) = agreement(&reduced, &full);
        eprintln!(
            "{name}: {:.3} % within 2/255, {:.3} % within 8/255, worst {worst}/255",
            100.0 * within_2,
            100.0 * within_8
        );
        assert!(
            within_2 >= least_2,
            "{name}: only {:.3} % within 2/255",
            100.0 * within_2
        );
        assert!(
            within_8 >= least_8,
            "{name}: only {:.3} % within 8/255",
            100.0 * within_8
        );
    }
}
