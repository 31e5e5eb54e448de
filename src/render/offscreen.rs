//! Headless rendering into images: the unshadowed raster, the log-SH renderer on the GPU,
//! and the f64 CPU reference shading the very surface points the GPU rasterised.

use glam::DVec3;
use rayon::prelude::*;

use super::cpu::{self, ShadingInputs, SurfacePoint};
use super::gpu_types::{GpuLight, environment_irradiance};
use super::logsh::{
    GpuBlockers, LogShPipeline, SURFACE_FORMAT, Shading, draw_objects, shadow_layout, surface_pipelines,
};
use super::per_vertex::VertexVisibility;
use super::pipeline::{COLOR_FORMAT, SAMPLE_COUNT, SceneLayouts, ScenePipeline};
use super::reduced_shading::LowResolutionTargets;
use super::target::{AntiAliasing, RenderTarget};
use super::{BakedIndirect, GpuContext, GpuScene, RenderError, RenderSettings, ShadowSettings};
use crate::blockers::Sphere;
use crate::scene::{Camera, Scene};

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
        let gpu_scene = GpuScene::upload(&gpu.device, &gpu.queue, &pipeline.layouts, scene);
        let target = RenderTarget::with_samples(&gpu.device, width, height, samples);
        gpu_scene.write_frame(&gpu.queue, camera, [width, height], settings.exposure_ev);
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
    /// The scene's lights as this frame shades them (`render::shading_lights`, weighing
    /// this frame's scene and blockers).
    pub fn shading_lights(&self) -> Vec<GpuLight> {
        let context = super::LightPathContext::of_scene(self.scene, self.blockers);
        super::shading_lights(&self.scene.lights, self.shadows, &context)
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

/// Everything a log-SH frame needs, uploaded once, so frames can be drawn repeatedly
/// (benchmarks, the study).
pub struct ShadowRenderer<'a> {
    gpu: &'a GpuContext,
    pipeline: LogShPipeline,
    gpu_scene: GpuScene,
    blockers: GpuBlockers,
    visibility: Option<VertexVisibility>,
    low_resolution: Option<LowResolutionTargets>,
    target: RenderTarget,
    background: [f64; 3],
}

