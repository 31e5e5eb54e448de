//! Small lights in the study: how well each shadow path draws penumbrae, on a scene whose
//! blockers are exact spheres (so the sphere fit is not the source of error). Three balls
//! over a white floor, under one sphere light 4 m up whose angular radius at the floor's
//! centre is 1°, 5°, 15°, 40° or 60° (same irradiance there), then under a uniform sky
//! alone. The path tracer sees the balls as fine meshes; the renderer gets the exact
//! spheres as blockers.
//!
//! Per floor pixel, the reference visibility is V = L_reference / L_reference without the
//! balls (direct light, luminance), and a path's is its shading over its own shading
//! without blockers, so that only shadows are compared; the penumbra is where
//! 5 % < V < 95 %, the umbra where V ≤ 5 %. The error of a path is V_path − V_reference
//! (a share of the unshadowed light), its RMS over each mask reported, with the f64
//! shading (the GPU agrees with it within 1/255: tests/exact_shadows.rs) and the time that
//! of GPU frames. The sky has no exact path: its
//! light comes through the SH in both.

use glam::{Vec3, Vec4};
use rayon::prelude::*;

use super::StudyError;
use crate::blockers::Sphere;
use crate::reference::{ProgressiveRender, SurfaceHit};
use crate::render::{AntiAliasing, GpuContext, Redraw, ShadowFrame, ShadowRenderer, capture_surfaces};
use crate::scene::{Camera, Environment, Light, LightKind, Material, Scene, luminance, shapes};
use crate::shading::cpu::{self, ShadingInputs, SurfacePoint};
use crate::shading::gpu_types::environment_irradiance;
use crate::shading::{LightPaths, RenderSettings, ShadowPath, ShadowSettings};

/// Light radii measured (degrees, at the floor's centre).
pub const LIGHT_HALF_ANGLES_DEG: [f64; 5] = [1.0, 5.0, 15.0, 40.0, 60.0];

/// One light and path.
#[derive(Debug, Clone, PartialEq)]
pub struct PenumbraRow {
    /// "5°" or "sky".
    pub light: String,
    pub path: ShadowPath,
    pub penumbra_pixels: usize,
    /// RMS of (L_path − L_reference)/L_unshadowed over the penumbra.
    pub penumbra_rms: f64,
    /// The same over the umbra (None: the light is too large to leave one).
    pub umbra_rms: Option<f64>,
    /// Largest value over the unshadowed light (above 1 would be an overshoot).
    pub max_over_unshadowed: f64,
    pub ms_per_frame: f64,
    /// RMS of the reference's own noise over the penumbra (from two halves).
    pub reference_noise: f64,
    /// The default settings with the default sphere fit of the meshes drew it, `path`
    /// being the one they chose for the light.
    pub defaults: bool,
}

const HEIGHT_M: f32 = 10.0;

fn balls() -> [Sphere; 3] {
    [
        Sphere {
            center: Vec3::new(0.0, 0.6, 0.0),
            radius_m: 0.35,
            disc_normal: glam::Vec3::ZERO,
        },
        Sphere {
            center: Vec3::new(1.1, 0.4, 0.5),
            radius_m: 0.25,
            disc_normal: glam::Vec3::ZERO,
        },
        Sphere {
            center: Vec3::new(-0.9, 0.9, -0.6),
            radius_m: 0.3,
            disc_normal: glam::Vec3::ZERO,
        },
    ]
}

/// The floor and (`with_balls`) the balls as meshes, lit by `light` or by a uniform sky.
fn scene(light: Option<Light>, with_balls: bool) -> Scene {
    let balls = balls()
        .iter()
        .enumerate()
        .filter(|_| with_balls)
        .map(|(i, ball)| {
            shapes::uv_sphere(ball.radius_m, 96, 48)
                .transformed(glam::Affine3A::from_translation(ball.center))
                .into_object(&format!("ball {i}"))
        })
        .collect();
    floor_scene(light, balls)
}

/// A white floor with `casters` over it, lit by `light` or by a uniform sky.
pub(super) fn floor_scene(light: Option<Light>, casters: Vec<crate::scene::MeshObject>) -> Scene {
    let mut objects = vec![shapes::plane(8.0, 8, 1.0).into_object("floor")];
    objects.extend(casters);
    Scene {
        objects,
        materials: vec![Material {
            base_color: Vec4::ONE,
            metallic: 0.0,
            specular: 0.0,
            ..Material::default()
        }],
        environment: light.is_none().then(|| Environment::uniform([1.0, 1.0, 1.0])),
        lights: light.into_iter().collect(),
        ..Scene::default()
    }
}

