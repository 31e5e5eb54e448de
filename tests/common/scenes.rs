//! Small scenes written as real glTF files for the tests.

use glam::Vec3;
use lightpaint::scene::gltf_write::{GltfBuilder, LightSpec, MaterialSpec};
use lightpaint::scene::shapes;

/// A white Lambertian (no specular) plane of side 2 at y = 0, seen from straight above by a
/// camera at height 5 with a 40° field of view (so the corners of the image see past it),
/// lit by `light` placed at `light_position` pointing down.
pub fn white_plane(light: LightSpec, light_position: Vec3) -> Vec<u8> {
    let mut b = GltfBuilder::new();
    let white = b.add_material(&MaterialSpec {
        specular: Some(0.0),
        ..MaterialSpec::plain("white", [1.0, 1.0, 1.0], 1.0)
    });
    let plane = shapes::plane(2.0, 4, 1.0);
    b.add_shape("plane", &plane, white, Vec3::ZERO, glam::Quat::IDENTITY);
    b.add_light_node("light", &light, light_position, Vec3::NEG_Y);
    b.add_camera_node(
        "top",
        40f32.to_radians(),
        0.1,
        Vec3::new(0.0, 5.0, 0.0),
        Vec3::NEG_Y,
        Vec3::NEG_Z,
    );
    b.to_glb()
}

/// One triangle whose positions are given as is (possibly NaN).
pub fn triangle(positions: [Vec3; 3]) -> Vec<u8> {
    let mut b = GltfBuilder::new();
    let mesh = b.add_mesh("triangle", &positions, None, None, &[0, 1, 2], None);
    b.add_mesh_node("triangle", mesh, Vec3::ZERO, glam::Quat::IDENTITY, Vec3::ONE);
    b.to_glb()
}

/// A triangle whose POSITION accessor claims more vertices than its buffer view holds.
pub fn out_of_range_accessor() -> Vec<u8> {
    let mut b = GltfBuilder::new();
    let positions: [f32; 9] = [0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0, 0.0];
    let view = b.push_view(bytemuck::cast_slice(&positions), Some(34962));
    let accessor = b.push_accessor(serde_json::json!({
        "bufferView": view, "componentType": 5126, "count": 300, "type": "VEC3",
        "min": [0.0, 0.0, 0.0], "max": [1.0, 1.0, 0.0],
    }));
    let mesh = b.add_raw_mesh("broken", serde_json::json!({"attributes": {"POSITION": accessor}}));
    b.add_node(serde_json::json!({"name": "broken", "mesh": mesh}));
    b.to_glb()
}

/// A mesh whose POSITION names an accessor that does not exist (the gltf-json 1.4
/// validator indexes it before checking, and panics).
pub fn dangling_position_accessor() -> Vec<u8> {
    let mut b = GltfBuilder::new();
    let mesh = b.add_raw_mesh("dangling", serde_json::json!({"attributes": {"POSITION": 9}}));
    b.add_node(serde_json::json!({"name": "dangling", "mesh": mesh}));
    b.to_glb()
}

/// A .glb with two scenes, "Day" (a triangle at the origin and a sun) and "Night" (the
/// triangle 5 m along +x, no light), whose default is "Night".
pub fn day_and_night() -> Vec<u8> {
    let mut b = GltfBuilder::new();
    let positions = [Vec3::ZERO, Vec3::X, Vec3::NEG_Z];
    let mesh = b.add_mesh("triangle", &positions, None, None, &[0, 1, 2], None);
    let day = b.add_mesh_node("day", mesh, Vec3::ZERO, glam::Quat::IDENTITY, Vec3::ONE);
    let night = b.add_mesh_node("night", mesh, Vec3::new(5.0, 0.0, 0.0), glam::Quat::IDENTITY, Vec3::ONE);
    let sun = b.add_light_node(
        "sun",
        &LightSpec::Directional {
            color: [1.0, 1.0, 1.0],
            illuminance_lux: 2.0,
        },
        Vec3::ONE,
        Vec3::NEG_Y,
    );
    let mut document = b.document(None);
    document["scenes"] = serde_json::json!([
        {"name": "Day", "nodes": [day, sun]},
        {"name": "Night", "nodes": [night]},
    ]);
    document["scene"] = serde_json::json!(1);
    lightpaint::scene::gltf_write::glb_bytes(&document, &b.bin())
}

/// A white light of `kind` at `position` aiming straight down, without a range.
pub fn white_light(kind: lightpaint::scene::LightKind, position: Vec3, intensity: f32) -> lightpaint::scene::Light {
    lightpaint::scene::Light {
        name: "light".into(),
        kind,
        color: Vec3::ONE,
        intensity,
        position,
        direction: Vec3::NEG_Y,
        range: None,
        locked: false,
    }
}

/// A 12 m floor with a ring of twelve props 3 m from its centre, posts and open cards
/// (one quad, both sides) in turn, and no light: what a light among props shadows.
pub fn ring_of_posts_and_cards() -> lightpaint::scene::Scene {
    use glam::Affine3A;
    let mut scene = lightpaint::scene::Scene::default();
    scene.materials.push(lightpaint::scene::Material::default());
    scene.objects.push(shapes::plane(12.0, 24, 1.0).into_object("floor"));
    for k in 0..12 {
        let angle = k as f32 * std::f32::consts::TAU / 12.0;
        let at = Vec3::new(3.0 * angle.cos(), 0.0, 3.0 * angle.sin());
        let shape = if k % 2 == 0 {
            shapes::cylinder(0.15, 1.8, 24)
        } else {
            shapes::plane(0.8, 1, 1.0).transformed(Affine3A::from_rotation_x(std::f32::consts::FRAC_PI_2))
        };
        let placed = shape.transformed(Affine3A::from_translation(at + Vec3::Y * 0.9 * (k % 2) as f32));
        scene.objects.push(placed.into_object(&format!("prop {k}")));
    }
    scene
}

/// A camera above [`ring_of_posts_and_cards`], seeing the whole ring.
pub fn ring_camera() -> lightpaint::scene::Camera {
    lightpaint::scene::Camera::looking_at(Vec3::new(0.0, 6.0, 7.5), Vec3::ZERO, 50f32.to_radians(), 0.05)
}

/// A `side` × `side` base colour texture named `name` whose texel (x, y) is `texel(x, y)`.
pub fn texture(name: &str, side: u32, texel: impl Fn(u32, u32) -> [u8; 4]) -> lightpaint::scene::TextureImage {
    lightpaint::scene::TextureImage {
        name: name.into(),
        width: side,
        height: side,
        rgba8: (0..side * side).flat_map(|i| texel(i % side, i / side)).collect(),
    }
}

/// A white dielectric material whose base colour is texture `texture` of the scene.
pub fn textured_white(texture: usize) -> lightpaint::scene::Material {
    lightpaint::scene::Material {
        base_color: glam::Vec4::ONE,
        metallic: 0.0,
        base_color_texture: Some(texture),
        ..lightpaint::scene::Material::default()
    }
}
