//! The shadow maps on the GPU: a `Depth32Float` array whose layers and quadrants hold the
//! views of the lights on the shadow-map path (`shading::shadow_maps` places the views,
//! `shading::shadow_atlas` their squares in the array), drawn from the scene's
//! triangles by a depth-only pass (shaders/shadow_map.wgsl), and what logsh.wgsl reads
//! them through: the layers as one array, a comparison sampler and the views' uniform
//! (bindings 7–9 of the shadow group). The maps are drawn only when asked
//! ([`ShadowMaps::draw`]): the scene holds still while the artist paints, so the
//! renderer redraws them when a light, an object's visibility or the map size changes —
//! of a moved light, only its own views, each cleared alone where it shares a layer with
//! views that are kept. Each view draws only the objects whose bounds
//! its frustum may see (`scene::Frustum`, as the camera's passes do): a cube face of a
//! point light among props sees about a quarter of them, and the maps are the same
//! (tests/view_culling.rs).

use wgpu::util::DeviceExt;

use super::layouts::vertex_layout;
use super::scene::GpuScene;
use crate::render::descriptors::{DEPTH_FORMAT, create_module, depth_attachment};
use crate::scene::Frustum;
use crate::shading::gpu_types::{GpuShadowView, MAX_SHADOW_VIEWS};
use crate::shading::shadow_maps::ShadowViews;
use crate::shading::wgsl::{self, slots};

/// Byte stride of one view in the draw pass's uniform (wgpu's dynamic offset alignment).
const DRAW_STRIDE: u64 = 256;

/// What the shading passes bind of the maps (cheap handles, cloned into each bind group).
#[derive(Clone)]
pub struct ShadowMapBinding {
    pub layers: wgpu::TextureView,
    pub sampler: wgpu::Sampler,
    pub views: wgpu::Buffer,
}

pub struct ShadowMaps {
    /// Texels per side and layers of the array as allocated.
    size: u32,
    layers: u32,
    texture: wgpu::Texture,
    binding: ShadowMapBinding,
    draw_views: wgpu::Buffer,
    /// Views the draw uniform holds.
    draw_capacity: usize,
    draw_group: wgpu::BindGroup,
    draw_layout: wgpu::BindGroupLayout,
    pipeline: wgpu::RenderPipeline,
    /// Writes the far depth over a viewport's square (one view's quadrant cleared while
    /// the rest of its layer is kept).
    clear_pipeline: wgpu::RenderPipeline,
    /// The views each layer holds, and the scene's surfaces generation they were drawn
    /// from: a later draw redraws only the layers whose view changed (a light that moved),
    /// or all of them when the scene did (objects hidden or shown).
    drawn: Vec<GpuShadowView>,
    drawn_from: Option<u64>,
    /// Views the last [`Self::draw`] redrew, and the triangles it drew into them.
    views_drawn: u64,
    triangles_drawn: u64,
}

