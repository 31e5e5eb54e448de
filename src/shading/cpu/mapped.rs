//! The f64 twin of the shadow maps (`shading::shadow_maps`): the share of a light a
//! surface point sees past the scene's triangles, by ray casts on the bake's BVH — the
//! exact visibility the maps approach as they grow.

use glam::DVec3;

use super::Incidence;
use crate::bake::scene_bvh::SceneBvh;

/// The exact visibility a shadow map approximates: 1 when nothing in `occluders` cuts the
/// segment from `p` (lifted off its surface along `n` by a millionth of the scene's
/// scale, `lift_m`) toward the light `to_light` at `distance_m` (infinite for the sun),
/// else 0.
pub fn ray_visibility(occluders: &SceneBvh, p: DVec3, n: DVec3, to_light: DVec3, distance_m: f64, lift_m: f64) -> f64 {
    let origin = p + n * lift_m.copysign(n.dot(to_light));
    let t_max = if distance_m.is_finite() {
        (distance_m - 2.0 * lift_m).max(0.0)
    } else {
        f64::INFINITY
    };
    let blocked = occluders.occluded(
        origin.as_vec3(),
        to_light.as_vec3(),
        lift_m as f32,
        t_max.min(f32::MAX as f64) as f32,
    );
    if blocked { 0.0 } else { 1.0 }
}

/// Rays [`mapped_visibility`] casts toward a sized light's disc.
pub const DISC_RAYS: usize = 64;

/// The golden angle (radians): successive points of a Vogel spiral turn by it, which
/// spreads any number of them evenly over a disc (Vogel 1979). WGSL `GOLDEN_ANGLE`.
pub const GOLDEN_ANGLE_RAD: f64 = 2.399_963_229_728_653;

/// The `k`-th of `count` points of a Vogel spiral over the unit disc: radius
/// √((k + ½)/count), angle k times the golden angle (equal areas per point).
pub fn vogel_point(k: usize, count: usize) -> (f64, f64) {
    let radius = ((k as f64 + 0.5) / count as f64).sqrt();
    let angle = k as f64 * GOLDEN_ANGLE_RAD;
    (radius * angle.cos(), radius * angle.sin())
}

/// The exact visibility a light's shadow maps approximate at the surface point `p` with
/// normal `n`, the light seen as `inc`: for a light of no size, [`ray_visibility`] toward
/// it; for a sphere or area light, the share of [`DISC_RAYS`] rays spread over its disc
/// (the cap of sine `inc.cap_ratio` around `inc.to_light`, as the exact path takes it,
/// sampled on the plane through the light's centre facing `p`) that nothing in
/// `occluders` stops.
pub fn mapped_visibility(occluders: &SceneBvh, p: DVec3, n: DVec3, inc: &Incidence) -> f64 {
    let lift_m = 1e-4 * (1.0 + p.length());
    let sine = inc.cap_ratio.clamp(0.0, 1.0);
    if sine == 0.0 || !inc.distance_m.is_finite() {
        return ray_visibility(occluders, p, n, inc.to_light, inc.distance_m, lift_m);
    }
    let tan_half = sine / (1.0 - sine * sine).max(1e-12).sqrt();
    let (t1, t2) = inc.to_light.any_orthonormal_pair();
    let free: f64 = (0..DISC_RAYS)
        .map(|k| {
            let (x, y) = vogel_point(k, DISC_RAYS);
            let offset = (t1 * x + t2 * y) * tan_half;
            let to_target = inc.to_light + offset;
            let length = to_target.length();
            ray_visibility(occluders, p, n, to_target / length, inc.distance_m * length, lift_m)
        })
        .sum();
    free / DISC_RAYS as f64
}

#[cfg(test)]
mod tests {
    use glam::Vec3;

    use super::*;
    use crate::shading::gpu_types::GpuLight;

    /// A sphere light straight above a receiver, a blocker plane halfway covering x < 0:
    /// half the disc is hidden (the Vogel spiral's 64 points split within a few of half);
    /// no blocker: all of it; a blocker over everything: none.
    #[test]
    fn the_disc_rays_see_the_share_of_a_sized_light_a_blocker_hides() {
        use crate::scene::{Scene, shapes};
        let light = GpuLight::new(&crate::scene::Light {
            name: "light".into(),
            kind: crate::scene::LightKind::Sphere { radius_m: 1.0 },
            color: Vec3::ONE,
            intensity: 1.0,
            position: Vec3::new(0.0, 10.0, 0.0),
            direction: Vec3::NEG_Y,
            range: None,
            locked: false,
        });
        let p = DVec3::ZERO;
        let inc = super::super::incidence(&light, p);
        let visibility_under = |blocker: Option<(f32, f32)>| {
            let mut scene = Scene::default();
            scene.materials.push(Default::default());
            scene.objects.push(
                shapes::plane(0.1, 1, 1.0)
                    .transformed(glam::Affine3A::from_translation(Vec3::new(0.0, -5.0, 0.0)))
                    .into_object("floor far below"),
            );
            if let Some((size, x)) = blocker {
                scene.objects.push(
                    shapes::plane(size, 1, 1.0)
                        .transformed(glam::Affine3A::from_translation(Vec3::new(x, 5.0, 0.0)))
                        .into_object("blocker"),
                );
            }
            let bvh = SceneBvh::build(&scene);
            mapped_visibility(&bvh, p, DVec3::Y, &inc)
        };
        assert_eq!(visibility_under(None), 1.0);
        assert_eq!(visibility_under(Some((40.0, 0.0))), 0.0);
        let half = visibility_under(Some((20.0, -10.0)));
        assert!((half - 0.5).abs() <= 3.0 / DISC_RAYS as f64, "{half}");
    }
}
