//! The arguments of `render` and the parsers of the values clap cannot check alone.

use std::path::PathBuf;

use lightpaint::blockers::SphereBudget;
use lightpaint::render::AntiAliasing;
use lightpaint::sh::ExpMethod;
use lightpaint::shading::{BrdfShading, LightPaths, parse_exp_method};

#[derive(clap::Args)]
pub struct RenderArgs {
    /// The project (.lightpaint) or .gltf/.glb scene.
    pub file: PathBuf,
    /// Output image: .png, or .jpg/.jpeg (checked before rendering; written whole or not at all).
    #[arg(short, long)]
    pub output: PathBuf,
    #[arg(long, default_value_t = 1280)]
    pub width: u32,
    #[arg(long, default_value_t = 720)]
    pub height: u32,
    /// Exposure in stops (radiance × 2^EV before tone mapping); default: the project's, or 0.
    #[arg(long, allow_negative_numbers = true, value_parser = parse_exposure)]
    pub exposure: Option<f32>,
    /// Background colour as 8-bit sRGB "R,G,B".
    #[arg(long, value_parser = parse_srgb8)]
    pub background: Option<[u8; 3]>,
    /// SH order of the shadows (bands, 2–8 on the GPU); default: the project's, or 4.
    #[arg(long)]
    pub order: Option<usize>,
    /// Exponentiation: dc, ol, hyb, ps<k> (power series of k terms) or ref (CPU only);
    /// default: the project's, or hyb.
    #[arg(long, value_parser = parse_exp_method)]
    pub exp: Option<ExpMethod>,
    /// Log-visibility of a blocked direction is ln(eps); default: the project's, or 0.1.
    #[arg(long)]
    pub eps: Option<f32>,
    /// Sphere blockers: "auto" (per-mesh error budget) or a total count for the scene;
    /// default: the project's.
    #[arg(long, value_parser = parse_blockers)]
    pub blockers: Option<SphereBudget>,
    /// Scale each blocker's log-visibility by r/d (Ren's ratio attenuation).
    #[arg(long)]
    pub ratio_attenuation: bool,
    /// How each light is shadowed: auto (point, spot and directional lights, and sphere and
    /// area lights up to 20° of angular radius, by shadow maps of the real triangles; other
    /// extended lights under 40° exactly; the rest through the SH), harmonics (all through
    /// the SH) or exact (all exactly);
    /// default: the project's.
    #[arg(long, value_parser = parse_light_paths)]
    pub light_paths: Option<LightPaths>,
    /// Under --light-paths auto, at most this many lights go the exact way (sphere and area
    /// lights, those whose shadows fall on most of the scene first, 0-64); default: the
    /// project's, or 4.
    #[arg(long)]
    pub exact_lights: Option<u32>,
    /// Under --light-paths auto, the texels along a side of a cube face of the shadow maps
    /// of point, spot and directional lights and small sphere and area lights (64-4096,
    /// e.g. 1024; single views — spots, the sun — twice as many while the maps take at most
    /// 256 MiB; larger: truer shadow edges), or 0 for none (those lights then take the exact path or the
    /// SH); default: the project's, or 1024.
    #[arg(long)]
    pub shadow_map_size: Option<u32>,
    /// How the BRDF meets the visibility: separate (each light's exact BRDF times its
    /// visibility), log (the log-BRDF added before exponentiating) or product (the BRDF
    /// multiplied in by the SH product); default: the project's, or separate.
    #[arg(long, value_parser = BrdfShading::parse)]
    pub brdf: Option<BrdfShading>,
    /// Terrain: marching directions per receiver (W, 3–64); default: the project's, or 16.
    #[arg(long)]
    pub terrain_azimuths: Option<u32>,
    /// Terrain: height pyramid levels read while marching (1–12); default: the project's, or 6.
    #[arg(long)]
    pub terrain_levels: Option<u32>,
    /// Exponentiate the visibility at the vertices and interpolate it (faster; orders ≤ 6).
    #[arg(long, conflicts_with = "cpu")]
    pub per_vertex: bool,
    /// Shade one pixel in every d × d and upsample the rest from the samples on each
    /// pixel's surface (1 shades every pixel; 1–4); default: the project's, or 3.
    #[arg(long, conflicts_with = "cpu")]
    pub shading_downsample: Option<u32>,
    /// Antialiasing of log-SH frames: filter (one sample per pixel, then an edge filter),
    /// msaa (4 samples per pixel) or none (one sample at each pixel centre, as --cpu
    /// shades). --no-shadows frames are multisampled.
    #[arg(long, default_value = "filter", value_parser = parse_anti_aliasing)]
    pub aa: AntiAliasing,
    /// Also time this many more GPU frames (after one warm-up) and print ms per frame, and,
    /// where the GPU has timestamps, the GPU time of each pass.
    #[arg(long, default_value_t = 0, conflicts_with_all = ["cpu", "no_shadows"])]
    pub time_frames: u32,
    /// Shade on the CPU in f64 (the reference), from surfaces rasterised on the GPU.
    #[arg(long, conflicts_with = "no_shadows")]
    pub cpu: bool,
    /// Render without shadows (the plain raster pass).
    #[arg(long)]
    pub no_shadows: bool,
    /// Leave out the baked indirect light (by default a project whose setting is on adds
    /// it from its bake cache, when there is one: see `lightpaint bake`).
    #[arg(long)]
    pub no_baked_indirect: bool,
    /// Render the ground truth with the path tracer (real geometry, no sphere proxies).
    #[arg(long, conflicts_with_all = ["cpu", "no_shadows", "per_vertex", "time_frames"])]
    pub reference: bool,
    /// Reference samples (paths) per pixel.
    #[arg(long, default_value_t = 64, requires = "reference", value_parser = clap::value_parser!(u32).range(1..=1_000_000))]
    pub spp: u32,
    /// Reference indirect bounces: 0 = direct light only.
    #[arg(long, default_value_t = 4, requires = "reference", value_parser = clap::value_parser!(u32).range(0..=lightpaint::reference::MAX_BOUNCES as i64))]
    pub bounces: u32,
    /// Seed of the reference's random numbers (the same seed gives the same image).
    #[arg(long, default_value_t = 1, requires = "reference")]
    pub seed: u64,
}

