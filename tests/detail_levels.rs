//! Levels of detail (`scene::detail_levels`, chosen in `GpuScene::write_frame`) on
//! lavapipe: a 100k-triangle sphere far from the camera is drawn with a fraction of its
//! triangles while its silhouette and its normals stay where the true sphere's are (ray
//! casts against the sphere itself, a closed form); beside a shadow-mapped lamp its level
//! stays within the maps' texels, and a lit frame of it on a floor stays the frame drawn
//! from the whole mesh, and a lamp brought near with the camera still redraws the finer
//! level it asks for; a flat, untextured floor under a spot is drawn from a sixteenth of
//! its triangles as from all of them, and from short edges again under baked light;
//! per-vertex frames draw the meshes as they are.

mod common;

use glam::{DVec3, Vec3};
use lightpaint::reference::CameraRays;
use lightpaint::render::{Detail, FrameQuality, GpuContext};
use lightpaint::scene::{Camera, Scene, shapes};
use lightpaint::shading::BakedIndirect;
use lightpaint::shading::RenderSettings;
use lightpaint::shading::shadow_maps::ShadowViews;

/// Pixels on a side of the square frames.
const SIDE_PX: u32 = 320;
const RADIUS_M: f32 = 1.0;
/// The triangles of the sphere of [`sphere_scene`] (320 × 160 segments).
const SPHERE_TRIANGLES: u64 = 101_760;

/// A unit sphere of 320 × 160 segments (101,760 triangles) at the origin, and a floor 1 m
/// below it, lit by a point light `light_m` above it and to the side (none: unlit).
fn sphere_scene(with_floor: bool, light_m: Option<f32>) -> Scene {
    let mut scene = Scene::default();
    scene.materials.push(lightpaint::scene::Material::default());
    scene
        .objects
        .push(shapes::uv_sphere(RADIUS_M, 320, 160).into_object("fine sphere"));
    if with_floor {
        let floor = shapes::plane(30.0, 30, 1.0).transformed(glam::Affine3A::from_translation(Vec3::NEG_Y * RADIUS_M));
        scene.objects.push(floor.into_object("floor"));
    }
    if let Some(distance_m) = light_m {
        scene.lights.push(common::scenes::white_light(
            lightpaint::scene::LightKind::Point,
            Vec3::new(0.5, 1.0, 0.6).normalize() * distance_m,
            10.0 * distance_m * distance_m,
        ));
    }
    scene
}

/// A camera `distance_m` from the sphere's centre, looking at it, a 40° field of view.
fn camera_at(distance_m: f32) -> Camera {
    Camera::looking_at(
        Vec3::new(0.0, 0.3, 1.0).normalize() * distance_m,
        Vec3::ZERO,
        40f32.to_radians(),
        0.05,
    )
}

/// Where the ray through pixel `index`'s centre first meets the true sphere, if it does.
fn true_hit(rays: &CameraRays, index: usize) -> Option<DVec3> {
    let (x, y) = (
        (index % SIDE_PX as usize) as f64 + 0.5,
        (index / SIDE_PX as usize) as f64 + 0.5,
    );
    let ray = rays.through(x, y);
    let (origin, direction) = (ray.origin.as_dvec3(), ray.direction.as_dvec3());
    // |o + t d|² = r²: t² + 2 (o·d) t + |o|² − r² = 0.
    let b = origin.dot(direction);
    let discriminant = b * b - (origin.length_squared() - (RADIUS_M as f64).powi(2));
    (discriminant >= 0.0).then(|| origin + (-b - discriminant.sqrt()) * direction)
}

