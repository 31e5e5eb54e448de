//! Blockers, their culling groups, the shadow parameters, the terrain and the shadow maps'
//! bindings on the GPU: bind group 2 of logsh.wgsl and terrain.wgsl, shared by the shading
//! pass and the per-vertex compute pass.

use bytemuck::Zeroable;
use wgpu::util::DeviceExt;

use super::shadow_maps::ShadowMapBinding;
use super::terrain::GpuTerrain;
use crate::blockers::Sphere;
use crate::render::descriptors::{buffer_type, layout_entry, slot_entries};
use crate::shading::ShadowSettings;
use crate::shading::blocker_groups::group_blockers;
use crate::shading::gpu_types::{GpuBlocker, GpuBlockerGroup, GpuShadowParams, UNIFORM_BLOCKER_CAPACITY};
use crate::shading::wgsl::slots;
use crate::terrain::HeightField;

/// Blockers, their culling groups and the shadow parameters on the GPU (bind group 2 of
/// logsh.wgsl). Groups depend on the influence cut-off and clusters on the order too, so
/// they are rebuilt with either.
pub struct GpuBlockers {
    params: wgpu::Buffer,
    bind_group_layout: wgpu::BindGroupLayout,
    spheres: Vec<Sphere>,
    /// The discs among `spheres` (at most `MAX_DISCS`), written with the parameters.
    discs: Vec<GpuBlocker>,
    /// The spheres the groups walk.
    walked_count: usize,
    /// The clusters, then the groups.
    groups: Vec<GpuBlockerGroup>,
    cluster_count: usize,
    /// The influence cut-off and the order the groups and clusters were built for.
    grouped_for: (f32, usize),
    terrain_field: Option<HeightField>,
    terrain: GpuTerrain,
    /// The uniform and storage copies of the ordered blockers and of the groups.
    buffers: [wgpu::Buffer; 4],
    maps: ShadowMapBinding,
    pub bind_group: wgpu::BindGroup,
}

impl GpuBlockers {
    pub fn upload(
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        layout: &wgpu::BindGroupLayout,
        spheres: &[Sphere],
        terrain: Option<&HeightField>,
        settings: &ShadowSettings,
        maps: &ShadowMapBinding,
    ) -> GpuBlockers {
        let params = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("shadow params"),
            size: std::mem::size_of::<GpuShadowParams>() as u64,
            usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        // Discs are shaded in their own loop (from the parameters), spheres in the walk.
        let (balls, discs) = crate::blockers::spheres_and_discs(spheres);
        let (ordered, groups, cluster_count) = gpu_groups(&balls, settings);
        let gpu_terrain = GpuTerrain::upload(device, terrain, settings);
        let [blockers_uniform, blockers_storage] = uniform_and_storage(device, "blockers", &ordered);
        let [groups_uniform, groups_storage] = uniform_and_storage(device, "blocker groups", &groups);
        let buffers = [blockers_uniform, blockers_storage, groups_uniform, groups_storage];
        let bind_group = shadow_bind_group(device, layout, &params, &buffers, &gpu_terrain, maps);
        let blockers = GpuBlockers {
            params,
            bind_group_layout: layout.clone(),
            spheres: spheres.to_vec(),
            discs: discs.iter().map(GpuBlocker::new).collect(),
            walked_count: ordered.len(),
            groups,
            cluster_count,
            grouped_for: (settings.min_cap_ratio, settings.order),
            terrain_field: terrain.cloned(),
            terrain: gpu_terrain,
            buffers,
            maps: maps.clone(),
            bind_group,
        };
        blockers.write_params(queue, settings);
        blockers
    }

    /// Replaces the blockers (keeping the terrain) and writes the parameters.
    pub fn update(
        &mut self,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        spheres: &[Sphere],
        settings: &ShadowSettings,
    ) {
        let terrain = self.terrain_field.take();
        *self = GpuBlockers::upload(
            device,
            queue,
            &self.bind_group_layout,
            spheres,
            terrain.as_ref(),
            settings,
            &self.maps.clone(),
        );
    }

    /// Binds new shadow-map layers (after [`super::ShadowMaps::draw`] allocated them).
    pub fn set_shadow_maps(&mut self, device: &wgpu::Device, maps: &ShadowMapBinding) {
        self.maps = maps.clone();
        self.bind_group = shadow_bind_group(
            device,
            &self.bind_group_layout,
            &self.params,
            &self.buffers,
            &self.terrain,
            &self.maps,
        );
    }

    /// Applies new settings; a new influence cut-off or order regroups the blockers, and a
    /// new order or terrain sampling rebuilds the terrain's model.
    pub fn apply_settings(&mut self, device: &wgpu::Device, queue: &wgpu::Queue, settings: &ShadowSettings) {
        let terrain_stale = self.terrain_field.is_some() && self.terrain.is_stale_for(settings);
        if (settings.min_cap_ratio, settings.order) == self.grouped_for && !terrain_stale {
            self.write_params(queue, settings);
        } else {
            let spheres = std::mem::take(&mut self.spheres);
            self.update(device, queue, &spheres, settings);
        }
    }

