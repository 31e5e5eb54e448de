//! What Auto's choice of each light's shadow path looks at besides the lights
//! (`light_paths::shading_lights`): the scene's centre and extent, a spread of its surface
//! points, the blockers, and which blockers are their meshes exactly.

use glam::{DVec3, Vec3};

use super::gpu_types::GpuLight;
use super::sphere_casters::SphereCasters;
use crate::blockers::Sphere;
use crate::scene::Scene;

/// Most surface points [`LightPathContext::of_scene`] keeps: enough to tell a light that
/// shadows much of the scene from one that shadows little, cheap enough to redo while a
/// light is dragged.
pub const MAX_RECEIVERS: usize = 128;

/// Most receiver–blocker tests weighing one light: with many blockers, fewer receivers
/// (at least [`MIN_RECEIVERS`]) are looked at, so the choice stays interactive.
const MAX_TESTS_PER_LIGHT: usize = 100_000;
const MIN_RECEIVERS: usize = 16;

/// What Auto's choice of exact lights looks at besides the lights: the scene's centre,
/// where each light's size and brightness are taken, and, to weigh the blockers that
/// matter, a spread of the scene's surface points and the blockers.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct LightPathContext {
    pub centre: Vec3,
    /// The radius of the scene's bounding sphere around `centre` (0: unknown), which a
    /// light outside it sees in one shadow-map view rather than a cube.
    pub radius_m: f32,
    /// Surface points (position, unit normal); none: every light's shadows count alike.
    pub receivers: Vec<(Vec3, Vec3)>,
    pub blockers: Vec<Sphere>,
    /// Which blockers are their meshes exactly (none known: every light's casters count
    /// as approximate).
    pub casters: SphereCasters,
}

impl LightPathContext {
    /// Lights ranked by their brightness at `centre` alone.
    pub fn at(centre: Vec3) -> LightPathContext {
        LightPathContext {
            centre,
            ..LightPathContext::default()
        }
    }

    /// As [`LightPathContext::at`] the centre of `bounds`, knowing their extent (as the
    /// shadow maps' views see it), without receivers.
    pub fn of_bounds(bounds: &crate::scene::Aabb) -> LightPathContext {
        let (centre, radius_m) = super::shadow_maps::bounding_sphere(bounds);
        LightPathContext {
            centre,
            radius_m,
            ..LightPathContext::default()
        }
    }

    /// The context of `scene` shadowed by `blockers`: its centre, and up to
    /// `MAX_RECEIVERS` of its vertices spread evenly over all its objects.
    pub fn of_scene(scene: &Scene, blockers: &[Sphere]) -> LightPathContext {
        let total: usize = scene.objects.iter().map(|o| o.positions.len()).sum();
        let stride = total.div_ceil(MAX_RECEIVERS).max(1);
        let receivers = scene
            .objects
            .iter()
            .flat_map(|o| o.positions.iter().copied().zip(o.normals.iter().copied()))
            .step_by(stride)
            .filter(|(p, n)| p.is_finite() && n.is_normalized())
            .collect();
        LightPathContext {
            receivers,
            blockers: blockers.to_vec(),
            casters: SphereCasters::of_scene(scene, blockers),
            ..LightPathContext::of_bounds(&scene.bounds())
        }
    }

    /// The centre, or the origin for a scene without geometry (whose centre is not finite).
    pub(super) fn centre(&self) -> DVec3 {
        if self.centre.is_finite() {
            self.centre.as_dvec3()
        } else {
            DVec3::ZERO
        }
    }

    /// The receivers weighing one light: all of them, or with many blockers an even
    /// spread of them, so the tests stay within `MAX_TESTS_PER_LIGHT`.
    fn sampled_receivers(&self) -> impl Iterator<Item = &(Vec3, Vec3)> {
        let affordable = (MAX_TESTS_PER_LIGHT / self.blockers.len().max(1)).max(MIN_RECEIVERS);
        let stride = self.receivers.len().div_ceil(affordable).max(1);
        self.receivers.iter().step_by(stride)
    }

    /// The blockers that cut `light`'s disc as the receiver at `p` facing `n` sees it (the
    /// exact path's cap test without the lens); none where the light does not reach.
    fn blockers_cutting(&self, light: &GpuLight, p: Vec3, n: Vec3, min_cap_ratio: f64) -> impl Iterator<Item = usize> {
        let (p, n) = (p.as_dvec3(), n.as_dvec3());
        let inc = super::cpu::incidence(light, p);
        let lit = inc.irradiance != DVec3::ZERO && n.dot(inc.to_light) > 0.0;
        let disc = inc.cap_ratio.clamp(0.0, 1.0).asin();
        self.blockers.iter().enumerate().filter_map(move |(index, b)| {
            let cap = b.cap_from(p, n, min_cap_ratio).filter(|_| lit)?;
            (cap.distance_m - (b.radius_m as f64) < inc.distance_m
                && cap.direction.angle_between(inc.to_light) < disc + cap.ratio.asin())
            .then_some(index)
        })
    }

    /// Share of the receivers that `light` lights and at which some blocker cuts its disc;
    /// 1 without receivers.
    pub(super) fn shadowed_share(&self, light: &GpuLight, min_cap_ratio: f64) -> f64 {
        if self.receivers.is_empty() {
            return 1.0;
        }
        let (mut shadowed, mut count) = (0, 0);
        for (p, n) in self.sampled_receivers() {
            count += 1;
            if self.blockers_cutting(light, *p, *n, min_cap_ratio).next().is_some() {
                shadowed += 1;
            }
        }
        shadowed as f64 / count as f64
    }

    /// Whether every blocker that cuts `light`'s disc at the receivers is a sphere that is
    /// its mesh ([`SphereCasters`]) and every mesh has blockers: then the exact path draws
    /// the light's true shadows. False without receivers to look at.
    pub(super) fn shadowed_only_by_exact_spheres(&self, light: &GpuLight, min_cap_ratio: f64) -> bool {
        !self.receivers.is_empty()
            && !self.casters.unrepresented
            && self.casters.exact.contains(&true)
            && self.sampled_receivers().all(|(p, n)| {
                self.blockers_cutting(light, *p, *n, min_cap_ratio)
                    .all(|b| self.casters.is_exact(b))
            })
    }
}