/// At 18 m the sphere spans about 50 pixels across 320: its level must drop most of the
/// triangles, and the pixels it covers must be those whose centre ray meets the sphere
/// but along the silhouette, where a level may lie inside by at most
/// `detail_levels::MAX_ERROR_PX` (a tenth of the rim's pixels allowed here), with the
/// shading normals within a few degrees of the sphere's (the worst at the rim, where the
/// ray meets the true sphere away from the facet). Measured (the line this prints) at a
/// fifth of a pixel of the levels' measured deviations: 6,360 of 101,760 triangles
/// drawn, no pixel off the rim, normals within 2.5°; at a quarter of them 3,180, normals
/// 7.1° off. With the simplifier's estimates instead: at a quarter 6,360 triangles, one
/// pixel off, 3.4°; at an eighth 12,720, none off, 0.9°.
#[test]
fn a_far_fine_sphere_keeps_its_silhouette_and_normals_with_a_fraction_of_its_triangles() {
    let Some(gpu) = common::gpu() else { return };
    // No light with shadow maps: the level is bound by the pixels alone.
    let scene = sphere_scene(false, None);
    let camera = camera_at(18.0);
    let settings = RenderSettings::default();
    let (_, renderer) = common::drawn_with(&gpu, (&scene, &[]), &settings, (&camera, [SIDE_PX; 2]), |_| {});
    let (drawn, shown) = renderer.triangles_in_view();
    assert!(
        4 * drawn <= shown,
        "a level of at most a quarter of the triangles: {drawn} of {shown}"
    );
    let surfaces = lightpaint::render::capture_surfaces_at(
        &gpu,
        &scene,
        &camera,
        None,
        [SIDE_PX; 2],
        Detail::Levels(&ShadowViews::default()),
    )
    .expect("surfaces");
    let rays = CameraRays::new(&camera, SIDE_PX, SIDE_PX);
    let (mut covered, mut missed, mut extra) = (0usize, 0usize, 0usize);
    let mut worst_normal_deg = 0.0f64;
    for (index, surface) in surfaces.iter().enumerate() {
        match (surface, true_hit(&rays, index)) {
            (Some(s), Some(hit)) => {
                covered += 1;
                let angle = s.normal.angle_between(hit.normalize()).to_degrees();
                worst_normal_deg = worst_normal_deg.max(angle);
            }
            (None, Some(_)) => missed += 1,
            (Some(_), None) => extra += 1,
            (None, None) => {}
        }
    }
    // The disc's circumference in pixels, from the pixels it covers.
    let circumference_px = 2.0 * (std::f64::consts::PI * covered as f64).sqrt();
    eprintln!(
        "far sphere: {drawn} of {shown} triangles drawn; {missed} pixels missed, {extra} beyond; normals within {worst_normal_deg:.2}°"
    );
    assert!(covered > 1500, "the sphere covers {covered} pixels");
    assert!(
        (missed + extra) as f64 <= 0.1 * circumference_px,
        "{missed} pixels missed and {extra} covered beyond the sphere along a rim of {circumference_px:.0} pixels"
    );
    assert!(
        worst_normal_deg < 3.5,
        "a shading normal {worst_normal_deg:.2}° off the sphere's"
    );
}

