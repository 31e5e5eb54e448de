//! "terrain": rolling hills (a generated height field) with the figure, a ring of standing
//! stones and boulders on them, under a low sun (a small sphere light), a warm lantern and
//! the sky: shadows of the hills on the objects and of the objects on the hills.

use glam::{Affine3A, Quat, Vec3};

use super::figure::figure_mesh;
use crate::scene::gltf_write::{GltfBuilder, LightSpec, MaterialSpec};
use crate::scene::shapes::{self, ShapeMesh};
use crate::scene::{Light, LightKind, TerrainSpec};
use crate::terrain::HeightField;

/// The sample's terrain: 129² samples over 30 m × 30 m, 7 m of relief.
pub fn terrain_spec() -> TerrainSpec {
    TerrainSpec {
        center_m: [0.0, -3.0, 0.0],
        ..TerrainSpec::hills(11, 129, 30.0, 7.0)
    }
}

fn ground_height(field: &HeightField, x: f32, z: f32) -> f32 {
    field.height_at(x as f64, z as f64) as f32
}

pub fn terrain_glb(field: &HeightField) -> Vec<u8> {
    let mut b = GltfBuilder::new();
    let stone = b.add_material(&MaterialSpec::plain("stone", [0.55, 0.53, 0.5], 0.8));
    let skin = b.add_material(&MaterialSpec::plain("mannequin", [0.78, 0.62, 0.48], 0.45));
    let add = |b: &mut GltfBuilder, name: &str, mesh: ShapeMesh, material: usize, at: Vec3| {
        b.add_shape(name, &mesh, material, at, Quat::IDENTITY);
    };
    let figure_at = Vec3::new(1.0, ground_height(field, 1.0, 2.0) - 0.02, 2.0);
    add(&mut b, "Figure", figure_mesh(), skin, figure_at);
    // Standing stones in a ring round the figure, sunk a little into the ground.
    for k in 0..7 {
        let angle = k as f32 * std::f32::consts::TAU / 7.0 + 0.3;
        let (x, z) = (1.0 + 4.5 * angle.cos(), 2.0 + 4.5 * angle.sin());
        let height = 1.6 + 0.4 * ((k * 5) % 3) as f32;
        let slab = shapes::cuboid(Vec3::new(0.45, height / 2.0, 0.25))
            .transformed(Affine3A::from_rotation_y(angle + std::f32::consts::FRAC_PI_2));
        add(
            &mut b,
            &format!("Stone {}", k + 1),
            slab,
            stone,
            Vec3::new(x, ground_height(field, x, z) + height / 2.0 - 0.2, z),
        );
    }
    for (k, (x, z, r)) in [(-4.0, -2.0, 0.8), (6.0, -3.0, 0.6), (-3.5, 5.5, 1.0), (7.0, 5.0, 0.7)]
        .into_iter()
        .enumerate()
    {
        let boulder = shapes::uv_sphere(1.0, 32, 16).transformed(Affine3A::from_scale(Vec3::new(r, 0.75 * r, 0.9 * r)));
        add(
            &mut b,
            &format!("Boulder {}", k + 1),
            boulder,
            stone,
            Vec3::new(x, ground_height(field, x, z) + 0.4 * r, z),
        );
    }
    b.add_light_node(
        "Lantern",
        &LightSpec::Point {
            color: [1.0, 0.7, 0.4],
            intensity_cd: 8.0,
        },
        Vec3::new(-1.5, ground_height(field, -1.5, 3.5) + 1.2, 3.5),
        Vec3::NEG_Y,
    );
    let eye = Vec3::new(-8.0, 7.0, 14.0);
    let target = Vec3::new(1.0, ground_height(field, 1.0, 2.0) + 0.5, 2.0);
    b.add_camera_node("Overview", 0.75, 0.1, eye, target - eye, Vec3::Y);
    b.to_glb()
}

/// The low sun: a sphere light 200 m away and 1.5° across (small enough for the exact
/// shadow path), 15° above the horizon on the camera's left; I/d² gives 4 lux on a
/// surface facing it.
pub fn sun() -> Light {
    let direction_to_sun = Vec3::new(-0.8, 0.26, 0.3).normalize();
    Light {
        name: "Sun".into(),
        kind: LightKind::Sphere {
            radius_m: 200.0 * (0.75f32).to_radians().tan(),
        },
        color: Vec3::new(1.0, 0.9, 0.75),
        intensity: 4.0 * 200.0 * 200.0,
        position: 200.0 * direction_to_sun,
        direction: -direction_to_sun,
        range: None,
        locked: false,
    }
}
