//! Thin and open casters over a floor, and the image measures their shadows are judged
//! by (tests/shadow_maps.rs, tests/soft_shadow_maps.rs).

use glam::{Affine3A, Quat, Vec3, Vec4};
use lightpaint::render::ShadowFrame;
use lightpaint::scene::shapes::{self, ShapeMesh};
use lightpaint::scene::{Camera, Light, LightKind, Material, Scene};
use lightpaint::shading::{RenderSettings, ShadowSettings};

/// The floor alone under `light`: what each renderer's shadows are measured against.
pub fn floor_only(light: Light) -> Scene {
    let mut scene = scene_with(ShapeMesh::default(), light);
    scene.objects.truncate(1);
    scene
}

/// One caster over a 6 m one-quad floor, white diffuse everywhere.
pub fn scene_with(caster: ShapeMesh, light: Light) -> Scene {
    let mut scene = Scene::default();
    scene.materials.push(Material {
        base_color: Vec4::new(0.8, 0.8, 0.8, 1.0),
        metallic: 0.0,
        ..Material::default()
    });
    scene.objects.push(shapes::plane(6.0, 1, 1.0).into_object("floor"));
    scene.objects.push(caster.into_object("caster"));
    scene.lights.push(light);
    scene
}

/// A single quad, 0.8 m square, tilted 30° and hovering 0.8 m up: no inside, one side.
pub fn card() -> ShapeMesh {
    shapes::plane(0.8, 1, 1.0).transformed(Affine3A::from_rotation_translation(
        Quat::from_rotation_x(0.5),
        Vec3::new(0.0, 0.8, 0.0),
    ))
}

/// Five bars each way, 2 cm thick, 0.7 m up: a grid of thin shadows.
pub fn lattice() -> ShapeMesh {
    let mut mesh = ShapeMesh::default();
    for k in 0..5 {
        let offset = -0.4 + 0.2 * k as f32;
        let along_x = shapes::cuboid(Vec3::new(0.5, 0.01, 0.01))
            .transformed(Affine3A::from_translation(Vec3::new(0.0, 0.7, offset)));
        let along_z = shapes::cuboid(Vec3::new(0.01, 0.01, 0.5))
            .transformed(Affine3A::from_translation(Vec3::new(offset, 0.72, 0.0)));
        mesh = mesh.merged(along_x).merged(along_z);
    }
    mesh
}

/// Two turns of a helix of 3 cm tubes around a vertical axis, 0.3 to 1.1 m up.
pub fn helix() -> ShapeMesh {
    let point = |t: f32| {
        let angle = t * 4.0 * std::f32::consts::PI;
        Vec3::new(0.35 * angle.cos(), 0.3 + 0.8 * t, 0.35 * angle.sin())
    };
    shapes::tube_along(point, 40, 0.015, 8)
}

/// A closed box, 0.5 × 0.3 × 0.4 m, turned and floating 0.6 m up.
pub fn closed_box() -> ShapeMesh {
    shapes::cuboid(Vec3::new(0.25, 0.15, 0.2)).transformed(Affine3A::from_rotation_translation(
        Quat::from_rotation_y(0.5),
        Vec3::new(0.0, 0.6, 0.0),
    ))
}