impl<'a> ShadowRenderer<'a> {
    pub fn new(
        gpu: &'a GpuContext,
        frame: &ShadowFrame,
        anti_aliasing: AntiAliasing,
    ) -> Result<ShadowRenderer<'a>, RenderError> {
        frame.check(gpu)?;
        let samples = anti_aliasing.samples();
        let layouts = SceneLayouts::new(&gpu.device);
        let lights = frame.shading_lights();
        let paths = super::compiled_paths(&lights, super::SceneLighting::of(frame.scene), frame.blockers.len());
        let pipeline = LogShPipeline::new(&gpu.device, &layouts, frame.shadows, samples, paths);
        let mut gpu_scene = GpuScene::upload(&gpu.device, &gpu.queue, &layouts, frame.scene);
        gpu_scene.update_lights(&gpu.device, &gpu.queue, &layouts, &lights);
        gpu_scene.set_baked_indirect(&gpu.queue, frame.baked_indirect);
        let blockers = GpuBlockers::upload(
            &gpu.device,
            &gpu.queue,
            &pipeline.shadow_layout,
            frame.blockers,
            frame.scene.terrain.as_ref().map(|t| &t.field),
            frame.shadows,
        );
        let target = RenderTarget::with_anti_aliasing(&gpu.device, frame.width, frame.height, anti_aliasing);
        gpu_scene.write_frame(
            &gpu.queue,
            frame.camera,
            [frame.width, frame.height],
            frame.settings.exposure_ev,
        );
        let visibility = if frame.shadows.per_vertex {
            pipeline.vertex_visibility(&gpu.device, &gpu_scene)
        } else {
            None
        };
        let low_resolution = pipeline.low_resolution_targets(&gpu.device, [target.width, target.height], None);
        Ok(ShadowRenderer {
            gpu,
            pipeline,
            gpu_scene,
            blockers,
            visibility,
            low_resolution,
            target,
            background: frame.settings.background_linear(),
        })
    }

    fn encode_frame(&self) -> wgpu::CommandEncoder {
        let mut encoder = self.gpu.device.create_command_encoder(&Default::default());
        self.pipeline.draw(
            &mut encoder,
            &self.target,
            &self.gpu_scene,
            &self.blockers,
            self.background,
            Shading::first_of(self.visibility.as_ref(), self.low_resolution.as_ref()),
        );
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

/// The visible surface point of every pixel (row-major; None where no geometry is seen),
/// rasterised on the GPU with one sample at each pixel centre; `baked_indirect` light, if
/// any, is part of each point's emission (it is unshadowed).
pub fn capture_surfaces(
    gpu: &GpuContext,
    scene: &Scene,
    camera: &Camera,
    baked_indirect: Option<&BakedIndirect>,
    width: u32,
    height: u32,
) -> Result<Vec<Option<SurfacePoint>>, RenderError> {
    check_size(gpu, width, height)?;
    let layouts = SceneLayouts::new(&gpu.device);
    let gpu_scene = GpuScene::upload(&gpu.device, &gpu.queue, &layouts, scene);
    gpu_scene.set_baked_indirect(&gpu.queue, baked_indirect);
    gpu_scene.write_frame(&gpu.queue, camera, [width, height], 0.0);
    // fs_surface reads no blocker, but its pipelines' layout has the shadow group.
    let shadows = shadow_layout(&gpu.device);
    let no_blockers = GpuBlockers::upload(&gpu.device, &gpu.queue, &shadows, &[], None, &ShadowSettings::default());
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
            pass.set_bind_group(0, &gpu_scene.frame_bind_group, &[]);
            pass.set_bind_group(2, &no_blockers.bind_group, &[]);
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
        .map(|t| super::gpu_terrain::terrain_shadow(&t.field, frame.shadows));
    let inputs = ShadingInputs {
        lights: &lights,
        environment_irradiance: &environment,
        blockers: frame.blockers,
        terrain: terrain.as_ref(),
        settings: frame.shadows,
        eye: frame.camera.position.as_dvec3(),
        pixel_angle_rad: super::gpu_types::pixel_angle_rad(frame.camera, frame.height),
    };
    let exposure = frame.settings.exposure_ev as f64;
    let background = frame.settings.background_srgb8;
    let pixels: Vec<u8> = surfaces
        .par_iter()
        .flat_map_iter(|surface| {
            let rgb = match surface {
                Some(s) => super::display_srgb8(cpu::shadowed_radiance(s, &inputs), exposure),
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

/// Submits `encoder` and reads `target`'s displayed (resolved, sRGB) colour back as an
/// image — what the editor's viewport shows, for exporting it.
pub fn read_target_image(
    device: &wgpu::Device,
    queue: &wgpu::Queue,
    encoder: wgpu::CommandEncoder,
    target: &RenderTarget,
) -> Result<image::RgbaImage, RenderError> {
    debug_assert_eq!(COLOR_FORMAT.block_copy_size(None), Some(4));
    let pixels = read_texture(device, queue, encoder, &target.color, 4, target.width, target.height)?;
    image::RgbaImage::from_raw(target.width, target.height, pixels)
        .ok_or_else(|| RenderError::Readback("image size mismatch".into()))
}

/// Submits `encoder` plus a copy of `texture` to the CPU (rows padded to wgpu's 256-byte
/// alignment on the way, unpadded here) and returns its bytes.
fn read_texture(
    device: &wgpu::Device,
    queue: &wgpu::Queue,
    mut encoder: wgpu::CommandEncoder,
    texture: &wgpu::Texture,
    bytes_per_pixel: u32,
    width: u32,
    height: u32,
) -> Result<Vec<u8>, RenderError> {
    let row_bytes = bytes_per_pixel * width;
    let padded_row_bytes = row_bytes.div_ceil(wgpu::COPY_BYTES_PER_ROW_ALIGNMENT) * wgpu::COPY_BYTES_PER_ROW_ALIGNMENT;
    let buffer = device.create_buffer(&wgpu::BufferDescriptor {
        label: Some("readback"),
        size: (padded_row_bytes * height) as u64,
        usage: wgpu::BufferUsages::COPY_DST | wgpu::BufferUsages::MAP_READ,
        mapped_at_creation: false,
    });
    encoder.copy_texture_to_buffer(
        texture.as_image_copy(),
        wgpu::TexelCopyBufferInfo {
            buffer: &buffer,
            layout: wgpu::TexelCopyBufferLayout {
                offset: 0,
                bytes_per_row: Some(padded_row_bytes),
                rows_per_image: Some(height),
            },
        },
        wgpu::Extent3d {
            width,
            height,
            depth_or_array_layers: 1,
        },
    );
    queue.submit([encoder.finish()]);

    let (sender, receiver) = std::sync::mpsc::channel();
    buffer.map_async(wgpu::MapMode::Read, .., move |result| {
        let _ = sender.send(result);
    });
    device
        .poll(wgpu::PollType::wait_indefinitely())
        .map_err(|e| RenderError::Readback(e.to_string()))?;
    receiver
        .recv()
        .map_err(|e| RenderError::Readback(e.to_string()))?
        .map_err(|e| RenderError::Readback(e.to_string()))?;
    let mapped = buffer
        .get_mapped_range(..)
        .map_err(|e| RenderError::Readback(e.to_string()))?;
    let mut bytes = Vec::with_capacity((row_bytes * height) as usize);
    for row in mapped.chunks_exact(padded_row_bytes as usize) {
        bytes.extend_from_slice(&row[..row_bytes as usize]);
    }
    drop(mapped);
    buffer.unmap();
    Ok(bytes)
}
