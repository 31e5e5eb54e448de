// The shadow group (bind group 2) of the log-SH pipelines: the shadow settings, the sphere
// blockers and their groups, the terrain, and the shadow maps. Its Rust twin is the
// layout in src/render/resources/blockers.rs.
// #import common slots

@group(SHADOW_GROUP) @binding(SHADOW_BINDING) var<uniform> shadow: ShadowParams;
// The blockers and their groups, read through blocker_at and group_at: the first
// UNIFORM_BLOCKER_CAPACITY from uniform arrays, the rest (when there are more) from
// every_blocker and every_group (see `lights` in scene.wgsl for why).
@group(SHADOW_GROUP) @binding(BLOCKERS_BINDING) var<uniform> blockers: array<Blocker, UNIFORM_BLOCKER_CAPACITY>;
@group(SHADOW_GROUP) @binding(GROUPS_BINDING) var<uniform> groups: array<PackedBlockerGroup, UNIFORM_BLOCKER_CAPACITY>;
@group(SHADOW_GROUP) @binding(TERRAIN_BINDING) var<uniform> terrain: TerrainParams;
// Every pyramid level's heights (world y, metres), row-major, level after level, then the
// surface cache (terrain.surface_first on): the marched sum at every finest sample.
@group(SHADOW_GROUP) @binding(TERRAIN_HEIGHTS_BINDING) var<storage, read> terrain_heights: array<f32>;
@group(SHADOW_GROUP) @binding(EVERY_BLOCKER_BINDING) var<storage, read> every_blocker: array<Blocker>;
@group(SHADOW_GROUP) @binding(EVERY_GROUP_BINDING) var<storage, read> every_group: array<PackedBlockerGroup>;

// The shadow maps of the lights on the shadow-map path: each view a depth layer or a quadrant of one (shading::shadow_atlas; depth
// reversed: 1 nearest the light), read with a comparison sampler (linear: each read filters the 2 × 2 texels around) or, for
// the blocker search, texel by texel; and the views' matrices.
@group(SHADOW_GROUP) @binding(SHADOW_MAPS_BINDING) var shadow_maps: texture_depth_2d_array;
@group(SHADOW_GROUP) @binding(SHADOW_MAP_SAMPLER_BINDING) var shadow_map_sampler: sampler_comparison;
@group(SHADOW_GROUP) @binding(SHADOW_VIEWS_BINDING) var<uniform> shadow_views: array<ShadowView, MAX_SHADOW_VIEWS>;
