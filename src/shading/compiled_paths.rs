//! Which shading code a frame's log-SH pipelines carry: the paths its lights take
//! (`super::light_paths`), its environment, terrain and blockers, as override constants.

use super::gpu_types::{
    GpuLight, SHADOW_PATH_EXACT, SHADOW_PATH_MAP, SHADOW_PATH_SH, UNIFORM_BLOCKER_CAPACITY, UNIFORM_LIGHT_CAPACITY,
};
use super::shadow_maps::CUBE_VIEW_COUNT;
use crate::scene::Scene;

/// Which shading code a log-SH pipeline compiles in (the override constants
/// EXACT_LIGHT_PATH, EXACT_WIDE, SHADOW_MAPS, SOFT_SHADOW_MAPS, SINGLE_VIEW_MAPS, SH_VISIBILITY,
/// ENVIRONMENT_LIGHT, TERRAIN_SHADOWS, RECT_LIGHTS, DISK_LIGHTS, LIGHT_OVERFLOW,
/// BLOCKER_OVERFLOW, LIGHT_WINDOWS, PER_POINT_WINDOWS and LIGHT_GRID): lavapipe runs the code of both sides of a branch
/// at every pixel whether taken or not, so code that the frame does not need is left out.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct CompiledPaths {
    /// Some light is on the exact path (EXACT_LIGHT_PATH).
    pub exact: bool,
    /// Some light is shadowed by its shadow map (SHADOW_MAPS).
    pub maps: bool,
    /// Some of those has a size: its maps' penumbra filter is compiled in
    /// (SOFT_SHADOW_MAPS).
    pub soft_maps: bool,
    /// Some of those has a single view (the sun, a spot, a light aimed at the scene), so
    /// the lookup reads the views' matrices (SINGLE_VIEW_MAPS); without it every such
    /// light has a cube of six, whose faces' projections the lookup works out from the
    /// light's position (shadow_lookup.wgsl's cube_face_tap): on lavapipe each read of a
    /// view's matrix is a gather per lane, and the large sample's 24 lamps spent about
    /// 10 ms of its passes on them (docs/performance.md).
    pub single_view_maps: bool,
    /// More than four lights are: the exact path takes them eight at a time rather than
    /// four (EXACT_WIDE).
    pub exact_wide: bool,
    /// The visibility SH are read: some light is on the SH path, or an environment lights
    /// the scene (SH_VISIBILITY).
    pub harmonics: bool,
    /// An environment lights the scene (ENVIRONMENT_LIGHT): its light through the
    /// visibility, a product of SH at every point shaded, is compiled in (without it the
    /// blocker bench's per-vertex pass took about 15 % less).
    pub environment: bool,
    /// The scene has a terrain (TERRAIN_SHADOWS).
    pub terrain: bool,
    /// Some light is a rect (RECT_LIGHTS), or a disk (DISK_LIGHTS): the exact vector
    /// irradiance of that polygon is compiled in, its edges written out (on lavapipe a
    /// loop over the polygon's edges cost the studio, which has neither, 5–7 ms a frame
    /// when it was always there, and the blocker bench's rect shaded per vertex 10–20 ms
    /// more than the rect's four edges alone, which also leave the disk's eight out).
    pub rect_lights: bool,
    pub disk_lights: bool,
    /// More lights than the shaders' uniform array holds: the rest are read from a storage
    /// buffer (LIGHT_OVERFLOW; [`UNIFORM_LIGHT_CAPACITY`]).
    pub light_overflow: bool,
    /// Likewise for the blockers (BLOCKER_OVERFLOW; [`UNIFORM_BLOCKER_CAPACITY`]).
    pub blocker_overflow: bool,
    /// How many windows of SH-path lights on the blockers the code holds (LIGHT_WINDOWS;
    /// `shading::light_windows`): the SH lights' count, at most 8 (4 under an
    /// environment; past that each point opens those that reach it) (the shaders decide
    /// per point which apply; lavapipe pays for every window compiled in).
    pub light_windows: u32,
    /// Past eight SH lights (four under an environment; windows compiled in), each point
    /// opens the windows of the lights that reach it or none, so the walk with windows
    /// and the one without are both compiled in and each point takes one
    /// (PER_POINT_WINDOWS): where more reach a point it does not pay the windows' tests
    /// at every blocker (the blocker bench with 256 lamps: 343 ms a frame with the
    /// windows' walk alone, against 280 without windows).
    pub per_point_windows: bool,
    /// A point walks the lights of its box of the lights' grid on the SH and shadow-map
    /// paths rather than all of them (LIGHT_GRID; `super::light_grid`): frames with at
    /// least `LIGHT_GRID_MIN_LIGHTS` of those lights with a range.
    pub light_grid: bool,
    /// Back faces are culled: every material of the scene is single-sided. Not code but
    /// the rasteriser's setting, fixed at pipeline creation all the same; lavapipe spent
    /// a tenth of the studio's default frame on the back faces it rasterised only for
    /// the depth test to reject them.
    pub cull_back_faces: bool,
}

