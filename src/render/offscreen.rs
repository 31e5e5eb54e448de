//! Headless rendering into images: the unshadowed raster, the log-SH renderer on the GPU,
//! and the f64 CPU reference shading the very surface points the GPU rasterised.

use crate::shading::wgsl::slots;
use glam::DVec3;
use rayon::prelude::*;

use super::descriptors::SAMPLE_COUNT;
use super::passes::ListedPixels;
use super::passes::logsh::{SURFACE_FORMAT, surface_pipelines};
use super::passes::raster::ScenePipeline;
use super::readback::{read_target_image, read_texture};
use super::renderer::{Compilation, FrameQuality, SceneRenderer};
use super::resources::{Detail, GpuBlockers, GpuScene, SceneLayouts, ShadowMaps, draw_objects, shadow_layout};
use super::target::{AntiAliasing, RenderTarget};
use super::{GpuContext, RenderError};
use crate::blockers::Sphere;
use crate::scene::{Camera, Scene};
use crate::shading::cpu::{self, ShadingInputs, SurfacePoint};
use crate::shading::gpu_types::{GpuLight, environment_irradiance};
use crate::shading::shadow_maps::ShadowViews;
use crate::shading::{BakedIndirect, RenderSettings, ShadowSettings};

/// Largest image side accepted by the renderers (lavapipe's 2D texture limit).
pub const MAX_IMAGE_SIDE: u32 = 16384;

fn check_size(gpu: &GpuContext, width: u32, height: u32) -> Result<(), RenderError> {
    let max = MAX_IMAGE_SIDE.min(gpu.device.limits().max_texture_dimension_2d);
    if width == 0 || height == 0 || width > max || height > max {
        return Err(RenderError::BadSize { width, height, max });
    }
    Ok(())
}

/// Renders `scene` seen by `camera` without shadows into an sRGB image of `width` ×
/// `height` pixels.
pub fn render_image(
    gpu: &GpuContext,
    scene: &Scene,
    camera: &Camera,
    settings: &RenderSettings,
    width: u32,
    height: u32,
) -> Result<image::RgbaImage, RenderError> {
    RasterRenderer::new(gpu, scene, camera, settings, width, height, SAMPLE_COUNT)?.read_image()
}

/// The plain raster pass (no shadows) with `samples` (1 or 4) per pixel, uploaded once so
/// frames can be drawn repeatedly.
pub struct RasterRenderer<'a> {
    gpu: &'a GpuContext,
    pipeline: ScenePipeline,
    gpu_scene: GpuScene,
    target: RenderTarget,
    background: [f64; 3],
}

impl<'a> RasterRenderer<'a> {
    pub fn new(
        gpu: &'a GpuContext,
        scene: &Scene,
        camera: &Camera,
        settings: &RenderSettings,
        width: u32,
        height: u32,
        samples: u32,
    ) -> Result<RasterRenderer<'a>, RenderError> {
        check_size(gpu, width, height)?;
        let pipeline = ScenePipeline::with_samples(&gpu.device, samples);
        let mut gpu_scene = GpuScene::upload(&gpu.device, &gpu.queue, &pipeline.layouts, scene);
        let target = RenderTarget::with_samples(&gpu.device, width, height, samples);
        gpu_scene.write_frame(
            &gpu.queue,
            camera,
            [width, height],
            (settings.exposure_ev, settings.background_linear()),
            Detail::Levels(&ShadowViews::default()),
        );
        Ok(RasterRenderer {
            gpu,
            pipeline,
            gpu_scene,
            target,
            background: settings.background_linear(),
        })
    }

    fn encode_frame(&self) -> wgpu::CommandEncoder {
        let mut encoder = self.gpu.device.create_command_encoder(&Default::default());
        self.pipeline
            .draw(&mut encoder, &self.target, &self.gpu_scene, self.background);
        encoder
    }

    /// Draws one frame and reads it back.
    pub fn read_image(&self) -> Result<image::RgbaImage, RenderError> {
        read_color(self.gpu, self.encode_frame(), &self.target)
    }

    /// Draws one frame and waits until the GPU has finished it.
    pub fn draw_and_wait(&self) -> Result<(), RenderError> {
        submit_and_wait(self.gpu, self.encode_frame())
    }
}