/// Each object's level is chosen anew with the camera: close up (half a metre from the
/// surface) the mesh is drawn as it is; far away under a point light 2.5 m from the
/// sphere's centre, whose cube maps' texels on the sphere are narrower than a fifth of
/// a pixel, it keeps more of its triangles than without the light (14,520 against 8,160
/// measured, the floor's included), and the frame of the sphere on
/// a floor with the defaults stays the frame drawn from the whole mesh but at a few
/// isolated pixels (the reduced shading's sample choices along the rim; none measured) —
/// no shadow of the mesh on its own level.
#[test]
fn a_lit_frame_drawn_from_levels_is_the_frame_drawn_from_the_whole_meshes() {
    let Some(gpu) = common::gpu() else { return };
    let scene = sphere_scene(true, Some(2.5));
    let settings = RenderSettings::default();
    let close = camera_at(1.5);
    let (_, renderer) = common::drawn_with(&gpu, (&scene, &[]), &settings, (&close, [SIDE_PX; 2]), |_| {});
    let (drawn, shown) = renderer.triangles_in_view();
    // Close up every triangle of the sphere is drawn: a level of it keeps at most 80 %
    // of them, which with the whole floor (1,800) would fall short of the sphere's own.
    // (The flat, untextured floor may be drawn from long triangles: nothing varies at
    // its vertices.)
    assert!(
        drawn >= SPHERE_TRIANGLES,
        "close up the whole sphere: {drawn} triangles drawn"
    );
    let far = camera_at(18.0);
    let frame = |levels: bool| {
        common::drawn_with(&gpu, (&scene, &[]), &settings, (&far, [SIDE_PX; 2]), |r| {
            r.set_detail_levels(levels)
        })
    };
    let ((with_levels, renderer), (whole, _)) = (frame(true), frame(false));
    let (drawn_lit, _) = renderer.triangles_in_view();
    let unlit = sphere_scene(true, None);
    let (_, unlit_renderer) = common::drawn_with(&gpu, (&unlit, &[]), &settings, (&far, [SIDE_PX; 2]), |_| {});
    let (drawn_unlit, _) = unlit_renderer.triangles_in_view();
    eprintln!(
        "sphere and floor from 18 m: {drawn_lit} triangles drawn under the lamp, {drawn_unlit} without, of {shown}"
    );
    assert!(
        drawn_unlit < drawn_lit && drawn_lit < shown,
        "the lamp's texels keep more triangles: {drawn_lit} lit, {drawn_unlit} unlit, of {shown}"
    );
    let far_apart = with_levels
        .pixels()
        .zip(whole.pixels())
        .filter(|(a, b)| a.0.iter().zip(b.0).any(|(x, y)| x.abs_diff(y) > 8))
        .count();
    assert!(far_apart <= 20, "{far_apart} pixels more than 8/255 apart");
}

/// A lamp brought up to the sphere with the camera still needs a finer level (its maps'
/// texels shrink): the frame after the move draws it, byte for byte the frame of a
/// renderer that never saw the lamp far away (the surfaces drawn for the coarser level
/// are not kept).
#[test]
fn a_lamp_moved_near_with_the_camera_still_redraws_the_finer_level() {
    let Some(gpu) = common::gpu() else { return };
    let settings = RenderSettings::default();
    let far = camera_at(18.0);
    let near_lamp = sphere_scene(true, Some(2.5));
    let far_lamp = sphere_scene(true, Some(40.0));
    let (_, mut moved) = common::drawn_with(&gpu, (&far_lamp, &[]), &settings, (&far, [SIDE_PX; 2]), |_| {});
    let (drawn_far_lamp, _) = moved.triangles_in_view();
    moved.set_lights(&near_lamp.lights);
    moved.render(&far, [SIDE_PX; 2], &settings, FrameQuality::default());
    let after_move = moved.read_image().expect("a frame was drawn").expect("readback");
    let (drawn_after_move, _) = moved.triangles_in_view();
    let (fresh, fresh_renderer) = common::drawn_with(&gpu, (&near_lamp, &[]), &settings, (&far, [SIDE_PX; 2]), |_| {});
    assert!(
        drawn_far_lamp < drawn_after_move,
        "the near lamp keeps more triangles: {drawn_after_move} against {drawn_far_lamp}"
    );
    assert_eq!(drawn_after_move, fresh_renderer.triangles_in_view().0);
    assert_eq!(common::differing_pixels(&after_move, &fresh), 0);
}

