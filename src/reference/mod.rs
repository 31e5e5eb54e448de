//! The ground truth: an unbiased path tracer over the same [`Scene`] the real-time
//! renderer draws — same camera projection, lights, reflectance model and environment —
//! on the bake's obvhs BVH of every triangle (no sphere proxies).
//!
//! Modes: direct light only (`bounces` = 0) or global illumination with up to
//! [`MAX_BOUNCES`] bounces (Russian roulette from the third). Rendering is progressive (one
//! sample per pixel per pass, passes averaged), seeded (the same seed gives the same image
//! on any number of threads: every pixel and pass has its own stream) and runs on all
//! cores (rayon).
//!
//! Where the real-time renderer approximates, this module does not: sphere and area
//! lights are sampled over their emitters, the environment is reflected by the glossy
//! lobe too, and light reaches surfaces only past the real triangles.

mod camera_rays;
mod emitters;
mod path;
mod surface;

pub use camera_rays::{CameraRay, CameraRays};
pub use emitters::{EmitterSample, sample_light};
pub use path::PathTracer;
pub use surface::{SurfaceHit, surface_at};

use glam::DVec3;
use rayon::prelude::*;

use crate::random::{SplitMix64, mix_seed};
use crate::scene::{Camera, Scene};

/// The most bounces a reference render follows (paths are rarely that long after Russian
/// roulette; the limit bounds the time of a pathological all-white scene).
pub const MAX_BOUNCES: u32 = 64;

/// What to render.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct ReferenceSettings {
    /// Samples (paths) per pixel.
    pub samples_per_pixel: u32,
    /// Indirect bounces: 0 = direct light only.
    pub bounces: u32,
    pub seed: u64,
}

impl Default for ReferenceSettings {
    fn default() -> Self {
        ReferenceSettings {
            samples_per_pixel: 64,
            bounces: 4,
            seed: 1,
        }
    }
}

/// A rendered (or partly rendered) reference image in linear radiance.
#[derive(Debug, Clone, PartialEq)]
pub struct ReferenceImage {
    pub width: u32,
    pub height: u32,
    /// Mean linear RGB radiance of the samples that met a surface, row-major (zero where
    /// none did).
    pub radiance: Vec<DVec3>,
    /// Share of each pixel's samples that met a surface (the rest show the background).
    pub coverage: Vec<f64>,
    pub samples_per_pixel: u32,
    /// Samples dropped because they were not finite (should stay 0; counted, not hidden).
    pub discarded_samples: u64,
    /// Rays traced to make it (camera, continuation and shadow rays).
    pub rays_cast: u64,
}

impl ReferenceImage {
    /// The image for display: exposure, the renderer's tone curve and sRGB, blended with
    /// the background by coverage.
    pub fn to_srgb8(&self, exposure_ev: f64, background_srgb8: [u8; 3]) -> image::RgbaImage {
        let pixels: Vec<u8> = self
            .radiance
            .iter()
            .zip(&self.coverage)
            .flat_map(|(radiance, &coverage)| {
                let shaded = crate::shading::display_srgb8(*radiance, exposure_ev);
                let blend = |k: usize| {
                    (shaded[k] as f64 * coverage + background_srgb8[k] as f64 * (1.0 - coverage)).round() as u8
                };
                [blend(0), blend(1), blend(2), 255]
            })
            .collect();
        image::RgbaImage::from_raw(self.width, self.height, pixels).expect("width × height RGBA pixels")
    }
}

/// Where each pixel's paths start.
enum Primary {
    /// Rays from the camera through jittered points of each pixel (box filter).
    Camera(CameraRays),
    /// Given visible surfaces (e.g. the rasteriser's, so that a comparison sees the same
    /// points, texture filtering and edges) seen from an eye point; None shows background.
    Surfaces {
        surfaces: Vec<Option<SurfaceHit>>,
        eye: glam::Vec3,
    },
}

/// A reference render in progress: call [`ProgressiveRender::run_pass`] until enough
/// samples are in, looking at [`ProgressiveRender::image`] whenever wanted.
pub struct ProgressiveRender<'a> {
    tracer: PathTracer<'a>,
    primary: Primary,
    width: u32,
    height: u32,
    seed: u64,
    sums: Vec<DVec3>,
    hits: Vec<u32>,
    passes: u32,
    discarded: u64,
}

impl<'a> ProgressiveRender<'a> {
    pub fn new(scene: &'a Scene, camera: &Camera, width: u32, height: u32, bounces: u32, seed: u64) -> Self {
        let primary = Primary::Camera(CameraRays::new(camera, width, height));
        ProgressiveRender::start(scene, primary, width, height, bounces, seed)
    }