impl ShadowMaps {
    /// One 1 × 1 layer until the first [`Self::draw`] (lights take no view before it).
    pub fn new(device: &wgpu::Device) -> ShadowMaps {
        let draw_layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("shadow map view"),
            entries: &[wgpu::BindGroupLayoutEntry {
                binding: slots::SHADOW_VIEW.binding,
                visibility: wgpu::ShaderStages::VERTEX,
                ty: wgpu::BindingType::Buffer {
                    ty: wgpu::BufferBindingType::Uniform,
                    has_dynamic_offset: true,
                    min_binding_size: wgpu::BufferSize::new(std::mem::size_of::<GpuShadowView>() as u64),
                },
                count: None,
            }],
        });
        let [pipeline, clear_pipeline] = depth_pipelines(device, &draw_layout);
        let views = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some("shadow views"),
            contents: bytemuck::cast_slice(&[<GpuShadowView as bytemuck::Zeroable>::zeroed(); MAX_SHADOW_VIEWS]),
            usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
        });
        let draw_views = draw_buffer(device, 1);
        let draw_group = draw_group(device, &draw_layout, &draw_views);
        let texture = layers_texture(device, 1, 1);
        let binding = ShadowMapBinding {
            layers: array_view(&texture),
            sampler: device.create_sampler(&wgpu::SamplerDescriptor {
                label: Some("shadow map"),
                mag_filter: wgpu::FilterMode::Linear,
                min_filter: wgpu::FilterMode::Linear,
                // Reversed depth (shading::shadow_maps): lit where the receiver is at least as
                // near as what the map holds.
                compare: Some(wgpu::CompareFunction::GreaterEqual),
                ..Default::default()
            }),
            views,
        };
        ShadowMaps {
            size: 1,
            layers: 1,
            texture,
            binding,
            draw_views,
            draw_capacity: 1,
            draw_group,
            draw_layout,
            pipeline,
            clear_pipeline,
            drawn: Vec::new(),
            drawn_from: None,
            views_drawn: 0,
            triangles_drawn: 0,
        }
    }

    /// The views the last [`Self::draw`] redrew and the triangles it drew into them.
    pub fn last_drawn(&self) -> (u64, u64) {
        (self.views_drawn, self.triangles_drawn)
    }

    /// The views the layers hold, as last drawn.
    pub fn drawn(&self) -> &[GpuShadowView] {
        &self.drawn
    }

    pub fn binding(&self) -> &ShadowMapBinding {
        &self.binding
    }

    /// Draws `views` of `scene` into the array their atlas describes, submitting the
    /// work — only the views that differ from the one drawn in their slot last, each
    /// square cleared alone when other views of its layer are kept (a moved point light's
    /// six faces share layers with other lights' faces), unless the layers or the scene's
    /// visible objects are new; true when the layers were
    /// allocated anew (the bind groups that read them must be made again from
    /// [`Self::binding`]).
    pub fn draw(&mut self, device: &wgpu::Device, queue: &wgpu::Queue, scene: &GpuScene, views: &ShadowViews) -> bool {
        let (atlas, views) = (&views.atlas, &views.views[..views.views.len().min(MAX_SHADOW_VIEWS)]);
        let size = atlas.layer_size.max(1);
        let layers = atlas.layers.max(1);
        let reallocated = size != self.size || layers > self.layers;
        if reallocated {
            self.texture = layers_texture(device, size, layers);
            self.binding.layers = array_view(&self.texture);
            self.size = size;
            self.layers = layers;
        }
        if reallocated || views.len() > self.draw_capacity {
            self.draw_capacity = views.len().max(1);
            self.draw_views = draw_buffer(device, self.draw_capacity as u64);
            self.draw_group = draw_group(device, &self.draw_layout, &self.draw_views);
        }
        let mut padded = vec![0u8; DRAW_STRIDE as usize * views.len().max(1)];
        for (k, view) in views.iter().enumerate() {
            let at = k * DRAW_STRIDE as usize;
            padded[at..at + std::mem::size_of::<GpuShadowView>()].copy_from_slice(bytemuck::bytes_of(view));
        }
        queue.write_buffer(&self.draw_views, 0, &padded);
        queue.write_buffer(&self.binding.views, 0, bytemuck::cast_slice(views));
        let everything = reallocated || self.drawn_from != Some(scene.surfaces_generation());
        // A view is drawn again when it differs from the one its slot held (a light moved,
        // or the atlas placed it elsewhere); the views beside it in its layer are kept.
        let stale: Vec<bool> = (0..views.len())
            .map(|k| everything || views.get(k) != self.drawn.get(k))
            .collect();
        let mut encoder = device.create_command_encoder(&Default::default());
        (self.views_drawn, self.triangles_drawn) = (0, 0);
        for layer in 0..self.layers {
            let in_layer: Vec<usize> = (0..views.len())
                .filter(|&k| placed(&views[k]) && views[k].atlas[3] as u32 == layer)
                .collect();
            let redrawn: Vec<usize> = in_layer.iter().copied().filter(|&k| stale[k]).collect();
            if redrawn.is_empty() {
                continue;
            }
            // Every view of the layer drawn: cleared whole; else each redrawn view's square
            // is cleared alone, by a triangle at the far depth.
            let whole = redrawn.len() == in_layer.len();
            let target = layer_view(&self.texture, layer);
            let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
                label: Some("shadow map"),
                color_attachments: &[],
                // Reversed depth: cleared to the far plane, 0.
                depth_stencil_attachment: Some(depth_attachment(&target, whole.then_some(0.0), true)),
                timestamp_writes: None,
                occlusion_query_set: None,
                multiview_mask: None,
            });
            for k in redrawn {
                let view = &views[k];
                let [u, v, side, _] = view.atlas;
                let (x, y, width) = (u * size as f32, v * size as f32, side * size as f32);
                pass.set_viewport(x, y, width, width, 0.0, 1.0);
                pass.set_scissor_rect(x as u32, y as u32, width as u32, width as u32);
                if !whole {
                    pass.set_pipeline(&self.clear_pipeline);
                    pass.draw(0..3, 0..1);
                }
                pass.set_pipeline(&self.pipeline);
                pass.set_bind_group(slots::IMAGE_GROUP, &self.draw_group, &[(k as u64 * DRAW_STRIDE) as u32]);
                self.views_drawn += 1;
                let frustum = Frustum::from_view_projection(glam::Mat4::from_cols_array_2d(&view.view_proj));
                let seen = |o: &&super::scene::GpuObject| !scene.view_culling() || frustum.may_see(&o.bounds);
                for object in scene.objects.iter().filter(|o| !o.hidden).filter(seen) {
                    self.triangles_drawn += object.index_count as u64 / 3;
                    pass.set_vertex_buffer(0, object.vertex_buffer.slice(..));
                    pass.set_index_buffer(object.index_buffer.slice(..), wgpu::IndexFormat::Uint32);
                    pass.draw_indexed(0..object.index_count, 0, 0..1);
                }
            }
        }
        queue.submit([encoder.finish()]);
        self.drawn = views.to_vec();
        self.drawn_from = Some(scene.surfaces_generation());
        reallocated
    }
}

