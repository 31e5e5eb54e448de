//! `lightpaint render`: a project or scene rendered offscreen — log-SH on the GPU, the f64
//! CPU twin, the raster without shadows, or the reference path tracer — into a PNG.

use std::path::Path;

use lightpaint::project::{Document, sphere_cache};
use lightpaint::render::{
    AntiAliasing, GpuContext, Redraw, ShadowFrame, ShadowRenderer, render_cpu_image, render_image,
};
use lightpaint::shading::BakedIndirect;
use lightpaint::shading::blocker_reach::mean_blockers_in_reach;

use super::CliError;
use super::args::RenderArgs;

pub fn render(args: &RenderArgs) -> Result<(), CliError> {
    let document = super::open_document(&args.file)?;
    let mut settings = document.settings;
    if let Some(exposure) = args.exposure {
        settings.exposure_ev = exposure;
    }
    if let Some(background) = args.background {
        settings.background_srgb8 = background;
    }
    let format = super::output::check_output(&args.output)?;
    let camera = document.view().camera();
    // Hidden objects are neither drawn nor cast shadows, as in the editor.
    let scene = document.shown_scene();
    if args.reference {
        let reference = lightpaint::reference::ReferenceSettings {
            samples_per_pixel: args.spp,
            bounces: args.bounces,
            seed: args.seed,
        };
        return render_reference_png(&args.file, &scene, &camera, &settings, &reference, args, format);
    }
    let gpu = GpuContext::headless()?;
    let mut shadows = settings.shadows;
    shadows.order = args.order.unwrap_or(shadows.order);
    shadows.exp = args.exp.unwrap_or(shadows.exp);
    shadows.epsilon = args.eps.unwrap_or(shadows.epsilon);
    shadows.ratio_attenuation |= args.ratio_attenuation;
    shadows.light_paths = args.light_paths.unwrap_or(shadows.light_paths);
    shadows.brdf = args.brdf.unwrap_or(shadows.brdf);
    shadows.exact_light_budget = args.exact_lights.unwrap_or(shadows.exact_light_budget);
    shadows.shadow_map_size = args.shadow_map_size.unwrap_or(shadows.shadow_map_size);
    shadows.terrain.azimuths = args.terrain_azimuths.unwrap_or(shadows.terrain.azimuths);
    shadows.terrain.pyramid_levels = args.terrain_levels.unwrap_or(shadows.terrain.pyramid_levels);
    // The CPU reference shades every pixel; a project's per-vertex choice is for the GPU.
    shadows.per_vertex = (shadows.per_vertex || args.per_vertex) && !args.cpu;
    shadows.shading_downsample = match args.cpu {
        true => 1,
        false => args.shading_downsample.unwrap_or(shadows.shading_downsample),
    };
    let no_shadows = args.no_shadows || !shadows.enabled;
    let problems = if args.cpu {
        shadows.problems()
    } else {
        shadows.gpu_problems()
    };
    if !no_shadows && !problems.is_empty() {
        return Err(CliError::Usage(problems.join("; ")));
    }
    let mut blocker_settings = settings.blockers;
    if let Some(budget) = args.blockers {
        blocker_settings.budget = budget;
    }
    let fitted = std::time::Instant::now();
    let blockers = if no_shadows {
        Vec::new()
    } else {
        let project = document.project_path.as_deref();
        let fit = sphere_cache::cached_or_fitted(&document.scene, &blocker_settings, project);
        for line in fit.report(&document.scene) {
            log::info!("blockers: {line}");
        }
        // No mesh is left out silently: say which cast no soft (SH) shadow, and why.
        let without: Vec<(String, String)> = fit
            .per_object
            .iter()
            .zip(&document.scene.objects)
            .enumerate()
            .filter(|(index, _)| !document.hidden_objects.contains(index))
            .filter_map(|(_, (set, object))| set.skipped.as_ref().map(|why| (object.name.clone(), why.clone())))
            .collect();
        if !without.is_empty() {
            say!(
                "no sphere blockers, so no soft shadows from: {}{}",
                objects_by_reason(&without),
                if shadows.shadow_map_size > 0 {
                    " — their shadows of the lights on shadow maps (points, spots, the sun, small sphere and area lights) come from those"
                } else {
                    " — shadow maps (--shadow-map-size, off here) would give their shadows of points, spots, the sun and small sphere and area lights"
                }
            );
        }
        fit.shown_spheres(&document.hidden_objects)
    };
    let fit_ms = fitted.elapsed().as_secs_f64() * 1000.0;
    let indirect = if settings.baked_indirect && !args.no_baked_indirect {
        baked_indirect(&document)
    } else {
        None
    };
    let frame = ShadowFrame {
        baked_indirect: indirect.as_ref(),
        scene: &scene,
        camera: &camera,
        settings: &settings,
        shadows: &shadows,
        blockers: &blockers,
        width: args.width,
        height: args.height,
    };
    let started = std::time::Instant::now();
    let (image, renderer) = if no_shadows {
        (
            render_image(&gpu, &scene, &camera, &settings, args.width, args.height)?,
            "raster, no shadows".to_string(),
        )
    } else if args.cpu {
        (
            render_cpu_image(&gpu, &frame)?,
            format!(
                "CPU f64 reference, {}{}",
                describe(&frame, &document.hidden_objects),
                describe_indirect(&indirect)
            ),
        )
    } else {
        let mut shadow_renderer = ShadowRenderer::new(&gpu, &frame, args.aa)?;
        let image = shadow_renderer.read_image()?;
        // Per vertex, which meshes the frame lit at their vertices
        // (`shading::vertex_lighting`); the others shade each pixel.
        let lit = if shadows.per_vertex {
            let meshes = scene.objects.iter().filter(|o| !o.indices.is_empty()).count();
            let lit = shadow_renderer.objects_lit_at_vertices();
            format!("; per vertex, {lit} of {meshes} meshes lit at their vertices")
        } else {
            String::new()
        };
        (
            image,
            format!(
                "log-SH, {}{lit}{}",
                describe(&frame, &document.hidden_objects),
                describe_indirect(&indirect)
            ),
        )
    };
    let elapsed = started.elapsed();
    if args.time_frames > 0 && !no_shadows {
        time_frames(&gpu, &frame, args.time_frames, args.aa)?;
    }
    super::output::write_image(&args.output, &image, format)?;
    say!(
        "rendered {} ({}×{}, {renderer}) with {} in {:.0} ms (sphere fit {fit_ms:.0} ms) → {}",
        args.file.display(),
        args.width,
        args.height,
        gpu.adapter_summary(),
        elapsed.as_secs_f64() * 1000.0,
        args.output.display()
    );
    Ok(())
}