pub fn parse_light_paths(text: &str) -> Result<LightPaths, String> {
    match text.trim() {
        "auto" => Ok(LightPaths::Auto),
        "harmonics" | "sh" => Ok(LightPaths::Harmonics),
        "exact" => Ok(LightPaths::Exact),
        other => Err(format!("'{other}' is not one of auto, harmonics, exact")),
    }
}

pub fn parse_anti_aliasing(text: &str) -> Result<AntiAliasing, String> {
    match text.trim() {
        "filter" => Ok(AntiAliasing::EdgeFilter),
        "msaa" => Ok(AntiAliasing::Multisample),
        "none" => Ok(AntiAliasing::None),
        other => Err(format!("'{other}' is not one of filter, msaa, none")),
    }
}

pub fn parse_blockers(text: &str) -> Result<SphereBudget, String> {
    if text.trim().eq_ignore_ascii_case("auto") {
        return Ok(lightpaint::blockers::BlockerSettings::default().budget);
    }
    match text.trim().parse::<usize>() {
        Ok(count) if count <= 100_000 => Ok(SphereBudget::Total(count)),
        _ => Err(format!("expected 'auto' or a sphere count up to 100000, got '{text}'")),
    }
}

pub fn parse_threshold(text: &str) -> Result<f32, String> {
    match text.parse::<f32>() {
        Ok(t) if (0.0..=1.0).contains(&t) => Ok(t),
        _ => Err(format!("expected a share between 0 and 1, got '{text}'")),
    }
}

pub fn parse_exposure(text: &str) -> Result<f32, String> {
    match text.parse::<f32>() {
        Ok(ev) if ev.is_finite() && ev.abs() <= 64.0 => Ok(ev),
        _ => Err(format!("expected an exposure between -64 and 64 EV, got '{text}'")),
    }
}

pub fn parse_srgb8(text: &str) -> Result<[u8; 3], String> {
    let parts: Vec<&str> = text.split(',').map(str::trim).collect();
    let values: Result<Vec<u8>, _> = parts.iter().map(|p| p.parse::<u8>()).collect();
    match values {
        Ok(v) if v.len() == 3 => Ok([v[0], v[1], v[2]]),
        _ => Err(format!("expected three integers 0–255 as R,G,B, got '{text}'")),
    }
}

pub fn parse_sample(text: &str) -> Result<lightpaint::samples::Sample, String> {
    lightpaint::samples::Sample::from_name(text)
        .ok_or_else(|| format!("expected sample, studio, interior, large, terrain or lamp-room, got '{text}'"))
}
