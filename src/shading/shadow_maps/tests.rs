//! The shadow maps' views against their geometry: faces, ranges, depths, drafts, texels.

use bytemuck::Zeroable;
use glam::Mat4;

use super::*;

fn mapped(kind: crate::scene::LightKind, position: Vec3, direction: Vec3) -> GpuLight {
    let mut light = GpuLight::new(&crate::scene::Light {
        name: "light".into(),
        kind,
        color: Vec3::ONE,
        intensity: 1.0,
        position,
        direction,
        range: None,
        locked: false,
    });
    light.shadow_path = super::super::gpu_types::SHADOW_PATH_MAP;
    light.first_shadow_view = 0;
    light.shadow_view_count = view_count(&light, Vec3::ZERO, 0.0).unwrap_or(0) as u32;
    light
}

fn clip(view: &GpuShadowView, p: Vec3) -> Vec3 {
    let c = Mat4::from_cols_array_2d(&view.view_proj) * p.extend(1.0);
    c.truncate() / c.w
}

#[test]
fn the_finest_texel_on_a_box_is_a_cube_faces_at_its_nearest_point_or_a_suns_everywhere() {
    let bounds = Aabb::from_points(&[Vec3::splat(-8.0), Vec3::splat(8.0)]);
    let lamp = mapped(crate::scene::LightKind::Point, Vec3::ZERO, Vec3::NEG_Y);
    let views = shadow_views(&[lamp], &bounds, 512);
    // A box whose nearest point lies 4 m from the lamp: a 90° face of 512 texels is
    // 2 tan 45° / 512 wide per metre there (its margin widens it a little).
    let far_box = Aabb::from_points(&[Vec3::new(4.0, -1.0, -1.0), Vec3::new(5.0, 1.0, 1.0)]);
    let lamp_texel = views.finest_texel_m(&far_box);
    let nominal = 2.0 * 4.0 / 512.0;
    assert!(
        (nominal..1.1 * nominal).contains(&lamp_texel),
        "{lamp_texel} against {nominal}"
    );
    // A box holding the lamp: no finer texel than at the eye itself.
    assert_eq!(views.finest_texel_m(&bounds), 0.0);
    let sun = mapped(
        crate::scene::LightKind::Directional,
        Vec3::ZERO,
        Vec3::new(0.3, -1.0, 0.2).normalize(),
    );
    let sun_views = shadow_views(&[sun], &bounds, 1024);
    let texel = sun_views.finest_texel_m(&far_box);
    assert_eq!(texel, sun_views.views[0].texel[1]);
    assert!(texel > 0.0 && texel < 1.0);
    assert_eq!(ShadowViews::default().finest_texel_m(&far_box), f32::INFINITY);
    // A zeroed slot stands for no view.
    let mut with_empty_slot = views.clone();
    with_empty_slot.views.push(GpuShadowView::zeroed());
    assert_eq!(with_empty_slot.finest_texel_m(&far_box), lamp_texel);
}

#[test]
fn a_point_lights_faces_see_each_direction_in_the_face_cube_face_picks() {
    let light = mapped(crate::scene::LightKind::Point, Vec3::new(0.5, 1.0, -0.25), Vec3::NEG_Y);
    let bounds = Aabb::from_points(&[Vec3::splat(-3.0), Vec3::splat(3.0)]);
    let views = shadow_views(&[light], &bounds, 256).views;
    assert_eq!(views.len(), 6);
    let eye = Vec3::new(0.5, 1.0, -0.25);
    // Directions spread over the sphere, edges and corners included.
    for i in 0..200 {
        let z = -1.0 + 2.0 * (i as f32 + 0.5) / 200.0;
        let phi = i as f32 * 2.399_963;
        let d = Vec3::new((1.0 - z * z).sqrt() * phi.cos(), z, (1.0 - z * z).sqrt() * phi.sin());
        let p = eye + d * 1.7;
        let q = clip(&views[cube_face(d)], p);
        assert!(
            q.x.abs() <= 1.0 && q.y.abs() <= 1.0,
            "{d} lands at {q} on face {}",
            cube_face(d)
        );
        assert!((0.0..=1.0).contains(&q.z), "depth {}", q.z);
    }
}

