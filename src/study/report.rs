//! The study's outputs: `study.csv` (one row per scene and knob setting), `study.md` (the
//! table, Pareto front marked), `pareto.png` (error against time per frame, plotters) and
//! `images/` (reference | real time | error heat map).

use std::fmt::Write as _;
use std::path::Path;

use plotters::prelude::*;

use super::grid::{Knobs, Lighting};
use super::metrics::DisplayImage;
use super::{StudyError, StudyResults, StudyRow};
use crate::sh::ExpMethod;

pub fn write_all(results: &StudyResults, dir: &Path) -> Result<(), StudyError> {
    write_text(&dir.join("study.csv"), &csv(results))?;
    write_text(&dir.join("study.md"), &markdown(results))?;
    pareto_plot(results, &dir.join("pareto.png"))
}

fn write_text(path: &Path, text: &str) -> Result<(), StudyError> {
    crate::project::write_atomically(path, text.as_bytes()).map_err(|source| StudyError::Write {
        path: path.to_path_buf(),
        source,
    })
}

/// Indices of the rows of `rows` no other row beats on both time and RMSE (the Pareto
/// front), fastest first.
pub fn pareto_front(rows: &[&StudyRow]) -> Vec<usize> {
    let mut order: Vec<usize> = (0..rows.len()).collect();
    order.sort_by(|&a, &b| {
        rows[a]
            .ms_per_frame
            .total_cmp(&rows[b].ms_per_frame)
            .then(rows[a].errors.rmse.total_cmp(&rows[b].errors.rmse))
    });
    let mut front = Vec::new();
    let mut best_error = f64::INFINITY;
    for i in order {
        if rows[i].errors.rmse < best_error {
            best_error = rows[i].errors.rmse;
            front.push(i);
        }
    }
    front
}

fn csv(results: &StudyResults) -> String {
    let mut text = String::from(
        "scene,knobs,order,exp,epsilon,ratio_attenuation,per_vertex,blockers,reference_bounces,baked_indirect,ms_per_frame,rmse,relative_l1,ssim,shadow_rmse,extreme_pixels\n",
    );
    for row in &results.rows {
        let s = row.knobs.shadows;
        let _ = writeln!(
            text,
            "{},{},{},{},{},{},{},{},{},{},{:.3},{:.5},{:.5},{:.5},{},{}",
            row.scene,
            row.knobs.label(),
            s.map_or(String::new(), |s| s.order.to_string()),
            s.map_or("none".into(), |s| super::grid::method_label(s.exp)),
            s.map_or(String::new(), |s| s.epsilon.to_string()),
            s.is_some_and(|s| s.ratio_attenuation),
            s.is_some_and(|s| s.per_vertex),
            row.blocker_count,
            match row.knobs.lighting {
                Lighting::Direct => 0,
                Lighting::Gi { .. } => crate::bake::BakeSettings::default().bounces,
            },
            row.knobs.lighting == Lighting::Gi { baked_indirect: true },
            row.ms_per_frame,
            row.errors.rmse,
            row.errors.relative_l1,
            row.errors.ssim,
            row.errors.shadow_rmse.map_or(String::new(), |e| format!("{e:.5}")),
            row.extreme_pixels
        );
    }
    text
}