fn submit_and_wait(gpu: &GpuContext, encoder: wgpu::CommandEncoder) -> Result<(), RenderError> {
    gpu.queue.submit([encoder.finish()]);
    gpu.device
        .poll(wgpu::PollType::wait_indefinitely())
        .map(|_| ())
        .map_err(|e| RenderError::Readback(e.to_string()))
}

/// A log-SH frame request: what to render and how.
#[derive(Debug, Clone, Copy)]
pub struct ShadowFrame<'a> {
    pub scene: &'a Scene,
    pub camera: &'a Camera,
    pub settings: &'a RenderSettings,
    pub shadows: &'a ShadowSettings,
    pub blockers: &'a [Sphere],
    /// Baked indirect light to add (None: none).
    pub baked_indirect: Option<&'a BakedIndirect>,
    pub width: u32,
    pub height: u32,
}

impl ShadowFrame<'_> {
    /// The scene's lights as this frame shades them (`shading::shading_lights`, weighing
    /// this frame's scene and blockers).
    pub fn shading_lights(&self) -> Vec<GpuLight> {
        let context = crate::shading::LightPathContext::of_scene(self.scene, self.blockers);
        crate::shading::shading_lights(&self.scene.lights, self.shadows, &context)
    }

    fn check(&self, gpu: &GpuContext) -> Result<(), RenderError> {
        check_size(gpu, self.width, self.height)?;
        let problems = self.shadows.gpu_problems();
        if !problems.is_empty() {
            return Err(RenderError::BadSettings(problems.join("; ")));
        }
        Ok(())
    }
}

/// Renders a frame with log-SH shadows on the GPU, antialiased as `anti_aliasing` says.
pub fn render_logsh_image(
    gpu: &GpuContext,
    frame: &ShadowFrame,
    anti_aliasing: AntiAliasing,
) -> Result<image::RgbaImage, RenderError> {
    ShadowRenderer::new(gpu, frame, anti_aliasing)?.read_image()
}

/// A log-SH frame, set up once in the [`SceneRenderer`] the editor draws with too, so it
/// can be drawn repeatedly (benchmarks, the study, `render --time-frames`).
pub struct ShadowRenderer<'a> {
    gpu: &'a GpuContext,
    renderer: SceneRenderer,
    /// The scene's lights, set again before a frame drawn as after a light edit.
    lights: Vec<crate::scene::Light>,
    /// Frames drawn after moving the first light ([`Redraw::AfterLightMove`]).
    moves: u32,
    camera: Camera,
    size: [u32; 2],
    settings: RenderSettings,
}

/// How much of a frame [`ShadowRenderer`] draws anew.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Redraw {
    /// Everything, as for a new view.
    Everything,
    /// What an edit of the lights changes (a stroke, an intensity): the lights are set
    /// again and the surfaces the last frame rasterised are kept.
    AfterLightEdit,
    /// What a drag of the scene's first light changes: it moves by a centimetre (back
    /// and forth), so its shadow maps are drawn again.
    AfterLightMove,
    /// The same, as the editor draws it while the light is dragged: a single view's map
    /// at half its resolution (`FrameQuality::draft_moved_maps`).
    AfterLightMoveDrafted,
}

