//! Objects outside the camera's frustum are left out of the passes drawn from it
//! (`scene::Frustum`, `GpuScene::write_frame`), on lavapipe: the frame must be byte for
//! byte the one drawn with every object, in the default (deferred) mode and per vertex,
//! and the culling must have left something out for the comparison to mean anything.

mod common;

use lightpaint::blockers::fit_scene;
use lightpaint::project::Document;
use lightpaint::render::{AntiAliasing, Compilation, FrameQuality, GpuContext, SceneRenderer};
use lightpaint::scene::Camera;
use lightpaint::shading::RenderSettings;

const SIZE: [u32; 2] = [320, 180];

/// The frame `settings` give of the sample from `camera`, with or without culling, and the
/// triangles drawn from the camera against those shown.
fn frame(
    gpu: &GpuContext,
    document: &Document,
    settings: &RenderSettings,
    camera: &Camera,
    culling: bool,
) -> (image::RgbaImage, (u64, u64)) {
    let blockers = fit_scene(&document.scene, &settings.blockers).spheres();
    let mut renderer = SceneRenderer::new(
        &gpu.device,
        &gpu.queue,
        &document.scene,
        &blockers,
        &settings.shadows,
        AntiAliasing::default(),
        Compilation::Blocking,
    );
    renderer.set_view_culling(culling);
    renderer.render(camera, SIZE, settings, FrameQuality::default());
    let image = renderer.read_image().expect("a frame was drawn").expect("readback");
    (image, renderer.triangles_in_view())
}

#[test]
fn culling_what_the_camera_cannot_see_leaves_the_frame_unchanged() {
    let Some(gpu) = common::gpu() else { return };
    let document = Document::open(&common::repo_path("projects/sample/sample.lightpaint")).expect("sample opens");
    let whole = document
        .camera
        .map_or_else(|| document.scene.initial_camera(), |o| o.camera());
    // Close to the smallest object, from the side the sample's camera sees it from,
    // turned 50° to the side: some objects leave the view, the floor and the wall stay.
    let smallest = document
        .scene
        .objects
        .iter()
        .map(|o| o.bounds())
        .min_by(|a, b| a.radius().total_cmp(&b.radius()))
        .expect("the sample has objects");
    let toward_camera = (whole.position - smallest.center()).normalize();
    let position = smallest.center() + toward_camera * 3.0 * smallest.radius();
    let turn = glam::Quat::from_rotation_y(50f32.to_radians());
    let close = Camera::looking_at(
        position,
        position + turn * (smallest.center() - position),
        whole.yfov_rad,
        whole.znear,
    );
    for per_vertex in [false, true] {
        let mut settings = document.settings;
        settings.shadows.per_vertex = per_vertex;
        let (culled, (in_view, shown)) = frame(&gpu, &document, &settings, &close, true);
        let (every_object, (all_drawn, _)) = frame(&gpu, &document, &settings, &close, false);
        assert!(
            in_view < shown,
            "the close view must cull something ({in_view} of {shown} triangles)"
        );
        assert_eq!(all_drawn, shown, "without culling every shown triangle is drawn");
        let differing = culled
            .pixels()
            .zip(every_object.pixels())
            .filter(|(a, b)| a != b)
            .count();
        assert_eq!(
            differing, 0,
            "per vertex {per_vertex}: the culled frame differs from the whole one at {differing} pixels"
        );
    }
}