/// `render --reference`: the path tracer, with a progress bar over its passes.
fn render_reference_png(
    file: &Path,
    scene: &lightpaint::scene::Scene,
    camera: &lightpaint::scene::Camera,
    settings: &lightpaint::shading::RenderSettings,
    reference: &lightpaint::reference::ReferenceSettings,
    args: &RenderArgs,
    format: image::ImageFormat,
) -> Result<(), CliError> {
    if args.width == 0 || args.height == 0 || args.width > 16_384 || args.height > 16_384 {
        return Err(CliError::Usage(format!(
            "a reference image must be 1–16384 pixels on each side, not {}×{}",
            args.width, args.height
        )));
    }
    let started = std::time::Instant::now();
    let bar = indicatif::ProgressBar::new(reference.samples_per_pixel as u64);
    bar.set_style(
        indicatif::ProgressStyle::with_template("path tracing {bar:40} {pos}/{len} samples per pixel, {eta} left")
            .unwrap_or_else(|_| indicatif::ProgressStyle::default_bar()),
    );
    let image = lightpaint::reference::render_reference(scene, camera, args.width, args.height, reference, |passes| {
        bar.set_position(passes as u64)
    });
    bar.finish_and_clear();
    let elapsed = started.elapsed().as_secs_f64();
    let display = image.to_srgb8(settings.exposure_ev as f64, settings.background_srgb8);
    super::output::write_image(&args.output, &display, format)?;
    if image.discarded_samples > 0 {
        eprintln!(
            "warning: {}: {} samples were not finite and were left out",
            file.display(),
            image.discarded_samples
        );
    }
    let mode = if reference.bounces == 0 {
        "direct light".to_string()
    } else {
        format!("{} bounces", reference.bounces)
    };
    say!(
        "rendered {} ({}×{}, reference path tracer, {} spp, {mode}, seed {}) in {elapsed:.1} s, {:.2} M rays/s → {}",
        file.display(),
        args.width,
        args.height,
        reference.samples_per_pixel,
        reference.seed,
        image.rays_cast as f64 / elapsed.max(1e-9) / 1e6,
        args.output.display()
    );
    Ok(())
}

