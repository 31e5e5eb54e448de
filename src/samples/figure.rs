//! "studio": a jointed figure (a mannequin built from spheres and capsules, one mesh of
//! about 10k vertices) standing on a floor before a backdrop wall, lit by 9 lights.

use std::f32::consts::FRAC_PI_4;

use glam::{Affine3A, Quat, Vec3};

use super::checker_png;
use crate::scene::gltf_write::{GltfBuilder, LightSpec, MaterialSpec};
use crate::scene::shapes::{self, ShapeMesh};

/// A capsule from `a` to `b` of `radius`: a cylinder with a sphere at each end.
fn capsule(a: Vec3, b: Vec3, radius: f32) -> ShapeMesh {
    let axis = b - a;
    let rotation = Quat::from_rotation_arc(Vec3::Y, axis.normalize());
    let body =
        shapes::cylinder(radius, axis.length(), 16).transformed(Affine3A::from_rotation_translation(rotation, a));
    let ball = |at: Vec3| shapes::uv_sphere(radius, 16, 8).transformed(Affine3A::from_translation(at));
    body.merged(ball(a)).merged(ball(b))
}

fn ellipsoid(at: Vec3, radii: Vec3) -> ShapeMesh {
    shapes::uv_sphere(1.0, 32, 16).transformed(Affine3A::from_scale_rotation_translation(radii, Quat::IDENTITY, at))
}

/// The figure, standing at the origin, about 1.8 m tall, left arm raised.
pub fn figure_mesh() -> ShapeMesh {
    let mut figure = ellipsoid(Vec3::new(0.0, 1.65, 0.0), Vec3::new(0.11, 0.13, 0.12)); // head
    figure = figure.merged(capsule(Vec3::new(0.0, 1.48, 0.0), Vec3::new(0.0, 1.55, 0.0), 0.05)); // neck
    figure = figure.merged(ellipsoid(Vec3::new(0.0, 1.28, 0.0), Vec3::new(0.2, 0.22, 0.12))); // chest
    figure = figure.merged(ellipsoid(Vec3::new(0.0, 0.98, 0.0), Vec3::new(0.17, 0.14, 0.11))); // pelvis
    for side in [-1.0f32, 1.0] {
        let shoulder = Vec3::new(0.22 * side, 1.4, 0.0);
        let (elbow, wrist) = if side < 0.0 {
            (Vec3::new(-0.42, 1.6, 0.05), Vec3::new(-0.5, 1.85, 0.12))
        } else {
            (Vec3::new(0.3, 1.12, 0.02), Vec3::new(0.33, 0.86, 0.1))
        };
        figure = figure.merged(capsule(shoulder, elbow, 0.05));
        figure = figure.merged(capsule(elbow, wrist, 0.04));
        figure = figure.merged(ellipsoid(
            wrist + (wrist - elbow).normalize() * 0.07,
            Vec3::new(0.04, 0.07, 0.03),
        ));
        let hip = Vec3::new(0.1 * side, 0.92, 0.0);
        let knee = Vec3::new(0.12 * side, 0.5, 0.04 - 0.06 * side);
        let ankle = Vec3::new(0.13 * side, 0.08, -0.02 - 0.04 * side);
        figure = figure.merged(capsule(hip, knee, 0.07));
        figure = figure.merged(capsule(knee, ankle, 0.05));
        figure = figure.merged(ellipsoid(
            ankle + Vec3::new(0.0, -0.03, 0.08),
            Vec3::new(0.05, 0.04, 0.12),
        ));
    }
    figure
}

pub fn studio_glb() -> Vec<u8> {
    let mut b = GltfBuilder::new();
    let floor = b.add_material(&MaterialSpec {
        base_color_png: Some(checker_png(128, 16, [190, 188, 184], [160, 158, 154])),
        ..MaterialSpec::plain("floor", [1.0, 1.0, 1.0], 0.7)
    });
    let backdrop = b.add_material(&MaterialSpec::plain("backdrop", [0.55, 0.57, 0.6], 0.9));
    let skin = b.add_material(&MaterialSpec::plain("mannequin", [0.78, 0.62, 0.48], 0.45));
    let mut add = |name: &str, mesh: ShapeMesh, material: usize| {
        b.add_shape(name, &mesh, material, Vec3::ZERO, Quat::IDENTITY);
    };
    add("Floor", shapes::plane(10.0, 40, 5.0), floor);
    let wall =
        shapes::cuboid(Vec3::new(4.0, 2.0, 0.1)).transformed(Affine3A::from_translation(Vec3::new(0.0, 2.0, -3.0)));
    add("Backdrop", wall, backdrop);
    add("Figure", figure_mesh(), skin);

    let target = Vec3::new(0.0, 1.1, 0.0);
    let spot = |b: &mut GltfBuilder, name: &str, color: [f32; 3], intensity_cd: f32, at: Vec3, half_angle: f32| {
        b.add_light_node(
            name,
            &LightSpec::Spot {
                color,
                intensity_cd,
                inner_cone_rad: half_angle * 0.6,
                outer_cone_rad: half_angle,
            },
            at,
            target - at,
        );
    };
    spot(
        &mut b,
        "Key",
        [1.0, 0.85, 0.7],
        40.0,
        Vec3::new(2.5, 3.5, 2.5),
        FRAC_PI_4 * 0.7,
    );
    spot(
        &mut b,
        "Rim left",
        [0.6, 0.75, 1.0],
        30.0,
        Vec3::new(-2.0, 2.5, -2.0),
        FRAC_PI_4 * 0.5,
    );
    spot(
        &mut b,
        "Rim right",
        [1.0, 0.6, 0.4],
        25.0,
        Vec3::new(2.2, 2.2, -1.8),
        FRAC_PI_4 * 0.5,
    );
    spot(
        &mut b,
        "Top",
        [1.0, 1.0, 0.95],
        15.0,
        Vec3::new(0.0, 4.5, 0.3),
        FRAC_PI_4 * 0.4,
    );
    spot(
        &mut b,
        "Kicker",
        [0.5, 1.0, 0.7],
        25.0,
        Vec3::new(-2.5, 0.6, 1.0),
        FRAC_PI_4 * 0.6,
    );
    let point = |b: &mut GltfBuilder, name: &str, color: [f32; 3], intensity_cd: f32, at: Vec3| {
        b.add_light_node(name, &LightSpec::Point { color, intensity_cd }, at, Vec3::NEG_Y);
    };
    point(&mut b, "Fill", [0.7, 0.8, 1.0], 6.0, Vec3::new(-3.0, 1.8, 2.5));
    point(&mut b, "Backdrop wash", [0.9, 0.5, 1.0], 3.0, Vec3::new(0.0, 0.5, -2.2));
    point(&mut b, "Floor bounce", [1.0, 0.9, 0.8], 1.0, Vec3::new(0.8, 0.15, 1.2));
    b.add_light_node(
        "Sky",
        &LightSpec::Directional {
            color: [0.8, 0.88, 1.0],
            illuminance_lux: 0.25,
        },
        Vec3::new(0.0, 6.0, 0.0),
        Vec3::new(0.2, -1.0, -0.3),
    );
    let eye = Vec3::new(2.6, 1.9, 4.2);
    b.add_camera_node("Camera", 38f32.to_radians(), 0.05, eye, target - eye, Vec3::Y);
    b.to_glb()
}
