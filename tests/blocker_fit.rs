//! The sphere fit on arbitrary triangle soups: it never panics, and every sphere it returns
//! is finite with a positive radius, centred within the mesh's bounds (plus a margin).

use glam::Vec3;
use lightpaint::blockers::{BlockerSettings, SphereBudget, fit_scene};
use lightpaint::scene::{MeshObject, Scene};
use proptest::prelude::*;

fn soup() -> impl Strategy<Value = (Vec<Vec3>, Vec<u32>)> {
    let point = (-5.0f32..5.0, -5.0f32..5.0, -5.0f32..5.0).prop_map(|(x, y, z)| Vec3::new(x, y, z));
    (
        prop::collection::vec(point, 3..40),
        prop::collection::vec(any::<u32>(), 0..90),
    )
        .prop_map(|(positions, raw)| {
            let n = positions.len() as u32;
            let indices: Vec<u32> = raw.iter().map(|i| i % n).collect();
            let whole = indices.len() / 3 * 3;
            (positions, indices[..whole].to_vec())
        })
}

fn scene_of(positions: Vec<Vec3>, indices: Vec<u32>) -> Scene {
    let normals = MeshObject::generate_normals(&positions, &indices);
    let uvs = vec![glam::Vec2::ZERO; positions.len()];
    Scene {
        objects: vec![MeshObject {
            name: "soup".into(),
            positions,
            normals,
            uvs,
            indices,
            material: 0,
        }],
        ..Default::default()
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(48))]

    #[test]
    fn any_triangle_soup_fits_without_panicking((positions, indices) in soup(), total in 0usize..20) {
        let scene = scene_of(positions, indices);
        let bounds = scene.bounds();
        let margin = (bounds.max - bounds.min).max_element() * 0.2 + 1e-3;
        for budget in [SphereBudget::FitError(0.35), SphereBudget::Total(total)] {
            let settings = BlockerSettings { budget, cell_budget: 20_000, ..BlockerSettings::default() };
            let first = fit_scene(&scene, &settings);
            for s in first.spheres() {
                prop_assert!(s.center.is_finite() && s.radius_m.is_finite() && s.radius_m > 0.0, "{s:?}");
                prop_assert!(s.center.cmpge(bounds.min - margin).all() && s.center.cmple(bounds.max + margin).all(), "{s:?}");
            }
        }
    }
}

#[test]
fn an_empty_scene_and_an_empty_mesh_have_no_blockers() {
    assert_eq!(
        fit_scene(&Scene::default(), &BlockerSettings::default()).sphere_count(),
        0
    );
    let scene = scene_of(vec![Vec3::ZERO, Vec3::X, Vec3::Y], Vec::new());
    let fitted = fit_scene(&scene, &BlockerSettings::default());
    assert_eq!(fitted.sphere_count(), 0);
    assert!(fitted.per_object[0].skipped.is_some());
}