fn markdown(results: &StudyResults) -> String {
    let mut text = format!(
        "# Study results\n\n{}×{} pixels on {}. Errors are of the displayed image against the \
         reference path tracer (direct light; rows ending in `-gi` against the reference with \
         one bounce, `-gi-baked` adding the baked maps' indirect light); ms per frame are GPU \
         frames (CPU shading for `ref`). ★ marks the Pareto front of each scene among the \
         direct-light rows (no setting is both faster and more accurate).\n\n",
        results.width, results.height, results.adapter
    );
    for reference in &results.references {
        let _ = writeln!(
            text,
            "- {}: reference ({} bounces) {} spp in {:.1} s, its own noise RMSE {:.4}",
            reference.scene, reference.bounces, reference.samples_per_pixel, reference.seconds, reference.noise_rmse
        );
    }
    text.push_str(
        "\n| scene | knobs | blockers | ms/frame | RMSE | rel. L1 | SSIM | shadow RMSE | extreme px | front |\n",
    );
    text.push_str("|---|---|---:|---:|---:|---:|---:|---:|---:|:---:|\n");
    for scene in scene_names(results) {
        let rows: Vec<&StudyRow> = results
            .rows
            .iter()
            .filter(|r| r.scene == scene && r.knobs.lighting == Lighting::Direct)
            .collect();
        let front = pareto_front(&rows);
        let gi_rows = results
            .rows
            .iter()
            .filter(|r| r.scene == scene && r.knobs.lighting != Lighting::Direct);
        for (i, row) in rows.iter().copied().chain(gi_rows).enumerate() {
            let _ = writeln!(
                text,
                "| {} | {} | {} | {:.1} | {:.4} | {:.4} | {:.4} | {} | {} | {} |",
                row.scene,
                row.knobs.label(),
                row.blocker_count,
                row.ms_per_frame,
                row.errors.rmse,
                row.errors.relative_l1,
                row.errors.ssim,
                row.errors.shadow_rmse.map_or("–".into(), |e| format!("{e:.4}")),
                row.extreme_pixels,
                if front.contains(&i) { "★" } else { "" }
            );
        }
    }
    text.push_str(&equal_error_markdown(results));
    text.push_str(&penumbra_markdown(results));
    text.push_str(&sphere_fit_markdown(results));
    text.push_str(&stability_markdown(results));
    text
}

/// Per scene: the path tracer's samples per pixel to match the default frame's shadows.
fn equal_error_markdown(results: &StudyResults) -> String {
    if results.equal_error.is_empty() {
        return String::new();
    }
    let mut text = String::from(
        "\n## Path tracing to the same shadow error\n\nThe fewest samples per pixel (powers of \
         two) at which an independent path-traced image of direct light is as close to the \
         converged reference over the shadowed pixels as the default real-time frame, and \
         its tracing time (all cores) against the frame's; then the path tracer's own \
         shadowed-pixel RMSE at each count tried, to one past the match.\n\n| scene | frame \
         shadow RMSE | frame ms | path tracer spp | path tracer ms | ratio | path tracer \
         (spp: RMSE) |\n|---|---:|---:|---:|---:|---:|---|\n",
    );
    for e in &results.equal_error {
        let _ = writeln!(
            text,
            "| {} | {:.4} | {:.1} | {} | {:.0} | {:.1}× | {} |",
            e.scene,
            e.frame_shadow_rmse,
            e.frame_ms,
            e.samples_per_pixel.map_or("not reached".into(), |n| n.to_string()),
            e.trace_ms,
            e.trace_ms / e.frame_ms.max(1e-3),
            e.curve
                .iter()
                .map(|(spp, rmse)| format!("{spp}: {rmse:.4}"))
                .collect::<Vec<_>>()
                .join(", ")
        );
    }
    text
}

