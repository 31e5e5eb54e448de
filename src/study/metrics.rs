//! Image error metrics of the study, all on what the artist sees: 8-bit display images
//! (after exposure, tone curve and sRGB), compared per channel as values in [0, 1].
//!
//! - RMSE: √(mean (a − b)²) over pixels and channels, of the sRGB-decoded values;
//! - relative L1: Σ|a − b| / Σ|b| of the decoded values (b the reference);
//! - SSIM (Wang et al. 2004): mean structural similarity of the encoded luma, with an
//!   11 × 11 Gaussian window (σ = 1.5) and C1 = (0.01)², C2 = (0.03)²;
//! - shadow RMSE: the RMSE over the pixels a mask marks as shadowed.

use crate::shading::srgb_to_linear;

/// A display image as decoded linear values in [0, 1], row-major RGB.
#[derive(Debug, Clone, PartialEq)]
pub struct DisplayImage {
    pub width: usize,
    pub height: usize,
    pub rgb: Vec<[f64; 3]>,
}

impl DisplayImage {
    pub fn from_rgba8(image: &image::RgbaImage) -> DisplayImage {
        DisplayImage {
            width: image.width() as usize,
            height: image.height() as usize,
            rgb: image
                .pixels()
                .map(|p| [0, 1, 2].map(|c| srgb_to_linear(p[c] as f64 / 255.0)))
                .collect(),
        }
    }

    /// Rec. 709 luminance of each pixel's decoded values.
    pub fn luminance(&self) -> Vec<f64> {
        self.rgb
            .iter()
            .map(|c| crate::scene::luminance(glam::DVec3::from_array(*c)))
            .collect()
    }
}

/// How far an image is from the reference.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ImageErrors {
    pub rmse: f64,
    pub relative_l1: f64,
    pub ssim: f64,
    /// RMSE over the shadowed pixels (None when no pixel is shadowed).
    pub shadow_rmse: Option<f64>,
}

/// The errors of `image` against `reference` (same size), with `shadowed` marking the
/// pixels of the shadow RMSE.
pub fn image_errors(image: &DisplayImage, reference: &DisplayImage, shadowed: &[bool]) -> ImageErrors {
    assert_eq!(
        (image.width, image.height),
        (reference.width, reference.height),
        "images of one size"
    );
    let squared = |a: &[f64; 3], b: &[f64; 3]| (0..3).map(|c| (a[c] - b[c]).powi(2)).sum::<f64>();
    let total: f64 = image.rgb.iter().zip(&reference.rgb).map(|(a, b)| squared(a, b)).sum();
    let rmse = (total / (3 * image.rgb.len().max(1)) as f64).sqrt();
    let difference: f64 = image
        .rgb
        .iter()
        .zip(&reference.rgb)
        .map(|(a, b)| (0..3).map(|c| (a[c] - b[c]).abs()).sum::<f64>())
        .sum();
    let magnitude: f64 = reference.rgb.iter().map(|b| b.iter().sum::<f64>()).sum();
    let (shadow_sum, shadow_count) = image
        .rgb
        .iter()
        .zip(&reference.rgb)
        .zip(shadowed)
        .filter(|(_, s)| **s)
        .fold((0.0, 0usize), |(sum, n), ((a, b), _)| (sum + squared(a, b), n + 1));
    ImageErrors {
        rmse,
        relative_l1: difference / magnitude.max(f64::MIN_POSITIVE),
        ssim: ssim(image, reference),
        shadow_rmse: (shadow_count > 0).then(|| (shadow_sum / (3 * shadow_count) as f64).sqrt()),
    }
}

/// Encoded luma of each pixel (SSIM works on perceptually encoded values).
fn luma(image: &DisplayImage) -> Vec<f64> {
    image
        .luminance()
        .into_iter()
        .map(crate::shading::linear_to_srgb)
        .collect()
}

