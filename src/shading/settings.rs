//! The knobs of the log-SH shadow renderer: SH order, exponentiation method, ε, ratio
//! attenuation, the influence cut-off, which lights go the exact way, the terrain's
//! horizon sampling and the shading resolution. Users trade speed for accuracy with them.

use crate::sh::{ExpMethod, MAX_REALTIME_ORDER};

/// Largest shading downsampling factor d (one shaded sample per d × d pixels).
pub const MAX_SHADING_DOWNSAMPLE: u32 = 4;

#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct ShadowSettings {
    /// Draw log-SH shadows (false: the plain raster pass).
    pub enabled: bool,
    /// Number of SH bands, 2..=8 on the GPU (n² coefficients per receiver).
    pub order: usize,
    /// How log-visibility is exponentiated. `Reference` is CPU-only.
    pub exp: ExpMethod,
    /// Log-visibility of a blocked direction is ln ε (shading-model.md §4; 0.1 measured best).
    pub epsilon: f32,
    /// Scale each blocker's log-visibility by r/d (off by default: measured worse, §4b).
    pub ratio_attenuation: bool,
    /// Blockers with sin(cap half-angle) = r/d below this are skipped: at 0.03 a cap covers
    /// under 0.1 % of the hemisphere.
    pub min_cap_ratio: f32,
    /// Exponentiate at the vertices and interpolate the visibility SH across triangles
    /// (cost follows the vertex count, not the pixel count; orders up to 6).
    pub per_vertex: bool,
    /// Which lights are shadowed per light and exactly (`crate::penumbra`) instead of
    /// through the visibility SH (project format 4).
    #[serde(default)]
    pub light_paths: LightPaths,
    /// How finely a height-field terrain's horizons are sampled (project format 5).
    #[serde(default)]
    pub terrain: TerrainShading,
    /// d: shade one pixel in every d × d and upsample guided by each pixel's surface
    /// (`render::passes::reduced_shading`); 1 shades every pixel, up to
    /// [`MAX_SHADING_DOWNSAMPLE`]. Per-vertex shading ignores it (project format 7).
    #[serde(default = "default_shading_downsample")]
    pub shading_downsample: u32,
    /// How each light's BRDF meets the visibility (project format 8).
    #[serde(default)]
    pub brdf: BrdfShading,
    /// Under [`LightPaths::Auto`], at most this many lights take the exact path (each
    /// costs a pass over the blockers per pixel): the brightest sphere and area lights at
    /// the scene's centre (project format 8).
    #[serde(default = "default_exact_light_budget")]
    pub exact_light_budget: u32,
    /// Texels along each side of a cube face of a shadow map (the real geometry's shadows
    /// of point, spot and directional lights under [`LightPaths::Auto`]); a single view (a
    /// spot, the sun, a light aimed at the scene) takes twice as many per side while the
    /// maps stay within a memory budget (`shading::shadow_atlas`): larger maps draw
    /// sharper, truer shadow edges; 0 draws no maps (those lights take the SH path). Written only
    /// when not the default, so projects that keep it open in older builds.
    #[serde(
        default = "default_shadow_map_size",
        skip_serializing_if = "is_default_shadow_map_size"
    )]
    pub shadow_map_size: u32,
    /// Scale each blocker's log-visibility so that, through the SH's band limit, its cap
    /// blocks the light it truly blocks (`sh::cap_mass_scales`); off, a small blocker's
    /// soft shadow takes up to |ln ε|/(1 − ε) times too much light (2.5× at ε = 0.1).
    /// Written only when off, so projects that keep it open in older builds.
    #[serde(default = "keep_shadow_mass", skip_serializing_if = "is_kept")]
    pub preserve_shadow_mass: bool,
}

fn keep_shadow_mass() -> bool {
    true
}

fn is_kept(preserve: &bool) -> bool {
    *preserve
}

/// Texels along a shadow map's side by default: [`SUGGESTED_SHADOW_MAP_SIZE`], so the
/// lights of no size cast the real triangles' shadows (the studio's default frame 1.2
/// times as long as with those lights on the SH, docs/performance.md).
pub const DEFAULT_SHADOW_MAP_SIZE: u32 = SUGGESTED_SHADOW_MAP_SIZE;
/// The size the tests and the docs measure shadow maps at.
pub const SUGGESTED_SHADOW_MAP_SIZE: u32 = 1024;
/// The range of [`ShadowSettings::shadow_map_size`].
pub const SHADOW_MAP_SIZES: std::ops::RangeInclusive<u32> = 64..=4096;

