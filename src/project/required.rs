//! The fields a project file cannot do without, all checked before it is read, so that a
//! hand-written file learns of every missing one at once (serde stops at the first).
//! Everything else has a documented default (docs/file-format.md): `format_version`,
//! `scene.gltf` and `lights` are required; in a light its `name`, `kind.type`,
//! `intensity` and its kind's sizes and cone; in an environment its `hdr`.

use serde_json::Value;

/// The required fields missing from `project` (a parsed project of the current format),
/// as paths such as `lights[2].intensity`.
pub fn missing_fields(project: &Value) -> Vec<String> {
    let mut missing = Vec::new();
    let mut need = |present: bool, path: String| {
        if !present {
            missing.push(path);
        }
    };
    match project.get("scene") {
        Some(scene) => need(scene.get("gltf").is_some(), "scene.gltf".into()),
        None => need(false, "scene".into()),
    }
    match project.get("lights").and_then(Value::as_array) {
        Some(lights) => {
            for (i, light) in lights.iter().enumerate() {
                for field in ["name", "intensity"] {
                    need(light.get(field).is_some(), format!("lights[{i}].{field}"));
                }
                let Some(kind) = light.get("kind") else {
                    need(false, format!("lights[{i}].kind"));
                    continue;
                };
                let sizes: &[&str] = match kind.get("type").and_then(Value::as_str) {
                    Some("spot") => &["inner_cone_rad", "outer_cone_rad"],
                    Some("sphere" | "disk") => &["radius_m"],
                    Some("rect") => &["width_m", "height_m"],
                    Some(_) => &[],
                    None => {
                        need(false, format!("lights[{i}].kind.type"));
                        &[]
                    }
                };
                for size in sizes {
                    need(kind.get(*size).is_some(), format!("lights[{i}].kind.{size}"));
                }
            }
        }
        None => need(project.get("lights").is_some(), "lights".into()),
    }
    if let Some(environment) = project.get("environment") {
        need(environment.get("hdr").is_some(), "environment.hdr".into());
    }
    missing
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_missing_field_is_named() {
        let project = serde_json::json!({
            "format_version": 10,
            "scene": {},
            "lights": [
                { "kind": { "type": "spot", "outer_cone_rad": 0.5 }, "intensity": 3.0 },
                { "name": "ok", "kind": { "type": "point" }, "intensity": 1.0 },
                { "name": "box", "kind": { "type": "rect", "width_m": 1.0 } },
                { "name": "no kind", "intensity": 1.0 }
            ],
            "environment": { "intensity": 2.0 }
        });
        assert_eq!(
            missing_fields(&project),
            [
                "scene.gltf",
                "lights[0].name",
                "lights[0].kind.inner_cone_rad",
                "lights[2].intensity",
                "lights[2].kind.height_m",
                "lights[3].kind",
                "environment.hdr",
            ]
        );
    }

    #[test]
    fn the_smallest_project_needs_nothing_more() {
        let project = serde_json::json!({
            "format_version": 10,
            "scene": { "gltf": "a.glb" },
            "lights": [{ "name": "p", "kind": { "type": "point" }, "intensity": 1.0 }]
        });
        assert!(missing_fields(&project).is_empty());
        assert_eq!(
            missing_fields(&serde_json::json!({ "format_version": 10 })),
            ["scene", "lights"]
        );
    }
}
