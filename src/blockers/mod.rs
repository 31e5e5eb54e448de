//! Shadow proxies: every mesh approximated by a set of spheres (Ren et al. 2006), the
//! blockers whose log-visibility caps the log-SH renderer sums.
//!
//! Each mesh is voxelised as a solid ([`voxel`]) and fitted by k-means spheres ([`fit`]).
//! The number of spheres comes from an error budget: k grows (1, 2, 3, 4, 6, 8, 12, …) until
//! the fit error — the volume where mesh and spheres disagree, over the mesh's volume — is
//! within budget, so a ball gets one sphere and a figure dozens. Meshes with no inside (open
//! surfaces, or thinner than a cell: floors, walls, cards) and meshes no sphere set fits
//! within [`BlockerSettings::max_error`] are fitted on their surface instead ([`surface`]:
//! discs for planar patches, spheres for tubes and lattices); the report says which. Fits
//! are cached in memory by a hash of the mesh and the settings.

pub mod disc;
pub mod fit;
pub mod surface;
pub mod voxel;

use std::collections::HashMap;
use std::sync::{Arc, Mutex, OnceLock};

use glam::Vec3;

use crate::scene::{MeshObject, Scene};
pub use disc::{MAX_DISCS, spheres_and_discs, within_disc_capacity};
use voxel::VoxelGrid;

/// One blocker in world space: a sphere, or — with a nonzero `disc_normal` — a flat disc of
/// that radius facing `disc_normal`, the proxy of a planar patch of an open or thin mesh
/// ([`surface`]).
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Sphere {
    pub center: Vec3,
    pub radius_m: f32,
    /// Unit normal of a disc blocker; zero for a sphere.
    #[serde(default)]
    pub disc_normal: Vec3,
}

/// A blocker's cap as a receiver sees it (`Sphere::cap_from`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BlockerCap {
    /// Unit direction from the receiver to the blocker's centre (a disc's: the mean
    /// direction over it).
    pub direction: glam::DVec3,
    pub distance_m: f64,
    /// sin of the cap's angular radius: r/d for a sphere; for a disc, that of the cap
    /// of the disc's solid angle.
    pub ratio: f64,
    /// 1 above the receiver's tangent plane, fading smoothly to 0 as the blocker sinks
    /// below it: smoothstep(−1, 1, (c − p)·n / h), h the blocker's half-extent along n.
    pub horizon: f64,
}

impl Sphere {
    /// A sphere blocker.
    pub fn ball(center: Vec3, radius_m: f32) -> Sphere {
        Sphere {
            center,
            radius_m,
            disc_normal: Vec3::ZERO,
        }
    }

    /// A disc blocker of radius `radius_m` facing `normal` (normalised here).
    pub fn disc(center: Vec3, radius_m: f32, normal: Vec3) -> Sphere {
        Sphere {
            center,
            radius_m,
            disc_normal: normal.normalize_or_zero(),
        }
    }

    pub fn is_disc(&self) -> bool {
        self.disc_normal != Vec3::ZERO
    }

    /// The cap this blocker covers in the sky of a receiver at `p` with unit normal `n`,
    /// or None for the blockers every shadow path skips: a sphere containing p (a
    /// sphere-fit artefact on its own mesh), a blocker too small in the sky (sin of its
    /// cap's radius < `min_cap_ratio`), and one wholly below the tangent plane. The fade
    /// keeps a fitted sphere straddling its own surface from darkening its receivers in
    /// blotches (a hard cut leaves them).
    ///
    /// A disc is taken as the cap of its solid angle around the mean direction over it
    /// ([`disc::disc_seen`]: a receiver just above a large disc sees it fill the
    /// hemisphere below); a receiver in the disc's plane (its own patch) sees nothing of
    /// it. A disc is not faded: its solid angle is its own, and it lies in no surface
    /// of its receivers (faded like a sphere over its radius, the floor's and the walls'
    /// discs counted only in part for the surfaces standing on them, whose foot then
    /// saw too much sky against the path tracer). It counts while any of it can be above
    /// the tangent plane.
    pub fn cap_from(&self, p: glam::DVec3, n: glam::DVec3, min_cap_ratio: f64) -> Option<BlockerCap> {
        let offset = self.center.as_dvec3() - p;
        let radius = self.radius_m as f64;
        let distance2 = offset.length_squared();
        let distance = distance2.sqrt();
        let (ratio, direction, half_extent) = if self.is_disc() {
            let normal = self.disc_normal.as_dvec3();
            let (solid_angle, direction) = disc::disc_seen(self.center.as_dvec3(), radius, normal, p);
            let tilt2 = (1.0 - n.dot(normal).powi(2)).max(0.0);
            (
                disc::cap_sine_of_solid_angle(solid_angle),
                direction,
                radius * tilt2.sqrt().max(1e-4),
            )
        } else {
            if distance2 <= radius * radius {
                return None;
            }
            (radius / distance, offset / distance, radius)
        };
        let t = ((offset.dot(n) / half_extent + 1.0) / 2.0).clamp(0.0, 1.0);
        let horizon = if self.is_disc() {
            if t > 0.0 { 1.0 } else { 0.0 }
        } else {
            t * t * (3.0 - 2.0 * t)
        };
        (ratio >= min_cap_ratio && horizon > 0.0).then_some(BlockerCap {
            direction,
            distance_m: distance,
            ratio,
            horizon,
        })
    }
}

