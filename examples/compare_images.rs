//! How far one PNG lies from another, by the study's image errors (`study::metrics`: on
//! the sRGB-decoded values in [0, 1] that the artist sees): RMSE, relative L1 and SSIM of
//! the whole frame, and the RMSE and the mean difference (bias: negative where the image
//! is too dark) over its lower part (rows from FLOOR_ROW on; the blocker bench's floor in
//! front of its casters at 960 × 540 starts at row 300).
//!
//! `cargo run --release --example compare_images IMAGE REFERENCE [FLOOR_ROW]`, e.g. the
//! blocker bench's frame against the same frame on the exact path (`BENCH_EXACT=1`
//! `bench_passes … PNG 1`): docs/performance.md.

use std::io::Write;

use lightpaint::study::metrics::{DisplayImage, image_errors};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let (Some(image), Some(reference)) = (args.first(), args.get(1)) else {
        return Err("usage: compare_images IMAGE REFERENCE [FLOOR_ROW]".into());
    };
    let open = |path: &str| {
        image::open(path)
            .map(|i| DisplayImage::from_rgba8(&i.to_rgba8()))
            .map_err(|err| format!("{path}: {err}"))
    };
    let (a, b) = (open(image)?, open(reference)?);
    if (a.width, a.height) != (b.width, b.height) {
        return Err(format!(
            "{image} is {} × {} but {reference} is {} × {}",
            a.width, a.height, b.width, b.height
        )
        .into());
    }
    let floor_row: usize = args.get(2).map(|r| r.parse()).transpose()?.unwrap_or(a.height / 2);
    let on_floor: Vec<bool> = (0..a.width * a.height).map(|i| i / a.width >= floor_row).collect();
    let errors = image_errors(&a, &b, &on_floor);
    let (sum, count) = a
        .rgb
        .iter()
        .zip(&b.rgb)
        .zip(&on_floor)
        .filter(|(_, floor)| **floor)
        .fold((0.0, 0usize), |(sum, n), ((p, q), _)| {
            (sum + (0..3).map(|c| p[c] - q[c]).sum::<f64>(), n + 3)
        });
    let mut out = std::io::stdout().lock();
    writeln!(
        out,
        "frame: RMSE {:.4}, relative L1 {:.4}, SSIM {:.4}",
        errors.rmse, errors.relative_l1, errors.ssim
    )?;
    writeln!(
        out,
        "rows from {floor_row}: RMSE {:.4}, bias {:+.4}",
        errors.shadow_rmse.unwrap_or(0.0),
        sum / count.max(1) as f64
    )?;
    Ok(())
}