/// A sphere light 10 m above the floor's centre, `half_angle_deg` in radius there, giving
/// the centre 3 lux.
pub(super) fn sphere_light(half_angle_deg: f64) -> Light {
    let radius = HEIGHT_M * half_angle_deg.to_radians().sin() as f32;
    Light {
        name: format!("{half_angle_deg}°"),
        kind: LightKind::Sphere { radius_m: radius },
        color: Vec3::ONE,
        intensity: 3.0 * HEIGHT_M * HEIGHT_M,
        position: Vec3::new(0.2, HEIGHT_M, 0.1),
        direction: Vec3::NEG_Y,
        range: None,
        locked: false,
    }
}

/// The cost the exact path must stay under: 8 small sphere lights (5°) and 50 blockers,
/// both paths timed on GPU frames of `size`² pixels.
pub fn cost_of_eight_lights(gpu: &GpuContext, size: u32, frames: u32) -> Result<Vec<(LightPaths, f64)>, StudyError> {
    let mut scene = scene(None, false);
    scene.environment = None;
    scene.lights = (0..8)
        .map(|k| {
            let turn = k as f32 * std::f32::consts::TAU / 8.0;
            Light {
                position: Vec3::new(3.0 * turn.cos(), HEIGHT_M, 3.0 * turn.sin()),
                ..sphere_light(5.0)
            }
        })
        .collect();
    // 50 balls on a jittered 7 × 7 (+1) grid over the floor.
    let blockers: Vec<Sphere> = (0..50)
        .map(|k| {
            let (i, j) = ((k % 7) as f32, (k / 7) as f32);
            Sphere {
                center: Vec3::new(-3.0 + i, 0.5 + 0.1 * (k % 3) as f32, -3.0 + j),
                radius_m: 0.2 + 0.02 * (k % 5) as f32,
                disc_normal: glam::Vec3::ZERO,
            }
        })
        .collect();
    let camera = Camera {
        position: Vec3::new(0.0, 7.0, 0.01),
        forward: Vec3::NEG_Y,
        up: Vec3::NEG_Z,
        yfov_rad: 60f32.to_radians(),
        znear: 0.1,
        zfar: None,
    };
    [LightPaths::Harmonics, LightPaths::Exact]
        .into_iter()
        .map(|path| {
            let shadows = ShadowSettings {
                light_paths: path,
                ..ShadowSettings::default().every_pixel()
            };
            Ok((path, frame_ms(gpu, &scene, &camera, &shadows, &blockers, size, frames)?))
        })
        .collect()
}

/// Image size (square) and reference samples per pixel of the small-light suites.
pub(super) fn size_and_spp(quick: bool) -> (u32, u32) {
    if quick { (64, 512) } else { (128, 2048) }
}

/// The camera looking straight down at the floor's centre from 7 m.
pub(super) fn overhead_camera() -> Camera {
    Camera {
        position: Vec3::new(0.0, 7.0, 0.01),
        forward: Vec3::NEG_Y,
        up: Vec3::NEG_Z,
        yfov_rad: 45f32.to_radians(),
        znear: 0.1,
        zfar: None,
    }
}