impl CompiledPaths {
    /// Every path (a pipeline any frame can be drawn with).
    pub const ALL: CompiledPaths = CompiledPaths {
        exact: true,
        maps: true,
        soft_maps: true,
        single_view_maps: true,
        exact_wide: true,
        harmonics: true,
        environment: true,
        terrain: true,
        rect_lights: true,
        disk_lights: true,
        light_overflow: true,
        blocker_overflow: true,
        light_windows: super::light_windows::MAX_WINDOW_LIGHTS as u32,
        per_point_windows: true,
        light_grid: true,
        cull_back_faces: false,
    };

    /// These paths as a pass that keeps one visibility for every light compiles them (the
    /// per-vertex visibility): at most
    /// [`MAX_SHARED_WINDOW_LIGHTS`](super::light_windows::MAX_SHARED_WINDOW_LIGHTS)
    /// windows, and past that many SH lights each point decides whether they open.
    pub fn with_one_visibility(self) -> CompiledPaths {
        let most = super::light_windows::MAX_SHARED_WINDOW_LIGHTS as u32;
        CompiledPaths {
            light_windows: self.light_windows.min(most),
            per_point_windows: self.per_point_windows || self.light_windows > most,
            ..self
        }
    }

    /// Whether a pipeline of these paths shades `light` on the path it was given: a
    /// pipeline without that path, or compiled for cubes of maps alone
    /// (`single_view_maps` off: it reads no view's matrix) where the light has one
    /// view, does not.
    pub fn shades(&self, light: &GpuLight) -> bool {
        match light.shadow_path {
            SHADOW_PATH_EXACT => self.exact,
            SHADOW_PATH_MAP => self.maps && (self.single_view_maps || light.shadow_view_count == CUBE_VIEW_COUNT),
            _ => self.harmonics,
        }
    }

    /// No optional path (a pipeline that shades no light).
    pub const NONE: CompiledPaths = CompiledPaths {
        exact: false,
        maps: false,
        soft_maps: false,
        single_view_maps: false,
        exact_wide: false,
        harmonics: false,
        environment: false,
        terrain: false,
        rect_lights: false,
        disk_lights: false,
        light_overflow: false,
        blocker_overflow: false,
        light_windows: 0,
        per_point_windows: false,
        light_grid: false,
        cull_back_faces: false,
    };
}

/// What a frame lights a scene with, besides its lights.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct SceneLighting {
    pub has_environment: bool,
    pub has_terrain: bool,
    /// Every material is single-sided: back faces are culled
    /// ([`Scene::every_material_single_sided`]).
    pub single_sided: bool,
}

impl SceneLighting {
    pub fn of(scene: &Scene) -> SceneLighting {
        SceneLighting {
            has_environment: super::gpu_types::environment_lights(scene.environment.as_ref()),
            has_terrain: scene.terrain.is_some(),
            single_sided: scene.every_material_single_sided(),
        }
    }
}

/// Exact-path lights per half of the shaders' eight-light batch: one `vec4` lane each
/// (`ExactBatch` in exact_lights.wgsl). A frame with more needs the wide batch
/// (EXACT_WIDE).
const EXACT_LIGHTS_PER_HALF_BATCH: usize = 4;

/// The paths a frame needs for its lights as [`shading_lights`](super::shading_lights) put them on their paths,
/// and `blocker_count` blockers.
pub fn compiled_paths(shaded: &[GpuLight], lighting: SceneLighting, blocker_count: usize) -> CompiledPaths {
    let exact_count = shaded
        .iter()
        .filter(|light| light.shadow_path == SHADOW_PATH_EXACT)
        .count();
    CompiledPaths {
        exact: exact_count > 0,
        maps: shaded.iter().any(|light| light.shadow_path == SHADOW_PATH_MAP),
        soft_maps: shaded
            .iter()
            .any(|light| light.shadow_path == SHADOW_PATH_MAP && light.source_size > 0.0),
        single_view_maps: shaded
            .iter()
            .any(|light| light.shadow_path == SHADOW_PATH_MAP && light.shadow_view_count != CUBE_VIEW_COUNT),
        exact_wide: exact_count > EXACT_LIGHTS_PER_HALF_BATCH,
        harmonics: lighting.has_environment || shaded.iter().any(|light| light.shadow_path == SHADOW_PATH_SH),
        environment: lighting.has_environment,
        terrain: lighting.has_terrain,
        rect_lights: shaded
            .iter()
            .any(|light| light.kind == super::gpu_types::LIGHT_AREA && light.is_rect()),
        disk_lights: shaded
            .iter()
            .any(|light| light.kind == super::gpu_types::LIGHT_AREA && !light.is_rect()),
        light_overflow: shaded.len() > UNIFORM_LIGHT_CAPACITY,
        blocker_overflow: blocker_count > UNIFORM_BLOCKER_CAPACITY,
        light_windows: super::light_windows::compiled_windows(shaded, lighting.has_environment),
        per_point_windows: super::light_windows::windows_per_point(shaded, lighting.has_environment),
        light_grid: super::light_grid::grid_worth_it(shaded),
        cull_back_faces: lighting.single_sided,
    }
}
