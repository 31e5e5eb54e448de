//! "lamp-room": a room at night lit by 30 small lamps of 1.5 m range, furnished with the
//! shapes real sets are made of and whose shadows the live view must get right — two
//! walls that are single quads, a shelf that is one open quad, an open tilted card, a
//! standing lattice of 2 cm bars, a closed box, a thin pole and a ball of about 100,000
//! triangles — over a textured floor. No sky: every light is a lamp, and each lamp
//! lights and shadows a patch of the room, so a lamp's shadow that is missing or
//! misplaced shows as a pool of light that is wrong.

use std::f32::consts::FRAC_PI_2;

use glam::{Affine3A, Quat, Vec3};

use crate::scene::gltf_write::{GltfBuilder, LightSpec, MaterialSpec};
use crate::scene::shapes::{self, ShapeMesh};

/// Each lamp's range, metres (glTF `range`).
pub const LAMP_RANGE_M: f32 = 1.5;

/// The room's half-width: its floor is a square of twice this, walls stand at −x and −z.
const HALF_WIDTH_M: f32 = 3.0;

/// The walls' height, metres.
const WALL_HEIGHT_M: f32 = 3.0;

fn placed(mesh: ShapeMesh, scale: Vec3, rotation: Quat, position: Vec3) -> ShapeMesh {
    mesh.transformed(Affine3A::from_scale_rotation_translation(scale, rotation, position))
}

/// One quad (two triangles), `width_m` × `height_m`, facing `rotation` · +y.
fn quad(width_m: f32, height_m: f32, rotation: Quat, centre: Vec3) -> ShapeMesh {
    placed(
        shapes::plane(1.0, 1, 1.0),
        Vec3::new(width_m, 1.0, height_m),
        rotation,
        centre,
    )
}

/// A standing lattice 1 m wide and 1.2 m tall of 2 cm bars, five each way, in the plane
/// z = `centre.z`.
fn lattice(centre: Vec3) -> ShapeMesh {
    let mut mesh = ShapeMesh::default();
    for k in 0..5 {
        let across = -0.4 + 0.2 * k as f32;
        let upright = shapes::cuboid(Vec3::new(0.01, 0.6, 0.01));
        let rail = shapes::cuboid(Vec3::new(0.5, 0.01, 0.01));
        mesh = mesh
            .merged(upright.transformed(Affine3A::from_translation(centre + Vec3::new(across, 0.0, 0.0))))
            .merged(rail.transformed(Affine3A::from_translation(centre + Vec3::new(0.0, 1.2 * across, 0.02))));
    }
    mesh
}

/// The 30 lamps: where they hang and their intensity in candela — eight dim sconces along
/// the back wall and six along the left one, 0.3 m from it, and sixteen brighter lamps
/// over the floor in a 4 × 4 grid at two heights.
pub fn lamps() -> Vec<(Vec3, f32)> {
    let mut lamps = Vec::new();
    for k in 0..8 {
        lamps.push((Vec3::new(-2.6 + 5.2 * k as f32 / 7.0, 1.9, -HALF_WIDTH_M + 0.3), 0.12));
    }
    for k in 0..6 {
        lamps.push((Vec3::new(-HALF_WIDTH_M + 0.3, 1.6, -2.2 + 4.4 * k as f32 / 5.0), 0.12));
    }
    for row in 0..4 {
        for col in 0..4 {
            let height = if (row + col) % 2 == 0 { 0.8 } else { 1.3 };
            let position = Vec3::new(-2.1 + 1.4 * col as f32, height, -2.1 + 1.4 * row as f32);
            lamps.push((position, 0.8));
        }
    }
    lamps
}

pub fn lamp_room_glb() -> Vec<u8> {
    let mut b = GltfBuilder::new();
    let plaster = b.add_material(&MaterialSpec::plain("plaster", [0.8, 0.78, 0.74], 0.95));
    let boards = b.add_material(&MaterialSpec {
        base_color_png: Some(super::checker_png(256, 8, [200, 184, 160], [120, 104, 88])),
        ..MaterialSpec::plain("checked boards", [1.0, 1.0, 1.0], 0.8)
    });
    let wood = b.add_material(&MaterialSpec::plain("wood", [0.55, 0.38, 0.22], 0.6));
    let clay = b.add_material(&MaterialSpec::plain("clay", [0.7, 0.45, 0.35], 0.9));
    let mut add = |name: &str, mesh: ShapeMesh, material: usize| {
        b.add_shape(name, &mesh, material, Vec3::ZERO, Quat::IDENTITY);
    };
    let size = 2.0 * HALF_WIDTH_M;
    add("Floor", shapes::plane(size, 1, 6.0), boards);
    add(
        "Back wall",
        quad(
            size,
            WALL_HEIGHT_M,
            Quat::from_rotation_x(FRAC_PI_2),
            Vec3::new(0.0, 0.5 * WALL_HEIGHT_M, -HALF_WIDTH_M),
        ),
        plaster,
    );
    add(
        "Left wall",
        quad(
            WALL_HEIGHT_M,
            size,
            Quat::from_rotation_z(-FRAC_PI_2),
            Vec3::new(-HALF_WIDTH_M, 0.5 * WALL_HEIGHT_M, 0.0),
        ),
        plaster,
    );
    add(
        "Shelf",
        quad(1.6, 0.3, Quat::IDENTITY, Vec3::new(-1.4, 1.2, -HALF_WIDTH_M + 0.15)),
        wood,
    );
    add(
        "Card",
        quad(0.6, 0.6, Quat::from_rotation_x(0.5), Vec3::new(-1.6, 0.8, 0.5)),
        wood,
    );
    add("Lattice", lattice(Vec3::new(0.3, 0.9, -1.3)), wood);
    add(
        "Box",
        placed(
            shapes::cuboid(Vec3::splat(0.3)),
            Vec3::ONE,
            Quat::from_rotation_y(0.4),
            Vec3::new(-0.5, 0.3, 1.0),
        ),
        clay,
    );
    add(
        "Pole",
        shapes::cylinder(0.015, 1.7, 12).transformed(Affine3A::from_translation(Vec3::new(2.3, 0.0, 1.4))),
        wood,
    );
    // 320 × 160 quads: about 102,000 triangles.
    add(
        "Ball",
        shapes::uv_sphere(0.4, 320, 160).transformed(Affine3A::from_translation(Vec3::new(1.5, 0.4, -0.7))),
        clay,
    );
    for (k, (position, intensity_cd)) in lamps().into_iter().enumerate() {
        b.add_ranged_light_node(
            &format!("Lamp {}", k + 1),
            &LightSpec::Point {
                color: [1.0, 0.85, 0.65],
                intensity_cd,
            },
            position,
            Vec3::NEG_Y,
            LAMP_RANGE_M,
        );
    }
    let eye = Vec3::new(0.6, 2.1, 5.2);
    b.add_camera_node(
        "Camera",
        55f32.to_radians(),
        0.05,
        eye,
        Vec3::new(-0.2, 0.9, -1.0) - eye,
        Vec3::Y,
    );
    b.to_glb()
}