/// How many spheres to use.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "snake_case", deny_unknown_fields)]
pub enum SphereBudget {
    /// Per mesh, the fewest spheres whose fit error is at most this (e.g. 0.35), or
    /// the best fit found once more spheres stop reducing the error.
    FitError(f32),
    /// About this many spheres in the whole scene, shared among meshes by volume.
    Total(usize),
}

#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct BlockerSettings {
    pub budget: SphereBudget,
    /// Most spheres for one mesh under [`SphereBudget::FitError`].
    pub max_spheres_per_mesh: usize,
    /// A mesh whose best solid fit errs more than this is not sphere-like: it is fitted on
    /// its surface instead ([`surface`]).
    pub max_error: f32,
    /// Voxel cells over a mesh's bounds: finer grids fit thin limbs better.
    pub cell_budget: usize,
}

impl BlockerSettings {
    /// Every problem with these settings, as (field, message) pairs.
    pub fn problems(&self) -> Vec<(&'static str, String)> {
        let mut problems = Vec::new();
        match self.budget {
            SphereBudget::FitError(e) if !(e.is_finite() && e > 0.0) => {
                problems.push(("budget", format!("fit error budget {e} must be positive")))
            }
            SphereBudget::Total(n) if n > 100_000 => {
                problems.push(("budget", format!("{n} spheres is more than the 100000 supported")))
            }
            _ => {}
        }
        if !(1..=4096).contains(&self.max_spheres_per_mesh) {
            problems.push((
                "max_spheres_per_mesh",
                format!("{} is outside 1..=4096", self.max_spheres_per_mesh),
            ));
        }
        if !(self.max_error.is_finite() && self.max_error > 0.0) {
            problems.push(("max_error", format!("{} must be positive", self.max_error)));
        }
        if !(1_000..=20_000_000).contains(&self.cell_budget) {
            problems.push((
                "cell_budget",
                format!("{} is outside 1000..=20000000 cells", self.cell_budget),
            ));
        }
        problems
    }
}

impl Default for BlockerSettings {
    fn default() -> Self {
        BlockerSettings {
            budget: SphereBudget::FitError(0.35),
            max_spheres_per_mesh: 64,
            max_error: 0.8,
            cell_budget: 150_000,
        }
    }
}

/// The spheres of one mesh and how well they fit it.
#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct SphereSet {
    pub spheres: Vec<Sphere>,
    /// |mesh △ spheres| / |mesh| of the chosen fit (0 for meshes without spheres).
    pub fit_error: f32,
    /// Why the mesh has no spheres, if it has none.
    pub skipped: Option<String>,
    /// Whether the blockers were fitted to the surface ([`surface`]: the mesh has no
    /// inside, or no sphere set fits its solid), `fit_error` then being the silhouettes'.
    #[serde(default)]
    pub on_surface: bool,
}

impl SphereSet {
    /// What casts the object's soft shadows, in a few words: its spheres and their fit
    /// error, its blockers on the surface (discs and spheres) and their silhouettes'
    /// error, or why it has none (the CLI's summary and the inspector say the same).
    pub fn describe(&self) -> String {
        match &self.skipped {
            Some(reason) => format!("no spheres ({reason})"),
            None if self.on_surface => format!(
                "{} blocker(s) on its surface ({} discs; it has no sphere-like inside), silhouette error {:.0} %",
                self.spheres.len(),
                self.spheres.iter().filter(|s| s.is_disc()).count(),
                100.0 * self.fit_error
            ),
            None => format!(
                "{} sphere(s), fit error {:.0} %",
                self.spheres.len(),
                100.0 * self.fit_error
            ),
        }
    }
}

/// The sphere sets of every object of a scene, in object order.
#[derive(Debug, Clone, Default, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct SceneBlockers {
    pub per_object: Vec<SphereSet>,
}