/// Measures every light size and the sky with both paths; `quick` uses a small image and
/// fewer reference samples.
pub fn measure_penumbrae(gpu: &GpuContext, quick: bool) -> Result<Vec<PenumbraRow>, StudyError> {
    let (size, spp) = size_and_spp(quick);
    let camera = overhead_camera();
    let mut rows = Vec::new();
    let lights: Vec<Option<Light>> = LIGHT_HALF_ANGLES_DEG
        .iter()
        .map(|&a| Some(sphere_light(a)))
        .chain([None])
        .collect();
    for light in lights {
        let (scene, open) = (scene(light.clone(), true), scene(light.clone(), false));
        let label = light.as_ref().map_or("sky".to_string(), |l| l.name.clone());
        let surfaces = capture_surfaces(gpu, &scene, &camera, None, size, size)?;
        let reference = References::render(&scene, &open, &surfaces, camera.position, size, spp);
        let paths = if light.is_some() {
            vec![LightPaths::Harmonics, LightPaths::Exact]
        } else {
            vec![LightPaths::Harmonics]
        };
        for path in paths {
            let shadows = ShadowSettings {
                light_paths: path,
                ..ShadowSettings::default().every_pixel()
            };
            let mut row = compare(&scene, &surfaces, &reference, &shadows, &balls(), &camera);
            row.light = label.clone();
            row.ms_per_frame = frame_ms(
                gpu,
                &scene,
                &camera,
                &shadows,
                &balls(),
                size,
                if quick { 2 } else { 8 },
            )?;
            rows.push(row);
        }
        // Shadow maps where Auto gives them: lights up to the mapped size.
        let mapped = light.as_ref().is_some_and(|l| {
            let half_angle_deg: f64 = l.name.trim_end_matches('°').parse().unwrap_or(f64::INFINITY);
            half_angle_deg <= crate::shading::shadow_maps::MAX_MAPPED_HALF_ANGLE_DEG
        });
        if mapped {
            let mut row = compare_maps(gpu, &scene, &open, &surfaces, &reference, &camera, size)?;
            row.light = label.clone();
            row.ms_per_frame = maps_frame_ms(gpu, &scene, &camera, size, if quick { 2 } else { 8 })?;
            rows.push(row);
        }
        // What the defaults do, fitting spheres to the meshes as a loaded scene would.
        if light.is_some() {
            let (mut row, ms) = compare_defaults(
                gpu,
                (&scene, &open),
                &surfaces,
                &reference,
                &camera,
                (size, if quick { 2 } else { 8 }),
            )?;
            row.light = label.clone();
            row.ms_per_frame = ms;
            rows.push(row);
        }
    }
    Ok(rows)
}

/// The shadow-map path as the suites measure it: Auto with 1024² maps, every pixel shaded.
fn maps_settings() -> ShadowSettings {
    ShadowSettings {
        light_paths: LightPaths::Auto,
        shadow_map_size: crate::shading::SUGGESTED_SHADOW_MAP_SIZE,
        ..ShadowSettings::default().every_pixel()
    }
}

/// Mean GPU time of the shadow-map path's frames (no sphere blockers).
fn maps_frame_ms(gpu: &GpuContext, scene: &Scene, camera: &Camera, size: u32, frames: u32) -> Result<f64, StudyError> {
    let shadows = maps_settings();
    frame_ms(gpu, scene, camera, &shadows, &[], size, frames)
}

/// The reference luminance of each pixel with and without the casters, and the noise of
/// the first.
pub(super) struct References {
    shadowed: Vec<f64>,
    unshadowed: Vec<f64>,
    noise: Vec<f64>,
}

impl References {
    /// Path-traces `scene` and `open` (the same without casters) at the `surfaces`.
    pub(super) fn render(
        scene: &Scene,
        open: &Scene,
        surfaces: &[Option<SurfacePoint>],
        eye: Vec3,
        size: u32,
        spp: u32,
    ) -> References {
        let (shadowed, noise) = reference(scene, surfaces, eye, size, spp);
        let (unshadowed, _) = reference(open, surfaces, eye, size, spp);
        References {
            shadowed,
            unshadowed,
            noise,
        }
    }
}

/// The direct-light reference of every pixel (luminance), and its noise per pixel from two
/// independent halves (|a − b|/2).
fn reference(scene: &Scene, surfaces: &[Option<SurfacePoint>], eye: Vec3, size: u32, spp: u32) -> (Vec<f64>, Vec<f64>) {
    let hits: Vec<Option<SurfaceHit>> = surfaces.iter().map(|s| s.as_ref().map(super::surface_hit)).collect();
    let half = |seed: u64| {
        let mut render = ProgressiveRender::from_surfaces(scene, hits.clone(), eye, size, 0, seed);
        for _ in 0..(spp / 2).max(1) {
            render.run_pass();
        }
        render.image().radiance.into_iter().map(luminance).collect::<Vec<f64>>()
    };
    let (a, b) = (half(11), half(12));
    let mean = a.iter().zip(&b).map(|(x, y)| 0.5 * (x + y)).collect();
    let noise = a.iter().zip(&b).map(|(x, y)| 0.5 * (x - y).abs()).collect();
    (mean, noise)
}

/// One lit floor pixel, relative to its unshadowed light.
struct PixelSample {
    /// Visibility of the path − the reference's (a share of the unshadowed light).
    error: f64,
    /// The reference's noise/unshadowed.
    noise: f64,
    reference_visibility: f64,
    shaded_visibility: f64,
}

