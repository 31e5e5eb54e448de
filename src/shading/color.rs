//! Colour transforms of the CPU side (the f64 shading reference, the path tracer, tests).
//! The GPU versions live in `shaders/common.wgsl`.

/// The sRGB transfer both ways (written beside the textures they decode and whose mip
/// levels they encode, in `scene`).
pub use crate::scene::{linear_to_srgb, srgb_to_linear};

/// Narkowicz's (2015) fit of the ACES filmic curve, clamped to [0, 1].
pub fn tonemap_aces_fit(x: f64) -> f64 {
    let x = x.max(0.0);
    (x * (2.51 * x + 0.03) / (x * (2.43 * x + 0.59) + 0.14)).clamp(0.0, 1.0)
}

/// Inverse of [`tonemap_aces_fit`] on [0, 1): y(2.43x² + 0.59x + 0.14) = 2.51x² + 0.03x
/// solved for x ≥ 0 in closed form; displayed white (y ≥ 1, which the curve only
/// approaches) is read as the x that gives 0.9999.
pub fn untonemap_aces_fit(y: f64) -> f64 {
    let y = y.clamp(0.0, 0.9999);
    if y == 0.0 {
        return 0.0;
    }
    let (a, b, c) = (2.43 * y - 2.51, 0.59 * y - 0.03, 0.14 * y);
    (-b - (b * b - 4.0 * a * c).sqrt()) / (2.0 * a)
}

/// The linear radiance a displayed 8-bit sRGB pixel stands for: [`display_srgb8`] undone
/// (sRGB decoding, the tone curve, the exposure), within its 8-bit rounding.
pub fn displayed_radiance(srgb8: [u8; 3], exposure_ev: f64) -> glam::DVec3 {
    let [r, g, b] = srgb8.map(|v| untonemap_aces_fit(srgb_to_linear(v as f64 / 255.0)));
    glam::DVec3::new(r, g, b) * (-exposure_ev).exp2()
}

/// Exposure, tone curve and sRGB encoding of a linear radiance, to 8 bits per channel.
pub fn display_srgb8(radiance: glam::DVec3, exposure_ev: f64) -> [u8; 3] {
    let scaled = radiance * exposure_ev.exp2();
    [scaled.x, scaled.y, scaled.z].map(|c| {
        let encoded = linear_to_srgb(tonemap_aces_fit(c));
        (encoded * 255.0).round().clamp(0.0, 255.0) as u8
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn srgb_round_trips_every_8_bit_value() {
        for v in 0..=255u8 {
            let encoded = v as f64 / 255.0;
            assert!((linear_to_srgb(srgb_to_linear(encoded)) - encoded).abs() < 1e-12);
        }
    }

    #[test]
    fn the_tone_curve_undone_gives_back_the_radiance() {
        for i in 0..2000 {
            let x = i as f64 * 0.002;
            let back = untonemap_aces_fit(tonemap_aces_fit(x));
            assert!((back - x).abs() < 1e-9 * (1.0 + x), "{x} → {back}");
        }
        // Through 8 bits: within the rounding of the display.
        for v in [0.05, 0.3, 1.0, 2.5] {
            let shown = display_srgb8(glam::DVec3::splat(v), 0.5);
            let back = displayed_radiance(shown, 0.5).x;
            assert_eq!(display_srgb8(glam::DVec3::splat(back), 0.5), shown, "{v} → {back}");
        }
    }

    #[test]
    fn tone_curve_is_monotone_from_black_to_white() {
        assert_eq!(tonemap_aces_fit(0.0), 0.0);
        assert_eq!(tonemap_aces_fit(1e6), 1.0);
        let samples: Vec<f64> = (0..1000).map(|i| tonemap_aces_fit(i as f64 * 0.01)).collect();
        assert!(samples.windows(2).all(|w| w[1] >= w[0]));
    }
}
