//! The f64 reference of the log-SH shading in `shaders/logsh.wgsl` (and, without blockers,
//! of `raster.wgsl`), term by term:
//!
//! - log-visibility F(p, n) = Σ ln ε·fade·[r/d]·rotate(cap_zh(r/d), toward the blocker),
//!   over the blockers that do not contain p and whose r/d reaches `min_cap_ratio`, where
//!   fade = smoothstep(−1, 1, (c − p)·n / r) removes blockers below the tangent plane
//!   smoothly (a hard cut leaves blotches where fitted spheres straddle their own surface);
//!   where a point opens light windows (the windows of at most eight SH lights), each of
//!   those lights reads an F of its own, every cap weighed by how near it comes to that
//!   light's cap and scaled for its mean instead of by k(s), while an environment reads
//!   the F above (`shading::light_windows`, `windows.rs`, `harmonic_visibility.rs`);
//! - visibility G = exp*(F) by the chosen [`crate::sh::ExpMethod`];
//! - radiance = emissive + environment diffuse · clamp(⟨G, cos_n⟩, 0, 1) plus, summed
//!   over lights, unshadowed(light) · clamp(V̄(light), 0, 1) (with the default
//!   [`super::BrdfShading::Separate`]; the BRDF-in-SH variants are in `lobes`), where
//!   V̄ is the mean of G over the cap the light subtends: V̄ = Σ_lm w_l(s) G_lm y_lm(d)
//!   with w_0 = 1 and w_l = (1 + c)·P_l′(c)/(l(l+1)) = z_l/(z_0 √(2l+1)) of the cap
//!   (s = sin of its half-angle, c = √(1 − s²)); for a point light (s = 0) this is G(d).
//!   Lights on the exact path (`GpuLight::shadow_path`, chosen per light for the frame by
//!   `shading::shading_lights`) take `penumbra::light_visibility` instead (the share of
//!   their disc no blocker hides);
//! - lights on the shadow-map path take the exact visibility of the scene's triangles by
//!   ray casts (`ShadingInputs::occluders`; toward the light, or spread over a sized
//!   light's disc), which the GPU's maps approach;
//! - with a terrain, F gains its log-visibility (`TerrainShadow::log_visibility`, the twin
//!   of terrain.wgsl) and exact-path lights the share of their disc above its horizon.
//!
//! Lights come in their GPU form ([`GpuLight`]) so CPU and GPU read the same parameters.

pub mod area;
mod harmonic_visibility;
pub mod lobes;
mod mapped;
mod surface;
mod vertex_light;
mod visibility;
mod windows;

use glam::DVec3;

pub use harmonic_visibility::{HarmonicVisibility, harmonic_log_visibility};
pub use mapped::{DISC_RAYS, GOLDEN_ANGLE_RAD, mapped_visibility, ray_visibility, vogel_point};
pub use surface::{
    Incidence, SurfacePoint, direct_lobes, direct_radiance, environment_irradiance_at, environment_radiance, incidence,
    mirrored_view,
};
pub use vertex_light::{VertexLight, vertex_light};
pub use visibility::{
    BlockersInReach, blockers_in_reach, exact_visibility, log_visibility, log_visibility_within, scene_log_visibility,
    visibility_cosine, visibility_toward,
};
pub use windows::{LightWindow, LightWindows};

use crate::bake::scene_bvh::SceneBvh;
use crate::blockers::Sphere;
use crate::shading::ShadowSettings;
use crate::shading::gpu_types::{GpuLight, SHADOW_PATH_MAP};
use crate::terrain::TerrainShadow;
pub use lobes::environment_through_visibility;
use lobes::{environment_through, light_through, lobes_from_log_visibility};
use visibility::exp_for_shading;

/// What shades a frame besides the surface: lights, environment, blockers, settings.
#[derive(Clone, Copy)]
pub struct ShadingInputs<'a> {
    pub lights: &'a [GpuLight],
    /// Order-3 SH of the environment's irradiance, as `Frame::environment_irradiance`.
    pub environment_irradiance: &'a [[f32; 4]; 9],
    pub blockers: &'a [Sphere],
    /// The terrain's shadow model, if the scene has a terrain.
    pub terrain: Option<&'a TerrainShadow>,
    pub settings: &'a ShadowSettings,
    pub eye: DVec3,
    /// The angle one pixel subtends (`gpu_types::pixel_angle_rad`): exact-path shadow edges
    /// ramp over one pixel's width; 0 leaves them hard.
    pub pixel_angle_rad: f64,
    /// The scene's triangles, which shadow the lights on the shadow-map path by ray casts
    /// (`mapped_visibility`, what the maps converge to); None: those lights
    /// are unshadowed.
    pub occluders: Option<&'a SceneBvh>,
}

/// Linear radiance toward the eye with log-SH shadows (`shadowed_radiance` in logsh.wgsl).
pub fn shadowed_radiance(s: &SurfacePoint, inputs: &ShadingInputs) -> DVec3 {
    let settings = inputs.settings;
    let visibility = harmonic_log_visibility(
        settings,
        inputs.blockers,
        inputs.terrain,
        inputs.environment_irradiance,
        inputs.lights,
        s.position,
        s.normal,
    );
    let lobes =
        visibility.map(|f| lobes_from_log_visibility(settings, s, inputs.eye, f, |f| exp_for_shading(settings.exp, f)));
    let mut radiance = s.emissive;
    if let Some(shared) = &lobes.shared {
        radiance += environment_through(settings, s, inputs.environment_irradiance, shared);
    }
    let footprint = (inputs.eye - s.position).length() * inputs.pixel_angle_rad;
    for (index, light) in inputs.lights.iter().enumerate() {
        let inc = incidence(light, s.position);
        let unshadowed = direct_radiance(s, &inc, inputs.eye);
        if unshadowed == DVec3::ZERO {
            continue;
        }
        if light.shadow_path == SHADOW_PATH_MAP {
            let visibility = inputs
                .occluders
                .map_or(1.0, |bvh| mapped_visibility(bvh, s.position, s.normal, &inc));
            radiance += unshadowed * visibility;
            continue;
        }
        radiance += match exact_visibility(s, light, &inc, settings, inputs.blockers, inputs.terrain, footprint) {
            Some(visibility) => unshadowed * visibility,
            // A light with no visibility of its own at s is one the windows found not to
            // reach it (out of its range or cone): it adds nothing there.
            None => lobes
                .of_light(index)
                .map_or(DVec3::ZERO, |lobes| light_through(settings, s, &inc, inputs.eye, lobes)),
        };
    }
    radiance
}
