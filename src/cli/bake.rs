//! `lightpaint bake`: the source-importance maps baked into the project's cache.

use std::path::Path;

use super::CliError;

pub fn bake(file: &Path, settings: &lightpaint::bake::BakeSettings) -> Result<(), CliError> {
    let document = super::open_document(file)?;
    let scene = &document.scene;
    let order = settings.order;
    let bar = indicatif::ProgressBar::new(scene.vertex_count() as u64);
    bar.set_style(
        indicatif::ProgressStyle::with_template("baking {bar:40} {pos}/{len} vertices, {eta} left")
            .unwrap_or_else(|_| indicatif::ProgressStyle::default_bar()),
    );
    let started = std::time::Instant::now();
    let never = std::sync::atomic::AtomicBool::new(false);
    let progress = |done: usize, _: usize| bar.set_position(done as u64);
    // A project keeps its maps in the bake cache beside it; a bare scene has none.
    let maps = match &document.project_path {
        Some(project) => {
            let cache = lightpaint::project::bake_cache::cache_path(project);
            lightpaint::project::bake_cache::bake_with_cache(scene, settings, &cache, &progress, &never).map(
                |(maps, what)| {
                    bar.finish_and_clear();
                    say!("{what}");
                    maps
                },
            )
        }
        None => lightpaint::bake::bake_maps_counting(scene, settings, &progress, &never).map(|(maps, rays)| {
            let seconds = started.elapsed().as_secs_f64().max(1e-9);
            bar.finish_and_clear();
            say!("baked ({rays} rays, {:.2} M rays/s)", rays as f64 / seconds / 1e6);
            maps
        }),
    };
    bar.finish_and_clear();
    let Some(maps) = maps else {
        return Err(CliError::Usage("the bake was cancelled".into()));
    };
    let pairs = scene.vertex_count() * scene.lights.len();
    let entries = maps.entry_count();
    say!(
        "maps of {}: {} vertices × {} lights, {entries} (vertex, light) pairs stored ({:.0} % of {pairs}; {:.2} % of the pairs light reaches kept at threshold {}), order {order}, {:.1} MiB in memory, in {:.0} ms ({} bounce(s))",
        file.display(),
        scene.vertex_count(),
        scene.lights.len(),
        if pairs == 0 {
            0.0
        } else {
            100.0 * entries as f64 / pairs as f64
        },
        100.0 * maps.kept_fraction(),
        settings.relative_threshold,
        maps.memory_bytes() as f64 / (1024.0 * 1024.0),
        started.elapsed().as_secs_f64() * 1000.0,
        settings.bounces
    );
    Ok(())
}