/// Mean SSIM of the two images' luma.
pub fn ssim(image: &DisplayImage, reference: &DisplayImage) -> f64 {
    const C1: f64 = 0.01 * 0.01;
    const C2: f64 = 0.03 * 0.03;
    let (w, h) = (image.width, image.height);
    let (x, y) = (luma(image), luma(reference));
    let product = |a: &[f64], b: &[f64]| a.iter().zip(b).map(|(p, q)| p * q).collect::<Vec<f64>>();
    let [mx, my, xx, yy, xy] =
        [x.clone(), y.clone(), product(&x, &x), product(&y, &y), product(&x, &y)].map(|map| gaussian_blur(&map, w, h));
    let n = (w * h).max(1);
    (0..w * h)
        .map(|i| {
            let (vx, vy, cxy) = (xx[i] - mx[i] * mx[i], yy[i] - my[i] * my[i], xy[i] - mx[i] * my[i]);
            ((2.0 * mx[i] * my[i] + C1) * (2.0 * cxy + C2)) / ((mx[i] * mx[i] + my[i] * my[i] + C1) * (vx + vy + C2))
        })
        .sum::<f64>()
        / n as f64
}

/// Separable Gaussian blur (σ = 1.5, radius 5), the window renormalised at the borders.
fn gaussian_blur(map: &[f64], width: usize, height: usize) -> Vec<f64> {
    const RADIUS: i64 = 5;
    let kernel: Vec<f64> = (-RADIUS..=RADIUS)
        .map(|k| (-(k * k) as f64 / (2.0 * 1.5 * 1.5)).exp())
        .collect();
    let pass = |source: &[f64], along_x: bool| -> Vec<f64> {
        (0..width * height)
            .map(|i| {
                let (px, py) = ((i % width) as i64, (i / width) as i64);
                let (mut sum, mut weight) = (0.0, 0.0);
                for (k, w) in (-RADIUS..=RADIUS).zip(&kernel) {
                    let (qx, qy) = if along_x { (px + k, py) } else { (px, py + k) };
                    if (0..width as i64).contains(&qx) && (0..height as i64).contains(&qy) {
                        sum += w * source[qy as usize * width + qx as usize];
                        weight += w;
                    }
                }
                sum / weight
            })
            .collect()
    };
    pass(&pass(map, true), false)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn image(width: usize, height: usize, value: impl Fn(usize, usize) -> f64) -> DisplayImage {
        DisplayImage {
            width,
            height,
            rgb: (0..width * height).map(|i| [value(i % width, i / width); 3]).collect(),
        }
    }

    #[test]
    fn an_image_has_no_error_against_itself() {
        let a = image(20, 12, |x, y| ((x * 7 + y * 3) % 11) as f64 / 10.0);
        let e = image_errors(&a, &a, &[true; 240]);
        assert_eq!((e.rmse, e.relative_l1, e.shadow_rmse), (0.0, 0.0, Some(0.0)));
        assert!((e.ssim - 1.0).abs() < 1e-12, "{}", e.ssim);
    }

    #[test]
    fn a_constant_offset_gives_its_rmse_and_relative_l1() {
        let reference = image(16, 16, |_, _| 0.5);
        let brighter = image(16, 16, |_, _| 0.6);
        let mut shadowed = vec![false; 256];
        shadowed[0] = true;
        let e = image_errors(&brighter, &reference, &shadowed);
        assert!(
            (e.rmse - 0.1).abs() < 1e-12 && (e.relative_l1 - 0.2).abs() < 1e-12,
            "{e:?}"
        );
        assert!((e.shadow_rmse.expect("one shadowed pixel") - 0.1).abs() < 1e-12);
        assert_eq!(image_errors(&brighter, &reference, &[false; 256]).shadow_rmse, None);
    }

    #[test]
    fn ssim_falls_as_structure_is_lost() {
        // A checkerboard against its blur and against flat grey of the same mean.
        let board = image(32, 32, |x, y| if (x / 4 + y / 4) % 2 == 0 { 0.8 } else { 0.1 });
        let flat = image(32, 32, |_, _| 0.45);
        let soft = {
            let l: Vec<f64> = board.rgb.iter().map(|c| c[0]).collect();
            let blurred = gaussian_blur(&l, 32, 32);
            DisplayImage {
                width: 32,
                height: 32,
                rgb: blurred.into_iter().map(|v| [v; 3]).collect(),
            }
        };
        let (s_soft, s_flat) = (ssim(&soft, &board), ssim(&flat, &board));
        assert!(1.0 > s_soft && s_soft > s_flat, "soft {s_soft}, flat {s_flat}");
    }
}