/// Draws `count` frames after a warm-up and prints the mean and best time per frame: each
/// drawn anew (as for a new view), then each after the lights were set again (as after a
/// stroke or an intensity edit, which keeps the surfaces the view rasterised), then each
/// after the first light moved a centimetre (as while it is dragged: its maps redrawn).
fn time_frames(gpu: &GpuContext, frame: &ShadowFrame, count: u32, anti_aliasing: AntiAliasing) -> Result<(), CliError> {
    let mut renderer = ShadowRenderer::new(gpu, frame, anti_aliasing)?;
    renderer.draw_and_wait(Redraw::Everything)?;
    if let Some(grid) = renderer.light_grid_in_words() {
        say!("lights' grid: {grid} (each point walks its box's lights on the SH and shadow-map paths)");
    }
    let (in_view, shown) = renderer.triangles_in_view();
    say!(
        "triangles drawn from the camera: {in_view} of {shown} (objects outside its view culled, far ones at a coarser level of detail)"
    );
    let (map_views, map_triangles) = renderer.shadow_map_triangles();
    if map_views > 0 {
        say!(
            "triangles drawn into the shadow maps: {map_triangles} in {map_views} views, {:.1} % of every shown one in each (objects outside a view culled)",
            100.0 * map_triangles as f64 / (map_views * shown.max(1)) as f64
        );
    }
    if let Some(listed) = renderer.listed_pixels() {
        let listed = listed?;
        say!(
            "pixels the upsampling left: {} to the soft layer (two levels), {} shaded in full; low-resolution samples the soft layer left: {}",
            listed.from_soft_layer,
            listed.in_full,
            listed.samples_in_full
        );
    }
    let batches = [
        (Redraw::Everything, ""),
        (Redraw::AfterLightEdit, " after a light edit (same view)"),
        (Redraw::AfterLightMove, " after the first light moved (same view)"),
        (
            Redraw::AfterLightMoveDrafted,
            " while the first light is dragged (its moved maps drafted, as in the editor)",
        ),
    ];
    for (redraw, what) in batches {
        // A new timer for each kind of frame: the passes' times are of these frames alone.
        let timed_passes = renderer.time_passes();
        let (mean, best) = mean_and_best_ms(count, || renderer.draw_and_wait(redraw))?;
        say!(
            "{count} frames{what}: mean {mean:.1} ms ({:.1} fps), best {best:.1} ms",
            1000.0 / mean
        );
        if timed_passes {
            let passes: Vec<String> = renderer
                .pass_times_ms()
                .iter()
                .map(|(pass, ms)| format!("{pass} {ms:.1} ms"))
                .collect();
            say!("GPU time per pass: {}", passes.join(", "));
        }
        if matches!(redraw, Redraw::AfterLightMove | Redraw::AfterLightMoveDrafted) {
            let (views, triangles) = renderer.shadow_map_triangles();
            say!("shadow maps redrawn each frame: {views} views, {triangles} triangles");
        }
    }
    Ok(())
}

/// Mean and best wall-clock milliseconds of `count` calls of `draw`.
fn mean_and_best_ms(
    count: u32,
    mut draw: impl FnMut() -> Result<(), lightpaint::render::RenderError>,
) -> Result<(f64, f64), CliError> {
    let mut times_ms = Vec::with_capacity(count as usize);
    for _ in 0..count {
        let started = std::time::Instant::now();
        draw()?;
        times_ms.push(started.elapsed().as_secs_f64() * 1000.0);
    }
    let mean = times_ms.iter().sum::<f64>() / times_ms.len().max(1) as f64;
    let best = times_ms.iter().copied().fold(f64::INFINITY, f64::min);
    Ok((mean, best))
}

