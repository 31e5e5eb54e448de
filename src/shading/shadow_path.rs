//! The shadow path a light takes, as the editor names it and explains it: the path of each
//! light as `light_paths::shading_lights` chose it, its size where it is asked, and why.

use glam::Vec3;

use super::gpu_types::{GpuLight, SHADOW_PATH_EXACT, SHADOW_PATH_MAP};
use super::light_paths::{LightPathContext, shading_lights};
use super::{LightPaths, ShadowSettings};
use crate::scene::Light;

/// For each of `lights`: whether it takes the exact shadow path under `settings` (see
/// [`shading_lights`]) and its angular radius seen from `point` in degrees (the editor
/// asks at the view's pivot).
pub fn light_paths_at(
    lights: &[Light],
    point: Vec3,
    settings: &ShadowSettings,
    context: &LightPathContext,
) -> Vec<(ShadowPath, f64)> {
    paths_and_sizes_at(&shading_lights(lights, settings, context), point)
}

/// The shadow path a light takes, as the editor names it.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ShadowPath {
    /// Through the log-SH visibility of the sphere blockers.
    Harmonics,
    /// The exact share of its disc the sphere blockers hide.
    Exact,
    /// A shadow map of the real triangles.
    Map,
}

impl ShadowPath {
    /// The path of a light as the shaders take it (`GpuLight::shadow_path`).
    pub fn of(light: &GpuLight) -> ShadowPath {
        match light.shadow_path {
            SHADOW_PATH_EXACT => ShadowPath::Exact,
            SHADOW_PATH_MAP => ShadowPath::Map,
            _ => ShadowPath::Harmonics,
        }
    }

    /// Plain words for the editor.
    pub fn words(self) -> &'static str {
        match self {
            ShadowPath::Harmonics => "soft (SH)",
            ShadowPath::Exact => "exact",
            ShadowPath::Map => "shadow map",
        }
    }
}

/// Why a light takes `path` under `settings`, in plain words for the inspector: `sized`
/// says whether it has a size (sphere, rect, disk), `half_angle_deg` its angular radius
/// at the scene's centre.
pub fn path_reason(path: ShadowPath, sized: bool, half_angle_deg: f64, settings: &ShadowSettings) -> &'static str {
    let maps_on = settings.light_paths == LightPaths::Auto && settings.shadow_map_size > 0;
    let mappable = !sized || half_angle_deg <= super::shadow_maps::MAX_MAPPED_HALF_ANGLE_DEG;
    match path {
        ShadowPath::Map if sized => "a small light: maps of the real triangles, penumbrae sized by the light",
        ShadowPath::Map => "a light of no size: maps of the real triangles, hard edges",
        ShadowPath::Exact if settings.light_paths == LightPaths::Exact => "every light is exact (light paths: exact)",
        // Auto sends a light exact past the maps' size or before them only when its
        // blockers are spheres that are their meshes (light_paths::exact_sphere_lights).
        ShadowPath::Exact if (maps_on && mappable) || half_angle_deg >= super::AUTO_EXACT_BELOW_HALF_ANGLE_DEG => {
            "its shadows come from meshes that are spheres (balls): the exact share they hide"
        }
        ShadowPath::Exact => "a small light the maps do not take: the exact share the spheres hide",
        ShadowPath::Harmonics if settings.light_paths == LightPaths::Harmonics => {
            "every light is soft (light paths: harmonics)"
        }
        ShadowPath::Harmonics if sized && half_angle_deg >= super::AUTO_EXACT_BELOW_HALF_ANGLE_DEG => {
            "a wide light: its soft shadows are the SH's"
        }
        ShadowPath::Harmonics if !sized && !maps_on => "shadow maps are off: soft shadows of the sphere blockers",
        ShadowPath::Harmonics if maps_on && mappable => {
            "the shadow maps' views are all taken: soft shadows of the spheres"
        }
        ShadowPath::Harmonics => "over the exact-light budget: soft shadows of the sphere blockers",
    }
}

/// For lights as the shaders take them: the shadow path of each, and its angular radius
/// seen from `point` in degrees.
pub fn paths_and_sizes_at(lights: &[GpuLight], point: Vec3) -> Vec<(ShadowPath, f64)> {
    lights
        .iter()
        .map(|light| {
            let inc = super::cpu::incidence(light, point.as_dvec3());
            (ShadowPath::of(light), inc.cap_ratio.clamp(0.0, 1.0).asin().to_degrees())
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn each_path_says_why_in_plain_words() {
        let auto = ShadowSettings::default();
        let off = ShadowSettings {
            shadow_map_size: 0,
            ..auto
        };
        let (map, exact, soft) = (ShadowPath::Map, ShadowPath::Exact, ShadowPath::Harmonics);
        assert!(path_reason(map, true, 5.0, &auto).contains("penumbrae"));
        assert!(path_reason(map, false, 0.0, &auto).contains("hard"));
        assert!(path_reason(exact, true, 30.0, &auto).contains("do not take"));
        assert!(path_reason(exact, true, 1.0, &auto).contains("spheres (balls)"));
        assert!(path_reason(exact, true, 60.0, &auto).contains("spheres (balls)"));
        assert!(path_reason(soft, true, 60.0, &auto).contains("wide"));
        assert!(path_reason(soft, false, 0.0, &auto).contains("all taken"));
        assert!(path_reason(soft, false, 0.0, &off).contains("off"));
        assert!(path_reason(soft, true, 10.0, &off).contains("budget"));
        assert!(path_reason(soft, true, 30.0, &auto).contains("budget"));
        let harmonics = ShadowSettings {
            light_paths: LightPaths::Harmonics,
            ..auto
        };
        assert!(path_reason(soft, true, 5.0, &harmonics).contains("harmonics"));
    }
}
