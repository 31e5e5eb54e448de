//! The project file: JSON, documented in docs/file-format.md. Loading checks, in order:
//! UTF-8 and JSON syntax (with line and column), `format_version` (newer files are refused,
//! older ones migrated), the fields and their types (with the field path), then the values
//! (every problem collected, not just the first).

use std::path::{Path, PathBuf};

use serde::{Deserialize, Serialize};

use super::error::{Problem, ProjectError};
use super::migrate::FORMAT_VERSION;
use super::painting_state::PaintingState;
use crate::scene::{Light, OrbitCamera, TerrainSpec};
use crate::shading::RenderSettings;

/// Extension of project files.
pub const PROJECT_EXTENSION: &str = "lightpaint";

/// Everything a project file holds (format version 5).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ProjectFile {
    pub format_version: u64,
    pub scene: SceneReference,
    /// The complete light list (the glTF's lights as imported, then edited).
    pub lights: Vec<Light>,
    /// Absent: the defaults.
    #[serde(default)]
    pub render: RenderSettings,
    /// The editor's camera when the project was saved (absent: the scene's own camera,
    /// else a view of the whole scene).
    #[serde(default)]
    pub camera: Option<OrbitCamera>,
    /// Light from an equirectangular HDR image all around the scene.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub environment: Option<EnvironmentReference>,
    /// The strokes painted so far and the brush the next one uses (absent: none yet).
    #[serde(default)]
    pub painting: PaintingState,
    /// A height-field terrain under the scene (format 5); image paths relative to the
    /// project file's directory (or absolute).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub terrain: Option<TerrainSpec>,
    /// Objects hidden in the viewport (format 6), by index in the scene's object list
    /// (the glTF's flattened primitives, then the terrain): they are not drawn and the
    /// brush sees through them; they still cast shadows and take part in the bake.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub hidden_objects: Vec<usize>,
    /// Names given to objects in the editor (format 6), by object index as above; they
    /// replace the glTF's names.
    #[serde(default, skip_serializing_if = "std::collections::BTreeMap::is_empty")]
    pub object_names: std::collections::BTreeMap<usize, String>,
}

/// An environment light: an equirectangular HDR image, scaled and turned about +y.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct EnvironmentReference {
    /// Path of the .hdr, relative to the project file's directory (or absolute).
    pub hdr: PathBuf,
    /// Multiplier on the image's radiance (≥ 0; absent: 1).
    #[serde(default = "unit")]
    pub intensity: f32,
    /// Rotation about world +y, radians (absent: 0).
    #[serde(default)]
    pub rotation_rad: f32,
}

/// The glTF scene a project is built on.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SceneReference {
    /// Path of the .gltf/.glb, relative to the project file's directory (or absolute).
    pub gltf: PathBuf,
    /// BLAKE3 hash (hex) of the glTF file when the project was saved (absent: unknown,
    /// and no warning that the file changed).
    #[serde(default)]
    pub blake3: String,
    /// Which scene of a glTF file that has several (numbered from 0); absent: the file's
    /// default scene. Written whenever the file has more than one, so a later change of
    /// the file's default does not change what the project shows.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub gltf_scene: Option<usize>,
}

impl ProjectFile {
    /// Pretty JSON with a trailing newline; deterministic, so save → load → save is
    /// byte-identical.
    pub fn to_json(&self) -> String {
        let mut text = serde_json::to_string_pretty(self).expect("project values always serialise");
        text.push('\n');
        text
    }

    /// Every problem with the values (types and syntax were checked while parsing).
    pub fn problems(&self) -> Vec<Problem> {
        let mut problems = Vec::new();
        for (i, light) in self.lights.iter().enumerate() {
            for (field, message) in light.problems() {
                problems.push(Problem {
                    field: format!("lights[{i}].{field}"),
                    message: format!("light '{}': {message}", light.name),
                });
            }
        }
        if !self.render.exposure_ev.is_finite() || self.render.exposure_ev.abs() > 64.0 {
            problems.push(Problem {
                field: "render.exposure_ev".into(),
                message: format!("{} is not an exposure between −64 and 64 EV", self.render.exposure_ev),
            });
        }
        let scale = self.render.viewport_resolution_scale;
        if !(0.25..=1.0).contains(&scale) {
            problems.push(Problem {
                field: "render.viewport_resolution_scale".into(),
                message: format!("{scale} is outside 0.25–1"),
            });
        }
        for message in self.render.shadows.problems() {
            problems.push(Problem {
                field: "render.shadows".into(),
                message,
            });
        }
        for (field, message) in self.render.blockers.problems() {
            problems.push(Problem {
                field: format!("render.blockers.{field}"),
                message,
            });
        }
        if let Some(camera) = &self.camera
            && !camera.is_valid()
        {
            problems.push(Problem {
                field: "camera".into(),
                message: "must be finite, with a positive distance and a field of view in (0, π)".into(),
            });
        }
        if let Some(environment) = &self.environment {
            if !(environment.intensity.is_finite() && environment.intensity >= 0.0) {
                problems.push(Problem {
                    field: "environment.intensity".into(),
                    message: format!("{} must be finite and non-negative", environment.intensity),
                });
            }
            if !environment.rotation_rad.is_finite() {
                problems.push(Problem {
                    field: "environment.rotation_rad".into(),
                    message: "must be finite".into(),
                });
            }
        }
        for (i, stroke) in self.painting.strokes.iter().enumerate() {
            for message in stroke.problems() {
                problems.push(Problem {
                    field: format!("painting.strokes[{i}]"),
                    message,
                });
            }
        }
        for message in self.painting.settings.problems() {
            problems.push(Problem {
                field: "painting.settings".into(),
                message,
            });
        }
        if let Some(brush) = &self.painting.brush {
            for message in brush.problems() {
                problems.push(Problem {
                    field: "painting.brush".into(),
                    message,
                });
            }
        }
        if let Some(terrain) = &self.terrain {
            for message in terrain.problems() {
                problems.push(Problem {
                    field: "terrain".into(),
                    message,
                });
            }
        }
        let blake3 = &self.scene.blake3;
        if !blake3.is_empty() && (blake3.len() != 64 || !blake3.bytes().all(|b| b.is_ascii_hexdigit())) {
            problems.push(Problem {
                field: "scene.blake3".into(),
                message: "is not a 64-digit hexadecimal BLAKE3 hash".into(),
            });
        }
        problems
    }
}