impl SceneBlockers {
    /// Every sphere of the scene, object after object.
    /// (At most [`MAX_DISCS`] discs: [`within_disc_capacity`].)
    pub fn spheres(&self) -> Vec<Sphere> {
        within_disc_capacity(self.per_object.iter().flat_map(|s| s.spheres.iter().copied()).collect())
    }

    /// The spheres of the objects `hidden` does not list (indices into the scene's
    /// objects): hidden objects cast no shadow. (At most [`MAX_DISCS`] discs.)
    pub fn shown_spheres(&self, hidden: &std::collections::BTreeSet<usize>) -> Vec<Sphere> {
        within_disc_capacity(
            self.per_object
                .iter()
                .enumerate()
                .filter(|(object, _)| !hidden.contains(object))
                .flat_map(|(_, s)| s.spheres.iter().copied())
                .collect(),
        )
    }

    pub fn sphere_count(&self) -> usize {
        self.per_object.iter().map(|s| s.spheres.len()).sum()
    }

    /// One line per object: its sphere count and fit error, or why it has none.
    pub fn report(&self, scene: &Scene) -> Vec<String> {
        self.per_object
            .iter()
            .zip(&scene.objects)
            .map(|(set, object)| format!("{}: {}", object.name, set.describe()))
            .collect()
    }
}

/// Sphere counts tried, in order, under [`SphereBudget::FitError`].
pub(crate) const K_LADDER: [usize; 14] = [1, 2, 3, 4, 6, 8, 12, 16, 24, 32, 48, 64, 96, 128];

/// Fits sphere sets to every object of `scene` (in parallel, cached per mesh).
pub fn fit_scene(scene: &Scene, settings: &BlockerSettings) -> SceneBlockers {
    use rayon::prelude::*;
    // The terrain (always the last object) shadows through its horizons, not spheres.
    let casters = match &scene.terrain {
        Some(terrain) => &scene.objects[..terrain.object.min(scene.objects.len())],
        None => &scene.objects[..],
    };
    if settings.budget == SphereBudget::Total(0) {
        // A budget of none means none: no object gets a sphere.
        return SceneBlockers {
            per_object: scene
                .objects
                .iter()
                .map(|_| SphereSet {
                    spheres: Vec::new(),
                    fit_error: 0.0,
                    skipped: Some("no sphere blockers asked for (a budget of 0)".to_string()),
                    on_surface: false,
                })
                .collect(),
        };
    }
    let grids: Vec<Arc<Solid>> = casters.par_iter().map(|o| solid(o, settings)).collect();
    let mut per_object: Vec<SphereSet> = match settings.budget {
        SphereBudget::FitError(_) => grids.par_iter().map(|solid| fit_solid(solid, settings, None)).collect(),
        SphereBudget::Total(total) => {
            // The total goes only to the meshes the automatic fit finds sphere-like: a
            // large wall or cyclorama would otherwise take most of it by volume and then
            // be refused, leaving the figures that do cast shadows with none.
            let automatic = BlockerSettings {
                budget: BlockerSettings::default().budget,
                ..*settings
            };
            let casters: Vec<bool> = grids
                .par_iter()
                .map(|solid| fit_solid(solid, &automatic, None).skipped.is_none())
                .collect();
            let volume_m3 = |g: &Solid| g.inside.len() as f64 * g.grid.cell_volume_m3() as f64;
            let caster_volume_m3: f64 = grids
                .iter()
                .zip(&casters)
                .filter(|(_, c)| **c)
                .map(|(g, _)| volume_m3(g))
                .sum();
            grids
                .par_iter()
                .zip(casters)
                .map(|(solid, caster)| {
                    if !caster {
                        return fit_solid(solid, &automatic, None);
                    }
                    let share = total as f64 * volume_m3(solid) / caster_volume_m3.max(f64::MIN_POSITIVE);
                    fit_solid(solid, settings, Some((share.round() as usize).max(1)))
                })
                .collect()
        }
    };
    // Meshes the solid fit leaves without spheres are fitted on their surface instead: no
    // mesh is dropped because it is open or thin.
    per_object
        .par_iter_mut()
        .zip(casters.par_iter())
        .for_each(|(set, object)| {
            if set.spheres.is_empty()
                && let Some(on_surface) = surface::fit_mesh(object, settings)
            {
                *set = on_surface;
            }
        });
    // The terrain's entry, after every caster's.
    per_object.resize_with(scene.objects.len(), || SphereSet {
        spheres: Vec::new(),
        fit_error: 0.0,
        skipped: Some("terrain: it shadows through its horizons".to_string()),
        on_surface: false,
    });
    SceneBlockers { per_object }
}

