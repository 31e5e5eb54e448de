//! Screenshots of the editor compared with reviewed images, with a tolerance measured on
//! the machines the suite runs on.
//!
//! llvmpipe generates different code on AVX2 and AVX-512 hosts, so the same frame can
//! differ in a few pixels. Measured on the editor's three reviewed images (taken on an
//! AVX2 host, rendered on an AVX-512 one, 1280 × 800): the largest channel difference
//! was 18/255 at one pixel, 6 pixels differed by more than 4/255 and one by more than
//! 8/255, every one of them isolated (no two neighbours); the rest by at most 2/255
//! (`LP_NATIVE_VECTOR_WIDTH=128`, which would emulate a narrower host, crashes llvmpipe
//! on that machine). kittest's perceptual metric at its default threshold counted 127,
//! 69 and 4 failing pixels for the same images, so its default options fail there.
//!
//! A pixel differs when one of its channels moves by more than [`PIXEL_TOLERANCE`]; an
//! image matches when no two differing pixels touch (8-neighbourhood) and at most
//! [`ISOLATED_PIXEL_BUDGET`] differ. A real change of the UI or the lighting moves runs of
//! neighbouring pixels — a one-pixel-wide line, a shadow's edge — and fails: see
//! `snapshot_tolerance` in tests/ui_editor.rs.

use std::path::PathBuf;

/// Largest channel difference (of 255) a pixel may show and still count as the same.
pub const PIXEL_TOLERANCE: u8 = 8;
/// How many isolated pixels may differ by more (measured: 1; a margin for other hosts).
pub const ISOLATED_PIXEL_BUDGET: usize = 32;

/// How an image compares with its reviewed one.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Comparison {
    /// Pixels whose channels differ by more than [`PIXEL_TOLERANCE`].
    pub differing: usize,
    /// Of those, the ones with a differing neighbour.
    pub clustered: usize,
    /// The largest channel difference.
    pub max_difference: u8,
}

impl Comparison {
    pub fn matches(&self) -> bool {
        self.clustered == 0 && self.differing <= ISOLATED_PIXEL_BUDGET
    }
}

/// Compares `image` with `reviewed` pixel by pixel (sizes must agree).
pub fn compare(image: &image::RgbaImage, reviewed: &image::RgbaImage) -> Comparison {
    assert_eq!(image.dimensions(), reviewed.dimensions(), "the image's size changed");
    let (width, height) = image.dimensions();
    let mut max_difference = 0u8;
    let differs: Vec<bool> = image
        .pixels()
        .zip(reviewed.pixels())
        .map(|(a, b)| {
            let d = a.0.iter().zip(b.0).map(|(x, y)| x.abs_diff(y)).max().unwrap_or(0);
            max_difference = max_difference.max(d);
            d > PIXEL_TOLERANCE
        })
        .collect();
    let at = |x: i64, y: i64| {
        x >= 0 && y >= 0 && x < width as i64 && y < height as i64 && differs[(y * width as i64 + x) as usize]
    };
    let mut clustered = 0;
    for y in 0..height as i64 {
        for x in 0..width as i64 {
            if at(x, y) && (-1..=1).any(|dy| (-1..=1).any(|dx| (dx, dy) != (0, 0) && at(x + dx, y + dy))) {
                clustered += 1;
            }
        }
    }
    Comparison {
        differing: differs.iter().filter(|d| **d).count(),
        clustered,
        max_difference,
    }
}

fn snapshot_path(name: &str, suffix: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join(format!("tests/snapshots/{name}{suffix}.png"))
}

/// The reviewed image `name` (tests/snapshots/NAME.png).
pub fn reviewed(name: &str) -> image::RgbaImage {
    let path = snapshot_path(name, "");
    image::open(&path)
        .unwrap_or_else(|e| panic!("{}: {e} (UPDATE_SNAPSHOTS=1 writes it)", path.display()))
        .to_rgba8()
}

/// Asserts that `image` looks as the reviewed image `name`; with `UPDATE_SNAPSHOTS=1`
/// it becomes the reviewed image instead. A mismatch leaves NAME.new.png beside it and
/// NAME.diff.png marking the differing pixels.
pub fn assert_looks_as_reviewed(image: &image::RgbaImage, name: &str) {
    if std::env::var("UPDATE_SNAPSHOTS").is_ok_and(|v| v == "1" || v == "true") {
        image.save(snapshot_path(name, "")).expect("reviewed image written");
        return;
    }
    let reviewed = reviewed(name);
    if image.dimensions() != reviewed.dimensions() {
        image.save(snapshot_path(name, ".new")).expect("new image written");
        panic!(
            "{name}: size {:?}, reviewed {:?}",
            image.dimensions(),
            reviewed.dimensions()
        );
    }
    let comparison = compare(image, &reviewed);
    if !comparison.matches() {
        image.save(snapshot_path(name, ".new")).expect("new image written");
        let mut diff = image::RgbaImage::from_pixel(image.width(), image.height(), image::Rgba([255, 255, 255, 255]));
        for ((out, a), b) in diff.pixels_mut().zip(image.pixels()).zip(reviewed.pixels()) {
            if a.0.iter().zip(b.0).any(|(x, y)| x.abs_diff(y) > PIXEL_TOLERANCE) {
                *out = image::Rgba([255, 0, 0, 255]);
            }
        }
        diff.save(snapshot_path(name, ".diff")).expect("diff image written");
        panic!(
            "{name} does not look as reviewed: {comparison:?} (see tests/snapshots/{name}.new.png and .diff.png; \
             UPDATE_SNAPSHOTS=1 accepts it after review)"
        );
    }
}
