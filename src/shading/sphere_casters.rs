//! Which blockers are their meshes exactly: a mesh whose every vertex lies on the surface of
//! one of the solid spheres fitted inside its bounds *is* those spheres (a ball, a bead, a
//! lamp globe), up to its tessellation. For a light shadowed only by such spheres the
//! exact path's closed-form share of the light's disc (`src/penumbra/`) is the true
//! shadow, sharper than shadow maps can place it and cheaper, at any light size; Auto
//! sends such lights that way (`light_paths::shading_lights`).

use glam::Vec3;

use crate::blockers::Sphere;
use crate::scene::Scene;

/// How far off a sphere's surface a vertex may lie, as a share of the radius, and still
/// count as on it: a sphere fitted to a 24 × 12 UV sphere is 1.1 % smaller than its
/// vertices' radius (its faces sag 0.9 % between them); a box or a capsule misses by far
/// more (a cube's corners lie 73 % beyond its inscribed sphere).
pub const ON_SURFACE_TOLERANCE: f32 = 0.02;

/// What the blockers stand for, as far as the exact path can tell.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct SphereCasters {
    /// Per blocker: a sphere on whose surface some mesh's vertices lie, that mesh lying
    /// entirely on such spheres.
    pub exact: Vec<bool>,
    /// Some object has no blocker inside its bounds (none fitted, hidden, or a budget of
    /// none) or the scene has a terrain (which shadows through its horizons): shadows no
    /// blocker stands for, which only the shadow maps draw.
    pub unrepresented: bool,
}

impl SphereCasters {
    /// Looks at every object of `scene` against `blockers`. Each object stops at its
    /// first vertex off every sphere, so only meshes that are spheres are read whole.
    pub fn of_scene(scene: &Scene, blockers: &[Sphere]) -> SphereCasters {
        let mut exact = vec![false; blockers.len()];
        let mut unrepresented = scene.terrain.is_some();
        for object in &scene.objects {
            let bounds = object.bounds();
            if bounds.is_empty() {
                continue;
            }
            let inside = |c: Vec3| c.cmpge(bounds.min - 1e-4).all() && c.cmple(bounds.max + 1e-4).all();
            let own: Vec<usize> = (0..blockers.len()).filter(|&b| inside(blockers[b].center)).collect();
            if own.is_empty() {
                unrepresented = true;
                continue;
            }
            let spheres: Vec<usize> = own.into_iter().filter(|&b| !blockers[b].is_disc()).collect();
            let mut touched = vec![false; spheres.len()];
            let on_spheres = !spheres.is_empty()
                && object.positions.iter().all(|&v| {
                    let on = spheres.iter().position(|&b| {
                        let s = &blockers[b];
                        ((v - s.center).length() - s.radius_m).abs() <= ON_SURFACE_TOLERANCE * s.radius_m
                    });
                    if let Some(k) = on {
                        touched[k] = true;
                    }
                    on.is_some()
                });
            if on_spheres {
                for (k, &b) in spheres.iter().enumerate() {
                    exact[b] |= touched[k];
                }
            }
        }
        SphereCasters { exact, unrepresented }
    }

    /// Whether blocker `index` is a sphere that is its mesh.
    pub fn is_exact(&self, index: usize) -> bool {
        self.exact.get(index).copied().unwrap_or(false)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::blockers::{BlockerSettings, fit_scene};
    use crate::scene::shapes;

    fn scene_of(objects: Vec<crate::scene::MeshObject>) -> Scene {
        Scene {
            objects,
            ..Scene::default()
        }
    }

    fn ball(radius_m: f32, at: Vec3, segments: u32) -> crate::scene::MeshObject {
        shapes::uv_sphere(radius_m, segments, segments / 2)
            .transformed(glam::Affine3A::from_translation(at))
            .into_object("ball")
    }

    /// Balls, coarse or fine, are their fitted spheres; a cube, a floor's disc and a
    /// two-ball mesh fitted with one sphere are not; a mesh without blockers is
    /// unrepresented.
    #[test]
    fn balls_are_their_spheres_and_nothing_else_is() {
        let floor = shapes::plane(8.0, 8, 1.0).into_object("floor");
        let fine = ball(0.35, Vec3::new(0.0, 0.6, 0.0), 96);
        let coarse = ball(0.3, Vec3::new(2.0, 0.5, 0.0), 24);
        let scene = scene_of(vec![floor, fine, coarse]);
        let blockers = fit_scene(&scene, &BlockerSettings::default()).spheres();
        let casters = SphereCasters::of_scene(&scene, &blockers);
        assert!(!casters.unrepresented);
        let exact: Vec<bool> = (0..blockers.len()).map(|b| casters.is_exact(b)).collect();
        let discs: Vec<bool> = blockers.iter().map(|b| b.is_disc()).collect();
        // The floor's disc is not exact, each ball's one sphere is.
        assert_eq!(exact, discs.iter().map(|d| !d).collect::<Vec<_>>(), "{blockers:?}");

        // A cube's fitted spheres are not its surface.
        let cube = shapes::cuboid(Vec3::splat(0.5)).into_object("cube");
        let scene = scene_of(vec![cube]);
        let blockers = fit_scene(&scene, &BlockerSettings::default()).spheres();
        assert!(!blockers.is_empty());
        let casters = SphereCasters::of_scene(&scene, &blockers);
        assert!(casters.exact.iter().all(|e| !e));

        // A ball with a wrongly sized sphere (3 % too small) is not exact either.
        let scene = scene_of(vec![ball(1.0, Vec3::ZERO, 48)]);
        let shrunk = [Sphere::ball(Vec3::ZERO, 0.97)];
        assert!(!SphereCasters::of_scene(&scene, &shrunk).is_exact(0));
        assert!(SphereCasters::of_scene(&scene, &[Sphere::ball(Vec3::ZERO, 0.995)]).is_exact(0));

        // No blockers: the ball casts a shadow nothing stands for.
        assert!(SphereCasters::of_scene(&scene, &[]).unrepresented);
    }
}