fn default_shadow_map_size() -> u32 {
    DEFAULT_SHADOW_MAP_SIZE
}

fn is_default_shadow_map_size(size: &u32) -> bool {
    *size == DEFAULT_SHADOW_MAP_SIZE
}

/// Four exact lights: key, rim and two accents, at about the SH path's cost each.
fn default_exact_light_budget() -> u32 {
    4
}

/// The most exact lights the budget may ask for.
pub const MAX_EXACT_LIGHT_BUDGET: u32 = 64;

/// A third of the resolution along each side: a ninth of the shading cost (the studio's
/// frame at 64 ms against 84 ms for one pixel in 2 × 2 on lavapipe, 2026-12-02), and the
/// log-SH lighting it interpolates is smooth where the upsampling interpolates it: 98.6 %
/// of the studio's pixels within 2/255 of shading every pixel, as at 2 × 2 (480×270,
/// `cargo nextest run --test reduced_shading --no-capture`; docs/performance.md).
fn default_shading_downsample() -> u32 {
    3
}

/// The knobs of terrain shadows (`crate::terrain`): more azimuths remove the banding of
/// discrete horizon directions, more pyramid levels read far terrain prefiltered rather
/// than point-sampled; both cost per pixel.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
#[serde(deny_unknown_fields)]
pub struct TerrainShading {
    /// W: marching directions per receiver, 3..=MAX_TERRAIN_AZIMUTHS.
    pub azimuths: u32,
    /// Height pyramid levels read while marching (1: the finest only), 1..=MAX_TERRAIN_LEVELS.
    pub pyramid_levels: u32,
}

pub const MAX_TERRAIN_AZIMUTHS: u32 = 64;
pub const MAX_TERRAIN_LEVELS: u32 = 12;

impl Default for TerrainShading {
    fn default() -> Self {
        TerrainShading {
            azimuths: 16,
            pyramid_levels: 6,
        }
    }
}

/// How each light's shadow is computed.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum LightPaths {
    /// Lights of no size (points, spots, the sun) by shadow maps of the real triangles
    /// when [`ShadowSettings::shadow_map_size`] is set (else through the SH), as many as
    /// [`super::gpu_types::MAX_SHADOW_VIEWS`] views hold (a point light takes six);
    /// extended lights (spheres, rectangles, disks) under
    /// [`AUTO_EXACT_BELOW_HALF_ANGLE_DEG`] of angular radius at the scene's centre exactly,
    /// as many as the settings' budget allows (brightest first); larger ones through the
    /// SH. The choice is one per light for the whole frame, so no receiver shows a seam
    /// where a light changes path.
    #[default]
    Auto,
    /// Every light through the visibility SH (the log-SH papers' method).
    Harmonics,
    /// Every light exactly, per light and blocker (point lights: hard shadows).
    Exact,
}

/// How the BRDF meets the visibility SH for the lights that take the SH path (lights on the
/// exact path always shade their exact BRDF times their exact visibility).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum BrdfShading {
    /// Each light's exact unshadowed BRDF times the visibility averaged over the light
    /// (shading-model.md §4b: the SH never carry the cosine, so grazing light does not ring).
    #[default]
    Separate,
    /// Ren et al.'s log-BRDF: the diffuse and Phong lobes' logs (shading-model.md §4) added to the
    /// log-visibility before exponentiating, one exponentiation per lobe; each light reads
    /// the product averaged over its cap. Per-pixel and reduced shading only.
    Log,
    /// The visibility SH times each lobe's SH by the truncated SH product after
    /// exponentiating; each light reads the product averaged over its cap.
    Product,
}

impl BrdfShading {
    pub const ALL: [BrdfShading; 3] = [BrdfShading::Separate, BrdfShading::Log, BrdfShading::Product];

