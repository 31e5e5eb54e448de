//! WGSL sources and the code generated for them (no wgpu here: `render` compiles them).
//! Each file under `shaders/` says which modules it imports (`// #import …` lines) and
//! [`compose()`] writes a shader from the modules it needs, each once, after its imports:
//! `common.wgsl` (shared structs and colour functions), `scene.wgsl` (the frame and
//! material bindings, vertex stage, lights, surfaces), `shadow_bindings.wgsl` (the shadow
//! group), `blockers.wgsl` (the blocker walk) and so on, so shared code lives in exactly
//! one place. The log-SH shader also takes modules generated for its settings: `sh` (the
//! SH code of its order and exponentiation method, [`sh`]), `lobes` (its BRDF variant,
//! [`lobes`]) and `terrain_sh` ([`terrain`]).

pub mod compose;
pub mod lobes;
pub mod sh;
pub mod slots;
pub mod terrain;

pub use compose::{ComposeError, WgslModule, compose};

use super::BrdfShading;
use crate::sh::ExpMethod;

pub const COMMON: &str = include_str!("../../../shaders/common.wgsl");
pub const SCENE: &str = include_str!("../../../shaders/scene.wgsl");
pub const RASTER: &str = include_str!("../../../shaders/raster.wgsl");
pub const SHADOW_BINDINGS: &str = include_str!("../../../shaders/shadow_bindings.wgsl");
pub const BLOCKERS: &str = include_str!("../../../shaders/blockers.wgsl");
pub const LOGSH: &str = include_str!("../../../shaders/logsh.wgsl");
pub const LIGHT_WINDOWS: &str = include_str!("../../../shaders/light_windows.wgsl");
pub const EXACT_LIGHTS: &str = include_str!("../../../shaders/exact_lights.wgsl");
pub const TERRAIN: &str = include_str!("../../../shaders/terrain.wgsl");
pub const REDUCED_SHADING: &str = include_str!("../../../shaders/reduced_shading.wgsl");
pub const LOW_RESOLUTION: &str = include_str!("../../../shaders/low_resolution.wgsl");
pub const FULL_RESOLUTION: &str = include_str!("../../../shaders/full_resolution.wgsl");
pub const LISTED_SAMPLES: &str = include_str!("../../../shaders/listed_samples.wgsl");
pub const LOGSH_PER_VERTEX: &str = include_str!("../../../shaders/logsh_per_vertex.wgsl");
pub const HEAT_MAP: &str = include_str!("../../../shaders/heat_map.wgsl");
pub const SHADOW_MAP: &str = include_str!("../../../shaders/shadow_map.wgsl");
pub const SHADOW_LOOKUP: &str = include_str!("../../../shaders/shadow_lookup.wgsl");
/// Reads a finished frame, not the scene.
pub const EDGE_FILTER: &str = include_str!("../../../shaders/edge_filter.wgsl");
/// The editor's viewport image drawn into egui's frame.
pub const VIEWPORT_IMAGE: &str = include_str!("../../../shaders/viewport_image.wgsl");
/// The full-screen triangle's corners, for every full-screen pass.
pub const FULL_SCREEN: &str = include_str!("../../../shaders/full_screen.wgsl");

/// Every file under `shaders/`, by the name modules import it by (its file stem).
pub const FILES: [WgslModule<'static>; 20] = [
    WgslModule {
        name: "common",
        source: COMMON,
    },
    WgslModule {
        name: "scene",
        source: SCENE,
    },
    WgslModule {
        name: "raster",
        source: RASTER,
    },
    WgslModule {
        name: "shadow_bindings",
        source: SHADOW_BINDINGS,
    },
    WgslModule {
        name: "blockers",
        source: BLOCKERS,
    },
    WgslModule {
        name: "logsh",
        source: LOGSH,
    },
    WgslModule {
        name: "light_windows",
        source: LIGHT_WINDOWS,
    },
    WgslModule {
        name: "exact_lights",
        source: EXACT_LIGHTS,
    },
    WgslModule {
        name: "terrain",
        source: TERRAIN,
    },
    WgslModule {
        name: "reduced_shading",
        source: REDUCED_SHADING,
    },
    WgslModule {
        name: "low_resolution",
        source: LOW_RESOLUTION,
    },
    WgslModule {
        name: "full_resolution",
        source: FULL_RESOLUTION,
    },
    WgslModule {
        name: "listed_samples",
        source: LISTED_SAMPLES,
    },
    WgslModule {
        name: "logsh_per_vertex",
        source: LOGSH_PER_VERTEX,
    },
    WgslModule {
        name: "heat_map",
        source: HEAT_MAP,
    },
    WgslModule {
        name: "shadow_map",
        source: SHADOW_MAP,
    },
    WgslModule {
        name: "shadow_lookup",
        source: SHADOW_LOOKUP,
    },
    WgslModule {
        name: "edge_filter",
        source: EDGE_FILTER,
    },
    WgslModule {
        name: "viewport_image",
        source: VIEWPORT_IMAGE,
    },
    WgslModule {
        name: "full_screen",
        source: FULL_SCREEN,
    },
];

