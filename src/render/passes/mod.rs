//! The passes that draw a frame: the raster preview without shadows (`raster`), the
//! log-SH shading with its reduced-resolution (`reduced_shading`) and per-vertex
//! (`per_vertex`) forms (`logsh`) and its deferred full-resolution frame in compute
//! passes (`full_resolution`; the low-resolution samples the soft layer leaves likewise,
//! `listed_samples`), and the importance heat map (`heat_map`).

mod full_resolution;
pub mod heat_map;
mod kept_harmonic;
mod listed_samples;
pub mod logsh;
mod low_resolution;
pub mod per_vertex;
pub mod raster;
pub mod reduced_shading;
mod scene_pipeline;

pub use full_resolution::ListedPixels;
mod surface_buffer;
