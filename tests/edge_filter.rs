//! The edge filter that antialiases single-sample frames by default
//! (`render::filter_edges`, shaders/edge_filter.wgsl), on the GPU: it leaves images without
//! edges alone, and brings a slanted edge's staircase closer to the share of each pixel
//! the edge's half-plane covers (the value 4×4 supersampling approaches).

mod common;

use glam::{Affine3A, Quat, Vec3, Vec4};
use image::{Rgba, RgbaImage};
use lightpaint::render::{AntiAliasing, ShadowFrame, filter_edges, render_logsh_image};
use lightpaint::scene::{Camera, Light, LightKind, Material, Scene, shapes};
use lightpaint::shading::RenderSettings;

/// A `width` × `height` image lit (white) where `inside(x, y)` holds at the pixel centre.
fn staircase(width: u32, height: u32, inside: impl Fn(f64, f64) -> bool) -> RgbaImage {
    RgbaImage::from_fn(width, height, |x, y| {
        let v = if inside(x as f64 + 0.5, y as f64 + 0.5) { 255 } else { 0 };
        Rgba([v, v, v, 255])
    })
}

/// The share of pixel (x, y) inside the half-plane, by 64 × 64 point sampling.
fn coverage(x: u32, y: u32, inside: &impl Fn(f64, f64) -> bool) -> f64 {
    let n = 64;
    let hits = (0..n * n)
        .filter(|k| {
            let (i, j) = (k % n, k / n);
            inside(
                x as f64 + (i as f64 + 0.5) / n as f64,
                y as f64 + (j as f64 + 0.5) / n as f64,
            )
        })
        .count();
    hits as f64 / (n * n) as f64
}

#[test]
fn an_image_without_edges_comes_through_unchanged() {
    let Some(gpu) = common::gpu() else { return };
    // A smooth gradient: every step between neighbours is far below the contrast floor.
    let gradient = RgbaImage::from_fn(64, 48, |x, y| Rgba([(x + 40) as u8, (y + 60) as u8, 128, 255]));
    assert_eq!(filter_edges(&gpu, &gradient).expect("filter"), gradient);
    let flat = RgbaImage::from_pixel(33, 17, Rgba([200, 30, 90, 255]));
    assert_eq!(filter_edges(&gpu, &flat).expect("filter"), flat);
}

/// A straight edge: inside where `across > offset + slope · along`, with (along, across)
/// = (x, y) for a near-horizontal edge and (y, x) for a near-vertical one.
struct Edge {
    horizontal: bool,
    offset: f64,
    slope: f64,
}

impl Edge {
    fn inside(&self, x: f64, y: f64) -> bool {
        let (along, across) = if self.horizontal { (x, y) } else { (y, x) };
        across > self.offset + self.slope * along
    }

    /// Distance in pixels from pixel (x, y)'s centre to the edge.
    fn distance_px(&self, x: u32, y: u32) -> f64 {
        let (along, across) = if self.horizontal { (x, y) } else { (y, x) };
        let gap = across as f64 + 0.5 - self.offset - self.slope * (along as f64 + 0.5);
        gap.abs() / (1.0 + self.slope * self.slope).sqrt()
    }
}

#[test]
fn a_slanted_edge_moves_toward_its_pixel_coverage() {
    let Some(gpu) = common::gpu() else { return };
    let (width, height) = (96, 64);
    let edges = [
        Edge {
            horizontal: true,
            offset: 20.0,
            slope: 0.13,
        },
        Edge {
            horizontal: false,
            offset: 30.0,
            slope: 0.21,
        },
    ];
    for edge in edges {
        let inside = |x: f64, y: f64| edge.inside(x, y);
        let image = staircase(width, height, inside);
        let filtered = filter_edges(&gpu, &image).expect("filter");
        let (mut before, mut after, mut pixels) = (0.0, 0.0, 0);
        for y in 0..height {
            for x in 0..width {
                let original = image.get_pixel(x, y)[0] as f64;
                let smoothed = filtered.get_pixel(x, y)[0] as f64;
                if edge.distance_px(x, y) > 3.0 {
                    assert_eq!(smoothed, original, "({x}, {y}) is far from the edge");
                    continue;
                }
                let truth = coverage(x, y, &inside);
                if truth == 0.0 || truth == 1.0 {
                    continue;
                }
                // The filter blends the stored (sRGB-encoded) values: compare there.
                let encoded = 255.0 * lightpaint::shading::linear_to_srgb(truth);
                before += (original - encoded).abs();
                after += (smoothed - encoded).abs();
                pixels += 1;
            }
        }
        let (before, after) = (before / pixels as f64, after / pixels as f64);
        eprintln!(
            "edge (horizontal {}): mean error at its {pixels} pixels {before:.1} → {after:.1} (of 255)",
            edge.horizontal
        );
        assert!(after < 0.7 * before, "{before:.1} → {after:.1}");
    }
}