    /// A render whose paths start at given visible surfaces (row-major, `width` wide),
    /// seen from `eye`: the light is path traced, the first hit is not.
    pub fn from_surfaces(
        scene: &'a Scene,
        surfaces: Vec<Option<SurfaceHit>>,
        eye: glam::Vec3,
        width: u32,
        bounces: u32,
        seed: u64,
    ) -> Self {
        let height = (surfaces.len() / width.max(1) as usize) as u32;
        let mut render =
            ProgressiveRender::start(scene, Primary::Surfaces { surfaces, eye }, width, height, bounces, seed);
        // Each captured point as the eye sees it: a point the depth test kept inside other
        // geometry (at a crack, where meshes meet) would otherwise be lit by nothing.
        if let Primary::Surfaces { surfaces, eye } = &mut render.primary {
            let tracer = &render.tracer;
            surfaces
                .par_iter_mut()
                .for_each(|s| *s = s.map(|s| tracer.as_seen_from(*eye, s)));
        }
        render
    }

    fn start(scene: &'a Scene, primary: Primary, width: u32, height: u32, bounces: u32, seed: u64) -> Self {
        let pixels = width as usize * height as usize;
        ProgressiveRender {
            tracer: PathTracer::new(scene, bounces.min(MAX_BOUNCES)),
            primary,
            width,
            height,
            seed,
            sums: vec![DVec3::ZERO; pixels],
            hits: vec![0; pixels],
            passes: 0,
            discarded: 0,
        }
    }

    /// Adds one sample to every pixel (a jittered point of the pixel, one path).
    pub fn run_pass(&mut self) {
        let (width, pass, seed) = (self.width as usize, self.passes as u64, self.seed);
        let (tracer, primary) = (&self.tracer, &self.primary);
        let discarded: u64 = self
            .sums
            .par_chunks_mut(width.max(1))
            .zip(self.hits.par_chunks_mut(width.max(1)))
            .enumerate()
            .map(|(row, (sums, hits))| {
                let mut discarded = 0;
                for (column, (sum, hit)) in sums.iter_mut().zip(hits.iter_mut()).enumerate() {
                    let pixel = (row * width + column) as u64;
                    let mut random = SplitMix64(mix_seed(&[seed, pixel, pass]));
                    let radiance = match primary {
                        Primary::Camera(rays) => {
                            let x = column as f64 + random.next_f64();
                            let y = row as f64 + random.next_f64();
                            let ray = rays.through(x, y);
                            tracer.radiance(ray.origin, ray.direction, ray.t_min, ray.t_max, &mut random)
                        }
                        Primary::Surfaces { surfaces, eye } => {
                            surfaces.get(pixel as usize).copied().flatten().map(|surface| {
                                let to_eye = (*eye - surface.position).normalize_or(surface.normal);
                                tracer.radiance_leaving(surface, to_eye, &mut random)
                            })
                        }
                    };
                    match radiance {
                        Some(radiance) if radiance.is_finite() => {
                            *sum += radiance;
                            *hit += 1;
                        }
                        Some(_) => discarded += 1,
                        None => {}
                    }
                }
                discarded
            })
            .sum();
        self.discarded += discarded;
        self.passes += 1;
    }

    pub fn passes_done(&self) -> u32 {
        self.passes
    }

    /// The mean of the passes so far.
    pub fn image(&self) -> ReferenceImage {
        let passes = self.passes.max(1) as f64;
        ReferenceImage {
            width: self.width,
            height: self.height,
            radiance: self
                .sums
                .iter()
                .zip(&self.hits)
                .map(|(sum, &hits)| if hits > 0 { *sum / hits as f64 } else { DVec3::ZERO })
                .collect(),
            coverage: self.hits.iter().map(|&h| h as f64 / passes).collect(),
            samples_per_pixel: self.passes,
            discarded_samples: self.discarded,
            rays_cast: self.tracer.rays_cast(),
        }
    }
}

/// Renders `scene` from `camera` with all of `settings.samples_per_pixel`, calling
/// `progress(passes done)` after each pass.
pub fn render_reference(
    scene: &Scene,
    camera: &Camera,
    width: u32,
    height: u32,
    settings: &ReferenceSettings,
    mut progress: impl FnMut(u32),
) -> ReferenceImage {
    let mut render = ProgressiveRender::new(scene, camera, width, height, settings.bounces, settings.seed);
    for _ in 0..settings.samples_per_pixel {
        render.run_pass();
        progress(render.passes_done());
    }
    render.image()
}

#[cfg(test)]
mod tests;
