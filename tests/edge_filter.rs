//! The edge filter that antialiases single-sample frames by default
//! (`render::filter_edges`, shaders/edge_filter.wgsl), on the GPU: it leaves images without
//! edges alone, and brings a slanted edge's staircase closer to the share of each pixel
//! the edge's half-plane covers (the value 4×4 supersampling approaches).

mod common;

use image::{Rgba, RgbaImage};
use lightpaint::render::filter_edges;

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
