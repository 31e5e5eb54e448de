//! Numerical stability at the extremes, in CI (`lightpaint::study::stability` lists the
//! cases: 10,000 blockers, coincident blockers, a blocker touching the receiver, a
//! receiver inside a blocker, scene scales of 1e-4 and 1e4, intensities 0 and 1e6, a
//! grazing light, order 8 with HYB in f32). For each, the f64 shading of every visible
//! point is finite, non-negative and never brighter than the unshadowed light (shadows only
//! take light away), and the f32 GPU frame agrees with it.

mod common;

use lightpaint::study::stability::{measure, stability_cases};

#[test]
fn shading_stays_finite_bounded_and_matches_f64_at_the_extremes() {
    let Some(gpu) = common::gpu() else { return };
    let cases = stability_cases();
    assert_eq!(cases.len(), 10, "every extreme of the suite");
    let (width, height) = (64, 48);
    for case in &cases {
        let result = measure(&gpu, case, width, height).expect("the case renders");
        eprintln!(
            "{}: {:.2} % of pixels within 2/255 of f64, worst {}/255",
            result.name,
            100.0 * result.gpu_within_2,
            result.gpu_worst
        );
        assert!(
            result.visible_pixels > (width * height / 2) as usize,
            "{}: the floor fills the view ({} px)",
            result.name,
            result.visible_pixels
        );
        assert_eq!(result.non_finite, 0, "{}: NaN or inf", result.name);
        assert_eq!(result.negative, 0, "{}: negative light", result.name);
        assert_eq!(
            result.above_unshadowed, 0,
            "{}: shadowed brighter than unshadowed",
            result.name
        );
        assert!(
            result.gpu_within_2 >= 0.99,
            "{}: only {:.2} % within 2/255 (worst {})",
            result.name,
            100.0 * result.gpu_within_2,
            result.gpu_worst
        );
        assert!(result.holds());
    }
}
