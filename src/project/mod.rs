//! Projects: the versioned file that reopens a lighting session exactly as it was left,
//! saved atomically (docs/file-format.md).

mod atomic;
pub mod bake_cache;
mod document;
mod error;
mod file;
mod migrate;
mod painting_state;
mod required;
pub mod sphere_cache;

pub use atomic::{backup_path, replace_atomically, write_atomically, write_atomically_with};
pub use document::{Document, is_project_path};
pub use error::{Problem, ProjectError};
pub use file::{
    EnvironmentReference, PROJECT_EXTENSION, ProjectFile, SceneReference, parse_project, read_project_file,
};
pub use migrate::FORMAT_VERSION;
pub use painting_state::PaintingState;