#[test]
fn a_lamps_faces_end_at_its_range_and_keep_its_reach_as_fine_as_the_scene() {
    // A lamp of 1 m range inside a scene of radius 5√3 m ≈ 8.7 m: its faces halve while
    // a texel at 1 m stays no wider than a 1024² face's at 8.7 m (1024/8 = 128 ≥ 118).
    let mut lamp = mapped(crate::scene::LightKind::Point, Vec3::new(1.0, 0.5, 0.0), Vec3::NEG_Y);
    lamp.direction_range[3] = 1.0;
    let bounds = Aabb::from_points(&[Vec3::splat(-5.0), Vec3::splat(5.0)]);
    let ranged = shadow_views(&[lamp], &bounds, 1024);
    assert_eq!(ranged.atlas.view_size(0), 128);
    let texel_at_range = ranged.views[0].texel[0] * 1.0;
    let full_face_at_radius = 2.0 / 1024.0 * bounds.radius();
    assert!(
        texel_at_range <= full_face_at_radius,
        "{texel_at_range} > {full_face_at_radius}"
    );
    for view in &ranged.views {
        let far = view.depth_range[1];
        assert!((1.0..1.02).contains(&far), "far plane at {far} m, not at the range");
    }
    // Depth still falls with distance, and a point past the range is past the far plane.
    let eye = Vec3::new(1.0, 0.5, 0.0);
    let (inside, past) = (
        clip(&ranged.views[0], eye + Vec3::new(0.9, 0.0, 0.0)).z,
        clip(&ranged.views[0], eye + Vec3::new(1.5, 0.0, 0.0)).z,
    );
    assert!(inside > 0.0 && past < 0.0, "{inside} {past}");
    // Without the range: full faces to the scene's far side.
    lamp.direction_range[3] = 0.0;
    let unranged = shadow_views(&[lamp], &bounds, 1024);
    assert_eq!(unranged.atlas.view_size(0), 1024);
    assert!(unranged.views[0].depth_range[1] > 8.0);
}

#[test]
fn depth_falls_with_distance_along_a_view() {
    let light = mapped(crate::scene::LightKind::Point, Vec3::ZERO, Vec3::NEG_Y);
    let bounds = Aabb::from_points(&[Vec3::splat(-2.0), Vec3::splat(2.0)]);
    let views = shadow_views(&[light], &bounds, 512).views;
    let near = clip(&views[0], Vec3::new(0.5, 0.0, 0.0)).z;
    let far = clip(&views[0], Vec3::new(2.5, 0.0, 0.0)).z;
    assert!(1.0 > near && near > far && far > 0.0, "{near} {far}");
}

/// The distance a perspective view's depth stands for, as shadow_lookup.wgsl's
/// view_distance inverts it: d = near·far / (near + z·(far − near)).
fn view_distance(view: &GpuShadowView, depth: f32) -> f32 {
    let [near, far, ..] = view.depth_range;
    near * far / (near + depth * (far - near))
}

#[test]
fn depth_steps_stay_a_small_share_of_the_distance() {
    // A light inside the scene: the near plane at a millimetre. One float step of the
    // stored depth must stand for far less than a 4096² map's texel (about 0.05 % of
    // the distance for a 90° face) at any distance in the scene.
    let light = mapped(crate::scene::LightKind::Point, Vec3::ZERO, Vec3::NEG_Y);
    let bounds = Aabb::from_points(&[Vec3::splat(-10.0), Vec3::splat(10.0)]);
    let view = shadow_views(&[light], &bounds, 4096).views[0];
    for distance in [0.05_f32, 0.5, 2.0, 5.0, 12.0, 17.0] {
        let z = clip(&view, Vec3::new(distance, 0.0, 0.0)).z;
        let round_trip = view_distance(&view, z);
        assert!(
            (round_trip - distance).abs() < 1e-4 * distance,
            "{distance} → {round_trip}"
        );
        let step = view_distance(&view, z - z * f32::EPSILON) - distance;
        assert!(step.abs() < 2e-5 * distance, "a depth step at {distance} m is {step} m");
    }
}

