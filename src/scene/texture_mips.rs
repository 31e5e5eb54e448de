//! The mip chain of an sRGB texture, averaged in linear light.
//!
//! Each level halves the one above (rounding down, never below 1) and each of its texels
//! is the mean of the 2 × 2 texels it covers — 2 × 1, 1 × 2 or 3 wide where a side is odd
//! (the last row or column is folded into its neighbour's texel, weighted by how much of
//! it the texel covers: the box filter of the exact footprint). Colour is decoded to linear
//! before averaging and encoded after: averaging the sRGB code values instead darkens a
//! distant texture (a black-and-white checker's mean is 0.5 in linear light, 0.21 when
//! its codes are averaged), which the path tracer, averaging the linear colours its
//! samples meet, does not. Alpha is linear and averaged as it is.

use super::material::{TextureImage, linear_to_srgb, srgb_to_linear};

/// Every level from `texture` itself down to 1 × 1, as RGBA8 images (sRGB colour,
/// linear alpha). A texture whose pixels are missing gives one white texel.
pub fn mip_chain(texture: &TextureImage) -> Vec<image::RgbaImage> {
    let (width, height) = (texture.width as usize, texture.height as usize);
    if width == 0 || height == 0 || texture.rgba8.len() < width * height * 4 {
        return vec![image::RgbaImage::from_pixel(1, 1, image::Rgba([255; 4]))];
    }
    let base_bytes = &texture.rgba8[..width * height * 4];
    // The first halving decodes the codes as it reads them (a linear copy of a large
    // texture would take four times its memory); later levels are a quarter as large.
    let decoded = |i: usize| {
        let c = &base_bytes[i * 4..i * 4 + 4];
        [
            DECODE[c[0] as usize],
            DECODE[c[1] as usize],
            DECODE[c[2] as usize],
            c[3] as f32 / 255.0,
        ]
    };
    let base = image::RgbaImage::from_raw(texture.width, texture.height, base_bytes.to_vec());
    let mut levels = vec![base.unwrap_or_else(|| image::RgbaImage::from_pixel(1, 1, image::Rgba([255; 4])))];
    if (width, height) == (1, 1) {
        return levels;
    }
    let (mut linear, mut size) = halve(decoded, (width, height));
    levels.push(encode(&linear, size));
    while size != (1, 1) {
        let (next, next_size) = halve(|i| linear[i], size);
        levels.push(encode(&next, next_size));
        linear = next;
        size = next_size;
    }
    levels
}

/// Linear value of each sRGB code.
static DECODE: std::sync::LazyLock<[f32; 256]> =
    std::sync::LazyLock::new(|| std::array::from_fn(|code| srgb_to_linear(code as f64 / 255.0) as f32));

/// Weights with which the source texels along one side fall into each halved texel: for
/// an even side 2 × ½; for an odd side (n = 2m + 1 → m texels) each target texel covers
/// n/m source texels, so the box over its exact footprint weighs the texels it spans
/// partly by the share it covers.
fn footprints(source: usize) -> Vec<Vec<(usize, f32)>> {
    let target = (source / 2).max(1);
    let scale = source as f64 / target as f64;
    (0..target)
        .map(|t| {
            let (start, end) = (t as f64 * scale, (t + 1) as f64 * scale);
            (start.floor() as usize..(end.ceil() as usize).min(source))
                .map(|s| {
                    let covered = (end.min(s as f64 + 1.0) - start.max(s as f64)).max(0.0);
                    (s, (covered / scale) as f32)
                })
                .filter(|&(_, w)| w > 0.0)
                .collect()
        })
        .collect()
}

fn halve(texel_at: impl Fn(usize) -> [f32; 4], (width, height): (usize, usize)) -> (Vec<[f32; 4]>, (usize, usize)) {
    let (columns, rows) = (footprints(width), footprints(height));
    let mut next = Vec::with_capacity(columns.len() * rows.len());
    for row in &rows {
        for column in &columns {
            let mut sum = [0.0f32; 4];
            for &(y, wy) in row {
                for &(x, wx) in column {
                    let texel = texel_at(y * width + x);
                    for (s, t) in sum.iter_mut().zip(texel) {
                        *s += wx * wy * t;
                    }
                }
            }
            next.push(sum);
        }
    }
    (next, (columns.len(), rows.len()))
}

