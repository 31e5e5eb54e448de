//! Random byte mutations of a valid project and of a valid .glb never panic the loaders:
//! they load or they fail with an error.

mod common;

use std::path::Path;

use glam::Vec3;
use lightpaint::project::parse_project;
use lightpaint::scene::gltf_write::{GltfBuilder, LightSpec, MaterialSpec};
use lightpaint::scene::{parse_gltf, shapes};
use proptest::prelude::*;

/// A small scene that exercises every part of the importer: a textured mesh, lights of
/// each kind, a camera.
fn small_glb() -> Vec<u8> {
    let mut b = GltfBuilder::new();
    let material = b.add_material(&MaterialSpec {
        base_color_png: Some(lightpaint::samples::checker_png(8, 2, [200, 10, 10], [10, 10, 200])),
        ..MaterialSpec::plain("checker", [1.0, 1.0, 1.0], 0.5)
    });
    let sphere = shapes::uv_sphere(1.0, 8, 4);
    b.add_shape("ball", &sphere, material, Vec3::Y, glam::Quat::IDENTITY);
    b.add_light_node(
        "p",
        &LightSpec::Point {
            color: [1.0, 1.0, 1.0],
            intensity_cd: 5.0,
        },
        Vec3::splat(2.0),
        Vec3::NEG_Y,
    );
    b.add_light_node(
        "s",
        &LightSpec::Spot {
            color: [1.0, 0.5, 0.5],
            intensity_cd: 5.0,
            inner_cone_rad: 0.2,
            outer_cone_rad: 0.5,
        },
        Vec3::new(0.0, 3.0, 1.0),
        Vec3::NEG_Y,
    );
    b.add_light_node(
        "d",
        &LightSpec::Directional {
            color: [0.5, 0.5, 1.0],
            illuminance_lux: 1.0,
        },
        Vec3::ZERO,
        Vec3::NEG_Y,
    );
    b.add_camera_node("cam", 0.8, 0.1, Vec3::new(0.0, 1.0, 5.0), Vec3::NEG_Z, Vec3::Y);
    b.to_glb()
}

fn mutate(bytes: &[u8], edits: &[(usize, u8)], truncate_to: Option<usize>) -> Vec<u8> {
    let mut out = bytes.to_vec();
    for &(position, value) in edits {
        let i = position % out.len();
        out[i] = value;
    }
    if let Some(len) = truncate_to {
        out.truncate(len % (bytes.len() + 1));
    }
    out
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(200))]

    #[test]
    fn mutated_glb_never_panics(
        edits in prop::collection::vec((any::<usize>(), any::<u8>()), 1..8),
        truncate_to in prop::option::of(any::<usize>()),
    ) {
        let original = small_glb();
        prop_assume!(parse_gltf(Path::new("small.glb"), &original).is_ok());
        let bytes = mutate(&original, &edits, truncate_to);
        let _ = parse_gltf(Path::new("mutated.glb"), &bytes);
    }

    #[test]
    fn mutated_project_never_panics(
        edits in prop::collection::vec((any::<usize>(), any::<u8>()), 1..8),
        truncate_to in prop::option::of(any::<usize>()),
    ) {
        let original = std::fs::read(common::repo_path(lightpaint::samples::SAMPLE_PROJECT)).unwrap();
        let bytes = mutate(&original, &edits, truncate_to);
        let _ = parse_project(Path::new("mutated.lightpaint"), &bytes);
    }
}

/// Mutating the JSON chunk of a .glb as text (digits and punctuation) reaches deeper into
/// the importer than random bytes, which mostly break the container.
#[test]
fn glb_with_every_digit_of_its_json_changed_never_panics() {
    let original = small_glb();
    let json_length = u32::from_le_bytes(original[12..16].try_into().unwrap()) as usize;
    for position in 20..20 + json_length {
        if !original[position].is_ascii_digit() {
            continue;
        }
        for replacement in [b'9', b'0', b'-'] {
            let mut bytes = original.clone();
            bytes[position] = replacement;
            let _ = parse_gltf(Path::new("digit.glb"), &bytes);
        }
    }
}
