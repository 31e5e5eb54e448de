//! The passes that draw a frame: the raster preview without shadows (`raster`), the
//! log-SH shading with its reduced-resolution (`reduced_shading`) and per-vertex
//! (`per_vertex`) forms (`logsh`) and the pixels the upsampling leaves shaded densely
//! (`listed_pixels`), and the importance heat map (`heat_map`).

pub mod heat_map;
mod listed_pixels;
pub mod logsh;
mod low_resolution;
pub mod per_vertex;
pub mod raster;
pub mod reduced_shading;
mod scene_pipeline;
mod surface_buffer;
