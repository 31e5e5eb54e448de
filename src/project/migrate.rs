//! Migrations of older project formats to [`FORMAT_VERSION`], one step per version,
//! applied to the parsed JSON before it is read into [`super::ProjectFile`].
//!
//! Format history:
//! - 1 (lightpaint 0.1): scene reference, lights, render settings (exposure, background),
//!   camera, environment.
//! - 2: render settings gain `shadows` (log-SH knobs), `blockers` (sphere fit) and
//!   `viewport_resolution_scale`; files
//!   of format 1 get the defaults, which is how they were drawn (format 1 had no shadows
//!   setting because it had no shadows: they open with shadows on).
//! - 3: `painting` (the stroke log, the brush and the painting strategies); files of
//!   format 2 had no painting, so they get an empty log and the default strategies.
//! - 4: `scene.gltf_scene` (which scene of a glTF file with several) and
//!   `render.baked_indirect`; files of format 3 showed the file's default scene, which is
//!   what an absent `gltf_scene` means, and were drawn without baked indirect light, so
//!   they get `baked_indirect: false`; `render.shadows.light_paths` (exact shadows for
//!   small lights): format 3 shadowed every light through the SH, so "harmonics".
//! - 5: `terrain` (a height-field terrain) and `render.shadows.terrain` (its horizon
//!   sampling); format 4 had no terrain, which is what their absence means.
//! - 6: `hidden_objects` (objects hidden in the viewport) and `object_names` (objects
//!   renamed in the editor); format 5 showed every object under its glTF name.
//! - 7: `render.shadows.shading_downsample` (reduced-resolution shading); format 6 shaded
//!   every pixel, so 1.
//! - 8: `render.shadows.brdf` (the BRDF carried in the SH or not); format 7 shaded each
//!   light's exact BRDF through its visibility, which is what its absence means; and
//!   `render.shadows.exact_light_budget` (at most so many exact lights under Auto): format
//!   7 had no limit, so the largest budget.
//! - 9: rect lights' `turn_rad` (a turn about their normal); format 8 rects lay on the
//!   default width axis, which is what an absent turn means.
//! - 10: a light's `locked` (painting leaves it as it is), a stroke's `locked_lights` and
//!   the `release` brush; format 9 had neither, which is what their absence means.
//!
//! A new format adds a `vN_to_vN+1` step here, applied in sequence, and a test that a
//! committed file of every older format opens.

use serde_json::Value;

/// The format this build writes and the newest it reads: the one the migrations lead to.
pub const FORMAT_VERSION: u64 = 10;

/// Brings `value`, a project of format `version` (1 ≤ version ≤ current), to the current
/// format, one step at a time.
pub fn to_current(mut value: Value, version: u64) -> Value {
    debug_assert!((1..=FORMAT_VERSION).contains(&version));
    if version < 2 {
        value = v1_to_v2(value);
    }
    if version < 3 {
        value = v2_to_v3(value);
    }
    if version < 4 {
        value = v3_to_v4(value);
    }
    if version < 5 {
        value = v4_to_v5(value);
    }
    if version < 6 {
        value = v5_to_v6(value);
    }
    if version < 7 {
        value = v6_to_v7(value);
    }
    if version < 8 {
        value = v7_to_v8(value);
    }
    if version < 9 {
        set_format(&mut value, 9);
    }
    if version < 10 {
        set_format(&mut value, 10);
    }
    value
}

fn v7_to_v8(mut value: Value) -> Value {
    // Format 7 had no budget: every small light could go exact.
    let unlimited = crate::shading::MAX_EXACT_LIGHT_BUDGET;
    set_shadow_setting(&mut value, "exact_light_budget", Value::from(unlimited));
    set_format(&mut value, 8);
    value
}

fn v6_to_v7(mut value: Value) -> Value {
    // Set, not defaulted: v1_to_v2 may have filled in today's defaults.
    set_shadow_setting(&mut value, "shading_downsample", Value::from(1));
    set_format(&mut value, 7);
    value
}

/// Sets `render.shadows.<key>` where the file has shadow settings.
fn set_shadow_setting(value: &mut Value, key: &str, setting: Value) {
    let shadows = value
        .get_mut("render")
        .and_then(|render| render.get_mut("shadows"))
        .and_then(Value::as_object_mut);
    if let Some(shadows) = shadows {
        shadows.insert(key.into(), setting);
    }
}

fn set_format(value: &mut Value, version: u64) {
    if let Some(object) = value.as_object_mut() {
        object.insert("format_version".into(), Value::from(version));
    }
}

fn v5_to_v6(mut value: Value) -> Value {
    if let Some(object) = value.as_object_mut() {
        object.insert("format_version".into(), Value::from(6));
    }
    value
}

fn v4_to_v5(mut value: Value) -> Value {
    if let Some(object) = value.as_object_mut() {
        object.insert("format_version".into(), Value::from(5));
    }
    value
}

fn v3_to_v4(mut value: Value) -> Value {
    if let Some(render) = value.get_mut("render").and_then(Value::as_object_mut) {
        // Set, not defaulted: v1_to_v2 may have filled in today's defaults.
        render.insert("baked_indirect".into(), Value::Bool(false));
        if let Some(shadows) = render.get_mut("shadows").and_then(Value::as_object_mut) {
            shadows.insert("light_paths".into(), Value::from("harmonics"));
        }
    }
    if let Some(object) = value.as_object_mut() {
        object.insert("format_version".into(), Value::from(4));
    }
    value
}

fn v2_to_v3(mut value: Value) -> Value {
    if let Some(object) = value.as_object_mut() {
        let painting = serde_json::to_value(super::painting_state::PaintingState::default()).unwrap_or(Value::Null);
        object.entry("painting").or_insert(painting);
        object.insert("format_version".into(), Value::from(3));
    }
    value
}

fn v1_to_v2(mut value: Value) -> Value {
    let defaults = serde_json::to_value(crate::shading::RenderSettings::default()).unwrap_or(Value::Null);
    if let (Some(render), Some(defaults)) = (
        value.get_mut("render").and_then(Value::as_object_mut),
        defaults.as_object(),
    ) {
        // Every render setting format 1 did not have takes its default.
        for (key, default) in defaults {
            render.entry(key.clone()).or_insert_with(|| default.clone());
        }
    }
    if let Some(object) = value.as_object_mut() {
        object.insert("format_version".into(), Value::from(2));
    }
    value
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn format_1_render_settings_gain_the_default_shadows_and_blockers() {
        let v1 = serde_json::json!({
            "format_version": 1,
            "render": {"exposure_ev": 0.5, "background_srgb8": [1, 2, 3]},
        });
        let v2 = v1_to_v2(v1);
        assert_eq!(v2["format_version"], 2);
        let render: crate::shading::RenderSettings =
            serde_json::from_value(v2["render"].clone()).expect("format 2 render settings");
        assert_eq!(render.exposure_ev, 0.5);
        assert_eq!(render.background_srgb8, [1, 2, 3]);
        assert_eq!(render.shadows, crate::shading::ShadowSettings::default());
        assert_eq!(render.blockers, crate::blockers::BlockerSettings::default());
        assert_eq!(render.viewport_resolution_scale, 1.0);
    }
}
