use std::path::PathBuf;

/// Why a scene could not be loaded. Every variant names the file; the message says the
/// cause in words an artist can act on.
#[derive(Debug, thiserror::Error)]
pub enum SceneError {
    #[error("{path}: file not found")]
    NotFound { path: PathBuf },
    #[error("{path}: cannot read file: {source}")]
    Io {
        path: PathBuf,
        #[source]
        source: std::io::Error,
    },
    #[error("{path}: unsupported file type (expected .gltf or .glb)")]
    UnsupportedExtension { path: PathBuf },
    #[error("{path}: not a valid glTF file: {reason}")]
    Malformed { path: PathBuf, reason: String },
    #[error("{path}: {what}")]
    Invalid { path: PathBuf, what: String },
}

impl SceneError {
    pub(crate) fn invalid(path: &std::path::Path, what: impl Into<String>) -> SceneError {
        SceneError::Invalid {
            path: path.to_path_buf(),
            what: what.into(),
        }
    }
}