    fn write_params(&self, queue: &wgpu::Queue, settings: &ShadowSettings) {
        let mut discs = [GpuBlocker::zeroed(); crate::blockers::MAX_DISCS];
        discs[..self.discs.len()].copy_from_slice(&self.discs);
        let params = GpuShadowParams {
            ln_epsilon: settings.epsilon.ln(),
            min_cap_ratio: settings.min_cap_ratio,
            blocker_count: self.walked_count as u32,
            ratio_attenuation: settings.ratio_attenuation as u32,
            group_count: (self.groups.len() - self.cluster_count) as u32,
            disc_count: self.discs.len() as u32,
            cluster_count: self.cluster_count as u32,
            _pad: 0,
            cap_mass_scale: GpuShadowParams::cap_mass_scale_for(settings),
            discs,
        };
        queue.write_buffer(&self.params, 0, bytemuck::bytes_of(&params));
    }
}

/// The spheres in walk order, and the clusters followed by the groups (as the shader's
/// `groups` array holds them), with the number of clusters.
fn gpu_groups(spheres: &[Sphere], settings: &ShadowSettings) -> (Vec<GpuBlocker>, Vec<GpuBlockerGroup>, usize) {
    let grouped = group_blockers(spheres, settings.min_cap_ratio, settings.order);
    let cluster_count = grouped.clusters.len();
    let clusters = grouped
        .clusters
        .iter()
        .map(|c| GpuBlockerGroup::cluster(c, cluster_count + c.first_group));
    (
        grouped.spheres.iter().map(GpuBlocker::new).collect(),
        clusters
            .chain(grouped.groups.iter().map(GpuBlockerGroup::new))
            .collect(),
        cluster_count,
    )
}

fn shadow_bind_group(
    device: &wgpu::Device,
    layout: &wgpu::BindGroupLayout,
    params: &wgpu::Buffer,
    [blockers, every_blocker, groups, every_group]: &[wgpu::Buffer; 4],
    terrain: &GpuTerrain,
    maps: &ShadowMapBinding,
) -> wgpu::BindGroup {
    device.create_bind_group(&wgpu::BindGroupDescriptor {
        label: Some("shadow"),
        layout,
        entries: &slot_entries([
            (slots::SHADOW, params.as_entire_binding()),
            (slots::BLOCKERS, blockers.as_entire_binding()),
            (slots::GROUPS, groups.as_entire_binding()),
            (slots::TERRAIN, terrain.params.as_entire_binding()),
            (slots::TERRAIN_HEIGHTS, terrain.heights.as_entire_binding()),
            (slots::EVERY_BLOCKER, every_blocker.as_entire_binding()),
            (slots::EVERY_GROUP, every_group.as_entire_binding()),
            (slots::SHADOW_MAPS, wgpu::BindingResource::TextureView(&maps.layers)),
            (slots::SHADOW_MAP_SAMPLER, wgpu::BindingResource::Sampler(&maps.sampler)),
            (slots::SHADOW_VIEWS, maps.views.as_entire_binding()),
        ]),
    })
}

/// The buffers logsh.wgsl reads `items` through: the first [`UNIFORM_BLOCKER_CAPACITY`] in
/// a uniform buffer of that many (zero-filled), and all of them in a storage buffer (one
/// zeroed item when there are none: a binding may not be empty).
fn uniform_and_storage<T: bytemuck::Pod>(device: &wgpu::Device, label: &str, items: &[T]) -> [wgpu::Buffer; 2] {
    let mut first = vec![T::zeroed(); UNIFORM_BLOCKER_CAPACITY];
    let shown = items.len().min(UNIFORM_BLOCKER_CAPACITY);
    first[..shown].copy_from_slice(&items[..shown]);
    let every = if items.is_empty() { &first[..1] } else { items };
    let buffer = |contents: &[T], usage| {
        device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some(label),
            contents: bytemuck::cast_slice(contents),
            usage,
        })
    };
    [
        buffer(&first, wgpu::BufferUsages::UNIFORM),
        buffer(every, wgpu::BufferUsages::STORAGE),
    ]
}

/// The bind group layout of [`GpuBlockers`].
pub fn shadow_layout(device: &wgpu::Device) -> wgpu::BindGroupLayout {
    let visibility = wgpu::ShaderStages::FRAGMENT | wgpu::ShaderStages::COMPUTE;
    let entry = |slot, ty| layout_entry(slot, visibility, ty);
    let uniform = buffer_type(wgpu::BufferBindingType::Uniform);
    let storage = buffer_type(wgpu::BufferBindingType::Storage { read_only: true });
    device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
        label: Some("shadow"),
        entries: &[
            entry(slots::SHADOW, uniform),
            entry(slots::BLOCKERS, uniform),
            entry(slots::GROUPS, uniform),
            entry(slots::TERRAIN, uniform),
            entry(slots::TERRAIN_HEIGHTS, storage),
            entry(slots::EVERY_BLOCKER, storage),
            entry(slots::EVERY_GROUP, storage),
            entry(
                slots::SHADOW_MAPS,
                wgpu::BindingType::Texture {
                    sample_type: wgpu::TextureSampleType::Depth,
                    view_dimension: wgpu::TextureViewDimension::D2Array,
                    multisampled: false,
                },
            ),
            entry(
                slots::SHADOW_MAP_SAMPLER,
                wgpu::BindingType::Sampler(wgpu::SamplerBindingType::Comparison),
            ),
            entry(slots::SHADOW_VIEWS, uniform),
        ],
    })
}
