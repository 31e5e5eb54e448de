//! Scripted strokes (`lightpaint paint FILE --strokes strokes.json`), documented in
//! docs/strokes.md: a default view, then strokes given as screen-space polylines or as
//! world-space points (projected through the stroke's view), each with its brush and
//! strategies. The script resolves to [`StrokeRecord`]s, the same records the editor
//! logs.

use std::path::{Path, PathBuf};

use glam::{Vec2, Vec3};

use super::brush::Brush;
use super::record::{PaintSettings, StrokeRecord, ViewRecord, dabs_along};

/// Why a stroke script cannot be used; every variant names the file.
#[derive(Debug, thiserror::Error)]
pub enum ScriptError {
    #[error("{path}: cannot read file: {source}")]
    Read {
        path: PathBuf,
        #[source]
        source: std::io::Error,
    },
    #[error("{path}: {field} (line {line}, column {column}): {message}")]
    Field {
        path: PathBuf,
        field: String,
        line: usize,
        column: usize,
        message: String,
    },
    #[error("{path}: {field}: {message}")]
    Invalid {
        path: PathBuf,
        field: String,
        message: String,
    },
}

/// A view written by hand: an eye looking at a target.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ScriptView {
    pub eye: Vec3,
    pub target: Vec3,
    #[serde(default = "default_up")]
    pub up: Vec3,
    #[serde(default = "default_yfov_deg")]
    pub yfov_deg: f32,
    #[serde(default = "default_width")]
    pub width_px: u32,
    #[serde(default = "default_height")]
    pub height_px: u32,
}

fn default_up() -> Vec3 {
    Vec3::Y
}
fn default_yfov_deg() -> f32 {
    45.0
}
fn default_width() -> u32 {
    1280
}
fn default_height() -> u32 {
    720
}
fn default_spacing() -> f32 {
    4.0
}

impl ScriptView {
    pub fn record(&self) -> ViewRecord {
        let forward = (self.target - self.eye).normalize_or_zero();
        let right = forward.cross(self.up).normalize_or_zero();
        ViewRecord {
            eye: self.eye,
            forward,
            up: right.cross(forward),
            yfov_rad: self.yfov_deg.to_radians(),
            width_px: self.width_px,
            height_px: self.height_px,
        }
    }
}

/// One scripted stroke: exactly one of `screen_px` and `world`.
#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ScriptStroke {
    #[serde(default)]
    pub view: Option<ScriptView>,
    pub brush: Brush,
    #[serde(default)]
    pub settings: Option<PaintSettings>,
    /// A polyline in pixels of the view (top-left origin, y down).
    #[serde(default)]
    pub screen_px: Option<Vec<Vec2>>,
    /// World points, each projected through the view to a dab.
    #[serde(default)]
    pub world: Option<Vec<Vec3>>,
    /// Distance between dabs along a screen polyline, pixels.
    #[serde(default = "default_spacing")]
    pub spacing_px: f32,
}

/// A stroke script.
#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Script {
    /// Seed of the strokes' random choices; stroke k uses seed + k.
    #[serde(default)]
    pub seed: u64,
    /// The view of strokes that name none (default: the project's camera).
    #[serde(default)]
    pub view: Option<ScriptView>,
    /// Settings of strokes that name none.
    #[serde(default)]
    pub settings: PaintSettings,
    /// Names of lights to lock before the strokes, as the editor's lock does: the strokes
    /// leave them as they are, and the saved project keeps them locked.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub locked_lights: Vec<String>,
    pub strokes: Vec<ScriptStroke>,
}

impl Script {
    pub fn load(path: &Path) -> Result<Script, ScriptError> {
        let text = std::fs::read_to_string(path).map_err(|source| ScriptError::Read {
            path: path.to_path_buf(),
            source,
        })?;
        Script::parse(&text, path)
    }

    pub fn parse(text: &str, path: &Path) -> Result<Script, ScriptError> {
        let deserializer = &mut serde_json::Deserializer::from_str(text);
        serde_path_to_error::deserialize(deserializer).map_err(|e| {
            let field = e.path().to_string();
            let inner = e.into_inner();
            ScriptError::Field {
                path: path.to_path_buf(),
                field,
                line: inner.line(),
                column: inner.column(),
                message: inner.to_string(),
            }
        })
    }

    /// Locks the lights `locked_lights` names among `lights` (every light of a name).
    /// A name no light has is an error naming it and the lights there are; nothing is
    /// locked then.
    pub fn lock_lights(&self, path: &Path, lights: &mut [crate::scene::Light]) -> Result<(), ScriptError> {
        for (k, name) in self.locked_lights.iter().enumerate() {
            if !lights.iter().any(|light| &light.name == name) {
                let names: Vec<&str> = lights.iter().map(|light| light.name.as_str()).collect();
                return Err(ScriptError::Invalid {
                    path: path.to_path_buf(),
                    field: format!("locked_lights[{k}]"),
                    message: format!("no light is called {name:?} (the lights: {})", names.join(", ")),
                });
            }
        }
        for light in lights.iter_mut() {
            light.locked |= self.locked_lights.contains(&light.name);
        }
        Ok(())
    }

