//! The default sample ("sample"), a studio set: a textured floor and a back wall, a sphere resting on a
//! pedestal, a glazed sphere, a torus and a pillar, lit by a warm key spot, a cool fill, a
//! magenta rim light and a dim pale sky directional, so that objects shadow the floor, the
//! wall and each other.

use std::f32::consts::FRAC_PI_4;

use glam::{Quat, Vec3};

use super::checker_png;
use crate::scene::gltf_write::{GltfBuilder, LightSpec, MaterialSpec};
use crate::scene::shapes::{self, ShapeMesh};

/// The sample scene as a `.glb` file.
pub fn sample_scene_glb() -> Vec<u8> {
    let mut b = GltfBuilder::new();
    let floor = b.add_material(&MaterialSpec {
        base_color_png: Some(checker_png(256, 8, [200, 200, 196], [150, 152, 156])),
        ..MaterialSpec::plain("floor", [1.0, 1.0, 1.0], 0.8)
    });
    let wall = b.add_material(&MaterialSpec::plain("plaster", [0.75, 0.72, 0.68], 0.9));
    let clay = b.add_material(&MaterialSpec::plain("terracotta", [0.70, 0.32, 0.20], 0.6));
    let pedestal = b.add_material(&MaterialSpec::plain("marble", [0.85, 0.85, 0.88], 0.35));
    let jade = b.add_material(&MaterialSpec::plain("jade", [0.20, 0.55, 0.38], 0.4));
    let glaze = b.add_material(&MaterialSpec::plain("blue glaze", [0.10, 0.22, 0.55], 0.3));
    let slate = b.add_material(&MaterialSpec::plain("slate", [0.25, 0.28, 0.34], 0.7));

    let mut place = |name: &str, mesh: ShapeMesh, material: usize, at: Vec3, rotation: Quat| {
        b.add_shape(name, &mesh, material, at, rotation);
    };
    place("Floor", shapes::plane(14.0, 64, 7.0), floor, Vec3::ZERO, Quat::IDENTITY);
    place(
        "Back wall",
        shapes::cuboid(Vec3::new(5.0, 1.6, 0.15)),
        wall,
        Vec3::new(0.0, 1.6, -3.2),
        Quat::IDENTITY,
    );
    place(
        "Pedestal",
        shapes::cuboid(Vec3::splat(0.6)),
        pedestal,
        Vec3::new(-1.2, 0.6, -0.6),
        Quat::from_rotation_y(0.3),
    );
    place(
        "Clay sphere",
        shapes::uv_sphere(0.75, 72, 36),
        clay,
        Vec3::new(-1.2, 1.95, -0.6),
        Quat::IDENTITY,
    );
    place(
        "Glazed sphere",
        shapes::uv_sphere(0.55, 72, 36),
        glaze,
        Vec3::new(1.4, 0.55, 0.9),
        Quat::IDENTITY,
    );
    place(
        "Jade torus",
        shapes::torus(0.7, 0.22, 96, 32),
        jade,
        Vec3::new(0.6, 0.8, -0.9),
        Quat::from_rotation_x(1.1) * Quat::from_rotation_z(0.2),
    );
    place(
        "Pillar",
        shapes::cylinder(0.3, 2.6, 48),
        slate,
        Vec3::new(2.5, 0.0, -1.6),
        Quat::IDENTITY,
    );

    let target = Vec3::new(0.0, 0.9, -0.5);
    let key_at = Vec3::new(3.5, 5.0, 3.0);
    b.add_light_node(
        "Key (warm spot)",
        &LightSpec::Spot {
            color: [1.0, 0.78, 0.55],
            intensity_cd: 180.0,
            inner_cone_rad: 0.45,
            outer_cone_rad: FRAC_PI_4 + 0.1,
        },
        key_at,
        target - key_at,
    );
    b.add_light_node(
        "Fill (cool point)",
        &LightSpec::Point {
            color: [0.55, 0.70, 1.0],
            intensity_cd: 28.0,
        },
        Vec3::new(-4.0, 2.5, 2.5),
        Vec3::NEG_Y,
    );
    b.add_light_node(
        "Rim (magenta point)",
        &LightSpec::Point {
            color: [1.0, 0.35, 0.75],
            intensity_cd: 14.0,
        },
        Vec3::new(-0.2, 2.8, -2.4),
        Vec3::NEG_Y,
    );
    b.add_light_node(
        "Sky (directional)",
        &LightSpec::Directional {
            color: [0.75, 0.85, 1.0],
            illuminance_lux: 0.35,
        },
        Vec3::new(0.0, 8.0, 0.0),
        Vec3::new(-0.3, -1.0, -0.2),
    );
    let eye = Vec3::new(5.2, 3.6, 6.4);
    b.add_camera_node("Camera", 40f32.to_radians(), 0.05, eye, target - eye, Vec3::Y);
    b.to_glb()
}
