//! Baked indirect light in the real-time renderer: the per-vertex irradiance reaches the
//! right vertices of the right objects on the GPU (closed form k_d/π·E through the tone
//! curve), the CPU reference agrees, and `lightpaint render` adds a project's baked
//! indirect light from its bake cache.

mod common;

use std::f64::consts::PI;

use glam::{Affine3A, Vec3, Vec4};
use lightpaint::render::{AntiAliasing, GpuContext, ShadowFrame, render_cpu_image, render_logsh_image};
use lightpaint::scene::{Camera, Material, Scene, shapes};
use lightpaint::shading::{BakedIndirect, RenderSettings, ShadowSettings};

/// Two white Lambertian 1 m squares side by side (x < 0 and x > 0) seen from straight
/// above with −x on the left of the image, no lights, and before them an object with no
/// triangles (which the GPU does not upload, so object indices and GPU objects differ).
fn two_squares() -> (Scene, Camera) {
    let square = |x: f32, name: &str| {
        shapes::plane(1.0, 2, 1.0)
            .transformed(Affine3A::from_translation(Vec3::new(x, 0.0, 0.0)))
            .into_object(name)
    };
    let mut empty = square(0.0, "nothing");
    empty.indices.clear();
    let scene = Scene {
        objects: vec![empty, square(-0.5, "left"), square(0.5, "right")],
        materials: vec![Material {
            base_color: Vec4::ONE,
            metallic: 0.0,
            specular: 0.0,
            ..Material::default()
        }],
        ..Scene::default()
    };
    let camera = Camera {
        position: Vec3::new(0.0, 3.0, 0.0),
        forward: Vec3::NEG_Y,
        up: Vec3::NEG_Z,
        yfov_rad: 30f32.to_radians(),
        znear: 0.1,
        zfar: None,
    };
    (scene, camera)
}

#[test]
fn each_vertex_gets_its_own_baked_irradiance_on_the_gpu_and_the_cpu() {
    let Some(gpu) = common::gpu() else { return };
    // Every pixel shaded, and the default deferred frame, whose surface buffer draws an
    // untextured object without baked light by a pipeline of its own.
    for shadows in [ShadowSettings::default().every_pixel(), ShadowSettings::default()] {
        baked_irradiance_at_each_vertex(&gpu, &shadows);
    }
}

fn baked_irradiance_at_each_vertex(gpu: &GpuContext, shadows: &ShadowSettings) {
    let (scene, camera) = two_squares();
    let vertices = |o: usize| scene.objects[o].positions.len();
    let (red, blue) = ([2.0, 0.0, 0.0], [0.0, 0.0, 0.5]);
    let indirect = BakedIndirect {
        objects: vec![vec![], vec![red; vertices(1)], vec![blue; vertices(2)]],
    };
    let settings = RenderSettings::default();
    let frame = ShadowFrame {
        scene: &scene,
        camera: &camera,
        settings: &settings,
        shadows,
        blockers: &[],
        baked_indirect: Some(&indirect),
        width: 64,
        height: 32,
    };
    let gpu_image = render_logsh_image(gpu, &frame, AntiAliasing::None).expect("GPU frame");
    let cpu_image = render_cpu_image(gpu, &frame).expect("CPU frame");
    // A white Lambertian surface reflects k_d/π·E: 2/π red on the left, 0.5/π blue on the right.
    let expected = |e: f64| common::expected_8bit(e / PI, 0.0);
    for (image, name) in [(&gpu_image, "GPU"), (&cpu_image, "CPU")] {
        let (left, right) = (image.get_pixel(20, 16), image.get_pixel(44, 16));
        let checks = [
            (left[0], expected(2.0), "left red"),
            (left[2], expected(0.0), "left blue"),
            (right[0], expected(0.0), "right red"),
            (right[2], expected(0.5), "right blue"),
        ];
        for (actual, expected, what) in checks {
            assert!(
                (actual as f64 - expected).abs() <= 1.0,
                "{name} {what}: pixel {actual}, expected {expected:.2} (downsample {})",
                shadows.shading_downsample
            );
        }
    }

    let without = ShadowFrame {
        baked_indirect: None,
        ..frame
    };
    let dark = render_logsh_image(gpu, &without, AntiAliasing::None).expect("GPU frame");
    assert_eq!(dark.get_pixel(20, 16)[0], 0, "no light, no indirect: black");
}

/// `lightpaint render` on a baked project adds the indirect light: the frame gets brighter
/// and no pixel darker; `--no-baked-indirect` gives the frame of an unbaked project.
#[test]
fn render_adds_the_baked_indirect_light_of_a_baked_project() {
    if common::no_gpu_wanted() {
        eprintln!("GPU test not run: {}=1", common::NO_GPU_ENV);
        return;
    }
    let dir = tempfile::tempdir().unwrap();
    lightpaint::samples::write_sample_project(dir.path()).unwrap();
    let project = dir.path().join("sample.lightpaint");
    let render = |name: &str, extra: &[&str]| -> image::RgbaImage {
        let output = dir.path().join(name);
        let mut args: Vec<std::ffi::OsString> = vec!["render".into(), project.clone().into(), "-o".into()];
        args.push(output.clone().into());
        args.extend(["--width", "160", "--height", "90", "--aa", "none"].map(Into::into));
        args.extend(extra.iter().map(Into::into));
        let arg_refs: Vec<&std::ffi::OsStr> = args.iter().map(|a| a.as_os_str()).collect();
        let out = common::run_lightpaint(&arg_refs);
        assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
        image::open(&output).expect("a PNG").to_rgba8()
    };
    let unbaked = render("unbaked.png", &[]);
    let out = common::run_lightpaint(&[std::ffi::OsStr::new("bake"), project.as_os_str()]);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let baked = render("baked.png", &[]);
    let switched_off = render("off.png", &["--no-baked-indirect"]);
    assert_eq!(switched_off, unbaked, "--no-baked-indirect renders as before the bake");
    let luma = |image: &image::RgbaImage| {
        image
            .pixels()
            .map(|p| p[0] as u64 + p[1] as u64 + p[2] as u64)
            .sum::<u64>()
    };
    assert!(
        luma(&baked) > luma(&unbaked) * 101 / 100,
        "indirect light brightens the frame"
    );
    for (a, b) in baked.pixels().zip(unbaked.pixels()) {
        for c in 0..3 {
            assert!(
                a[c] as i32 + 1 >= b[c] as i32,
                "indirect light never darkens a pixel: {a:?} vs {b:?}"
            );
        }
    }
}
