//! `lightpaint paint`: scripted strokes applied to a project, saved with their log.

use std::path::Path;

use lightpaint::project::sphere_cache;

use super::CliError;

/// `paint`: the transfer comes from a bake with `bounces`, or (None) from the direct-only
/// log-SH estimate.
pub fn paint(file: &Path, strokes: &Path, output: &Path, bounces: Option<usize>) -> Result<(), CliError> {
    use lightpaint::paint::{Painter, Transfer, View, ViewRecord, script::Script};
    if !lightpaint::project::is_project_path(output) {
        return Err(CliError::Usage(format!(
            "{}: the output must be a project file (.lightpaint)",
            output.display()
        )));
    }
    let mut document = super::open_document(file)?;
    let script = Script::load(strokes)?;
    let camera = document.view().camera();
    let fallback = ViewRecord::of(&View {
        camera,
        width_px: 1280,
        height_px: 720,
    });
    script.lock_lights(strokes, &mut document.scene.lights)?;
    let mut records = script.records(strokes, fallback)?;
    // As the editor's strokes: the project's hidden objects neither take paint nor stop the
    // brush, and its locked lights stay as they are.
    for record in &mut records {
        record.hidden_objects = document.hidden_objects.iter().map(|&o| o as u32).collect();
        record.locked_lights = document.scene.locked_lights();
    }
    let started = std::time::Instant::now();
    let scene = &document.scene;
    let maps = match bounces {
        Some(bounces) => Some(baked_maps(&document, file, output, bounces)?),
        None => None,
    };
    // Strokes read the direct light through the blockers the editor shows (hidden objects
    // cast none), with or without maps: after a bake only the bounce comes from them.
    let blockers = sphere_cache::cached_or_fitted(scene, &document.settings.blockers, document.project_path.as_deref())
        .shown_spheres(&document.hidden_objects);
    let transfer: Box<dyn Transfer> =
        lightpaint::shading::frame_transfer::transfer_for(maps.as_ref(), scene, &blockers, &document.settings);
    let bvh = lightpaint::bake::scene_bvh::SceneBvh::build(scene);
    say!(
        "{} the transfer of {} lights in {:.0} ms",
        if maps.is_some() {
            "baked"
        } else {
            "estimated (direct light, log-SH shadows)"
        },
        scene.lights.len(),
        started.elapsed().as_secs_f64() * 1000.0
    );
    let mut intensities = scene.light_intensities();
    let mut painter = Painter::new();
    {
        let transfer = transfer.as_ref();
        let keeps = painter.carry_over(scene, &bvh, transfer, &intensities, &document.painting.strokes);
        if keeps > 0 {
            say!("{keeps} Keep area(s) of the saved strokes hold");
        }
        for (k, record) in records.into_iter().enumerate() {
            let started = std::time::Instant::now();
            let report = painter.paint(scene, &bvh, transfer, &mut intensities, record);
            let names: Vec<&str> = report.selected.iter().map(|&i| scene.lights[i].name.as_str()).collect();
            say!(
                "stroke {k}: {:?}, {} vertices, lights [{}]: {} ({:.1} ms)",
                report.outcome,
                report.hit_vertices,
                names.join(", "),
                report.message,
                started.elapsed().as_secs_f64() * 1000.0
            );
        }
    }
    drop(transfer);
    document.scene.set_light_intensities(&intensities);
    document.painting.strokes.extend(painter.log().cloned());
    document.save(output)?;
    say!(
        "wrote {} ({} strokes in its log)",
        output.display(),
        document.painting.strokes.len()
    );
    Ok(())
}

/// The maps of `document`'s scene with `bounces`: from the project's bake cache when it is
/// fresh (in whatever precision it was baked; only changed lights re-baked), else baked;
/// written to `output`'s cache, never to the input's.
fn baked_maps(
    document: &lightpaint::project::Document,
    file: &Path,
    output: &Path,
    bounces: usize,
) -> Result<lightpaint::bake::ImportanceMaps, CliError> {
    use lightpaint::project::bake_cache::{self, CacheLookup};
    let requested = lightpaint::bake::BakeSettings {
        bounces,
        ..Default::default()
    };
    let (found, settings) = match &document.project_path {
        Some(project) => {
            bake_cache::load_in_its_precision(&bake_cache::cache_path(project), &document.scene, &requested)
        }
        None => (CacheLookup::Missing, requested),
    };
    let never = std::sync::atomic::AtomicBool::new(false);
    let quiet = |_: usize, _: usize| {};
    let Some((maps, what, _)) = bake_cache::maps_from(&document.scene, &settings, found, &quiet, &never) else {
        return Err(CliError::Usage(format!("{}: the bake was cancelled", file.display())));
    };
    say!("{}: {what}", file.display());
    let key = bake_cache::BakeKey::of(&document.scene, &settings);
    if let Err(e) = bake_cache::save(&bake_cache::cache_path(output), &key, &maps) {
        eprintln!("warning: {}: cannot write the bake cache: {e}", output.display());
    }
    Ok(maps)
}