    /// The name the CLI and the inspector use.
    pub fn name(self) -> &'static str {
        match self {
            BrdfShading::Separate => "separate",
            BrdfShading::Log => "log",
            BrdfShading::Product => "product",
        }
    }

    /// Parses [`Self::name`].
    pub fn parse(text: &str) -> Result<BrdfShading, String> {
        let lower = text.trim().to_ascii_lowercase();
        BrdfShading::ALL
            .into_iter()
            .find(|b| b.name() == lower)
            .ok_or_else(|| format!("expected separate, log or product, got '{text}'"))
    }
}

/// In [`LightPaths::Auto`], lights that look smaller than this (angular radius, degrees)
/// take the exact path: the SH path's penumbra error grows quickly as lights shrink below
/// it (docs/speed-accuracy.md, "Small lights: the exact path"), while above it the SH
/// path is close and costs less with many lights.
pub const AUTO_EXACT_BELOW_HALF_ANGLE_DEG: f64 = 40.0;

impl LightPaths {
    /// Lights whose sin(angular radius) is below this take the exact path (0: none, 2: all).
    pub fn exact_below_cap_ratio(self) -> f64 {
        match self {
            LightPaths::Auto => AUTO_EXACT_BELOW_HALF_ANGLE_DEG.to_radians().sin(),
            LightPaths::Harmonics => 0.0,
            LightPaths::Exact => 2.0,
        }
    }

    /// Whether lights of no size (points, spots, directional) take the exact path.
    pub fn exact_point_lights(self) -> bool {
        self == LightPaths::Exact
    }

    /// Whether a light of sin(angular radius) `cap_ratio` takes the exact path.
    pub fn is_exact(self, cap_ratio: f64) -> bool {
        cap_ratio < self.exact_below_cap_ratio() && (cap_ratio > 0.0 || self.exact_point_lights())
    }
}

impl Default for ShadowSettings {
    fn default() -> Self {
        ShadowSettings {
            enabled: true,
            order: 4,
            exp: ExpMethod::Hyb,
            epsilon: 0.1,
            ratio_attenuation: false,
            min_cap_ratio: 0.03,
            per_vertex: false,
            light_paths: LightPaths::Auto,
            terrain: TerrainShading::default(),
            shading_downsample: default_shading_downsample(),
            brdf: BrdfShading::Separate,
            exact_light_budget: default_exact_light_budget(),
            shadow_map_size: DEFAULT_SHADOW_MAP_SIZE,
            preserve_shadow_mass: true,
        }
    }
}

impl ShadowSettings {
    /// The scales k(s) that keep each cap's blocked light through the band limit for
    /// `settings` (`sh::cap_mass_scales`, computed once per order and ε), all 1 when the
    /// settings do not preserve the shadow mass. The GPU reads the same table in f32.
    pub fn cap_mass_table(&self) -> [f64; crate::sh::CAP_MASS_ENTRIES] {
        use std::collections::HashMap;
        use std::sync::{Mutex, OnceLock};
        if !self.preserve_shadow_mass {
            return [1.0; crate::sh::CAP_MASS_ENTRIES];
        }
        type Tables = HashMap<(usize, u32), [f64; crate::sh::CAP_MASS_ENTRIES]>;
        static TABLES: OnceLock<Mutex<Tables>> = OnceLock::new();
        let key = (self.order, self.epsilon.to_bits());
        let tables = TABLES.get_or_init(Default::default);
        if let Some(table) = tables.lock().unwrap_or_else(|e| e.into_inner()).get(&key) {
            return *table;
        }
        // Rounded to f32 as the GPU reads it, so that both sides scale alike.
        let table = crate::sh::cap_mass_scales(self.order, self.epsilon as f64).map(|k| k as f32 as f64);
        tables.lock().unwrap_or_else(|e| e.into_inner()).insert(key, table);
        table
    }

    /// These settings shading every pixel: what the CPU reference does, so what GPU–CPU
    /// comparisons and the accuracy study measure.
    pub fn every_pixel(self) -> ShadowSettings {
        ShadowSettings {
            shading_downsample: 1,
            ..self
        }
    }

    /// Every problem with these settings for the GPU renderer, as messages: those of
    /// [`Self::problems`], and the reference exponential, which has no GPU form.
    pub fn gpu_problems(&self) -> Vec<String> {
        let mut problems = self.problems();
        if self.exp == ExpMethod::Reference {
            problems.push("the reference exponential runs on the CPU only (use --cpu)".into());
        }
        problems
    }