impl<'a> ShadowRenderer<'a> {
    pub fn new(
        gpu: &'a GpuContext,
        frame: &ShadowFrame,
        anti_aliasing: AntiAliasing,
    ) -> Result<ShadowRenderer<'a>, RenderError> {
        frame.check(gpu)?;
        let mut renderer = SceneRenderer::new(
            &gpu.device,
            &gpu.queue,
            frame.scene,
            frame.blockers,
            frame.shadows,
            anti_aliasing,
            Compilation::Blocking,
        );
        renderer.set_baked_indirect(frame.baked_indirect);
        let settings = RenderSettings {
            shadows: *frame.shadows,
            ..*frame.settings
        };
        Ok(ShadowRenderer {
            gpu,
            renderer,
            lights: frame.scene.lights.clone(),
            moves: 0,
            camera: frame.camera.clone(),
            size: [frame.width, frame.height],
            settings,
        })
    }

    /// Draws a frame, as much of it anew as `redraw` says.
    fn draw(&mut self, redraw: Redraw) {
        match redraw {
            Redraw::Everything => self.renderer.forget_surfaces(),
            Redraw::AfterLightEdit => self.renderer.set_lights(&self.lights),
            Redraw::AfterLightMove | Redraw::AfterLightMoveDrafted => {
                if let Some(first) = self.lights.first_mut() {
                    self.moves += 1;
                    first.position.x += if self.moves % 2 == 1 { 0.01 } else { -0.01 };
                }
                self.renderer.set_lights(&self.lights);
            }
        }
        let quality = FrameQuality {
            draft_moved_maps: redraw == Redraw::AfterLightMoveDrafted,
            ..FrameQuality::default()
        };
        self.renderer.render(&self.camera, self.size, &self.settings, quality);
    }

    /// Draws one frame and reads it back.
    pub fn read_image(&mut self) -> Result<image::RgbaImage, RenderError> {
        self.draw(Redraw::Everything);
        self.renderer
            .read_image()
            .unwrap_or_else(|| Err(RenderError::Readback("no frame was drawn".into())))
    }

    /// See [`SceneRenderer::set_detail_levels`]: off, the frame's surfaces are those
    /// [`capture_surfaces`] gives the f64 twin ([`render_cpu_image`]), so the two compare
    /// the shading alone.
    pub fn set_detail_levels(&mut self, enabled: bool) {
        self.renderer.set_detail_levels(enabled);
    }

    /// See [`SceneRenderer::set_light_grid`] (benchmarks time frames both ways).
    pub fn set_light_grid(&mut self, enabled: bool) {
        self.renderer.set_light_grid(enabled);
    }

    /// Draws one frame, as much of it anew as `redraw` says, and waits until the GPU has
    /// finished it.
    pub fn draw_and_wait(&mut self, redraw: Redraw) -> Result<(), RenderError> {
        self.draw(redraw);
        self.gpu
            .device
            .poll(wgpu::PollType::wait_indefinitely())
            .map_err(|e| RenderError::Readback(e.to_string()))?;
        self.renderer.collect_pass_times()
    }

    /// Times each pass of the frames drawn from now on, if the GPU has timestamps (false:
    /// it has not).
    pub fn time_passes(&mut self) -> bool {
        self.renderer.time_passes()
    }

    /// Mean GPU milliseconds per frame of each pass timed so far.
    pub fn pass_times_ms(&self) -> Vec<(&'static str, f64)> {
        self.renderer.pass_times_ms()
    }

    /// See [`SceneRenderer::listed_pixels`].
    pub fn listed_pixels(&self) -> Option<Result<ListedPixels, RenderError>> {
        self.renderer.listed_pixels()
    }

    /// See [`SceneRenderer::light_grid_in_words`].
    pub fn light_grid_in_words(&self) -> Option<String> {
        self.renderer.light_grid_in_words()
    }

    /// See [`SceneRenderer::triangles_in_view`].
    pub fn triangles_in_view(&self) -> (u64, u64) {
        self.renderer.triangles_in_view()
    }

    /// See [`SceneRenderer::vertices_computed`].
    pub fn vertices_computed(&self) -> u64 {
        self.renderer.vertices_computed()
    }

    /// See [`SceneRenderer::objects_lit_at_vertices`].
    pub fn objects_lit_at_vertices(&self) -> usize {
        self.renderer.objects_lit_at_vertices()
    }

    /// See [`SceneRenderer::shadow_map_triangles`].
    pub fn shadow_map_triangles(&self) -> (u64, u64) {
        self.renderer.shadow_map_triangles()
    }
}