/// A flat, untextured floor of 96 × 96 quads under a spot (a hot spot and a cone's edge
/// shaded per pixel), seen from 3 m: nothing varies at its vertices, so the frame draws
/// it from a level of long edges, a sixteenth of its triangles or fewer, and the frame
/// is the frame drawn from the whole floor (its surface is the same plane, its normal
/// the same: at most a few pixels differ, by rounding at the new triangles' edges).
/// Baked light at its vertices brings back the edge rule (`MAX_EDGE_PX`): the light
/// interpolated between them would change with their spacing.
#[test]
fn a_flat_floor_with_nothing_varying_at_its_vertices_is_drawn_from_long_triangles() {
    let Some(gpu) = common::gpu() else { return };
    let mut scene = Scene::default();
    scene.materials.push(lightpaint::scene::Material::default());
    scene.objects.push(shapes::plane(8.0, 96, 1.0).into_object("floor"));
    let mut spot = common::scenes::white_light(
        lightpaint::scene::LightKind::Spot {
            inner_cone_rad: 0.3,
            outer_cone_rad: 0.5,
        },
        Vec3::new(0.3, 1.5, -0.2),
        6.0,
    );
    spot.direction = Vec3::new(0.2, -1.0, 0.1).normalize();
    scene.lights.push(spot);
    let settings = RenderSettings::default();
    let camera = Camera::looking_at(Vec3::new(0.0, 1.6, 2.6), Vec3::ZERO, 50f32.to_radians(), 0.05);
    let frame = |levels: bool, baked: bool| {
        let mut renderer = common::renderer_for(&gpu, &scene, &[], &settings);
        renderer.set_detail_levels(levels);
        if baked {
            let vertices = scene.objects[0].positions.len();
            renderer.set_baked_indirect(Some(&BakedIndirect {
                objects: vec![vec![[0.3, 0.2, 0.1]; vertices]],
            }));
        }
        renderer.render(&camera, [SIDE_PX; 2], &settings, FrameQuality::default());
        let image = renderer.read_image().expect("a frame was drawn").expect("readback");
        (image, renderer.triangles_in_view())
    };
    let (from_levels, (drawn, shown)) = frame(true, false);
    let (whole, _) = frame(false, false);
    eprintln!("flat floor from 3 m: {drawn} of {shown} triangles drawn");
    assert!(16 * drawn <= shown, "{drawn} of {shown} triangles drawn");
    let lit = whole.pixels().filter(|p| p.0[0] > 40).count();
    assert!(lit > 1000, "the spot lights the floor ({lit} pixels)");
    let far_apart = from_levels
        .pixels()
        .zip(whole.pixels())
        .filter(|(a, b)| a.0.iter().zip(b.0).any(|(x, y)| x.abs_diff(y) > 2))
        .count();
    let differing = common::differing_pixels(&from_levels, &whole);
    eprintln!("flat floor from 3 m: {differing} pixels differ, {far_apart} by more than 2/255");
    assert!(far_apart <= 8, "{far_apart} pixels more than 2/255 apart");
    let (_, (drawn_baked, _)) = frame(true, true);
    assert!(
        drawn_baked > 4 * drawn,
        "baked light keeps short edges: {drawn_baked} triangles against {drawn}"
    );
}

/// Per-vertex shading shows values at the vertices: its frames draw the meshes as they
/// are, byte for byte whether levels are on or not.
#[test]
fn per_vertex_frames_draw_the_whole_meshes() {
    let Some(gpu) = common::gpu() else { return };
    let scene = sphere_scene(true, Some(2.5));
    let mut settings = RenderSettings::default();
    settings.shadows.per_vertex = true;
    let far = camera_at(18.0);
    let frame = |levels: bool| drawn(&gpu, &scene, &settings, &far, levels);
    let ((with_levels, (drawn_triangles, shown)), (whole, _)) = (frame(true), frame(false));
    assert_eq!(drawn_triangles, shown);
    assert_eq!(common::differing_pixels(&with_levels, &whole), 0);
}

fn drawn(
    gpu: &GpuContext,
    scene: &Scene,
    settings: &RenderSettings,
    camera: &Camera,
    levels: bool,
) -> (image::RgbaImage, (u64, u64)) {
    let mut renderer = common::renderer_for(gpu, scene, &[], settings);
    renderer.set_detail_levels(levels);
    renderer.render(camera, [SIDE_PX; 2], settings, FrameQuality::default());
    let image = renderer.read_image().expect("a frame was drawn").expect("readback");
    (image, renderer.triangles_in_view())
}