    /// Every problem with these settings wherever they are used (a project file, the CPU
    /// reference), as messages.
    pub fn problems(&self) -> Vec<String> {
        let mut problems = Vec::new();
        if !(2..=MAX_REALTIME_ORDER).contains(&self.order) {
            problems.push(format!("order {} is outside 2..={MAX_REALTIME_ORDER}", self.order));
        }
        if !(self.epsilon > 0.0 && self.epsilon < 1.0) {
            problems.push(format!("epsilon {} must be in (0, 1)", self.epsilon));
        }
        if !(self.min_cap_ratio.is_finite() && (0.0..1.0).contains(&self.min_cap_ratio)) {
            problems.push(format!("min_cap_ratio {} must be in [0, 1)", self.min_cap_ratio));
        }
        if self.per_vertex && !super::wgsl::sh::supports_per_vertex(self.order) {
            problems.push(format!(
                "per-vertex shading supports orders up to 6, not {}",
                self.order
            ));
        }
        if self.per_vertex && self.brdf == BrdfShading::Log {
            problems.push(
                "the log-BRDF exponentiates per pixel: use it without per-vertex shading, or the product BRDF".into(),
            );
        }
        if self.exact_light_budget > MAX_EXACT_LIGHT_BUDGET {
            problems.push(format!(
                "exact light budget {} must be 0..={MAX_EXACT_LIGHT_BUDGET}",
                self.exact_light_budget
            ));
        }
        if let ExpMethod::Ps(terms) = self.exp
            && !(1..=32).contains(&terms)
        {
            problems.push(format!("power series with {terms} terms: use 1..=32"));
        }
        if !(3..=MAX_TERRAIN_AZIMUTHS).contains(&self.terrain.azimuths) {
            problems.push(format!(
                "terrain azimuths {} must be 3..={MAX_TERRAIN_AZIMUTHS}",
                self.terrain.azimuths
            ));
        }
        if !(1..=MAX_SHADING_DOWNSAMPLE).contains(&self.shading_downsample) {
            problems.push(format!(
                "shading downsample {} must be 1..={MAX_SHADING_DOWNSAMPLE}",
                self.shading_downsample
            ));
        }
        if self.shadow_map_size != 0 && !SHADOW_MAP_SIZES.contains(&self.shadow_map_size) {
            problems.push(format!(
                "shadow map size {} must be 0 (no maps) or {}..={}",
                self.shadow_map_size,
                SHADOW_MAP_SIZES.start(),
                SHADOW_MAP_SIZES.end()
            ));
        }
        if !(1..=MAX_TERRAIN_LEVELS).contains(&self.terrain.pyramid_levels) {
            problems.push(format!(
                "terrain pyramid levels {} must be 1..={MAX_TERRAIN_LEVELS}",
                self.terrain.pyramid_levels
            ));
        }
        problems
    }
}

/// Parses an exponentiation method as the CLI spells it: dc, ol, hyb, `ps<k>` (e.g. ps8), ref.
pub fn parse_exp_method(text: &str) -> Result<ExpMethod, String> {
    let lower = text.trim().to_ascii_lowercase();
    match lower.as_str() {
        "dc" => Ok(ExpMethod::Dc),
        "ol" => Ok(ExpMethod::Ol),
        "hyb" => Ok(ExpMethod::Hyb),
        "ref" | "reference" => Ok(ExpMethod::Reference),
        _ => match lower.strip_prefix("ps").map(str::parse::<usize>) {
            Some(Ok(terms)) if (1..=32).contains(&terms) => Ok(ExpMethod::Ps(terms)),
            _ => Err(format!("expected dc, ol, hyb, ps1..ps32 or ref, got '{text}'")),
        },
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn defaults_are_valid_and_methods_parse() {
        assert!(ShadowSettings::default().gpu_problems().is_empty());
        let reference = ShadowSettings {
            exp: ExpMethod::Reference,
            ..ShadowSettings::default()
        };
        assert!(reference.problems().is_empty() && reference.gpu_problems().len() == 1);
        assert_eq!(parse_exp_method("HYB"), Ok(ExpMethod::Hyb));
        assert_eq!(parse_exp_method("ps8"), Ok(ExpMethod::Ps(8)));
        assert!(parse_exp_method("ps0").is_err());
        assert!(parse_exp_method("fast").is_err());
    }
}