/// The visible surface point of every pixel (row-major; None where no geometry is seen),
/// rasterised on the GPU with one sample at each pixel centre from the meshes as they are
/// (the reference's rays and the f64 twin's meet them); `baked_indirect` light, if any,
/// is part of each point's emission (it is unshadowed).
pub fn capture_surfaces(
    gpu: &GpuContext,
    scene: &Scene,
    camera: &Camera,
    baked_indirect: Option<&BakedIndirect>,
    width: u32,
    height: u32,
) -> Result<Vec<Option<SurfacePoint>>, RenderError> {
    capture_surfaces_at(gpu, scene, camera, baked_indirect, [width, height], Detail::Whole)
}

/// [`capture_surfaces`] with the objects drawn at the levels of detail `detail` chooses
/// for `camera` and `size_px`: the surfaces a frame drawn from levels sees.
pub fn capture_surfaces_at(
    gpu: &GpuContext,
    scene: &Scene,
    camera: &Camera,
    baked_indirect: Option<&BakedIndirect>,
    [width, height]: [u32; 2],
    detail: Detail<'_>,
) -> Result<Vec<Option<SurfacePoint>>, RenderError> {
    check_size(gpu, width, height)?;
    let layouts = SceneLayouts::new(&gpu.device);
    let mut gpu_scene = GpuScene::upload(&gpu.device, &gpu.queue, &layouts, scene);
    gpu_scene.set_baked_indirect(&gpu.queue, baked_indirect);
    gpu_scene.write_frame(&gpu.queue, camera, [width, height], (0.0, [0.0; 3]), detail);
    // fs_surface reads no blocker, but its pipelines' layout has the shadow group.
    let shadows = shadow_layout(&gpu.device);
    let no_maps = ShadowMaps::new(&gpu.device);
    let no_blockers = GpuBlockers::upload(
        &gpu.device,
        &gpu.queue,
        &shadows,
        &[],
        None,
        &ShadowSettings::default(),
        no_maps.binding(),
    );
    let mut channels: Vec<Vec<[f32; 4]>> = Vec::with_capacity(5);
    for pipeline in surface_pipelines(&gpu.device, &layouts, &shadows, scene.every_material_single_sided()) {
        let texture = gpu.device.create_texture(&wgpu::TextureDescriptor {
            label: Some("surface channel"),
            size: wgpu::Extent3d {
                width,
                height,
                depth_or_array_layers: 1,
            },
            mip_level_count: 1,
            sample_count: 1,
            dimension: wgpu::TextureDimension::D2,
            format: SURFACE_FORMAT,
            usage: wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::COPY_SRC,
            view_formats: &[],
        });
        let view = texture.create_view(&Default::default());
        let depth = RenderTarget::with_samples(&gpu.device, width, height, 1);
        let mut encoder = gpu.device.create_command_encoder(&Default::default());
        {
            let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
                label: Some("surface channel"),
                color_attachments: &[Some(wgpu::RenderPassColorAttachment {
                    view: &view,
                    depth_slice: None,
                    resolve_target: None,
                    ops: wgpu::Operations {
                        load: wgpu::LoadOp::Clear(wgpu::Color::TRANSPARENT),
                        store: wgpu::StoreOp::Store,
                    },
                })],
                depth_stencil_attachment: Some(depth.depth_attachment()),
                timestamp_writes: None,
                occlusion_query_set: None,
                multiview_mask: None,
            });
            pass.set_pipeline(&pipeline);
            pass.set_bind_group(slots::FRAME_GROUP, &gpu_scene.frame_bind_group, &[]);
            pass.set_bind_group(slots::SHADOW_GROUP, &no_blockers.bind_group, &[]);
            draw_objects(&mut pass, &gpu_scene);
        }
        let bytes = read_texture(&gpu.device, &gpu.queue, encoder, &texture, 16, width, height)?;
        channels.push(bytemuck::pod_collect_to_vec(&bytes));
    }
    let d = |v: [f32; 4]| DVec3::new(v[0] as f64, v[1] as f64, v[2] as f64);
    Ok((0..(width * height) as usize)
        .map(|i| {
            (channels[0][i][3] > 0.5).then(|| SurfacePoint {
                position: d(channels[0][i]),
                normal: d(channels[1][i]),
                phong_exponent: channels[1][i][3] as f64,
                k_d: d(channels[2][i]),
                k_s: d(channels[3][i]),
                emissive: d(channels[4][i]),
            })
        })
        .collect())
}

