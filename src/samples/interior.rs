//! "interior": a furnished room (table, chairs, shelves of glossy and matte objects, a
//! metal lamp) with 12 ceiling lights, 2 desk spots, 2 wall washers and window daylight:
//! 17 lights and over 150k vertices.

use std::f32::consts::PI;

use glam::{Affine3A, Quat, Vec3};

use crate::scene::gltf_write::{GltfBuilder, LightSpec, MaterialSpec};
use crate::scene::shapes::{self, ShapeMesh};

fn at(mesh: ShapeMesh, position: Vec3) -> ShapeMesh {
    mesh.transformed(Affine3A::from_translation(position))
}

fn table(position: Vec3) -> ShapeMesh {
    let mut t = at(shapes::cuboid(Vec3::new(0.9, 0.03, 0.5)), position + Vec3::Y * 0.75);
    for (x, z) in [(-0.8, -0.4), (0.8, -0.4), (-0.8, 0.4), (0.8, 0.4)] {
        t = t.merged(at(shapes::cylinder(0.03, 0.72, 16), position + Vec3::new(x, 0.0, z)));
    }
    t
}

fn chair(position: Vec3, facing: f32) -> ShapeMesh {
    let mut c = at(shapes::cuboid(Vec3::new(0.22, 0.02, 0.22)), Vec3::Y * 0.45);
    c = c.merged(at(
        shapes::cuboid(Vec3::new(0.22, 0.25, 0.02)),
        Vec3::new(0.0, 0.72, -0.2),
    ));
    for (x, z) in [(-0.19, -0.19), (0.19, -0.19), (-0.19, 0.19), (0.19, 0.19)] {
        c = c.merged(at(shapes::cylinder(0.018, 0.44, 12), Vec3::new(x, 0.0, z)));
    }
    c.transformed(Affine3A::from_rotation_translation(
        Quat::from_rotation_y(facing),
        position,
    ))
}

pub fn interior_glb() -> Vec<u8> {
    let mut b = GltfBuilder::new();
    let plaster = b.add_material(&MaterialSpec::plain("plaster", [0.8, 0.78, 0.74], 0.95));
    let oak = b.add_material(&MaterialSpec::plain("oak", [0.55, 0.38, 0.22], 0.5));
    let floor = b.add_material(&MaterialSpec::plain("polished floor", [0.35, 0.3, 0.28], 0.15));
    let ceramic = b.add_material(&MaterialSpec::plain("glossy ceramic", [0.1, 0.3, 0.6], 0.12));
    let matte = b.add_material(&MaterialSpec::plain("matte clay", [0.7, 0.45, 0.35], 0.9));
    let brass = b.add_material(&MaterialSpec {
        metallic: 1.0,
        ..MaterialSpec::plain("brass", [0.9, 0.75, 0.4], 0.25)
    });
    let mut add = |name: &str, mesh: ShapeMesh, material: usize| {
        b.add_shape(name, &mesh, material, Vec3::ZERO, Quat::IDENTITY);
    };
    // Room 8 × 3 × 6 m, open towards +z for the camera.
    add("Floor", shapes::plane(8.0, 80, 4.0), floor);
    add(
        "Ceiling",
        at(shapes::cuboid(Vec3::new(4.0, 0.05, 3.0)), Vec3::new(0.0, 3.05, 0.0)),
        plaster,
    );
    add(
        "Back wall",
        at(shapes::cuboid(Vec3::new(4.0, 1.5, 0.05)), Vec3::new(0.0, 1.5, -3.05)),
        plaster,
    );
    add(
        "Left wall",
        at(shapes::cuboid(Vec3::new(0.05, 1.5, 3.0)), Vec3::new(-4.05, 1.5, 0.0)),
        plaster,
    );
    add("Table", table(Vec3::new(0.0, 0.0, 0.2)), oak);
    for (i, (x, z, facing)) in [(-0.5, -0.5, 0.0), (0.5, -0.5, 0.0), (-0.5, 0.9, PI), (0.5, 0.9, PI)]
        .iter()
        .enumerate()
    {
        add(&format!("Chair {}", i + 1), chair(Vec3::new(*x, 0.0, *z), *facing), oak);
    }
    // Shelves along the back wall, each carrying a row of objects.
    for shelf in 0..4 {
        let y = 0.5 + 0.6 * shelf as f32;
        add(
            &format!("Shelf {}", shelf + 1),
            at(shapes::cuboid(Vec3::new(2.5, 0.02, 0.2)), Vec3::new(0.0, y, -2.8)),
            oak,
        );
        for slot in 0..8 {
            let x = -2.2 + 0.63 * slot as f32;
            let (mesh, material) = if (shelf + slot) % 2 == 0 {
                (
                    at(shapes::uv_sphere(0.12, 96, 48), Vec3::new(x, y + 0.14, -2.8)),
                    ceramic,
                )
            } else {
                let torus = shapes::torus(0.1, 0.04, 96, 48).transformed(Affine3A::from_rotation_translation(
                    Quat::from_rotation_x(1.3),
                    Vec3::new(x, y + 0.14, -2.8),
                ));
                (torus, matte)
            };
            add(&format!("Object {}-{}", shelf + 1, slot + 1), mesh, material);
        }
    }
    let lamp = at(shapes::cylinder(0.02, 0.45, 24), Vec3::new(0.6, 0.78, 0.1))
        .merged(at(shapes::uv_sphere(0.09, 48, 24), Vec3::new(0.6, 1.28, 0.1)));
    add("Lamp", lamp, brass);

    for row in 0..3 {
        for col in 0..4 {
            let position = Vec3::new(-3.0 + 2.0 * col as f32, 2.6, -2.0 + 2.0 * row as f32);
            let warm = [1.0, 0.82 + 0.03 * col as f32, 0.6 + 0.05 * row as f32];
            b.add_light_node(
                &format!("Ceiling {}", row * 4 + col + 1),
                &LightSpec::Point {
                    color: warm,
                    intensity_cd: 1.2,
                },
                position,
                Vec3::NEG_Y,
            );
        }
    }
    for (i, x) in [-0.4f32, 0.4].iter().enumerate() {
        let from = Vec3::new(*x, 1.6, 0.2);
        b.add_light_node(
            &format!("Desk spot {}", i + 1),
            &LightSpec::Spot {
                color: [1.0, 0.9, 0.75],
                intensity_cd: 8.0,
                inner_cone_rad: 0.3,
                outer_cone_rad: 0.5,
            },
            from,
            Vec3::new(*x * 0.5, 0.78, 0.2) - from,
        );
    }
    for (i, x) in [-2.5f32, 2.5].iter().enumerate() {
        let from = Vec3::new(*x, 0.3, -2.6);
        b.add_light_node(
            &format!("Wall washer {}", i + 1),
            &LightSpec::Spot {
                color: [0.6, 0.7, 1.0],
                intensity_cd: 4.0,
                inner_cone_rad: 0.4,
                outer_cone_rad: 0.9,
            },
            from,
            Vec3::new(*x, 2.5, -3.0) - from,
        );
    }
    b.add_light_node(
        "Window daylight",
        &LightSpec::Directional {
            color: [0.85, 0.92, 1.0],
            illuminance_lux: 0.6,
        },
        Vec3::new(5.0, 4.0, 2.0),
        Vec3::new(-1.0, -0.6, -0.3),
    );
    let eye = Vec3::new(3.2, 1.9, 4.5);
    b.add_camera_node(
        "Camera",
        55f32.to_radians(),
        0.05,
        eye,
        Vec3::new(-0.3, 1.0, -1.0) - eye,
        Vec3::Y,
    );
    b.to_glb()
}