/// A voxelised mesh with its inside cells.
struct Solid {
    grid: VoxelGrid,
    inside: Vec<glam::IVec3>,
    key: blake3::Hash,
}

fn solid(object: &MeshObject, settings: &BlockerSettings) -> Arc<Solid> {
    let mut hasher = blake3::Hasher::new();
    hasher.update(bytemuck::cast_slice(&object.positions));
    hasher.update(bytemuck::cast_slice(&object.indices));
    hasher.update(&(settings.cell_budget as u64).to_le_bytes());
    let key = hasher.finalize();
    let grid = VoxelGrid::solid(&object.positions, &object.indices, settings.cell_budget);
    let inside = grid.inside_cells();
    Arc::new(Solid { grid, inside, key })
}

fn fit_solid(solid: &Solid, settings: &BlockerSettings, k: Option<usize>) -> SphereSet {
    let cache_key = {
        let mut hasher = blake3::Hasher::new();
        hasher.update(solid.key.as_bytes());
        hasher.update(format!("{settings:?} {k:?}").as_bytes());
        hasher.finalize()
    };
    static CACHE: OnceLock<Mutex<HashMap<blake3::Hash, SphereSet>>> = OnceLock::new();
    let cache = CACHE.get_or_init(Default::default);
    if let Some(hit) = cache.lock().unwrap_or_else(|e| e.into_inner()).get(&cache_key) {
        return hit.clone();
    }
    let set = fit_uncached(solid, settings, k);
    cache
        .lock()
        .unwrap_or_else(|e| e.into_inner())
        .insert(cache_key, set.clone());
    set
}