/// A checkered floor under a sun (a texture of 8 × 8 cells, each cell 8 texels, a repeat
/// every 4 m) seen from 1.2 m above it, looking down enough that it fills the view, with
/// `card`: a 1.2 m square card standing on it 3 m ahead, turned about the vertical.
fn checkered_floor(card: bool) -> (Scene, Camera) {
    let mut scene = Scene::default();
    scene.textures.push(common::scenes::texture("checker", 64, |x, y| {
        if (x / 8 + y / 8) % 2 == 0 {
            [210, 200, 180, 255]
        } else {
            [60, 50, 40, 255]
        }
    }));
    scene.materials.push(common::scenes::textured_white(0));
    scene.materials.push(Material {
        base_color: Vec4::new(0.9, 0.1, 0.1, 1.0),
        metallic: 0.0,
        ..Material::default()
    });
    // A texture repeat every 4 m.
    scene
        .objects
        .push(shapes::plane(200.0, 1, 200.0 / 4.0).into_object("floor"));
    if card {
        let mut object = shapes::cuboid(Vec3::new(0.6, 0.6, 0.005))
            .transformed(Affine3A::from_rotation_translation(
                Quat::from_rotation_y(0.5),
                Vec3::new(0.0, 0.6, 3.0),
            ))
            .into_object("card");
        object.material = 1;
        scene.objects.push(object);
    }
    scene.lights.push(Light {
        direction: Vec3::new(0.3, -1.0, -0.6).normalize(),
        ..common::scenes::white_light(LightKind::Directional, Vec3::ZERO, 2.0)
    });
    let camera = Camera::looking_at(Vec3::new(0.0, 1.2, 6.0), Vec3::new(0.0, 0.0, 3.5), 0.8, 0.05);
    (scene, camera)
}

/// The default frame of `scene` with the edge filter and with one sample at each pixel
/// centre and no filter.
fn filtered_and_unfiltered(scene: &Scene, camera: &Camera) -> (RgbaImage, RgbaImage) {
    let gpu = common::gpu().expect("checked by the caller");
    let settings = RenderSettings::default();
    let frame = ShadowFrame {
        scene,
        camera,
        settings: &settings,
        shadows: &settings.shadows,
        blockers: &[],
        baked_indirect: None,
        width: 320,
        height: 180,
    };
    let image = |aa| render_logsh_image(&gpu, &frame, aa).expect("render");
    (image(AntiAliasing::EdgeFilter), image(AntiAliasing::with_samples(1)))
}

/// The filter smooths the staircases of the surfaces' outlines, not the contrast within
/// one surface: a texture is already filtered over each pixel's footprint, and blurring
/// its cells again took the lamp room's checkered floor further from the path tracer
/// (docs/speed-accuracy.md). A floor filling the view comes through unchanged, though its
/// checker has contrast at every cell's border; a card standing on it has its outline
/// filtered (before the filter looked at the surfaces, 16,554 of the floor's 57,600
/// pixels moved).
#[test]
fn contrast_within_one_surface_is_left_alone_and_outlines_are_filtered() {
    if common::gpu().is_none() {
        return;
    }
    let (floor, camera) = checkered_floor(false);
    let (filtered, unfiltered) = filtered_and_unfiltered(&floor, &camera);
    let moved = common::differing_pixels(&filtered, &unfiltered);
    eprintln!("floor alone: {moved} pixels moved by the filter");
    assert_eq!(moved, 0, "the filter moved {moved} pixels within the floor");

    let (scene, camera) = checkered_floor(true);
    let (filtered, unfiltered) = filtered_and_unfiltered(&scene, &camera);
    // The card's outline: pixels whose 5 × 5 neighbourhood holds both the card's colour
    // (red dominant) and the floor's in the unfiltered frame (the card's 1 cm thick rim
    // is a fold of its own a pixel inside its outline).
    let reddish = |p: &Rgba<u8>| p[0] as i32 > p[1] as i32 + 40;
    let (w, h) = (unfiltered.width() as i32, unfiltered.height() as i32);
    let near_outline = |x: i32, y: i32| {
        let around: Vec<bool> = (-2..=2)
            .flat_map(|dy| (-2..=2).map(move |dx| (dx, dy)))
            .map(|(dx, dy)| {
                reddish(unfiltered.get_pixel((x + dx).clamp(0, w - 1) as u32, (y + dy).clamp(0, h - 1) as u32))
            })
            .collect();
        around.iter().any(|&r| r) && around.iter().any(|&r| !r)
    };
    let (mut on_outline, mut elsewhere) = (0usize, 0usize);
    for y in 0..h {
        for x in 0..w {
            let (a, b) = (
                filtered.get_pixel(x as u32, y as u32),
                unfiltered.get_pixel(x as u32, y as u32),
            );
            if (0..3).any(|c| a[c] != b[c]) {
                if near_outline(x, y) {
                    on_outline += 1
                } else {
                    elsewhere += 1
                }
            }
        }
    }
    eprintln!("with the card: {on_outline} pixels moved along its outline, {elsewhere} elsewhere");
    assert!(
        on_outline >= 20,
        "only {on_outline} pixels of the card's outline were filtered"
    );
    assert_eq!(elsewhere, 0, "{elsewhere} pixels away from the card's outline moved");
}