/// Whether `view` has a square in the atlas (a slot no light uses has none).
fn placed(view: &GpuShadowView) -> bool {
    view.atlas[2] > 0.0
}

fn layers_texture(device: &wgpu::Device, size: u32, layers: u32) -> wgpu::Texture {
    device.create_texture(&wgpu::TextureDescriptor {
        label: Some("shadow maps"),
        size: wgpu::Extent3d {
            width: size,
            height: size,
            depth_or_array_layers: layers,
        },
        mip_level_count: 1,
        sample_count: 1,
        dimension: wgpu::TextureDimension::D2,
        format: DEPTH_FORMAT,
        usage: wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::TEXTURE_BINDING,
        view_formats: &[],
    })
}

fn array_view(texture: &wgpu::Texture) -> wgpu::TextureView {
    texture.create_view(&wgpu::TextureViewDescriptor {
        label: Some("shadow map layers"),
        dimension: Some(wgpu::TextureViewDimension::D2Array),
        ..Default::default()
    })
}

fn layer_view(texture: &wgpu::Texture, layer: u32) -> wgpu::TextureView {
    texture.create_view(&wgpu::TextureViewDescriptor {
        label: Some("shadow map layer"),
        dimension: Some(wgpu::TextureViewDimension::D2),
        base_array_layer: layer,
        array_layer_count: Some(1),
        ..Default::default()
    })
}

fn draw_buffer(device: &wgpu::Device, views: u64) -> wgpu::Buffer {
    device.create_buffer(&wgpu::BufferDescriptor {
        label: Some("shadow map draw views"),
        size: DRAW_STRIDE * views.max(1),
        usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
        mapped_at_creation: false,
    })
}

fn draw_group(device: &wgpu::Device, layout: &wgpu::BindGroupLayout, buffer: &wgpu::Buffer) -> wgpu::BindGroup {
    device.create_bind_group(&wgpu::BindGroupDescriptor {
        label: Some("shadow map view"),
        layout,
        entries: &[wgpu::BindGroupEntry {
            binding: slots::SHADOW_VIEW.binding,
            resource: wgpu::BindingResource::Buffer(wgpu::BufferBinding {
                buffer,
                offset: 0,
                size: wgpu::BufferSize::new(std::mem::size_of::<GpuShadowView>() as u64),
            }),
        }],
    })
}

/// The depth-only pipeline drawing a view — both faces (open and single-sided meshes cast
/// shadows too) — and the one clearing a view's square to the far depth (reversed: 0),
/// whatever it held.
fn depth_pipelines(device: &wgpu::Device, layout: &wgpu::BindGroupLayout) -> [wgpu::RenderPipeline; 2] {
    let module = create_module(device, "shadow map", &wgsl::shadow_map_source());
    let draw_layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
        label: Some("shadow map"),
        bind_group_layouts: &[Some(layout)],
        immediate_size: 0,
    });
    let clear_layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
        label: Some("shadow map clear"),
        bind_group_layouts: &[],
        immediate_size: 0,
    });
    let vertex_buffers = [Some(vertex_layout())];
    let pipeline = |label, layout, entry_point, buffers, depth_compare| {
        device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
            label: Some(label),
            layout: Some(layout),
            vertex: wgpu::VertexState {
                module: &module,
                entry_point: Some(entry_point),
                compilation_options: Default::default(),
                buffers,
            },
            primitive: wgpu::PrimitiveState {
                topology: wgpu::PrimitiveTopology::TriangleList,
                cull_mode: None,
                ..Default::default()
            },
            depth_stencil: Some(wgpu::DepthStencilState {
                format: DEPTH_FORMAT,
                depth_write_enabled: Some(true),
                depth_compare: Some(depth_compare),
                stencil: Default::default(),
                // No rasterised bias: a slope-scaled one pushed the side faces of thin bars,
                // seen edge-on from the light, beyond the floor, and their shadows came out
                // narrower than the ray casts'; receivers are offset along their normal and
                // toward the light when they read the map instead (logsh.wgsl).
                bias: wgpu::DepthBiasState::default(),
            }),
            multisample: Default::default(),
            fragment: None,
            multiview_mask: None,
            cache: None,
        })
    };
    [
        pipeline(
            "shadow map",
            &draw_layout,
            "vs_shadow_map",
            &vertex_buffers[..],
            wgpu::CompareFunction::Greater,
        ),
        pipeline(
            "shadow map clear",
            &clear_layout,
            "vs_clear_view",
            &[],
            wgpu::CompareFunction::Always,
        ),
    ]
}
