//! Which shadow path each light takes (`super::compiled_paths` says which shading code a
//! frame's pipelines carry for it).
//!
//! One choice per light for the whole frame (no receiver shows a seam where a light
//! would change path), the same in the editor, the CLI, the CPU reference and painting:
//! every light exact under [`LightPaths::Exact`], none under [`LightPaths::Harmonics`];
//! under [`LightPaths::Auto`], first, sphere and area lights whose every blocker is a
//! sphere that is its mesh ([`super::sphere_casters`]: balls) go exact at any size, up to
//! the exact-light budget, brightest first (the closed form is their true shadow); then
//! with shadow maps on, as many as the shadow-map views
//! hold (lights of one view, then cubes, each brightest at the centre first), every
//! point, spot and directional light and every sphere or area light up to
//! [`super::shadow_maps::MAX_MAPPED_HALF_ANGLE_DEG`] in radius at the scene's centre
//! takes shadow maps of the real triangles (the sized ones with penumbrae); then of the rest, the sphere and area lights whose angular radius at the
//! scene's centre is under [`super::AUTO_EXACT_BELOW_HALF_ANGLE_DEG`] go exact, at most
//! the settings' `exact_light_budget` of them, those whose exact shadows matter most
//! first: brightness at the centre times the share of the scene's surface where some
//! blocker cuts the light's disc (a light no blocker shadows gains nothing from the
//! exact path); the others take the SH.

pub use super::compiled_paths::{CompiledPaths, SceneLighting, compiled_paths};
pub use super::light_path_context::LightPathContext;

use super::gpu_types::{GpuLight, MAX_SHADOW_VIEWS, SHADOW_PATH_EXACT, SHADOW_PATH_MAP, SHADOW_PATH_SH};
use super::{LightPaths, ShadowSettings};
use crate::scene::Light;

/// The lights as the shaders and the CPU reference take them, each on the shadow path
/// `settings` give it (`GpuLight::shadow_path`, and `first_shadow_view` for the lights with
/// shadow maps; see the module's documentation for the choice).
pub fn shading_lights(lights: &[Light], settings: &ShadowSettings, context: &LightPathContext) -> Vec<GpuLight> {
    let mut gpu_lights: Vec<GpuLight> = lights.iter().map(GpuLight::new).collect();
    // Lights whose path is settled: exact ones shadowed by true spheres, then mapped ones.
    let mut settled = vec![false; lights.len()];
    let mut exact_budget = settings.exact_light_budget as usize;
    if settings.light_paths == LightPaths::Auto {
        for i in exact_sphere_lights(&gpu_lights, settings, context) {
            gpu_lights[i].shadow_path = SHADOW_PATH_EXACT;
            settled[i] = true;
            exact_budget -= 1;
        }
    }
    if settings.light_paths == LightPaths::Auto && settings.shadow_map_size > 0 {
        // Lights of one view first (the sun, spots, far lights), then the cubes, each
        // group brightest at the centre first: when the views run out, the lights left
        // on the other paths are the dim ones that would each have taken six.
        let centre = context.centre();
        let mut wanted: Vec<(usize, usize, f64)> = gpu_lights
            .iter()
            .enumerate()
            .filter(|&(i, _)| !settled[i])
            .filter_map(|(i, light)| {
                let count = super::shadow_maps::view_count(light, context.centre, context.radius_m)?;
                let brightness = crate::scene::luminance(super::cpu::incidence(light, centre).irradiance);
                Some((i, count, brightness))
            })
            .collect();
        wanted.sort_by(|a, b| a.1.cmp(&b.1).then(b.2.total_cmp(&a.2)).then(a.0.cmp(&b.0)));
        let mut views = 0;
        for (i, count, _) in wanted {
            if views + count <= MAX_SHADOW_VIEWS {
                let light = &mut gpu_lights[i];
                light.shadow_path = SHADOW_PATH_MAP;
                light.first_shadow_view = views as u32;
                light.shadow_view_count = count as u32;
                views += count;
                settled[i] = true;
            }
        }
    }
    let exact: Vec<bool> = match settings.light_paths {
        LightPaths::Exact => vec![true; lights.len()],
        LightPaths::Harmonics => vec![false; lights.len()],
        LightPaths::Auto => auto_exact(&gpu_lights, settings, context, &settled, exact_budget),
    };
    for ((light, exact), settled) in gpu_lights.iter_mut().zip(exact).zip(settled) {
        if !settled {
            light.shadow_path = if exact { SHADOW_PATH_EXACT } else { SHADOW_PATH_SH };
        }
    }
    gpu_lights
}