fn fit_uncached(solid: &Solid, settings: &BlockerSettings, k: Option<usize>) -> SphereSet {
    let none = |reason: &str| SphereSet {
        spheres: Vec::new(),
        fit_error: 0.0,
        skipped: Some(reason.to_string()),
        on_surface: false,
    };
    if solid.inside.is_empty() {
        return none("no inside: an open surface, or thinner than a voxel");
    }
    let max_k = settings.max_spheres_per_mesh.max(1);
    let (spheres, error) = match (k, settings.budget) {
        // A total asked for explicitly is honoured beyond the per-mesh cap of the ladder.
        (Some(k), _) => fit::fit_k(&solid.grid, &solid.inside, k),
        (None, SphereBudget::FitError(budget)) => {
            let mut best: Option<(Vec<Sphere>, f32)> = None;
            let mut steps_without_gain = 0;
            for k in K_LADDER.into_iter().filter(|&k| k <= max_k) {
                let (spheres, error) = fit::fit_k(&solid.grid, &solid.inside, k);
                let best_error = best.as_ref().map_or(f32::INFINITY, |(_, e)| *e);
                // More spheres that do not fit better only cost time in every frame.
                steps_without_gain = if error < best_error { 0 } else { steps_without_gain + 1 };
                if error < best_error {
                    best = Some((spheres, error));
                }
                if error <= budget || steps_without_gain >= 3 {
                    break;
                }
            }
            best.unwrap_or_default()
        }
        (None, SphereBudget::Total(total)) => fit::fit_k(&solid.grid, &solid.inside, total),
    };
    // An explicit count is honoured however well it fits: the mesh has already been
    // found sphere-like by the automatic fit.
    if spheres.is_empty() || (k.is_none() && error > settings.max_error) {
        return SphereSet {
            fit_error: error,
            ..none(&format!("not sphere-like: best fit error {:.0} %", 100.0 * error))
        };
    }
    SphereSet {
        spheres,
        fit_error: error,
        skipped: None,
        on_surface: false,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::shapes::{self, ShapeMesh};

    fn object(name: &str, mesh: ShapeMesh) -> MeshObject {
        mesh.into_object(name)
    }

    fn scene(objects: Vec<MeshObject>) -> Scene {
        Scene {
            objects,
            ..Default::default()
        }
    }

    #[test]
    fn a_total_budget_of_zero_fits_no_sphere_and_says_why() {
        let ball = shapes::uv_sphere(0.5, 32, 16);
        let scene = scene(vec![object("ball", ball)]);
        let none = fit_scene(
            &scene,
            &BlockerSettings {
                budget: SphereBudget::Total(0),
                ..BlockerSettings::default()
            },
        );
        assert_eq!(none.sphere_count(), 0);
        assert!(
            none.per_object[0]
                .skipped
                .as_deref()
                .is_some_and(|why| why.contains("0"))
        );
    }

    #[test]
    fn a_total_budget_goes_to_the_meshes_that_cast_shadows() {
        // A thin 8 m slab has 40× the ball's volume but is no sphere set: under a total of
        // 12 the ball must not be starved by it.
        let ball = shapes::uv_sphere(0.5, 32, 16).transformed(glam::Affine3A::from_translation(Vec3::Y));
        let slab = shapes::cuboid(Vec3::new(4.0, 0.1, 4.0));
        let scene = scene(vec![object("ball", ball), object("slab", slab)]);
        let automatic = fit_scene(&scene, &BlockerSettings::default());
        assert!(
            automatic.per_object[1].on_surface && !automatic.per_object[0].on_surface,
            "the slab is not sphere-like: {:?}",
            automatic.per_object[1]
        );
        for total in [4, 12] {
            let fitted = fit_scene(
                &scene,
                &BlockerSettings {
                    budget: SphereBudget::Total(total),
                    ..BlockerSettings::default()
                },
            );
            assert_eq!(fitted.per_object[0].spheres.len(), total, "{:?}", fitted.per_object[0]);
            // The slab keeps the blockers on its surface it has without a total.
            assert_eq!(fitted.per_object[1], automatic.per_object[1]);
        }
    }

    #[test]
    fn a_ball_is_one_sphere_of_its_own_radius() {
        let ball =
            shapes::uv_sphere(0.5, 48, 24).transformed(glam::Affine3A::from_translation(Vec3::new(1.0, 2.0, 3.0)));
        let fitted = fit_scene(&scene(vec![object("ball", ball)]), &BlockerSettings::default());
        let set = &fitted.per_object[0];
        assert_eq!(set.spheres.len(), 1, "{set:?}");
        let s = set.spheres[0];
        assert!(s.center.distance(Vec3::new(1.0, 2.0, 3.0)) < 0.02, "{s:?}");
        assert!((s.radius_m - 0.5).abs() < 0.03, "{s:?}");
        assert!(set.fit_error < 0.15, "{set:?}");
    }

    #[test]
    fn an_elongated_box_needs_more_spheres_than_a_ball() {
        let bar = shapes::cuboid(Vec3::new(2.0, 0.25, 0.25));
        let fitted = fit_scene(&scene(vec![object("bar", bar)]), &BlockerSettings::default());
        let set = &fitted.per_object[0];
        // Spheres cannot fill a box's corners: the ladder stops when more stop helping.
        assert!((4..=48).contains(&set.spheres.len()), "{set:?}");
        assert!(set.fit_error <= 0.6, "{set:?}");
        // Spheres stay within the bar (up to the voxel size).
        for s in &set.spheres {
            assert!(s.center.y.abs() + s.radius_m < 0.25 + 0.11, "{s:?}");
        }
    }

    #[test]
    fn open_and_flat_meshes_cast_through_discs_on_their_surface() {
        // Neither a one-quad floor nor a 4 cm slab has an inside the voxels see: both get
        // discs lying in their plane, and say so.
        let floor = shapes::plane(10.0, 4, 1.0);
        let slab = shapes::cuboid(Vec3::new(5.0, 0.02, 5.0));
        let scene = scene(vec![object("floor", floor), object("slab", slab)]);
        let fitted = fit_scene(&scene, &BlockerSettings::default());
        for set in &fitted.per_object {
            assert!(
                set.on_surface && set.skipped.is_none() && !set.spheres.is_empty(),
                "{set:?}"
            );
            for disc in &set.spheres {
                assert!(
                    disc.is_disc() && disc.disc_normal.y.abs() > 0.999 && disc.center.y.abs() < 0.03,
                    "{disc:?}"
                );
            }
        }
        assert!(fitted.report(&scene).iter().all(|line| line.contains("on its surface")));
    }

    #[test]
    fn a_total_budget_is_shared_by_volume() {
        let big = shapes::uv_sphere(1.0, 32, 16);
        let small = shapes::uv_sphere(0.5, 32, 16).transformed(glam::Affine3A::from_translation(Vec3::X * 4.0));
        let settings = BlockerSettings {
            budget: SphereBudget::Total(18),
            ..Default::default()
        };
        let fitted = fit_scene(&scene(vec![object("big", big), object("small", small)]), &settings);
        let counts: Vec<usize> = fitted.per_object.iter().map(|s| s.spheres.len()).collect();
        assert!(counts[0] > counts[1] && counts[1] >= 1, "{counts:?}");
        assert!((16..=18).contains(&fitted.sphere_count()), "{counts:?}");
    }
}
