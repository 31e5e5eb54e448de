use std::path::PathBuf;

use crate::scene::SceneError;

/// One problem found in a project file: where (a field path such as `lights[2].intensity`)
/// and what.
#[derive(Debug, Clone, PartialEq)]
pub struct Problem {
    pub field: String,
    pub message: String,
}

impl std::fmt::Display for Problem {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{}: {}", self.field, self.message)
    }
}

/// Why a project could not be opened or saved. Every variant names the file.
#[derive(Debug, thiserror::Error)]
pub enum ProjectError {
    #[error("{path}: file not found")]
    NotFound { path: PathBuf },
    #[error("{path}: cannot read file: {source}")]
    Read {
        path: PathBuf,
        #[source]
        source: std::io::Error,
    },
    #[error("{path}: cannot save: {source}")]
    Write {
        path: PathBuf,
        #[source]
        source: std::io::Error,
    },
    #[error("{path}: not a valid project file (line {line}, column {column}): {message}")]
    Syntax {
        path: PathBuf,
        line: usize,
        column: usize,
        message: String,
    },
    #[error("{path}: {field}{}: {message}", location(*.line, *.column))]
    Field {
        path: PathBuf,
        field: String,
        line: Option<usize>,
        column: Option<usize>,
        message: String,
    },
    #[error("{path}: made by a newer lightpaint (project format {found}; this build reads up to {supported})")]
    NewerVersion { path: PathBuf, found: u64, supported: u64 },
    #[error("{path}: {} problem(s): {}", .problems.len(), join(.problems))]
    Invalid { path: PathBuf, problems: Vec<Problem> },
    #[error("{path}: the scene it references, {scene}, is missing")]
    MissingScene { path: PathBuf, scene: PathBuf },
    #[error("{project}: in the scene it references: {error}")]
    Scene {
        project: PathBuf,
        #[source]
        error: SceneError,
    },
    #[error("{project}: an asset it references cannot be used: {error}")]
    Asset {
        project: PathBuf,
        #[source]
        error: SceneError,
    },
    #[error(transparent)]
    SceneOnly(#[from] SceneError),
}

fn location(line: Option<usize>, column: Option<usize>) -> String {
    match (line, column) {
        (Some(line), Some(column)) => format!(" (line {line}, column {column})"),
        _ => String::new(),
    }
}

fn join(problems: &[Problem]) -> String {
    problems.iter().map(Problem::to_string).collect::<Vec<_>>().join("; ")
}