/// Reads and validates a project file (without opening the scene it references).
pub fn read_project_file(path: &Path) -> Result<ProjectFile, ProjectError> {
    let bytes = std::fs::read(path).map_err(|source| match source.kind() {
        std::io::ErrorKind::NotFound => ProjectError::NotFound {
            path: path.to_path_buf(),
        },
        _ => ProjectError::Read {
            path: path.to_path_buf(),
            source,
        },
    })?;
    parse_project(path, &bytes)
}

/// Parses and validates project bytes; `path` is only used in messages.
pub fn parse_project(path: &Path, bytes: &[u8]) -> Result<ProjectFile, ProjectError> {
    let text = std::str::from_utf8(bytes).map_err(|e| {
        let (line, column) = line_column(bytes, e.valid_up_to());
        ProjectError::Syntax {
            path: path.to_path_buf(),
            line,
            column,
            message: "the file is not UTF-8 text".into(),
        }
    })?;
    let value: serde_json::Value = serde_json::from_str(text).map_err(|e| ProjectError::Syntax {
        path: path.to_path_buf(),
        line: e.line(),
        column: e.column(),
        message: e.to_string(),
    })?;
    let version = match value.get("format_version").and_then(serde_json::Value::as_u64) {
        Some(version) if version >= 1 => version,
        _ => {
            return Err(ProjectError::Field {
                path: path.to_path_buf(),
                field: "format_version".into(),
                line: None,
                column: None,
                message: "missing, or not a positive integer (is this a lightpaint project?)".into(),
            });
        }
    };
    if version > FORMAT_VERSION {
        return Err(ProjectError::NewerVersion {
            path: path.to_path_buf(),
            found: version,
            supported: FORMAT_VERSION,
        });
    }
    let missing = if version == FORMAT_VERSION {
        super::required::missing_fields(&value)
    } else {
        Vec::new()
    };
    if !missing.is_empty() {
        return Err(ProjectError::Invalid {
            path: path.to_path_buf(),
            problems: missing
                .into_iter()
                .map(|field| Problem {
                    field,
                    message: "missing (required)".into(),
                })
                .collect(),
        });
    }
    let project: ProjectFile = if version == FORMAT_VERSION {
        // Straight from the text, so errors carry line and column as well as the field path.
        let mut deserializer = serde_json::Deserializer::from_str(text);
        serde_path_to_error::deserialize(&mut deserializer).map_err(|e| {
            let (line, column) = (e.inner().line(), e.inner().column());
            ProjectError::Field {
                path: path.to_path_buf(),
                field: e.path().to_string(),
                line: Some(line),
                column: Some(column),
                message: e.inner().to_string(),
            }
        })?
    } else {
        let migrated = super::migrate::to_current(value, version);
        serde_path_to_error::deserialize(migrated).map_err(|e| ProjectError::Field {
            path: path.to_path_buf(),
            field: e.path().to_string(),
            line: None,
            column: None,
            message: format!("{} (after migration from format {version})", e.inner()),
        })?
    };
    let problems = project.problems();
    if !problems.is_empty() {
        return Err(ProjectError::Invalid {
            path: path.to_path_buf(),
            problems,
        });
    }
    Ok(project)
}

fn unit() -> f32 {
    1.0
}

/// 1-based line and column of byte `offset`.
fn line_column(bytes: &[u8], offset: usize) -> (usize, usize) {
    let before = &bytes[..offset.min(bytes.len())];
    let line = before.iter().filter(|&&b| b == b'\n').count() + 1;
    let column = before.iter().rev().take_while(|&&b| b != b'\n').count() + 1;
    (line, column)
}