/// Small lights: each light size and shadow path (src/study/penumbra.rs).
fn penumbra_markdown(results: &StudyResults) -> String {
    if results.penumbrae.is_empty() {
        return String::new();
    }
    let mut text = String::from(
        "\n## Small lights: SH path against the exact path\n\nThree exact sphere blockers over a \
         white floor under one sphere light of the given angular radius (then a uniform sky); \
         the shadow maps (up to the size Auto maps) see the balls' meshes instead, and the \
         defaults fit spheres to those meshes and choose each light's path themselves; errors are the path's visibility minus the reference's (shares of the unshadowed light) \
         over the floor's penumbra (reference visibility 5–95 %) and umbra (≤ 5 %); the \
         reference's own noise over the penumbra is given beside them.\n\n| light | path | penumbra px | penumbra RMS | umbra RMS | max / unshadowed | ms/frame | reference noise |\n\
         |---|---|---:|---:|---:|---:|---:|---:|\n",
    );
    for r in &results.penumbrae {
        let _ = writeln!(
            text,
            "| {} | {} | {} | {:.4} | {} | {:.3} | {:.1} | {:.4} |",
            r.light,
            match (r.defaults, r.path) {
                (false, crate::shading::ShadowPath::Exact) => "exact",
                (false, crate::shading::ShadowPath::Harmonics) => "SH",
                (false, crate::shading::ShadowPath::Map) => "maps",
                (true, crate::shading::ShadowPath::Exact) => "defaults: exact",
                (true, crate::shading::ShadowPath::Harmonics) => "defaults: SH",
                (true, crate::shading::ShadowPath::Map) => "defaults: maps",
            },
            r.penumbra_pixels,
            r.penumbra_rms,
            r.umbra_rms.map_or("–".into(), |e| format!("{e:.4}")),
            r.max_over_unshadowed,
            r.ms_per_frame,
            r.reference_noise
        );
    }
    let _ = writeln!(
        text,
        "\nCost: 8 small sphere lights (5°) over 50 blockers at {0}×{0}: {1}.",
        results.cost_size,
        results
            .eight_light_cost
            .iter()
            .map(|(path, ms)| format!("{path:?} {ms:.1} ms per frame"))
            .collect::<Vec<_>>()
            .join(", ")
    );
    text
}

/// Small lights over mesh blockers: error by sphere budget (src/study/sphere_fit.rs).
fn sphere_fit_markdown(results: &StudyResults) -> String {
    if results.sphere_fit.is_empty() {
        return String::new();
    }
    let maps = results.mesh_maps.as_ref().map_or(String::new(), |m| {
        format!(
            "\nThe shadow maps, which see the meshes themselves (no spheres): penumbra RMS {:.4}, \
             umbra RMS {}.\n",
            m.penumbra_rms,
            m.umbra_rms.map_or("–".into(), |e| format!("{e:.4}"))
        )
    });
    format!(
        "\n## Small lights over meshes: the sphere fit's share\n\nA box, a torus and a cylinder \
         over the floor under a {}° sphere light; the path tracer sees the meshes, the renderer \
         spheres fitted with each budget. The exact path is exact for its spheres, so its \
         penumbra error is the fit's.\n\n{}{maps}",
        super::sphere_fit::LIGHT_HALF_ANGLE_DEG,
        super::sphere_fit::markdown_table(&results.sphere_fit)
    )
}

/// The stability suite's table: what each extreme measured.
fn stability_markdown(results: &StudyResults) -> String {
    if results.stability.is_empty() {
        return String::new();
    }
    let (width, height) = results.stability_size;
    let mut text = format!(
        "\n## Stability at the extremes\n\nEach case is a matte floor under one light at {width}×{height} \
         (`src/study/stability.rs`): the f64 shading of every visible point must be finite, \
         non-negative and no brighter than the unshadowed light, and the f32 GPU frame close \
         to it.\n\n| case | visible px | non-finite | negative | above unshadowed | GPU within 2/255 | GPU worst | holds |\n\
         |---|---:|---:|---:|---:|---:|---:|:---:|\n"
    );
    for r in &results.stability {
        let _ = writeln!(
            text,
            "| {} | {} | {} | {} | {} | {:.2} % | {}/255 | {} |",
            r.name,
            r.visible_pixels,
            r.non_finite,
            r.negative,
            r.above_unshadowed,
            100.0 * r.gpu_within_2,
            r.gpu_worst,
            if r.holds() { "yes" } else { "**no**" }
        );
    }
    text
}

fn scene_names(results: &StudyResults) -> Vec<String> {
    let mut names: Vec<String> = Vec::new();
    for row in &results.rows {
        if !names.contains(&row.scene) {
            names.push(row.scene.clone());
        }
    }
    names
}