/// Auto's first choice: the sized lights whose every blocker is a sphere that is its mesh
/// ([`SphereCasters`]), brightest at the centre first, at most the exact-light budget. For
/// them the exact path is the true shadow at any size, where maps would place a small
/// light's edge only to a texel and the SH blur a large one's.
fn exact_sphere_lights(lights: &[GpuLight], settings: &ShadowSettings, context: &LightPathContext) -> Vec<usize> {
    let centre = context.centre();
    let min_cap_ratio = settings.min_cap_ratio as f64;
    let mut chosen: Vec<(usize, f64)> = (0..lights.len())
        .filter(|&i| lights[i].source_size > 0.0)
        .filter(|&i| context.shadowed_only_by_exact_spheres(&lights[i], min_cap_ratio))
        .map(|i| {
            let brightness = crate::scene::luminance(super::cpu::incidence(&lights[i], centre).irradiance);
            (i, brightness)
        })
        .collect();
    chosen.sort_by(|a, b| b.1.total_cmp(&a.1).then(a.0.cmp(&b.0)));
    chosen.truncate(settings.exact_light_budget as usize);
    chosen.into_iter().map(|(i, _)| i).collect()
}

/// Auto's choice among the lights not `settled`: which go exact, at most `budget`.
fn auto_exact(
    lights: &[GpuLight],
    settings: &ShadowSettings,
    context: &LightPathContext,
    settled: &[bool],
    budget: usize,
) -> Vec<bool> {
    let centre = context.centre();
    let candidates: Vec<usize> = (0..lights.len())
        .filter(|&i| !settled[i])
        .filter(|&i| {
            let light = &lights[i];
            light.source_size > 0.0 && LightPaths::Auto.is_exact(super::cpu::incidence(light, centre).cap_ratio)
        })
        .collect();
    let mut exact = vec![false; lights.len()];
    // Within the budget every candidate goes: no need to weigh them.
    if candidates.len() <= budget {
        for i in candidates {
            exact[i] = true;
        }
        return exact;
    }
    let min_cap_ratio = settings.min_cap_ratio as f64;
    let mut ranked: Vec<(usize, f64, f64)> = candidates
        .into_iter()
        .map(|i| {
            let brightness = crate::scene::luminance(super::cpu::incidence(&lights[i], centre).irradiance);
            (
                i,
                brightness * context.shadowed_share(&lights[i], min_cap_ratio),
                brightness,
            )
        })
        .collect();
    // Most shadow first, then the brightest; equal ones in scene order, so the choice is
    // stable.
    ranked.sort_by(|a, b| b.1.total_cmp(&a.1).then(b.2.total_cmp(&a.2)).then(a.0.cmp(&b.0)));
    for &(i, _, _) in ranked.iter().take(budget) {
        exact[i] = true;
    }
    exact
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::blockers::Sphere;
    use crate::scene::Scene;
    use crate::shading::gpu_types::{UNIFORM_BLOCKER_CAPACITY, UNIFORM_LIGHT_CAPACITY};
    use glam::Vec3;

    fn light(kind: crate::scene::LightKind, intensity: f32) -> crate::scene::Light {
        crate::scene::Light {
            name: "light".into(),
            kind,
            color: glam::Vec3::ONE,
            intensity,
            position: glam::Vec3::Y,
            direction: glam::Vec3::NEG_Y,
            range: None,
            locked: false,
        }
    }

    #[test]
    fn pipelines_compile_only_the_paths_the_lights_take() {
        use crate::scene::LightKind;
        let points = [light(LightKind::Point, 1.0), light(LightKind::Directional, 1.0)];
        let sphere = light(LightKind::Sphere { radius_m: 0.1 }, 1.0);
        let one_sphere = std::slice::from_ref(&sphere);
        let with_sphere = [points[0].clone(), sphere.clone()];
        let five_spheres = vec![sphere.clone(); 5];
        let (auto, exact, harmonics) = (LightPaths::Auto, LightPaths::Exact, LightPaths::Harmonics);
        let origin = glam::Vec3::ZERO;
        // 0.1 m at 1 m is 5.7°; at 0.11 m the light is 65° wide, above Auto's 40°.
        let near_sphere = glam::Vec3::new(0.0, 0.89, 0.0);
        let (maps, no_maps) = (crate::shading::SUGGESTED_SHADOW_MAP_SIZE, 0);
        // (exact, exact_wide, harmonics, maps, soft maps) for these paths, budget, map
        // size, lights, centre and sky.
        let compiled = |light_paths,
                        exact_light_budget,
                        shadow_map_size,
                        lights: &[crate::scene::Light],
                        centre,
                        has_environment| {
            let settings = ShadowSettings {
                light_paths,
                exact_light_budget,
                shadow_map_size,
                ..ShadowSettings::default()
            };
            let lighting = SceneLighting {
                has_environment,
                has_terrain: false,
                single_sided: false,
            };
            let paths = compiled_paths(
                &shading_lights(lights, &settings, &LightPathContext::at(centre)),
                lighting,
                0,
            );
            (
                paths.exact,
                paths.exact_wide,
                paths.harmonics,
                paths.maps,
                paths.soft_maps,
            )
        };
        // Auto with maps: lights of no size and small sized ones take shadow maps (the
        // sized ones with the penumbra filter), wide ones the SH.
        let f = false;
        assert_eq!(compiled(auto, 4, maps, &points, origin, f), (f, f, f, true, f));
        assert_eq!(compiled(auto, 4, maps, &with_sphere, origin, f), (f, f, f, true, true));
        assert_eq!(
            compiled(auto, 4, maps, one_sphere, origin, true),
            (f, f, true, true, true)
        );
        assert_eq!(compiled(auto, 4, maps, one_sphere, near_sphere, f), (f, f, true, f, f));
        assert_eq!(compiled(auto, 4, maps, &five_spheres, origin, f), (f, f, f, true, true));
        // Without maps: small sized lights go exact, four at most unless the budget allows
        // more, the rest the SH.
        assert_eq!(compiled(auto, 4, no_maps, &points, origin, f), (f, f, true, f, f));
        assert_eq!(
            compiled(auto, 4, no_maps, &with_sphere, origin, f),
            (true, f, true, f, f)
        );
        assert_eq!(compiled(auto, 4, no_maps, one_sphere, origin, f), (true, f, f, f, f));
        assert_eq!(
            compiled(auto, 4, no_maps, one_sphere, origin, true),
            (true, f, true, f, f)
        );
        assert_eq!(
            compiled(auto, 4, no_maps, one_sphere, near_sphere, f),
            (f, f, true, f, f)
        );
        assert_eq!(
            compiled(auto, 4, no_maps, &five_spheres, origin, f),
            (true, f, true, f, f)
        );
        assert_eq!(
            compiled(auto, 8, no_maps, &five_spheres, origin, f),
            (true, true, f, f, f)
        );
        assert_eq!(compiled(auto, 0, no_maps, &with_sphere, origin, f), (f, f, true, f, f));
        assert_eq!(compiled(auto, 4, maps, &[], origin, f), (f, f, f, f, f));
        assert_eq!(compiled(exact, 0, maps, &points, origin, f), (true, f, f, f, f));
        assert_eq!(
            compiled(harmonics, 4, maps, &with_sphere, origin, f),
            (f, f, true, f, f)
        );
        // One point light more than the views hold cubes: it takes the SH.
        let more = vec![points[0].clone(); MAX_SHADOW_VIEWS / 6 + 1];
        assert_eq!(compiled(auto, 4, maps, &more, origin, f), (f, f, true, true, f));
        let terrain = SceneLighting {
            has_environment: false,
            has_terrain: true,
            single_sided: false,
        };
        assert!(compiled_paths(&[], terrain, 0).terrain);
        assert!(!compiled_paths(&[], terrain, 0).environment);
        let sky = SceneLighting {
            has_environment: true,
            ..terrain
        };
        assert!(compiled_paths(&[], sky, 0).environment);
        let single_sided = SceneLighting {
            single_sided: true,
            ..terrain
        };
        assert!(compiled_paths(&[], single_sided, 0).cull_back_faces);
        assert!(!compiled_paths(&[], terrain, 0).cull_back_faces);
        // A rect's polygon and a disk's are compiled in apart, each only for its lights.
        let area = |kind| {
            GpuLight::new(&Light {
                kind,
                ..points[0].clone()
            })
        };
        let rect = area(LightKind::Rect {
            width_m: 0.6,
            height_m: 0.4,
            turn_rad: 0.0,
        });
        let disk = area(LightKind::Disk { radius_m: 0.3 });
        let area_paths = |lights: &[GpuLight]| {
            let paths = compiled_paths(lights, terrain, 0);
            (paths.rect_lights, paths.disk_lights)
        };
        assert_eq!(area_paths(&[rect]), (true, false));
        assert_eq!(area_paths(&[disk]), (false, true));
        assert_eq!(area_paths(&[rect, disk]), (true, true));
        assert_eq!(area_paths(&[GpuLight::new(&points[0])]), (false, false));
    }

    /// Point lights take cubes of maps, the sun and a spot one view each: only a frame
    /// with such a single view compiles the views' matrices in, and a pipeline compiled
    /// for cubes alone does not shade a single view's light on the map path (while a
    /// pipeline that has them compiles, that light takes another path).
    #[test]
    fn the_views_matrices_are_compiled_in_only_for_lights_of_one_view() {
        use crate::scene::LightKind;
        let settings = ShadowSettings::default();
        let lighting = SceneLighting {
            has_environment: false,
            has_terrain: false,
            single_sided: false,
        };
        let context = LightPathContext::at(Vec3::ZERO);
        let point = light(LightKind::Point, 1.0);
        let sun = light(LightKind::Directional, 1.0);
        let cubes = shading_lights(std::slice::from_ref(&point), &settings, &context);
        let mixed = shading_lights(&[point.clone(), sun], &settings, &context);
        assert!(cubes.iter().all(|l| l.shadow_path == SHADOW_PATH_MAP));
        assert!(mixed.iter().all(|l| l.shadow_path == SHADOW_PATH_MAP));
        let cube_paths = compiled_paths(&cubes, lighting, 0);
        let mixed_paths = compiled_paths(&mixed, lighting, 0);
        assert!(cube_paths.maps && !cube_paths.single_view_maps);
        assert!(mixed_paths.maps && mixed_paths.single_view_maps);
        let (cube_light, sun_light) = (&mixed[0], &mixed[1]);
        assert_eq!(cube_light.shadow_view_count, 6);
        assert_eq!(sun_light.shadow_view_count, 1);
        assert!(cube_paths.shades(cube_light) && !cube_paths.shades(sun_light));
        assert!(mixed_paths.shades(cube_light) && mixed_paths.shades(sun_light));
        assert!(!CompiledPaths::NONE.shades(cube_light));
    }

    /// Twelve point lights, the last the dimmest, then a sun: the sun's one view comes
    /// first, then ten cubes (61 views) by brightness; the dimmest two take the SH.
    #[test]
    fn when_the_views_run_out_single_views_and_bright_lights_come_first() {
        use crate::scene::LightKind;
        // Two more cubes than the views hold after the sun's one.
        let cubes = (MAX_SHADOW_VIEWS - 1) / 6;
        let points = cubes + 2;
        let mut lights: Vec<Light> = (0..points)
            .map(|k| Light {
                position: Vec3::new(k as f32, 2.0, 0.0),
                ..light(LightKind::Point, points as f32 - k as f32)
            })
            .collect();
        lights.push(light(LightKind::Directional, 0.1));
        let settings = ShadowSettings {
            shadow_map_size: crate::shading::SUGGESTED_SHADOW_MAP_SIZE,
            ..ShadowSettings::default()
        };
        let shaded = shading_lights(&lights, &settings, &LightPathContext::at(Vec3::ZERO));
        let paths: Vec<u32> = shaded.iter().map(|l| l.shadow_path).collect();
        let mut expected = vec![SHADOW_PATH_MAP; cubes];
        expected.extend([SHADOW_PATH_SH, SHADOW_PATH_SH, SHADOW_PATH_MAP]);
        assert_eq!(paths, expected);
        assert_eq!(shaded[points].first_shadow_view, 0);
        assert_eq!(shaded[0].first_shadow_view, 1);
        assert_eq!(shaded[cubes - 1].first_shadow_view as usize, 1 + 6 * (cubes - 1));
    }

    #[test]
    fn storage_buffers_are_read_only_past_the_uniform_capacities() {
        let lighting = SceneLighting {
            has_environment: false,
            has_terrain: false,
            single_sided: false,
        };
        let lights = |n| vec![GpuLight::new(&light(crate::scene::LightKind::Point, 1.0)); n];
        let at_capacity = compiled_paths(&lights(UNIFORM_LIGHT_CAPACITY), lighting, UNIFORM_BLOCKER_CAPACITY);
        assert!(!at_capacity.light_overflow && !at_capacity.blocker_overflow);
        let past = compiled_paths(
            &lights(UNIFORM_LIGHT_CAPACITY + 1),
            lighting,
            UNIFORM_BLOCKER_CAPACITY + 1,
        );
        assert!(past.light_overflow && past.blocker_overflow);
    }

    #[test]
    fn the_budget_lets_the_brightest_sized_lights_go_exact() {
        use crate::scene::LightKind;
        let lights = [
            light(LightKind::Sphere { radius_m: 0.1 }, 2.0),
            light(LightKind::Point, 50.0),
            light(LightKind::Sphere { radius_m: 0.1 }, 9.0),
            light(LightKind::Disk { radius_m: 0.2 }, 100.0),
            light(LightKind::Sphere { radius_m: 0.1 }, 9.0),
        ];
        // Without maps, which would take every one of these lights.
        let allowed = |light_paths, exact_light_budget| -> Vec<u32> {
            let settings = ShadowSettings {
                light_paths,
                exact_light_budget,
                shadow_map_size: 0,
                ..ShadowSettings::default()
            };
            shading_lights(&lights, &settings, &LightPathContext::at(glam::Vec3::ZERO))
                .iter()
                .map(|l| u32::from(l.shadow_path == SHADOW_PATH_EXACT))
                .collect()
        };
        // At the centre, 1 m below them all: the disk (100 × π 0.2² ≈ 12.6 lux) outshines
        // the 9 cd spheres; of those equal two, the first in the scene wins; the point light
        // has no disc.
        assert_eq!(allowed(LightPaths::Auto, 2), [0, 0, 1, 1, 0]);
        assert_eq!(allowed(LightPaths::Auto, 3), [0, 0, 1, 1, 1]);
        assert_eq!(allowed(LightPaths::Auto, 64), [1, 0, 1, 1, 1]);
        assert_eq!(allowed(LightPaths::Auto, 0), [0; 5]);
        assert_eq!(allowed(LightPaths::Exact, 0), [1; 5]);
        assert_eq!(allowed(LightPaths::Harmonics, 64), [0; 5]);
    }

    /// Two small sphere lights over a floor, the right one brighter; a ball shadows the
    /// left one's light onto the floor's middle, while the right one's shadow of it falls
    /// off the floor. With room for one exact light, the left one goes: its shadows are
    /// the ones that matter. Without receivers to look at, the brighter one goes.
    #[test]
    fn the_budget_goes_to_the_lights_whose_blockers_matter() {
        use crate::scene::LightKind;
        let sphere_light = |x: f32, intensity| Light {
            position: Vec3::new(x, 3.0, 0.0),
            ..light(LightKind::Sphere { radius_m: 0.1 }, intensity)
        };
        let lights = [sphere_light(-2.0, 10.0), sphere_light(2.0, 12.0)];
        let ball = Sphere {
            center: Vec3::new(-1.0, 1.5, 0.0),
            radius_m: 0.3,
            disc_normal: glam::Vec3::ZERO,
        };
        // The floor from −2 to 2 m in x and z: the left light's shadow of the ball is
        // centred at x = 0, the right one's at x = −4.
        let receivers = (0..11)
            .flat_map(|i| (0..11).map(move |j| (Vec3::new(-2.0 + 0.4 * i as f32, 0.0, -2.0 + 0.4 * j as f32), Vec3::Y)))
            .collect();
        let floor = LightPathContext {
            centre: Vec3::ZERO,
            radius_m: 0.0,
            receivers,
            blockers: vec![ball],
            ..LightPathContext::default()
        };
        // Without maps, which would take both small lights.
        let settings = ShadowSettings {
            exact_light_budget: 1,
            shadow_map_size: 0,
            ..ShadowSettings::default()
        };
        let exact = |context: &LightPathContext| -> Vec<u32> {
            shading_lights(&lights, &settings, context)
                .iter()
                .map(|l| u32::from(l.shadow_path == SHADOW_PATH_EXACT))
                .collect()
        };
        assert!(floor.shadowed_share(&GpuLight::new(&lights[0]), 0.03) > 0.0);
        assert_eq!(floor.shadowed_share(&GpuLight::new(&lights[1]), 0.03), 0.0);
        assert_eq!(exact(&floor), [1, 0]);
        assert_eq!(exact(&LightPathContext::at(Vec3::ZERO)), [0, 1]);
    }

    /// Balls over a floor: their fitted spheres are the balls, so a small light and a
    /// wide one both go exact (maps would place the 1° edge only to a texel; the SH blurs
    /// the 60° one). Cubes in their place: the small light takes maps, the wide one the SH.
    #[test]
    fn lights_shadowed_only_by_true_spheres_go_exact_at_any_size() {
        use crate::blockers::{BlockerSettings, fit_scene};
        use crate::scene::{LightKind, shapes};
        let scene_with = |caster: &dyn Fn(Vec3) -> crate::scene::MeshObject| Scene {
            objects: vec![
                shapes::plane(8.0, 8, 1.0).into_object("floor"),
                caster(Vec3::new(0.0, 0.6, 0.0)),
                caster(Vec3::new(1.1, 0.4, 0.5)),
            ],
            ..Scene::default()
        };
        let balls = scene_with(&|at| {
            shapes::uv_sphere(0.3, 48, 24)
                .transformed(glam::Affine3A::from_translation(at))
                .into_object("ball")
        });
        let cubes = scene_with(&|at| {
            shapes::cuboid(Vec3::splat(0.3))
                .transformed(glam::Affine3A::from_translation(at))
                .into_object("cube")
        });
        // Sphere lights 10 m up, 1° and 60° in radius there.
        let sized = |half_angle_deg: f32| Light {
            position: Vec3::new(0.2, 10.0, 0.1),
            ..light(
                LightKind::Sphere {
                    radius_m: 10.0 * half_angle_deg.to_radians().sin(),
                },
                300.0,
            )
        };
        let settings = ShadowSettings::default();
        assert!(settings.shadow_map_size > 0 && settings.light_paths == LightPaths::Auto);
        let path = |scene: &Scene, half_angle_deg| {
            let blockers = fit_scene(scene, &BlockerSettings::default()).spheres();
            let context = LightPathContext::of_scene(scene, &blockers);
            shading_lights(&[sized(half_angle_deg)], &settings, &context)[0].shadow_path
        };
        assert_eq!(path(&balls, 1.0), SHADOW_PATH_EXACT);
        assert_eq!(path(&balls, 60.0), SHADOW_PATH_EXACT);
        assert_eq!(path(&cubes, 1.0), SHADOW_PATH_MAP);
        assert_eq!(path(&cubes, 60.0), SHADOW_PATH_SH);
        // A light of no size keeps its maps (hard edges of the real triangles).
        let blockers = fit_scene(&balls, &BlockerSettings::default()).spheres();
        let context = LightPathContext::of_scene(&balls, &blockers);
        let point = light(LightKind::Point, 1.0);
        assert_eq!(
            shading_lights(&[point], &settings, &context)[0].shadow_path,
            SHADOW_PATH_MAP
        );
    }
}