/// Every corner of `bounds` lands inside `view`'s clip volume.
fn assert_sees_every_corner(view: &GpuShadowView, bounds: &Aabb) {
    for p in bounds.corners() {
        let q = clip(view, p);
        assert!(
            q.x.abs() <= 1.0 && q.y.abs() <= 1.0 && (0.0..=1.0).contains(&q.z),
            "{p} → {q}"
        );
    }
}

#[test]
fn the_suns_view_covers_the_scene() {
    let light = mapped(
        crate::scene::LightKind::Directional,
        Vec3::ZERO,
        Vec3::new(0.3, -1.0, 0.2).normalize(),
    );
    let bounds = Aabb::from_points(&[Vec3::new(-4.0, 0.0, -2.0), Vec3::new(4.0, 3.0, 2.0)]);
    let view = shadow_views(&[light], &bounds, 1024).views[0];
    assert_sees_every_corner(&view, &bounds);
    // Depth is reversed: nearer the sun is deeper.
    assert!(clip(&view, Vec3::new(0.0, 3.0, 0.0)).z > clip(&view, Vec3::ZERO).z);
}

#[test]
fn a_light_far_outside_the_scene_sees_it_in_one_view_and_a_near_one_in_a_cube() {
    let bounds = Aabb::from_points(&[Vec3::new(-4.0, 0.0, -2.0), Vec3::new(4.0, 3.0, 2.0)]);
    let (centre, radius) = bounding_sphere(&bounds);
    let sun_like = |position: Vec3| {
        let mut light = mapped(crate::scene::LightKind::Sphere { radius_m: 0.5 }, position, Vec3::NEG_Y);
        light.shadow_view_count = view_count(&light, centre, radius).unwrap_or(0) as u32;
        light
    };
    let far = sun_like(Vec3::new(30.0, 60.0, -20.0));
    assert_eq!(far.shadow_view_count, 1);
    let view = shadow_views(&[far], &bounds, 1024).views[0];
    assert_sees_every_corner(&view, &bounds);
    // A spot wider than 60° that far out: one view aimed at the scene, not its cone.
    let mut wide_spot = mapped(
        crate::scene::LightKind::Spot {
            inner_cone_rad: 1.0,
            outer_cone_rad: 1.3,
        },
        Vec3::new(30.0, 60.0, -20.0),
        Vec3::new(-0.4, -0.8, 0.3).normalize(),
    );
    wide_spot.shadow_view_count = view_count(&wide_spot, centre, radius).unwrap_or(0) as u32;
    assert_eq!(wide_spot.shadow_view_count, 1);
    let spot_view = shadow_views(&[wide_spot], &bounds, 1024).views[0];
    assert_sees_every_corner(&spot_view, &bounds);
    assert!(
        spot_view.texel[0] < view.texel[0] * 1.01,
        "no coarser than the fitted view"
    );
    // Inside the scene's sphere: a cube.
    assert_eq!(sun_like(Vec3::new(3.0, 2.0, 1.0)).shadow_view_count, 6);
    // Too wide at the centre (a 1 m sphere 2 m away is 30° in radius): no maps.
    let wide = mapped(
        crate::scene::LightKind::Sphere { radius_m: 1.0 },
        centre + Vec3::Y * 2.0,
        Vec3::NEG_Y,
    );
    assert_eq!(view_count(&wide, centre, radius), None);
}