    /// The strokes as records, `fallback` the view of strokes (and a script) that name
    /// none. Every problem is an error naming the stroke.
    pub fn records(&self, path: &Path, fallback: ViewRecord) -> Result<Vec<StrokeRecord>, ScriptError> {
        let default_view = self.view.map(|v| v.record()).unwrap_or(fallback);
        self.strokes
            .iter()
            .enumerate()
            .map(|(k, stroke)| {
                let invalid = |message: String| ScriptError::Invalid {
                    path: path.to_path_buf(),
                    field: format!("strokes[{k}]"),
                    message,
                };
                let view = stroke.view.map(|v| v.record()).unwrap_or(default_view);
                let dabs_px = match (&stroke.screen_px, &stroke.world) {
                    (Some(points), None) => dabs_along(points, stroke.spacing_px),
                    (None, Some(points)) => {
                        if let Some(k) = points.iter().position(|p| !p.is_finite()) {
                            return Err(invalid(format!(
                                "world[{k}] is not a finite point (a coordinate beyond ±3.4e38 m, as f32 holds them, or not a number)"
                            )));
                        }
                        let projected = view.view();
                        points
                            .iter()
                            .map(|&p| projected.project(p))
                            .collect::<Option<Vec<Vec2>>>()
                            .ok_or_else(|| invalid("a world point is behind the stroke's camera".into()))?
                    }
                    _ => return Err(invalid("give exactly one of screen_px and world".into())),
                };
                let record = StrokeRecord {
                    view,
                    dabs_px,
                    brush: stroke.brush,
                    settings: stroke.settings.unwrap_or(self.settings),
                    seed: self.seed.wrapping_add(k as u64),
                    hidden_objects: Vec::new(),
                    locked_lights: Vec::new(),
                };
                let problems = record.problems();
                if problems.is_empty() {
                    Ok(record)
                } else {
                    Err(invalid(problems.join("; ")))
                }
            })
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn fallback() -> ViewRecord {
        ScriptView {
            eye: Vec3::new(0.0, 5.0, 5.0),
            target: Vec3::ZERO,
            up: Vec3::Y,
            yfov_deg: 45.0,
            width_px: 640,
            height_px: 480,
        }
        .record()
    }

    #[test]
    fn world_points_project_to_dabs_and_bad_fields_name_their_place() {
        let text = r#"{"seed": 3, "strokes": [
            {"brush": {"kind": "positive"}, "world": [[0, 0, 0]]},
            {"brush": {"kind": "negative", "radius_px": 20}, "screen_px": [[10, 10], [30, 10]]}
        ]}"#;
        let script = Script::parse(text, Path::new("s.json")).unwrap();
        let records = script.records(Path::new("s.json"), fallback()).unwrap();
        assert_eq!(records.len(), 2);
        assert!((records[0].dabs_px[0] - Vec2::new(320.0, 240.0)).length() < 1e-3);
        assert_eq!(records[1].seed, 4);
        assert!(records[1].dabs_px.len() >= 5);

        let bad = r#"{"strokes": [{"brush": {"kind": "sideways"}, "world": []}]}"#;
        let error = Script::parse(bad, Path::new("s.json")).unwrap_err().to_string();
        assert!(
            error.contains("s.json") && error.contains("strokes[0].brush.kind"),
            "{error}"
        );

        let both = r#"{"strokes": [{"brush": {"kind": "positive"}}]}"#;
        let script = Script::parse(both, Path::new("s.json")).unwrap();
        let error = script.records(Path::new("s.json"), fallback()).unwrap_err().to_string();
        assert!(error.contains("strokes[0]") && error.contains("exactly one"), "{error}");

        // A point too far for f32 is named as such, not as behind the camera; one behind
        // the camera is.
        let far = r#"{"strokes": [{"brush": {"kind": "positive"}, "world": [[0, 0, 0], [1e39, 0, 0]]}]}"#;
        let script = Script::parse(far, Path::new("s.json")).unwrap();
        let error = script.records(Path::new("s.json"), fallback()).unwrap_err().to_string();
        assert!(error.contains("world[1] is not a finite point"), "{error}");
        let behind = r#"{"strokes": [{"brush": {"kind": "positive"}, "world": [[0, 10, 10]]}]}"#;
        let script = Script::parse(behind, Path::new("s.json")).unwrap();
        let error = script.records(Path::new("s.json"), fallback()).unwrap_err().to_string();
        assert!(error.contains("behind the stroke's camera"), "{error}");
    }

    #[test]
    fn locked_lights_are_named_or_refused() {
        let light = |name: &str| crate::scene::Light {
            name: name.into(),
            kind: crate::scene::LightKind::Point,
            color: Vec3::ONE,
            intensity: 1.0,
            position: Vec3::Y,
            direction: Vec3::NEG_Y,
            range: None,
            locked: false,
        };
        let mut lights = vec![light("key"), light("fill"), light("key")];
        let script = Script::parse(r#"{"locked_lights": ["key"], "strokes": []}"#, Path::new("s.json")).unwrap();
        script.lock_lights(Path::new("s.json"), &mut lights).unwrap();
        assert_eq!(lights.iter().map(|l| l.locked).collect::<Vec<_>>(), [true, false, true]);
        let script = Script::parse(r#"{"locked_lights": ["rim"], "strokes": []}"#, Path::new("s.json")).unwrap();
        let error = script
            .lock_lights(Path::new("s.json"), &mut lights)
            .unwrap_err()
            .to_string();
        assert!(
            error.contains("locked_lights[0]") && error.contains("\"rim\"") && error.contains("key, fill"),
            "{error}"
        );
    }
}