/// Side-by-side images are written for the defaults, the baseline and each method at the
/// default order.
pub fn wants_side_by_side(knobs: &Knobs) -> bool {
    let defaults = crate::shading::ShadowSettings::default();
    match knobs.shadows {
        None => true,
        Some(s) => {
            matches!(knobs.blockers, crate::blockers::SphereBudget::FitError(_))
                && s.order == defaults.order
                && s.epsilon == defaults.epsilon
                && !s.ratio_attenuation
                && !s.per_vertex
        }
    }
}

/// Reference | real time | signed error heat map of the luminance: black where they
/// agree, red → yellow where the real-time image is brighter, blue → cyan where it is
/// darker, saturating at a difference of 0.1.
pub fn side_by_side(
    reference: &image::RgbaImage,
    real_time: &image::RgbaImage,
    reference_display: &DisplayImage,
    real_time_display: &DisplayImage,
) -> image::RgbaImage {
    let (w, h) = (reference.width(), reference.height());
    let mut out = image::RgbaImage::new(3 * w, h);
    image::imageops::replace(&mut out, reference, 0, 0);
    image::imageops::replace(&mut out, real_time, w as i64, 0);
    let errors = reference_display
        .luminance()
        .into_iter()
        .zip(real_time_display.luminance())
        .map(|(r, t)| ((t - r) / 0.1).clamp(-1.0, 1.0));
    for (i, e) in errors.enumerate() {
        let (x, y) = (i as u32 % w, i as u32 / w);
        let strong = (2.0 * e.abs()).min(1.0);
        let saturated = (2.0 * e.abs() - 1.0).max(0.0);
        let rgb = if e >= 0.0 {
            [strong, saturated, 0.0]
        } else {
            [0.0, saturated, strong]
        };
        let [r, g, b] = rgb.map(|c| (c * 255.0) as u8);
        out.put_pixel(2 * w + x, y, image::Rgba([r, g, b, 255]));
    }
    out
}

/// Error (RMSE) against milliseconds per frame on a log axis, one panel per scene, one
/// colour per exponentiation method, the Pareto front joined by a line.
fn pareto_plot(results: &StudyResults, path: &Path) -> Result<(), StudyError> {
    let scenes = scene_names(results);
    let (width, height) = (520 * scenes.len().max(1) as u32, 560u32);
    let mut pixels = vec![255u8; (width * height * 3) as usize];
    draw_pareto(results, &scenes, &mut pixels, (width, height)).map_err(|e| StudyError::Write {
        path: path.to_path_buf(),
        source: std::io::Error::other(e),
    })?;
    let image = image::RgbImage::from_raw(width, height, pixels).expect("width × height RGB pixels");
    image.save(path).map_err(|source| StudyError::Image {
        path: path.to_path_buf(),
        source,
    })
}

fn method_colour(knobs: &Knobs) -> RGBColor {
    match knobs.shadows.map(|s| s.exp) {
        None => RGBColor(120, 120, 120),
        Some(ExpMethod::Dc) => RGBColor(31, 119, 180),
        Some(ExpMethod::Ol) => RGBColor(255, 127, 14),
        Some(ExpMethod::Hyb) => RGBColor(44, 160, 44),
        Some(ExpMethod::Ps(_)) => RGBColor(148, 103, 189),
        Some(ExpMethod::Reference) => RGBColor(214, 39, 40),
    }
}

const LEGEND: [(&str, Option<ExpMethod>); 6] = [
    ("no shadows", None),
    ("DC", Some(ExpMethod::Dc)),
    ("OL", Some(ExpMethod::Ol)),
    ("HYB", Some(ExpMethod::Hyb)),
    ("PS", Some(ExpMethod::Ps(8))),
    ("exact exp (CPU)", Some(ExpMethod::Reference)),
];