/// The CPU reference image: the GPU rasterises the surface points ([`capture_surfaces`]),
/// the CPU shades each in f64 ([`cpu::shadowed_radiance`]); background pixels are exact.
pub fn render_cpu_image(gpu: &GpuContext, frame: &ShadowFrame) -> Result<image::RgbaImage, RenderError> {
    check_size(gpu, frame.width, frame.height)?;
    let surfaces = capture_surfaces(
        gpu,
        frame.scene,
        frame.camera,
        frame.baked_indirect,
        frame.width,
        frame.height,
    )?;
    shade_surfaces(&surfaces, frame)
}

/// Shades captured surface points (row-major, `frame.width` × `frame.height`) in f64 on
/// all cores: the CPU reference's share of a frame.
pub fn shade_surfaces(surfaces: &[Option<SurfacePoint>], frame: &ShadowFrame) -> Result<image::RgbaImage, RenderError> {
    let lights = frame.shading_lights();
    let environment = environment_irradiance(frame.scene.environment.as_ref());
    let terrain = frame
        .scene
        .terrain
        .as_ref()
        .map(|t| crate::shading::terrain::terrain_shadow(&t.field, frame.shadows));
    // The scene's triangles, for the lights the GPU shadows by shadow maps: the CPU casts
    // the exact rays the maps approximate.
    let occluders = lights
        .iter()
        .any(|l| l.shadow_path == crate::shading::gpu_types::SHADOW_PATH_MAP)
        .then(|| crate::bake::scene_bvh::SceneBvh::build(frame.scene));
    let inputs = ShadingInputs {
        lights: &lights,
        environment_irradiance: &environment,
        blockers: frame.blockers,
        terrain: terrain.as_ref(),
        settings: frame.shadows,
        eye: frame.camera.position.as_dvec3(),
        pixel_angle_rad: crate::shading::gpu_types::pixel_angle_rad(frame.camera, frame.height),
        occluders: occluders.as_ref(),
    };
    let exposure = frame.settings.exposure_ev as f64;
    let background = frame.settings.background_srgb8;
    let pixels: Vec<u8> = surfaces
        .par_iter()
        .flat_map_iter(|surface| {
            let rgb = match surface {
                Some(s) => crate::shading::display_srgb8(cpu::shadowed_radiance(s, &inputs), exposure),
                None => background,
            };
            [rgb[0], rgb[1], rgb[2], 255]
        })
        .collect();
    image::RgbaImage::from_raw(frame.width, frame.height, pixels)
        .ok_or_else(|| RenderError::Readback("image size mismatch".into()))
}

/// `image` (sRGB-encoded, as rendered) through the edge filter of
/// [`AntiAliasing::EdgeFilter`] frames.
pub fn filter_edges(gpu: &GpuContext, image: &image::RgbaImage) -> Result<image::RgbaImage, RenderError> {
    check_size(gpu, image.width(), image.height())?;
    let target = RenderTarget::with_anti_aliasing(&gpu.device, image.width(), image.height(), AntiAliasing::EdgeFilter);
    target.write_unfiltered(&gpu.queue, image.as_raw());
    let mut encoder = gpu.device.create_command_encoder(&Default::default());
    target.clear_depth(&mut encoder);
    target.finish(&mut encoder);
    read_color(gpu, encoder, &target)
}

fn read_color(
    gpu: &GpuContext,
    encoder: wgpu::CommandEncoder,
    target: &RenderTarget,
) -> Result<image::RgbaImage, RenderError> {
    read_target_image(&gpu.device, &gpu.queue, encoder, target)
}