/// The baked indirect light of a project from its bake cache, if it has a usable one
/// (a stale or unreadable cache is reported and left out; `lightpaint bake` rebuilds it).
fn baked_indirect(document: &Document) -> Option<BakedIndirect> {
    use lightpaint::project::bake_cache::{self, CacheLookup};
    let project = document.project_path.as_ref()?;
    let path = bake_cache::cache_path(project);
    match bake_cache::load_for_scene(&path, &document.scene) {
        CacheLookup::Fresh(maps) => Some(BakedIndirect::from_maps(&document.scene, &maps)),
        CacheLookup::LightsChanged { maps, lights } => {
            eprintln!(
                "warning: {}: {} light(s) moved since the bake; their indirect light is left out (run `lightpaint bake`)",
                path.display(),
                lights.len()
            );
            Some(BakedIndirect::from_maps(&document.scene, &maps))
        }
        CacheLookup::Missing => None,
        CacheLookup::Unusable(reason) => {
            eprintln!("warning: no baked indirect light: {reason} (run `lightpaint bake`)");
            None
        }
    }
}

fn describe_indirect(indirect: &Option<BakedIndirect>) -> &'static str {
    if indirect.is_some() {
        ", baked indirect light"
    } else {
        ""
    }
}

/// Receivers the summary's mean blocker counts are taken over (vertices, strided).
const SUMMARY_RECEIVERS: usize = 2000;

fn describe(frame: &ShadowFrame, hidden: &std::collections::BTreeSet<usize>) -> String {
    let (shadows, blockers, scene) = (frame.shadows, frame.blockers, frame.scene);
    let blocker_count = blockers.len();
    // What the SH path's blocker walk costs and finds per surface point.
    let reach = if blocker_count == 0 {
        String::new()
    } else {
        mean_blockers_in_reach(shadows, blockers, scene, hidden, SUMMARY_RECEIVERS)
            .map(|mean| format!(": {}", mean.in_words()))
            .unwrap_or_default()
    };
    let terrain = if scene.terrain.is_some() {
        format!(
            ", terrain W {} × {} levels",
            shadows.terrain.azimuths, shadows.terrain.pyramid_levels
        )
    } else {
        String::new()
    };
    let resolution = if shadows.per_vertex {
        ", per vertex".to_string()
    } else if shadows.shading_downsample > 1 {
        let d = shadows.shading_downsample;
        format!(", shaded 1 in {d}×{d} pixels")
    } else {
        String::new()
    };
    let maps = match shadows.shadow_map_size {
        0 => String::new(),
        size => {
            let lights = frame.shading_lights();
            let views = lightpaint::shading::shadow_maps::shadow_views(&lights, &frame.scene.bounds(), size);
            format!(", shadow maps: {}", views.atlas.in_words())
        }
    };
    format!(
        "order {}, {:?}, eps {}, {blocker_count} blockers{reach}{resolution}{terrain}, {:?} light paths{maps}, {} BRDF",
        shadows.order,
        shadows.exp,
        shadows.epsilon,
        shadows.light_paths,
        shadows.brdf.name()
    )
}

/// Objects named with why they have no spheres, `(name, why)`, as one line: each reason
/// once, after the names it holds for ("A, B (why); C (other)"), at most
/// [`NAMES_PER_REASON`] names a reason and then how many more — a scene of hundreds of
/// meshes fitted with a budget of 0 gets one short line, not hundreds of clauses.
fn objects_by_reason(without: &[(String, String)]) -> String {
    let mut reasons: Vec<(&str, Vec<&str>)> = Vec::new();
    for (name, why) in without {
        match reasons.iter_mut().find(|(reason, _)| reason == why) {
            Some((_, names)) => names.push(name),
            None => reasons.push((why, vec![name])),
        }
    }
    reasons
        .iter()
        .map(|(why, names)| {
            let shown = names
                .iter()
                .take(NAMES_PER_REASON)
                .copied()
                .collect::<Vec<_>>()
                .join(", ");
            match names.len().saturating_sub(NAMES_PER_REASON) {
                0 => format!("{shown} ({why})"),
                more => format!("{shown} and {more} more ({why})"),
            }
        })
        .collect::<Vec<_>>()
        .join("; ")
}

/// The most objects `objects_by_reason` names for one reason.
const NAMES_PER_REASON: usize = 8;

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn objects_without_spheres_are_grouped_by_reason_and_counted_past_eight() {
        let mut without = vec![("Floor".to_string(), "open".to_string())];
        without.extend((0..20).map(|i| (format!("Object {i}"), "a budget of 0".to_string())));
        without.push(("Card".to_string(), "open".to_string()));
        assert_eq!(
            objects_by_reason(&without),
            "Floor, Card (open); Object 0, Object 1, Object 2, Object 3, Object 4, Object 5, \
             Object 6, Object 7 and 12 more (a budget of 0)"
        );
    }
}
