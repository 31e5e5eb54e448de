//! Height-field terrain, pure f64 math (no GPU or UI): the heights and their prefiltered
//! pyramid (`height_field`), horizon marching (`horizon`), the slice occlusion vectors of
//! the normalised Legendre basis (`slice`), the wedge interpolation operator M_lin and
//! z-rotations (`wedge`), and the terrain's log-visibility at a receiver (`visibility`),
//! after Giraud & Nowrouzezahrai (EGSR 2015) and Nowrouzezahrai & Snyder (EGSR 2009).
//! `shaders/terrain.wgsl` is the f32 twin of `visibility`; terrain in the scene (sources,
//! placement, mesh) is `crate::scene::terrain`.

mod height_field;
mod horizon;
mod slice;
mod visibility;
mod wedge;

pub use height_field::{HeightField, HeightPyramid};
pub use horizon::{March, STEP_GROWTH, horizon_sin, horizon_sin_dense, slope_to_sin};
pub use slice::{slice_basis, slice_vector};
pub use visibility::{MAX_SURFACE_CACHE_SAMPLES, SURFACE_TOLERANCE, TerrainShadow, disc_share_above};
pub use wedge::{TERRAIN_TO_WORLD, WedgeOperator, azimuth_direction, terrain_to_world};