/// The three thin and open casters, by name.
pub fn casters() -> [(&'static str, ShapeMesh); 3] {
    [("card", card()), ("lattice", lattice()), ("helix", helix())]
}

pub fn light(kind: LightKind, position: Vec3, direction: Vec3, intensity: f32) -> Light {
    Light {
        name: "light".into(),
        kind,
        color: Vec3::ONE,
        intensity,
        position,
        direction: direction.normalize(),
        range: None,
        locked: false,
    }
}

/// Looking down at the floor's middle from the front, so every shadow is in view.
pub fn camera() -> Camera {
    Camera::looking_at(Vec3::new(0.0, 3.2, 3.2), Vec3::new(0.0, 0.2, 0.0), 0.9, 0.05)
}

/// Each pixel's luma in linear radiance × 2^EV: the sRGB encoding and the tone curve
/// t(x) = x(2.51x + 0.03)/(x(2.43x + 0.59) + 0.14) undone (solved for x in closed form),
/// so that shadows' masses add up as light does, whatever the display did to partly
/// shadowed pixels.
pub fn linear_luma(image: &image::RgbaImage) -> Vec<f64> {
    let untone = |encoded: u8| {
        let c = encoded as f64 / 255.0;
        let y = if c <= 0.04045 {
            c / 12.92
        } else {
            ((c + 0.055) / 1.055).powf(2.4)
        }
        .min(0.999);
        // y(2.43x² + 0.59x + 0.14) = 2.51x² + 0.03x, a quadratic in x.
        let (a, b, k) = (2.43 * y - 2.51, 0.59 * y - 0.03, 0.14 * y);
        if y <= 0.0 {
            0.0
        } else {
            (-b - (b * b - 4.0 * a * k).sqrt()) / (2.0 * a)
        }
    };
    image
        .pixels()
        .map(|p| 0.2126 * untone(p[0]) + 0.7152 * untone(p[1]) + 0.0722 * untone(p[2]))
        .collect()
}

pub fn luma(p: &image::Rgba<u8>) -> f64 {
    0.2126 * p[0] as f64 + 0.7152 * p[1] as f64 + 0.0722 * p[2] as f64
}

/// Share of pixels whose channels all lie within `tolerance` of the other image's.
pub fn within(a: &image::RgbaImage, b: &image::RgbaImage, tolerance: u8) -> f64 {
    let close = a
        .pixels()
        .zip(b.pixels())
        .filter(|(x, y)| (0..3).all(|c| x[c].abs_diff(y[c]) <= tolerance))
        .count();
    close as f64 / (a.width() * a.height()) as f64
}

/// The pixels a caster shadows: darker in `shadowed` than in `unshadowed` by over 20/255.
pub fn shadow_mask(shadowed: &image::RgbaImage, unshadowed: &image::RgbaImage) -> Vec<bool> {
    shadowed
        .pixels()
        .zip(unshadowed.pixels())
        .map(|(s, u)| luma(u) - luma(s) > 20.0)
        .collect()
}

/// How much light `shadowed` lacks against `floor` (linear luma of the same renderer's
/// image of the floor alone), summed over the pixels where the floor shows (`on_floor`):
/// the shadows' mass, which does not depend on how a pixel straddling a thin shadow's
/// edge is sampled (a ray through its centre, a filtered map, jittered paths).
pub fn darkening(shadowed: &[f64], floor: &[f64], on_floor: &[bool]) -> f64 {
    shadowed
        .iter()
        .zip(floor)
        .zip(on_floor)
        .filter(|(_, f)| **f)
        .map(|((s, u), _)| u - s)
        .sum()
}

/// The pixels where the floor, not the caster, is seen, two pixels clear of the caster's
/// silhouette (where a renderer that antialiases blends the two): the unshadowed scene
/// with the caster and the floor alone agree there (the twin's images, within 2/255).
pub fn floor_pixels(with_caster: &image::RgbaImage, floor: &image::RgbaImage) -> Vec<bool> {
    let (width, height) = (with_caster.width() as i64, with_caster.height() as i64);
    let floor_seen: Vec<bool> = with_caster
        .pixels()
        .zip(floor.pixels())
        .map(|(a, b)| (0..3).all(|c| a[c].abs_diff(b[c]) <= 2))
        .collect();
    let seen = |x: i64, y: i64| x < 0 || y < 0 || x >= width || y >= height || floor_seen[(y * width + x) as usize];
    (0..height)
        .flat_map(|y| (0..width).map(move |x| (x, y)))
        .map(|(x, y)| (-2..=2).all(|dy| (-2..=2).all(|dx| seen(x + dx, y + dy))))
        .collect()
}

/// RMS of a − b over the pixels where both exist and `b` is in shadow (under 0.95).
pub fn shadow_rms(a: &[Option<f64>], b: &[Option<f64>]) -> f64 {
    let errors: Vec<f64> = a
        .iter()
        .zip(b)
        .filter_map(|(a, b)| match (a, b) {
            (Some(a), Some(b)) if *b < 0.95 => Some(a - b),
            _ => None,
        })
        .collect();
    (errors.iter().map(|e| e * e).sum::<f64>() / errors.len().max(1) as f64).sqrt()
}

pub fn mean_over(image: &image::RgbaImage, mask: &[bool]) -> f64 {
    let (sum, count) = image
        .pixels()
        .zip(mask)
        .filter(|(_, m)| **m)
        .fold((0.0, 0usize), |(s, n), (p, _)| (s + luma(p), n + 1));
    sum / count.max(1) as f64
}

pub fn save_for_review(name: &str, image: &image::RgbaImage) {
    let dir = std::path::Path::new(env!("CARGO_TARGET_TMPDIR")).join("shadow_maps");
    let _ = std::fs::create_dir_all(&dir);
    let _ = image.save(dir.join(format!("{name}.png")));
}

/// A frame of `scene` without sphere blockers (every shadow is the maps') at `size`.
pub fn frame_of<'a>(
    scene: &'a Scene,
    camera: &'a Camera,
    settings: &'a RenderSettings,
    shadows: &'a ShadowSettings,
    (width, height): (u32, u32),
) -> ShadowFrame<'a> {
    ShadowFrame {
        scene,
        camera,
        settings,
        shadows,
        blockers: &[],
        baked_indirect: None,
        width,
        height,
    }
}

/// The path tracer's direct light of `scene` at `spp` samples per pixel, displayed as the
/// renderer displays its frames.
pub fn path_traced(
    scene: &Scene,
    camera: &Camera,
    settings: &RenderSettings,
    (width, height): (u32, u32),
    spp: u32,
) -> image::RgbaImage {
    let reference = lightpaint::reference::ReferenceSettings {
        samples_per_pixel: spp,
        bounces: 0,
        seed: 7,
    };
    lightpaint::reference::render_reference(scene, camera, width, height, &reference, |_| {})
        .to_srgb8(settings.exposure_ev as f64, settings.background_srgb8)
}
