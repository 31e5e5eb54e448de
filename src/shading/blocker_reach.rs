//! How many blockers a surface point sees, on average over a scene's surfaces: what the
//! SH path's blocker walk costs a pixel (the blockers it visits) and what it finds (those
//! that shadow the point), for the `render` summary and the editor's blocker overlay.
//! Receivers are the shown meshes' vertices, evenly strided to at most a given number, each
//! with its normal; the counts are the f64 twin's walk (`cpu::blockers_in_reach`), the
//! same tests in the same order as logsh.wgsl's.

use std::collections::BTreeSet;

use glam::DVec3;

use super::ShadowSettings;
use super::cpu::blockers_in_reach;
use crate::blockers::Sphere;
use crate::scene::Scene;

/// Means over receivers of [`crate::shading::cpu::BlockersInReach`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MeanBlockersInReach {
    /// Blockers the walk visits per receiver (spheres of groups in reach, group
    /// stand-ins, discs).
    pub walked: f64,
    /// Blockers whose cap shadows the receiver.
    pub shadowing: f64,
    /// Receivers averaged over.
    pub receivers: usize,
}

impl MeanBlockersInReach {
    /// "23.4 visited and 5.1 shadowing per surface point": how the summary and the
    /// overlay say it.
    pub fn in_words(&self) -> String {
        format!(
            "{:.1} visited and {:.1} shadowing per surface point",
            self.walked, self.shadowing
        )
    }
}

/// The means over at most `max_receivers` vertices of `scene`'s objects not in `hidden`;
/// None without such a vertex.
pub fn mean_blockers_in_reach(
    settings: &ShadowSettings,
    blockers: &[Sphere],
    scene: &Scene,
    hidden: &BTreeSet<usize>,
    max_receivers: usize,
) -> Option<MeanBlockersInReach> {
    let shown: Vec<_> = scene
        .objects
        .iter()
        .enumerate()
        .filter(|(index, _)| !hidden.contains(index))
        .map(|(_, object)| object)
        .collect();
    let total: usize = shown.iter().map(|o| o.positions.len().min(o.normals.len())).sum();
    if total == 0 || max_receivers == 0 {
        return None;
    }
    let stride = total.div_ceil(max_receivers);
    let (mut walked, mut shadowing, mut receivers) = (0usize, 0usize, 0usize);
    let mut first = 0usize;
    for object in shown {
        let count = object.positions.len().min(object.normals.len());
        // The global indices k · stride that fall in this object.
        let mut index = first.div_ceil(stride) * stride - first;
        while index < count {
            let p = object.positions[index].as_dvec3();
            let n = object.normals[index].as_dvec3().normalize_or(DVec3::Z);
            if p.is_finite() {
                let reach = blockers_in_reach(settings, blockers, p, n);
                walked += reach.walked;
                shadowing += reach.shadowing;
                receivers += 1;
            }
            index += stride;
        }
        first += count;
    }
    (receivers > 0).then(|| MeanBlockersInReach {
        walked: walked as f64 / receivers as f64,
        shadowing: shadowing as f64 / receivers as f64,
        receivers,
    })
}

#[cfg(test)]
mod tests {
    use glam::Vec3;

    use super::*;
    use crate::scene::MeshObject;

    /// A floor of `side` × `side` vertices, 1 m apart, facing up.
    fn floor(side: usize) -> MeshObject {
        let mut object = MeshObject::default();
        for i in 0..side {
            for j in 0..side {
                object.positions.push(Vec3::new(i as f32, 0.0, j as f32));
                object.normals.push(Vec3::Y);
            }
        }
        object
    }

    fn sphere(center: Vec3, radius_m: f32) -> Sphere {
        Sphere {
            center,
            radius_m,
            disc_normal: Vec3::ZERO,
        }
    }

    #[test]
    fn a_sphere_over_a_small_floor_is_seen_from_every_vertex_and_one_under_it_from_none() {
        let settings = ShadowSettings::default();
        let scene = Scene {
            objects: vec![floor(3)],
            ..Scene::default()
        };
        let none = BTreeSet::new();
        let above = mean_blockers_in_reach(&settings, &[sphere(Vec3::new(1.0, 1.0, 1.0), 0.5)], &scene, &none, 100)
            .expect("vertices");
        assert_eq!(above.receivers, 9);
        assert_eq!((above.walked, above.shadowing), (1.0, 1.0));
        let below = mean_blockers_in_reach(&settings, &[sphere(Vec3::new(1.0, -2.0, 1.0), 0.5)], &scene, &none, 100)
            .expect("vertices");
        assert_eq!(
            below.shadowing, 0.0,
            "a sphere below every vertex's horizon shadows none"
        );
    }

    #[test]
    fn a_far_sphere_is_out_of_reach_and_hidden_objects_are_left_out() {
        let settings = ShadowSettings::default();
        let scene = Scene {
            objects: vec![floor(3), floor(2)],
            ..Scene::default()
        };
        // Beyond its influence distance r / min_cap_ratio from every vertex.
        let far = sphere(Vec3::new(1.0, 1000.0, 1.0), 0.1);
        let seen = mean_blockers_in_reach(&settings, &[far], &scene, &BTreeSet::new(), 100).expect("vertices");
        assert_eq!((seen.walked, seen.shadowing, seen.receivers), (0.0, 0.0, 13));
        let hidden = BTreeSet::from([0]);
        let shown = mean_blockers_in_reach(&settings, &[far], &scene, &hidden, 100).expect("vertices");
        assert_eq!(shown.receivers, 4);
        assert!(mean_blockers_in_reach(&settings, &[far], &scene, &BTreeSet::from([0, 1]), 100).is_none());
    }

    #[test]
    fn receivers_are_strided_to_the_limit() {
        let settings = ShadowSettings::default();
        let scene = Scene {
            objects: vec![floor(10), floor(10)],
            ..Scene::default()
        };
        let seen = mean_blockers_in_reach(&settings, &[], &scene, &BTreeSet::new(), 30).expect("vertices");
        // 200 vertices at a stride of 7: indices 0, 7, …, 196.
        assert_eq!(seen.receivers, 29);
    }
}