/// Errors of one path, shading with `blockers` in f64, against the reference over the
/// floor's penumbra and umbra.
pub(super) fn compare(
    scene: &Scene,
    surfaces: &[Option<SurfacePoint>],
    reference: &References,
    shadows: &ShadowSettings,
    blockers: &[Sphere],
    camera: &Camera,
) -> PenumbraRow {
    let context = crate::shading::LightPathContext::of_scene(scene, blockers);
    let lights = crate::shading::shading_lights(&scene.lights, shadows, &context);
    let environment = environment_irradiance(scene.environment.as_ref());
    let inputs = ShadingInputs {
        lights: &lights,
        environment_irradiance: &environment,
        blockers,
        terrain: None,
        settings: shadows,
        eye: camera.position.as_dvec3(),
        // The reference samples each pixel at its centre, unfiltered: so does the shading
        // compared with it (no anti-aliasing of hard edges, which would widen them by a
        // pixel the reference does not blur).
        pixel_angle_rad: 0.0,
        occluders: None,
    };
    let open = ShadingInputs {
        blockers: &[],
        terrain: None,
        ..inputs
    };
    let path = lights.first().map_or(ShadowPath::Harmonics, ShadowPath::of);
    errors(surfaces, reference, path, |_, s| {
        let unshadowed = luminance(cpu::shadowed_radiance(s, &open));
        (unshadowed > 1e-6).then(|| luminance(cpu::shadowed_radiance(s, &inputs)) / unshadowed)
    })
}

/// Errors of the shadow-map path against the reference over the floor's penumbra and
/// umbra: GPU frames with 1024² maps and no sphere blockers. The maps are the GPU's alone
/// (their f64 twin casts rays, which is what they approximate), so they are measured on
/// the GPU.
pub(super) fn compare_maps(
    gpu: &GpuContext,
    scene: &Scene,
    open: &Scene,
    surfaces: &[Option<SurfacePoint>],
    reference: &References,
    camera: &Camera,
    size: u32,
) -> Result<PenumbraRow, StudyError> {
    let shadows = maps_settings();
    let no_blockers = GpuFrameSetup {
        shadows: &shadows,
        blockers: &[],
        open_blockers: &[],
    };
    compare_gpu(gpu, (scene, open), surfaces, reference, camera, size, &no_blockers)
}

/// What a GPU comparison draws with: settings, and the blockers of the scene with and
/// without its casters.
struct GpuFrameSetup<'a> {
    shadows: &'a ShadowSettings,
    blockers: &'a [Sphere],
    open_blockers: &'a [Sphere],
}

/// Errors of the GPU frames of `scenes` (with and without the casters) as `setup` draws
/// them, their displayed pixels turned back into linear light
/// ([`crate::shading::displayed_radiance`], within 8-bit rounding); the row's path is the
/// one the light takes.
fn compare_gpu(
    gpu: &GpuContext,
    (scene, open): (&Scene, &Scene),
    surfaces: &[Option<SurfacePoint>],
    reference: &References,
    camera: &Camera,
    size: u32,
    setup: &GpuFrameSetup,
) -> Result<PenumbraRow, StudyError> {
    let settings = RenderSettings::default();
    let linear_luminance = |scene: &Scene, blockers: &[Sphere]| -> Result<Vec<f64>, StudyError> {
        let frame = ShadowFrame {
            scene,
            camera,
            settings: &settings,
            shadows: setup.shadows,
            blockers,
            baked_indirect: None,
            width: size,
            height: size,
        };
        let image = crate::render::render_logsh_image(gpu, &frame, AntiAliasing::None)?;
        Ok(image
            .pixels()
            .map(|p| {
                luminance(crate::shading::displayed_radiance(
                    [p[0], p[1], p[2]],
                    settings.exposure_ev as f64,
                ))
            })
            .collect())
    };
    let shaded = linear_luminance(scene, setup.blockers)?;
    let unshadowed = linear_luminance(open, setup.open_blockers)?;
    let context = crate::shading::LightPathContext::of_scene(scene, setup.blockers);
    let path = crate::shading::shading_lights(&scene.lights, setup.shadows, &context)
        .first()
        .map_or(ShadowPath::Harmonics, ShadowPath::of);
    Ok(errors(surfaces, reference, path, |i, _| {
        (unshadowed[i] > 1e-6).then(|| shaded[i] / unshadowed[i])
    }))
}

