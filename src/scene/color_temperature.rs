//! Light colours from colour temperatures: the chromaticity of a black body at T kelvin
//! (Kim et al. 2002's cubic fits to the Planckian locus in CIE 1931 xy, valid from
//! 1667 K to 25 000 K), taken to linear sRGB (Rec. 709 primaries, D65 white) and scaled
//! so the largest channel is 1 — the convention of light colours in glTF and here, where
//! the intensity carries the brightness.

use glam::{DVec3, Vec3};

/// The temperatures the locus fit covers, in kelvin.
pub const TEMPERATURE_RANGE_K: std::ops::RangeInclusive<f32> = 1667.0..=25000.0;

/// CIE 1931 (x, y) chromaticity of a black body at `temperature_k` (clamped to
/// [`TEMPERATURE_RANGE_K`]).
pub fn planckian_xy(temperature_k: f64) -> (f64, f64) {
    let t = temperature_k.clamp(1667.0, 25000.0);
    let (t1, t2, t3) = (1e3 / t, 1e6 / (t * t), 1e9 / (t * t * t));
    let x = if t <= 4000.0 {
        -0.266_123_9 * t3 - 0.234_358_9 * t2 + 0.877_695_6 * t1 + 0.179_910
    } else {
        -3.025_846_9 * t3 + 2.107_037_9 * t2 + 0.222_634_7 * t1 + 0.240_390
    };
    let (a, b, c, d) = if t <= 2222.0 {
        (-1.106_381_4, -1.348_110_20, 2.185_558_32, -0.202_196_83)
    } else if t <= 4000.0 {
        (-0.954_947_6, -1.374_185_93, 2.091_370_15, -0.167_488_67)
    } else {
        (3.081_758_0, -5.873_386_70, 3.751_129_97, -0.370_014_83)
    };
    let y = ((a * x + b) * x + c) * x + d;
    (x, y)
}

/// Linear sRGB of chromaticity (x, y) at luminance Y = 1 (IEC 61966-2-1's XYZ → RGB).
fn xy_to_linear_srgb(x: f64, y: f64) -> DVec3 {
    let xyz = DVec3::new(x / y, 1.0, (1.0 - x - y) / y);
    DVec3::new(
        3.2406 * xyz.x - 1.5372 * xyz.y - 0.4986 * xyz.z,
        -0.9689 * xyz.x + 1.8758 * xyz.y + 0.0415 * xyz.z,
        0.0557 * xyz.x - 0.2040 * xyz.y + 1.0570 * xyz.z,
    )
}

/// The light colour of a black body at `temperature_k`: linear sRGB, largest channel 1,
/// channels outside the sRGB gamut clipped to 0.
pub fn color_of_temperature(temperature_k: f32) -> Vec3 {
    let (x, y) = planckian_xy(temperature_k as f64);
    let rgb = xy_to_linear_srgb(x, y).max(DVec3::ZERO);
    (rgb / rgb.max_element()).as_vec3()
}

/// The black-body temperature whose colour is nearest `color` (both scaled to a largest
/// channel of 1), if `color` is that close to one: within `0.04` in every channel. None
/// for colours off the locus (green, magenta, saturated) and for black.
pub fn temperature_of_color(color: Vec3) -> Option<f32> {
    let peak = color.max_element();
    if !(peak.is_finite() && peak > 0.0) {
        return None;
    }
    let target = color / peak;
    let distance = |t: f32| (color_of_temperature(t) - target).abs().max_element();
    // Coarse scan in mired (even steps in perceived warmth), then golden-section refine.
    let mired = |t: f32| 1e6 / t;
    let (lo_mired, hi_mired) = (mired(*TEMPERATURE_RANGE_K.end()), mired(*TEMPERATURE_RANGE_K.start()));
    let steps = 200;
    let at = |i: usize| 1e6 / (lo_mired + (hi_mired - lo_mired) * i as f32 / steps as f32);
    let best = (0..=steps).min_by(|&a, &b| distance(at(a)).total_cmp(&distance(at(b))))?;
    let (mut a, mut b) = (mired(at(best.saturating_sub(1))), mired(at((best + 1).min(steps))));
    let golden = 0.618_034_f32;
    for _ in 0..40 {
        let (c, d) = (b - golden * (b - a), a + golden * (b - a));
        if distance(1e6 / c) < distance(1e6 / d) {
            b = d;
        } else {
            a = c;
        }
    }
    let temperature_k = 1e6 / (0.5 * (a + b));
    (distance(temperature_k) <= 0.04).then_some(temperature_k)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn locus_meets_the_cie_illuminants_defined_by_temperature() {
        // CIE illuminant A is a black body at 2856 K: x = 0.44757, y = 0.40745 (CIE 15).
        let (x, y) = planckian_xy(2856.0);
        assert!((x - 0.44757).abs() < 1e-3 && (y - 0.40745).abs() < 1e-3, "({x}, {y})");
        // The Planckian locus at 6504 K passes just below D65 (0.3127, 0.3290): CIE 15
        // gives (0.3135, 0.3236) for the black body there.
        let (x, y) = planckian_xy(6504.0);
        assert!((x - 0.3135).abs() < 1e-3 && (y - 0.3236).abs() < 1e-3, "({x}, {y})");
    }

    #[test]
    fn d65_white_maps_to_equal_channels() {
        // sRGB's white point: (0.3127, 0.3290) must come out as R = G = B.
        let rgb = xy_to_linear_srgb(0.3127, 0.3290);
        assert!(
            (rgb / rgb.max_element() - DVec3::ONE).abs().max_element() < 2e-3,
            "{rgb}"
        );
    }

    #[test]
    fn lower_temperatures_are_warmer() {
        let mut previous = color_of_temperature(1700.0);
        for t in (2000..=20000).step_by(500) {
            let c = color_of_temperature(t as f32);
            assert!(c.max_element() == 1.0 && c.min_element() >= 0.0, "{t} K: {c}");
            assert!(c.z / c.x >= previous.z / previous.x, "{t} K is not bluer than below");
            previous = c;
        }
        let candle = color_of_temperature(1900.0);
        assert!(candle.x == 1.0 && candle.z < 0.3, "candle light is orange: {candle}");
        let sky = color_of_temperature(12000.0);
        assert!(sky.z == 1.0 && sky.x < 0.8, "clear sky is blue: {sky}");
    }

    #[test]
    fn temperature_of_a_locus_colour_is_found_again() {
        for t in [1800.0, 2700.0, 3200.0, 4000.0, 5600.0, 6500.0, 9000.0, 15000.0] {
            let found = temperature_of_color(0.37 * color_of_temperature(t)).expect("on the locus");
            assert!((found - t).abs() / t < 0.01, "{t} K read back as {found} K");
        }
    }

    #[test]
    fn colours_off_the_locus_have_no_temperature() {
        for color in [
            Vec3::new(0.0, 1.0, 0.0),
            Vec3::new(1.0, 0.0, 1.0),
            Vec3::ZERO,
            Vec3::NAN,
        ] {
            assert_eq!(temperature_of_color(color), None, "{color}");
        }
    }
}
