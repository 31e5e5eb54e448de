//! How much path tracing the default frame's shadows are worth: the path tracer's samples
//! per pixel to reach the same shadowed-pixel error, and their time.

use std::time::Instant;

use super::metrics::{DisplayImage, image_errors};
use super::{SceneStudy, shadow_mask, surface_hit};
use crate::reference::{ProgressiveRender, SurfaceHit};

/// How much path tracing matches the default frame's shadows: the fewest samples per
/// pixel (a power of two) at which the path tracer's own image is as close to the
/// converged reference over the shadowed pixels as the default real-time frame, and what
/// that costs against the frame.
#[derive(Debug, Clone, PartialEq)]
pub struct EqualError {
    pub scene: String,
    /// The default frame's shadowed-pixel RMSE.
    pub frame_shadow_rmse: f64,
    pub frame_ms: f64,
    /// None: not reached within the largest count tried.
    pub samples_per_pixel: Option<u32>,
    /// Wall time of the path tracer at that count (all cores), ms.
    pub trace_ms: f64,
    /// The path tracer's shadowed-pixel RMSE at each count tried (1, 2, 4, …), up to one
    /// count past the match: how far the frame's error is from the next count's.
    pub curve: Vec<(u32, f64)>,
}

/// What [`SceneStudy::equal_error_spp`] found.
pub(super) struct EqualErrorTrace {
    pub samples_per_pixel: Option<u32>,
    pub trace_ms: f64,
    pub curve: Vec<(u32, f64)>,
}

impl SceneStudy<'_> {
    /// The fewest samples per pixel (1, 2, 4, … up to `max_spp`) at which an independent
    /// path-traced image of direct light comes within `target` shadowed-pixel RMSE of
    /// `reference` (the mask as the grid's rows use), and the wall time its passes took to
    /// get there; None and the time of `max_spp` when it never does. The curve goes on
    /// to the next count past the match (within `max_spp`).
    pub(super) fn equal_error_spp(&self, reference: &image::RgbaImage, target: f64, max_spp: u32) -> EqualErrorTrace {
        let reference_display = DisplayImage::from_rgba8(reference);
        let shadowed = match self.unshadowed() {
            Ok(unshadowed) => shadow_mask(&reference_display, &DisplayImage::from_rgba8(&unshadowed)),
            Err(_) => {
                return EqualErrorTrace {
                    samples_per_pixel: None,
                    trace_ms: 0.0,
                    curve: Vec::new(),
                };
            }
        };
        let hits: Vec<Option<SurfaceHit>> = self.surfaces.iter().map(|s| s.as_ref().map(surface_hit)).collect();
        let mut render = ProgressiveRender::from_surfaces(self.scene, hits, self.camera.position, self.width, 0, 3);
        // Only the passes count, not the checks between them.
        let mut tracing = std::time::Duration::ZERO;
        let mut spp = 0;
        let mut next_check = 1;
        let mut curve = Vec::new();
        let mut found: Option<(u32, f64)> = None;
        while spp < max_spp.max(1) {
            let started = Instant::now();
            render.run_pass();
            tracing += started.elapsed();
            spp += 1;
            if spp < next_check {
                continue;
            }
            next_check *= 2;
            let elapsed_ms = tracing.as_secs_f64() * 1000.0;
            let image = render
                .image()
                .to_srgb8(self.settings.exposure_ev as f64, self.settings.background_srgb8);
            let errors = image_errors(&DisplayImage::from_rgba8(&image), &reference_display, &shadowed);
            if let Some(e) = errors.shadow_rmse {
                curve.push((spp, e));
            }
            if found.is_some() {
                break;
            }
            if errors.shadow_rmse.is_some_and(|e| e <= target) {
                found = Some((spp, elapsed_ms));
            }
        }
        EqualErrorTrace {
            samples_per_pixel: found.map(|(spp, _)| spp),
            trace_ms: found.map_or(tracing.as_secs_f64() * 1000.0, |(_, ms)| ms),
            curve,
        }
    }
}
