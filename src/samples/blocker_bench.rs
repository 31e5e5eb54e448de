//! A benchmark scene class for the blocker walk (`cargo bench --profile dev --bench frame`,
//! group `frame/sphere-count`): thin casters — a lattice ball of thin rings, a double
//! helix of thin tubes and a torus-like ring, about 45,000 triangles with the floor —
//! under one rect light, and any number of sphere blockers spread over the casters'
//! surfaces (600, 5,000 and 20,000 in the bench), and any number of lamps with a range
//! (`add_lamps`). The casters are our own, built from
//! `scene::shapes`; the sphere count is the knob, so the frame's cost can be read against
//! it.

use glam::{Affine3A, Quat, Vec3, Vec4};

use crate::blockers::Sphere;
use crate::random::SplitMix64;
use crate::scene::shapes::{self, ShapeMesh};
use crate::scene::{Camera, Light, LightKind, Material, Scene};

/// The floor (object 0, an 8 m square of 96 × 96 quads) and the three casters.
pub fn thin_casters_scene() -> Scene {
    let mut scene = Scene::default();
    scene.materials.push(Material {
        base_color: Vec4::new(0.75, 0.75, 0.75, 1.0),
        metallic: 0.0,
        ..Material::default()
    });
    scene.objects.push(shapes::plane(8.0, 96, 1.0).into_object("floor"));
    scene.objects.push(lattice_ball().into_object("lattice ball"));
    scene.objects.push(double_helix().into_object("double helix"));
    scene.objects.push(
        shapes::torus(0.45, 0.06, 128, 24)
            .transformed(Affine3A::from_rotation_translation(
                Quat::from_rotation_x(1.2),
                Vec3::new(1.4, 0.7, 0.2),
            ))
            .into_object("ring"),
    );
    scene.lights.push(Light {
        name: "panel".into(),
        kind: LightKind::Rect {
            width_m: 1.2,
            height_m: 0.8,
            turn_rad: 0.0,
        },
        color: Vec3::ONE,
        intensity: 40.0,
        position: Vec3::new(0.3, 3.2, 0.6),
        direction: Vec3::NEG_Y,
        range: None,
        locked: false,
    });
    scene
}

/// `count` lamps with a range added to the set (`frame/lamp-count`: a frame's cost against
/// its lights' count): warm point lights 0.4 m over the floor in a square grid over its
/// middle 7 m, each of 0.1 cd and 1 m range, so that each lights a patch of floor and
/// the casters near it. Past the shadow maps' views (384: 64 cubes) they take the SH path.
pub fn add_lamps(scene: &mut Scene, count: usize) {
    let side = (count as f32).sqrt().ceil().max(1.0) as usize;
    let at = |t: usize| -3.5 + 7.0 * (t as f32 + 0.5) / side as f32;
    for k in 0..count {
        scene.lights.push(Light {
            name: format!("lamp {k}"),
            kind: LightKind::Point,
            color: Vec3::new(1.0, 0.8, 0.6),
            intensity: 0.1,
            position: Vec3::new(at(k % side), 0.4, at(k / side)),
            direction: Vec3::NEG_Y,
            range: Some(1.0),
            locked: false,
        });
    }
}

/// The set's panel split into `count` panels (a studio rig of soft boxes, none with a
/// range) of the same size on a 1.5 m ring at its height around where it hung, sharing
/// its intensity; `count` 1 (or 0) leaves the panel as it is. Past eight such lights on
/// the SH path, reaching every point, no point opens light windows on the blockers
/// (`shading::light_windows`).
pub fn ring_of_panels(scene: &mut Scene, count: usize) {
    let Some(index) = scene.lights.iter().position(|light| light.name == "panel") else {
        return;
    };
    if count <= 1 {
        return;
    }
    let panel = scene.lights.remove(index);
    for k in 0..count {
        let angle = k as f32 / count as f32 * std::f32::consts::TAU;
        scene.lights.push(Light {
            name: format!("panel {k}"),
            position: panel.position + 1.5 * Vec3::new(angle.cos(), 0.0, angle.sin()),
            intensity: panel.intensity / count as f32,
            ..panel.clone()
        });
    }
}

/// The camera the bench frames the set with.
pub fn thin_casters_camera() -> Camera {
    Camera::looking_at(
        Vec3::new(0.0, 2.6, 4.2),
        Vec3::new(0.0, 0.6, 0.0),
        45f32.to_radians(),
        0.05,
    )
}

