//! "large": a 12 × 12 field of detailed objects (spheres, tori, columns) on a ground plane,
//! 24 coloured lights: over 500k vertices, for scale tests.

use std::f32::consts::TAU;

use glam::{Affine3A, Quat, Vec3};

use crate::scene::gltf_write::{GltfBuilder, LightSpec, MaterialSpec};
use crate::scene::shapes;

pub fn large_glb() -> Vec<u8> {
    let mut b = GltfBuilder::new();
    let ground = b.add_material(&MaterialSpec::plain("ground", [0.5, 0.5, 0.48], 0.9));
    let palette: Vec<usize> = [[0.8, 0.3, 0.2], [0.2, 0.6, 0.3], [0.25, 0.35, 0.8], [0.85, 0.8, 0.7]]
        .iter()
        .enumerate()
        .map(|(i, c)| b.add_material(&MaterialSpec::plain(&format!("paint {i}"), *c, 0.3 + 0.15 * i as f32)))
        .collect();
    let plane = shapes::plane(40.0, 100, 10.0);
    b.add_shape("Ground", &plane, ground, Vec3::ZERO, Quat::IDENTITY);
    for i in 0..12 {
        for j in 0..12 {
            let position = Vec3::new(-16.5 + 3.0 * i as f32, 0.0, -16.5 + 3.0 * j as f32);
            let mesh = match (i + j) % 3 {
                0 => shapes::uv_sphere(0.8, 64, 54).transformed(Affine3A::from_translation(Vec3::Y * 0.8)),
                1 => shapes::torus(0.7, 0.25, 80, 42).transformed(Affine3A::from_rotation_translation(
                    Quat::from_rotation_x(1.2),
                    Vec3::Y * 0.9,
                )),
                _ => shapes::cylinder(0.4, 2.2, 64)
                    .merged(shapes::uv_sphere(0.45, 56, 44).transformed(Affine3A::from_translation(Vec3::Y * 2.45))),
            };
            let name = format!("Object {i}-{j}");
            b.add_shape(&name, &mesh, palette[(i * 5 + j) % 4], position, Quat::IDENTITY);
        }
    }
    for k in 0..24 {
        let angle = k as f32 / 24.0 * TAU;
        let radius = if k % 2 == 0 { 10.0 } else { 17.0 };
        let position = Vec3::new(radius * angle.cos(), 4.0 + (k % 3) as f32, radius * angle.sin());
        let hue = k as f32 / 24.0;
        let color = [
            0.5 + 0.5 * (hue * TAU).cos(),
            0.5 + 0.5 * (hue * TAU + TAU / 3.0).cos(),
            0.5 + 0.5 * (hue * TAU + 2.0 * TAU / 3.0).cos(),
        ];
        b.add_light_node(
            &format!("Light {}", k + 1),
            &LightSpec::Point {
                color,
                intensity_cd: 15.0,
            },
            position,
            Vec3::NEG_Y,
        );
    }
    let eye = Vec3::new(24.0, 16.0, 24.0);
    b.add_camera_node("Camera", 45f32.to_radians(), 0.1, eye, -eye, Vec3::Y);
    b.to_glb()
}