/// The constants of [`slots`], generated once.
static SLOTS: std::sync::LazyLock<String> = std::sync::LazyLock::new(slots::wgsl_module);

/// Every module to compose from but those generated for a log-SH shader's settings: the
/// files under `shaders/` and `slots`.
pub fn modules() -> Vec<WgslModule<'static>> {
    let mut modules = FILES.to_vec();
    modules.push(WgslModule {
        name: "slots",
        source: SLOTS.as_str(),
    });
    modules
}

/// The modules generated for a log-SH shader's settings, with what each imports.
pub struct GeneratedModules {
    sh: String,
    lobes: String,
    terrain_sh: String,
}

impl GeneratedModules {
    /// The code generated for `order` and `method` (not `Reference`, which has no GPU
    /// form) and the `brdf` variant.
    pub fn new(order: usize, method: ExpMethod, brdf: BrdfShading) -> GeneratedModules {
        GeneratedModules {
            sh: "// #import common scene\n".to_string() + &sh::sh_module(order, method),
            lobes: "// #import sh scene\n".to_string() + &lobes::lobes_module(order, method, brdf),
            terrain_sh: "// #import sh shadow_bindings\n".to_string() + &terrain::terrain_module(order),
        }
    }

    /// Every module: [`modules`] and these.
    pub fn with_files(&self) -> Vec<WgslModule<'_>> {
        let mut modules = modules();
        modules.push(WgslModule {
            name: "sh",
            source: &self.sh,
        });
        modules.push(WgslModule {
            name: "lobes",
            source: &self.lobes,
        });
        modules.push(WgslModule {
            name: "terrain_sh",
            source: &self.terrain_sh,
        });
        modules
    }
}

/// `root` and what it imports from the files under `shaders/`. Those files are part of
/// the program, so a failure is a bug the tests catch (tests/wgsl_validate.rs).
fn compose_files(root: &str) -> String {
    compose(&[root], &modules()).unwrap_or_else(|err| panic!("{err}"))
}

/// The unshadowed raster module.
pub fn raster_source() -> String {
    compose_files("raster")
}

/// The edge filter's module.
pub fn edge_filter_source() -> String {
    compose_files("edge_filter")
}

/// The viewport image's module.
pub fn viewport_image_source() -> String {
    compose_files("viewport_image")
}

/// The shadow-map depth pass's module.
pub fn shadow_map_source() -> String {
    compose_files("shadow_map")
}

/// The importance heat map module.
pub fn heat_map_source() -> String {
    compose_files("heat_map")
}

/// The log-SH shadow module at `order` with `method` (not `Reference`, which has no GPU
/// form) and the `brdf` variant, with the reduced-resolution entry points and the
/// per-vertex ones where the order allows them.
pub fn logsh_source(order: usize, method: ExpMethod, brdf: BrdfShading) -> String {
    let generated = GeneratedModules::new(order, method, brdf);
    let roots: &[&str] = if sh::supports_per_vertex(order) {
        &[
            "logsh",
            "low_resolution",
            "full_resolution",
            "listed_samples",
            "logsh_per_vertex",
        ]
    } else {
        &["logsh", "low_resolution", "full_resolution", "listed_samples"]
    };
    compose(roots, &generated.with_files()).unwrap_or_else(|err| panic!("{err}"))
}