fn draw_pareto(results: &StudyResults, scenes: &[String], pixels: &mut [u8], size: (u32, u32)) -> Result<(), String> {
    let root = BitMapBackend::with_buffer(pixels, size).into_drawing_area();
    root.fill(&WHITE).map_err(|e| e.to_string())?;
    let panels = root.split_evenly((1, scenes.len().max(1)));
    for (scene, panel) in scenes.iter().zip(&panels) {
        // Errors against one reference: the rows measured against direct light.
        let rows: Vec<&StudyRow> = results
            .rows
            .iter()
            .filter(|r| &r.scene == scene && r.knobs.lighting == Lighting::Direct)
            .collect();
        let min_ms = rows
            .iter()
            .map(|r| r.ms_per_frame)
            .fold(f64::INFINITY, f64::min)
            .max(1e-3)
            * 0.8;
        let max_ms = rows.iter().map(|r| r.ms_per_frame).fold(1.0, f64::max) * 1.25;
        let max_error = rows.iter().map(|r| r.errors.rmse).fold(0.01, f64::max) * 1.1;
        let mut chart = ChartBuilder::on(panel)
            .caption(format!("{scene}: error against time per frame"), ("sans-serif", 20))
            .margin(12)
            .x_label_area_size(44)
            .y_label_area_size(60)
            .build_cartesian_2d((min_ms..max_ms).log_scale(), 0.0..max_error)
            .map_err(|e| e.to_string())?;
        chart
            .configure_mesh()
            .x_desc("ms per frame (log scale)")
            .y_desc("RMSE of the displayed image")
            .draw()
            .map_err(|e| e.to_string())?;
        let front: Vec<(f64, f64)> = pareto_front(&rows)
            .into_iter()
            .map(|i| (rows[i].ms_per_frame, rows[i].errors.rmse))
            .collect();
        chart
            .draw_series(LineSeries::new(front, BLACK.stroke_width(1)))
            .map_err(|e| e.to_string())?
            .label("Pareto front")
            .legend(|(x, y)| PathElement::new([(x, y), (x + 16, y)], BLACK));
        chart
            .draw_series(rows.iter().map(|row| {
                Circle::new(
                    (row.ms_per_frame, row.errors.rmse),
                    4,
                    method_colour(&row.knobs).filled(),
                )
            }))
            .map_err(|e| e.to_string())?;
        for (name, exp) in LEGEND {
            let knobs = Knobs {
                shadows: exp.map(|exp| crate::shading::ShadowSettings {
                    exp,
                    ..Default::default()
                }),
                blockers: crate::blockers::SphereBudget::Total(0),
                lighting: Lighting::Direct,
            };
            let colour = method_colour(&knobs);
            chart
                .draw_series(std::iter::empty::<Circle<(f64, f64), i32>>())
                .map_err(|e| e.to_string())?
                .label(name)
                .legend(move |(x, y)| Circle::new((x + 8, y), 4, colour.filled()));
        }
        chart
            .configure_series_labels()
            .background_style(WHITE.mix(0.9))
            .border_style(BLACK)
            .position(SeriesLabelPosition::LowerRight)
            .draw()
            .map_err(|e| e.to_string())?;
    }
    root.present().map_err(|e| e.to_string())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::study::metrics::ImageErrors;

    fn row(ms: f64, rmse: f64) -> StudyRow {
        StudyRow {
            scene: "s".into(),
            knobs: Knobs {
                shadows: None,
                blockers: crate::blockers::SphereBudget::Total(1),
                lighting: Lighting::Direct,
            },
            blocker_count: 0,
            ms_per_frame: ms,
            errors: ImageErrors {
                rmse,
                relative_l1: 0.0,
                ssim: 1.0,
                shadow_rmse: None,
            },
            extreme_pixels: 0,
        }
    }

    #[test]
    fn the_pareto_front_keeps_exactly_the_undominated_points() {
        let rows = [
            row(1.0, 0.5),
            row(2.0, 0.6),
            row(3.0, 0.2),
            row(0.5, 0.9),
            row(4.0, 0.2),
        ];
        let refs: Vec<&StudyRow> = rows.iter().collect();
        // (2.0, 0.6) is beaten by (1.0, 0.5); (4.0, 0.2) by (3.0, 0.2).
        assert_eq!(pareto_front(&refs), vec![3, 0, 2]);
    }
}
