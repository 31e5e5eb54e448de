//! Colour transforms of the CPU side (the f64 shading reference, the path tracer, tests).
//! The GPU versions live in `shaders/common.wgsl`.

/// sRGB electro-optical transfer: encoded [0, 1] → linear (IEC 61966-2-1).
pub fn srgb_to_linear(encoded: f64) -> f64 {
    if encoded <= 0.04045 {
        encoded / 12.92
    } else {
        ((encoded + 0.055) / 1.055).powf(2.4)
    }
}

/// Inverse of [`srgb_to_linear`]: linear [0, 1] → encoded.
pub fn linear_to_srgb(linear: f64) -> f64 {
    if linear <= 0.0031308 {
        linear * 12.92
    } else {
        1.055 * linear.powf(1.0 / 2.4) - 0.055
    }
}

/// Narkowicz's (2015) fit of the ACES filmic curve, clamped to [0, 1].
pub fn tonemap_aces_fit(x: f64) -> f64 {
    let x = x.max(0.0);
    (x * (2.51 * x + 0.03) / (x * (2.43 * x + 0.59) + 0.14)).clamp(0.0, 1.0)
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
    fn tone_curve_is_monotone_from_black_to_white() {
        assert_eq!(tonemap_aces_fit(0.0), 0.0);
        assert_eq!(tonemap_aces_fit(1e6), 1.0);
        let samples: Vec<f64> = (0..1000).map(|i| tonemap_aces_fit(i as f64 * 0.01)).collect();
        assert!(samples.windows(2).all(|w| w[1] >= w[0]));
    }
}