/// Errors of the default settings (every pixel shaded, as the suite's other rows are)
/// with the blockers the default fit gives the balls' meshes and the floor, measured as
/// the other rows of the path Auto chose: the f64 shading at pixel centres for the exact
/// and SH paths, GPU frames for the maps. (The GPU's exact path widens each light's disc
/// by half a pixel's footprint, so that a penumbra narrower than a pixel is spread over
/// one rather than aliased; against the reference's point samples that spread counts as
/// error where the penumbra is sub-pixel: docs/speed-accuracy.md.)
fn compare_defaults(
    gpu: &GpuContext,
    scenes: (&Scene, &Scene),
    surfaces: &[Option<SurfacePoint>],
    reference: &References,
    camera: &Camera,
    (size, frames): (u32, u32),
) -> Result<(PenumbraRow, f64), StudyError> {
    let fit = |scene: &Scene| crate::blockers::fit_scene(scene, &crate::blockers::BlockerSettings::default()).spheres();
    let (blockers, open_blockers) = (fit(scenes.0), fit(scenes.1));
    let shadows = ShadowSettings::default().every_pixel();
    let context = crate::shading::LightPathContext::of_scene(scenes.0, &blockers);
    let path = crate::shading::shading_lights(&scenes.0.lights, &shadows, &context)
        .first()
        .map_or(ShadowPath::Harmonics, ShadowPath::of);
    let mut row = if path == ShadowPath::Map {
        let setup = GpuFrameSetup {
            shadows: &shadows,
            blockers: &blockers,
            open_blockers: &open_blockers,
        };
        compare_gpu(gpu, scenes, surfaces, reference, camera, size, &setup)?
    } else {
        compare(scenes.0, surfaces, reference, &shadows, &blockers, camera)
    };
    row.defaults = true;
    let ms = frame_ms(gpu, scenes.0, camera, &shadows, &blockers, size, frames)?;
    Ok((row, ms))
}

/// The row of a path whose visibility at floor pixel `i` (surface point `s`) is
/// `visibility(i, s)`, against the reference.
fn errors(
    surfaces: &[Option<SurfacePoint>],
    reference: &References,
    path: ShadowPath,
    visibility: impl Fn(usize, &SurfacePoint) -> Option<f64> + Sync,
) -> PenumbraRow {
    let samples: Vec<PixelSample> = surfaces
        .par_iter()
        .enumerate()
        .filter_map(|(i, s)| {
            let s = s.as_ref().filter(|s| s.position.y.abs() < 1e-3)?;
            let reference_open = reference.unshadowed[i];
            if reference_open <= 1e-6 {
                return None;
            }
            let shaded = visibility(i, s)?;
            let reference_visibility = reference.shadowed[i] / reference_open;
            Some(PixelSample {
                error: shaded - reference_visibility,
                noise: reference.noise[i] / reference_open,
                reference_visibility,
                shaded_visibility: shaded,
            })
        })
        .collect();
    let in_penumbra = |s: &&PixelSample| s.reference_visibility > 0.05 && s.reference_visibility < 0.95;
    let in_umbra = |s: &&PixelSample| s.reference_visibility <= 0.05;
    let rms = |values: Vec<f64>| (values.iter().fold(0.0, |sum, e| sum + e * e) / values.len().max(1) as f64).sqrt();
    let umbra: Vec<f64> = samples.iter().filter(in_umbra).map(|s| s.error).collect();
    PenumbraRow {
        light: String::new(),
        path,
        penumbra_pixels: samples.iter().filter(in_penumbra).count(),
        penumbra_rms: rms(samples.iter().filter(in_penumbra).map(|s| s.error).collect()),
        umbra_rms: (!umbra.is_empty()).then(|| rms(umbra)),
        max_over_unshadowed: samples.iter().map(|s| s.shaded_visibility).fold(0.0, f64::max),
        ms_per_frame: 0.0,
        reference_noise: rms(samples.iter().filter(in_penumbra).map(|s| s.noise).collect()),
        defaults: false,
    }
}

/// Mean GPU time of `frames` frames (after one), one sample per pixel.
fn frame_ms(
    gpu: &GpuContext,
    scene: &Scene,
    camera: &Camera,
    shadows: &ShadowSettings,
    blockers: &[Sphere],
    size: u32,
    frames: u32,
) -> Result<f64, StudyError> {
    let settings = RenderSettings::default();
    let frame = ShadowFrame {
        scene,
        camera,
        settings: &settings,
        shadows,
        blockers,
        baked_indirect: None,
        width: size,
        height: size,
    };
    let mut renderer = ShadowRenderer::new(gpu, &frame, AntiAliasing::None)?;
    renderer.draw_and_wait(Redraw::Everything)?;
    super::mean_frame_ms(frames, || renderer.draw_and_wait(Redraw::Everything))
}