fn encode(linear: &[[f32; 4]], (width, height): (usize, usize)) -> image::RgbaImage {
    let bytes = linear
        .iter()
        .flat_map(|t| {
            let colour = |v: f32| {
                (linear_to_srgb((v as f64).clamp(0.0, 1.0)) * 255.0)
                    .round()
                    .clamp(0.0, 255.0) as u8
            };
            [
                colour(t[0]),
                colour(t[1]),
                colour(t[2]),
                (t[3] * 255.0).round().clamp(0.0, 255.0) as u8,
            ]
        })
        .collect();
    image::RgbaImage::from_raw(width as u32, height as u32, bytes).unwrap_or_else(|| image::RgbaImage::new(1, 1))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn texture(width: u32, height: u32, rgba8: Vec<u8>) -> TextureImage {
        TextureImage {
            name: "t".into(),
            width,
            height,
            rgba8,
        }
    }

    fn linear_mean(image: &image::RgbaImage, channel: usize) -> f64 {
        let n = (image.width() * image.height()) as f64;
        image
            .pixels()
            .map(|p| srgb_to_linear(p[channel] as f64 / 255.0))
            .sum::<f64>()
            / n
    }

    #[test]
    fn a_black_and_white_checker_averages_to_half_in_linear_light() {
        let rgba8 = (0..16)
            .flat_map(|i| {
                if (i % 4 + i / 4) % 2 == 0 {
                    [0, 0, 0, 255]
                } else {
                    [255; 4]
                }
            })
            .collect();
        let levels = mip_chain(&texture(4, 4, rgba8));
        let sizes: Vec<_> = levels.iter().map(|l| l.dimensions()).collect();
        assert_eq!(sizes, [(4, 4), (2, 2), (1, 1)]);
        // Linear 0.5 encodes to sRGB 0.7354 (code 188), not the codes' mean 128.
        for level in &levels[1..] {
            for p in level.pixels() {
                assert_eq!(p.0, [188, 188, 188, 255]);
            }
        }
    }

    #[test]
    fn every_level_keeps_the_linear_mean_of_any_size() {
        // Odd and even sides, non-square, random-ish codes: the box over exact
        // footprints conserves the mean (to the 8-bit rounding of each level).
        for (w, h) in [(5u32, 3u32), (7, 1), (6, 9), (1, 4), (13, 11)] {
            let rgba8: Vec<u8> = (0..w * h * 4).map(|i| ((i * 97 + 31) % 256) as u8).collect();
            let levels = mip_chain(&texture(w, h, rgba8));
            assert_eq!(levels.last().map(|l| l.dimensions()), Some((1, 1)));
            let base = linear_mean(&levels[0], 1);
            for level in &levels {
                let mean = linear_mean(level, 1);
                assert!(
                    (mean - base).abs() < 0.01,
                    "{w}×{h} level {:?}: mean {mean} against {base}",
                    level.dimensions()
                );
            }
        }
    }

    #[test]
    fn footprints_of_a_side_cover_each_source_texel_exactly_once() {
        for source in 1..40 {
            let mut total = vec![0.0f32; source];
            let parts = footprints(source);
            assert_eq!(parts.len(), (source / 2).max(1));
            for part in &parts {
                let sum: f32 = part.iter().map(|p| p.1).sum();
                assert!((sum - 1.0).abs() < 1e-5, "side {source}: weights sum to {sum}");
                for &(s, w) in part {
                    total[s] += w;
                }
            }
            let expected = parts.len() as f32 / source as f32;
            assert!(
                total.iter().all(|t| (t - expected).abs() < 1e-5),
                "side {source}: {total:?}"
            );
        }
    }

    #[test]
    fn missing_pixels_give_one_white_texel() {
        let levels = mip_chain(&texture(4, 4, vec![0; 12]));
        assert_eq!(levels.len(), 1);
        assert_eq!(levels[0].get_pixel(0, 0).0, [255; 4]);
    }
}