/// A ball 1.2 m across of six great circles through its poles and five parallels, each
/// a tube 2.4 cm thick, centred 1 m up on the left.
fn lattice_ball() -> ShapeMesh {
    let radius = 0.6;
    let centre = Vec3::new(-1.3, 1.0, 0.0);
    let mut mesh = ShapeMesh::default();
    for k in 0..6 {
        let meridian = Quat::from_rotation_y(k as f32 * std::f32::consts::PI / 6.0)
            * Quat::from_rotation_x(0.5 * std::f32::consts::PI);
        mesh = mesh.merged(
            shapes::torus(radius, 0.012, 96, 6).transformed(Affine3A::from_rotation_translation(meridian, centre)),
        );
    }
    for k in 1..=5 {
        let polar = k as f32 * std::f32::consts::PI / 6.0;
        let ring = shapes::torus(radius * polar.sin(), 0.012, 96, 6);
        mesh = mesh.merged(ring.transformed(Affine3A::from_translation(centre + Vec3::Y * (radius * polar.cos()))));
    }
    mesh
}

/// Two intertwined helices of 3 cm tubes, two turns each, 0.2 to 1.4 m up in the middle.
fn double_helix() -> ShapeMesh {
    let mut mesh = ShapeMesh::default();
    for strand in 0..2 {
        let point = |t: f32| {
            let angle = t * 4.0 * std::f32::consts::PI + strand as f32 * std::f32::consts::PI;
            Vec3::new(0.25 * angle.cos(), 0.2 + 1.2 * t, -0.6 + 0.25 * angle.sin())
        };
        mesh = mesh.merged(shapes::tube_along(point, 30, 0.015, 6));
    }
    mesh
}

/// `count` spheres spread over the casters' surfaces (every object but the floor,
/// object 0): centres at points drawn uniformly by area (a fixed seed, so the same set
/// every run), each sunk by its radius along the surface's normal, the radius chosen so
/// that the spheres' discs would cover the casters' area about twice over, and at least
/// 1 cm.
pub fn spheres_on_casters(scene: &Scene, count: usize) -> Vec<Sphere> {
    let triangles: Vec<[Vec3; 3]> = scene
        .objects
        .iter()
        .skip(1)
        .flat_map(|object| (object.indices.chunks_exact(3)).map(|t| [0, 1, 2].map(|k| object.positions[t[k] as usize])))
        .collect();
    let areas: Vec<f32> = triangles
        .iter()
        .map(|[a, b, c]| 0.5 * (*b - *a).cross(*c - *a).length())
        .collect();
    let total: f32 = areas.iter().sum();
    if count == 0 || total <= 0.0 {
        return Vec::new();
    }
    let radius_m = (2.0 * total / (count as f32 * std::f32::consts::PI)).sqrt().max(0.01);
    let cumulative: Vec<f32> = areas
        .iter()
        .scan(0.0, |sum, a| {
            *sum += a;
            Some(*sum)
        })
        .collect();
    let mut random = SplitMix64(0x5eed_b10c);
    (0..count)
        .map(|_| {
            let pick = random.next_f64() as f32 * total;
            let index = cumulative.partition_point(|&c| c < pick).min(triangles.len() - 1);
            let [a, b, c] = triangles[index];
            let (mut u, mut v) = (random.next_f64() as f32, random.next_f64() as f32);
            if u + v > 1.0 {
                (u, v) = (1.0 - u, 1.0 - v);
            }
            let point = a + (b - a) * u + (c - a) * v;
            let normal = (b - a).cross(c - a).normalize_or_zero();
            Sphere {
                center: point - normal * radius_m,
                radius_m,
                disc_normal: Vec3::ZERO,
            }
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_set_has_about_45k_triangles_and_its_spheres_sit_on_the_casters() {
        let scene = thin_casters_scene();
        let triangles: usize = scene.objects.iter().map(|o| o.indices.len() / 3).sum();
        assert!((35_000..=60_000).contains(&triangles), "{triangles} triangles");
        assert!(scene.lights.iter().all(|l| l.problems().is_empty()));
        for count in [0, 600, 5000] {
            let spheres = spheres_on_casters(&scene, count);
            assert_eq!(spheres.len(), count);
            let caster_vertices: Vec<Vec3> = scene
                .objects
                .iter()
                .skip(1)
                .flat_map(|o| o.positions.iter().copied())
                .collect();
            for sphere in spheres.iter().step_by(97) {
                let nearest = caster_vertices
                    .iter()
                    .map(|p| p.distance(sphere.center))
                    .fold(f32::INFINITY, f32::min);
                // Sunk by its radius from a point of a triangle no wider than 8 cm.
                assert!(nearest <= sphere.radius_m + 0.08, "{sphere:?}: {nearest} m");
            }
        }
        // More spheres, smaller ones: the area they cover stays about the same.
        let r = |n| spheres_on_casters(&scene, n)[0].radius_m;
        assert!(r(600) > r(5000) && r(5000) >= r(20_000));
    }
}
