//! The curve of the blocker bench's frame time against its sphere count, drawn from
//! criterion's estimates of `cargo bench --bench frame -- frame/sphere-count` into
//! docs/images/frame-time-against-spheres.png (docs/performance.md shows it).
//!
//! `cargo run --release --example sphere_count_plot [CRITERION_DIR] [OUT.png]`; the
//! defaults are target/criterion and the image above. Each point is criterion's mean
//! with its 95 % interval as an error bar; the dashed line is 3 × the 600-sphere frame
//! (the sublinear growth the blocker hierarchy is held to).

use std::path::{Path, PathBuf};

use plotters::prelude::*;

const GROUP: &str = "frame_sphere-count/thin-casters";

/// Mean and 95 % bounds of one benchmark, milliseconds.
struct Estimate {
    spheres: u32,
    mean_ms: f64,
    lower_ms: f64,
    upper_ms: f64,
}

fn read_estimates(criterion_dir: &Path) -> Result<Vec<Estimate>, String> {
    let group_dir = criterion_dir.join(GROUP);
    let entries = std::fs::read_dir(&group_dir).map_err(|e| format!("{}: {e}", group_dir.display()))?;
    let mut estimates = Vec::new();
    for entry in entries.flatten() {
        let Some(spheres) = entry.file_name().to_str().and_then(|name| name.parse::<u32>().ok()) else {
            continue;
        };
        let path = entry.path().join("new/estimates.json");
        let text = std::fs::read_to_string(&path).map_err(|e| format!("{}: {e}", path.display()))?;
        let json: serde_json::Value = serde_json::from_str(&text).map_err(|e| format!("{}: {e}", path.display()))?;
        let ns = |key: &str| json["mean"][key].as_f64();
        let interval = &json["mean"]["confidence_interval"];
        match (
            ns("point_estimate"),
            interval["lower_bound"].as_f64(),
            interval["upper_bound"].as_f64(),
        ) {
            (Some(mean), Some(lower), Some(upper)) => estimates.push(Estimate {
                spheres,
                mean_ms: mean * 1e-6,
                lower_ms: lower * 1e-6,
                upper_ms: upper * 1e-6,
            }),
            _ => return Err(format!("{}: no mean with a confidence interval", path.display())),
        }
    }
    estimates.sort_by_key(|e| e.spheres);
    if estimates.is_empty() {
        return Err(format!("{}: no estimates; run the bench first", group_dir.display()));
    }
    Ok(estimates)
}

const SIZE: (u32, u32) = (800, 520);

fn draw(estimates: &[Estimate], out: &Path) -> Result<(), Box<dyn std::error::Error>> {
    let mut pixels = vec![255u8; (SIZE.0 * SIZE.1 * 3) as usize];
    draw_into(estimates, &mut pixels)?;
    let image = image::RgbImage::from_raw(SIZE.0, SIZE.1, pixels).ok_or("image size")?;
    image.save(out)?;
    Ok(())
}

fn draw_into(estimates: &[Estimate], pixels: &mut [u8]) -> Result<(), String> {
    let root = BitMapBackend::with_buffer(pixels, SIZE).into_drawing_area();
    root.fill(&WHITE).map_err(|e| e.to_string())?;
    let max_spheres = estimates.iter().map(|e| e.spheres).max().unwrap_or(1) as f64 * 1.05;
    let at_600 = estimates.iter().find(|e| e.spheres == 600).map(|e| e.mean_ms);
    let max_ms = estimates
        .iter()
        .map(|e| e.upper_ms)
        .chain(at_600.map(|ms| 3.2 * ms))
        .fold(1.0, f64::max)
        * 1.1;
    let mut chart = ChartBuilder::on(&root)
        .caption(
            "Blocker bench at 960 × 540: frame time against sphere count",
            ("sans-serif", 20),
        )
        .margin(14)
        .x_label_area_size(44)
        .y_label_area_size(64)
        .build_cartesian_2d(0.0..max_spheres, 0.0..max_ms)
        .map_err(|e| e.to_string())?;
    chart
        .configure_mesh()
        .x_desc("spheres")
        .y_desc("ms per frame (criterion mean)")
        .x_label_formatter(&|x| format!("{x:.0}"))
        .y_label_formatter(&|y| format!("{y:.0}"))
        .draw()
        .map_err(|e| e.to_string())?;
    let points: Vec<(f64, f64)> = estimates.iter().map(|e| (e.spheres as f64, e.mean_ms)).collect();
    chart
        .draw_series(LineSeries::new(points.clone(), BLUE.stroke_width(2)))
        .map_err(|e| e.to_string())?
        .label("frame time")
        .legend(|(x, y)| PathElement::new([(x, y), (x + 16, y)], BLUE.stroke_width(2)));
    chart
        .draw_series(points.iter().map(|&p| Circle::new(p, 4, BLUE.filled())))
        .map_err(|e| e.to_string())?;
    chart
        .draw_series(estimates.iter().map(|e| {
            PathElement::new(
                [(e.spheres as f64, e.lower_ms), (e.spheres as f64, e.upper_ms)],
                BLUE.stroke_width(1),
            )
        }))
        .map_err(|e| e.to_string())?;
    if let Some(ms) = at_600 {
        let dashes = (0..40).map(|i| {
            let x0 = max_spheres * i as f64 / 40.0;
            PathElement::new(
                [(x0, 3.0 * ms), (x0 + max_spheres / 80.0, 3.0 * ms)],
                RED.stroke_width(1),
            )
        });
        chart
            .draw_series(dashes)
            .map_err(|e| e.to_string())?
            .label("3 × the 600-sphere frame")
            .legend(|(x, y)| PathElement::new([(x, y), (x + 16, y)], RED));
    }
    chart
        .configure_series_labels()
        .background_style(WHITE.mix(0.9))
        .border_style(BLACK)
        .position(SeriesLabelPosition::UpperLeft)
        .draw()
        .map_err(|e| e.to_string())?;
    root.present().map_err(|e| e.to_string())?;
    Ok(())
}

fn main() {
    let mut args = std::env::args().skip(1);
    let criterion_dir = args
        .next()
        .map(PathBuf::from)
        .unwrap_or_else(|| PathBuf::from("target/criterion"));
    let out = args
        .next()
        .map(PathBuf::from)
        .unwrap_or_else(|| PathBuf::from("docs/images/frame-time-against-spheres.png"));
    let result = read_estimates(&criterion_dir).and_then(|estimates| {
        for e in &estimates {
            println!(
                "{:>6} spheres: {:8.1} ms ({:.1}–{:.1})",
                e.spheres, e.mean_ms, e.lower_ms, e.upper_ms
            );
        }
        draw(&estimates, &out).map_err(|e| format!("{}: {e}", out.display()))
    });
    match result {
        Ok(()) => println!("wrote {}", out.display()),
        Err(message) => {
            eprintln!("error: {message}");
            std::process::exit(1);
        }
    }
}
