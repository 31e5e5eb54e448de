//! `lightpaint study`: the real-time renderer's knobs measured against the path tracer.

use std::path::PathBuf;

use lightpaint::render::GpuContext;

use super::CliError;

pub fn study(
    quick: bool,
    output_dir: PathBuf,
    scenes: Vec<lightpaint::samples::Sample>,
    knobs: Option<String>,
) -> Result<(), CliError> {
    let gpu = GpuContext::headless()?;
    let options = lightpaint::study::StudyOptions {
        quick,
        output_dir,
        only_scenes: (!scenes.is_empty()).then_some(scenes),
        only_knobs: knobs,
    };
    let started = std::time::Instant::now();
    let results = lightpaint::study::run_study(&gpu, &options, |line| say!("{line}"))?;
    say!(
        "study of {} settings on {} scene(s) in {:.0} s → {}",
        results.rows.len(),
        results.references.iter().filter(|r| r.bounces == 0).count(),
        started.elapsed().as_secs_f64(),
        options.output_dir.display()
    );
    Ok(())
}