#[test]
fn a_moved_single_view_is_drafted_until_drawn_at_rest_and_faces_never_are() {
    let bounds = Aabb::from_points(&[Vec3::new(-4.0, 0.0, -2.0), Vec3::new(4.0, 3.0, 2.0)]);
    let spot = |x: f32| {
        let mut light = mapped(
            crate::scene::LightKind::Spot {
                inner_cone_rad: 0.3,
                outer_cone_rad: 0.4,
            },
            Vec3::new(x, 2.5, 1.0),
            Vec3::NEG_Y,
        );
        light.first_shadow_view = 0;
        light
    };
    let mut point = mapped(crate::scene::LightKind::Point, Vec3::new(1.0, 2.0, 0.0), Vec3::NEG_Y);
    point.first_shadow_view = 1;
    let at_rest = shadow_views(&[spot(0.0), point], &bounds, 512);
    let moved = shadow_views(&[spot(0.1), point], &bounds, 512);
    let dragged = moved.drafted_where_moved(&at_rest.views);
    let draft = dragged.views[0];
    assert_eq!(draft.atlas, [0.0, 0.0, 0.5, moved.views[0].atlas[3]]);
    assert_eq!(draft.depth_range[2], moved.views[0].depth_range[2] / 2.0);
    assert_eq!(draft.texel[0], 2.0 * moved.views[0].texel[0]);
    assert_eq!(
        &dragged.views[1..],
        &moved.views[1..],
        "the point light's faces did not move"
    );
    // Held still while dragging: the draft is kept, not drawn again in full.
    assert_eq!(moved.drafted_where_moved(&dragged.views), dragged);
    // An unmoved light is drawn in full.
    assert_eq!(at_rest.drafted_where_moved(&at_rest.views), at_rest);
}

/// A cube face's projection worked out from the receiver's face coordinates
/// (cube_face_coordinates, as shadow_lookup.wgsl's cube_face_tap does) is the face's
/// matrix: the same texture coordinates and reversed depth for receivers all around the
/// lamp, on every face and across their edges.
#[test]
fn cube_face_coordinates_project_as_the_faces_matrices() {
    let bounds = Aabb::from_points(&[Vec3::splat(-8.0), Vec3::splat(8.0)]);
    let eye = Vec3::new(0.7, 1.3, -0.4);
    let lamp = mapped(crate::scene::LightKind::Point, eye, Vec3::NEG_Y);
    let views = shadow_views(&[lamp], &bounds, 512);
    assert_eq!(views.views.len(), 6);
    let mut faces_seen = [false; 6];
    // Directions on a Fibonacci sphere, at several distances.
    for k in 0..400 {
        let t = (k as f32 + 0.5) / 400.0;
        let z = 1.0 - 2.0 * t;
        let r = (1.0 - z * z).sqrt();
        let phi = k as f32 * 2.399_963;
        let direction = Vec3::new(r * phi.cos(), z, r * phi.sin());
        for distance in [0.5, 3.0, 9.0] {
            let offset = direction * distance;
            let own = cube_face(offset);
            faces_seen[own] = true;
            // Its own face, and any other it lies ahead of (a tap past an edge).
            for face in 0..6 {
                let view = &views.views[face];
                let v = cube_face_coordinates(offset, face);
                if face == own {
                    assert!(v.z > 0.0, "{offset} lies ahead of its face {face}");
                }
                // Past the view's square a tap is off whatever its coordinates.
                if v.z <= 0.1 * distance || v.x.abs().max(v.y.abs()) > 1.1 * v.z {
                    continue;
                }
                let from_matrix = clip(view, eye + offset);
                let [near, far, size, _] = view.depth_range;
                let h = 2.0 / (view.texel[0] * size);
                let worked_out = Vec3::new(h * v.x / v.z, h * v.y / v.z, near * (far - v.z) / (v.z * (far - near)));
                // Texture coordinates to a thousandth of a texel; depths (small near the
                // eye: the near plane is far · 10⁻⁴) to a millionth of their own size.
                let [du, dv, dz] = (worked_out - from_matrix).abs().to_array();
                assert!(
                    du.max(dv) < 2.0 / size * 1e-3 && dz <= 1e-6 * from_matrix.z.abs() + 1e-9,
                    "face {face}, offset {offset}: {worked_out} against the matrix's {from_matrix}"
                );
            }
        }
    }
    assert_eq!(faces_seen, [true; 6]);
}
