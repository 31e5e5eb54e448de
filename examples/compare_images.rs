//! How far one PNG lies from another, in 8-bit steps: the RMSE and the mean difference
//! (bias) of every colour channel over the frame and over its lower part (rows from
//! FLOOR_ROW on; the blocker bench's floor below its casters at 960 × 540 starts at row 300).
//!
//! `cargo run --release --example compare_images IMAGE REFERENCE [FLOOR_ROW]`, e.g. the
//! blocker bench's frame against the same frame on the exact path (`BENCH_EXACT=1`
//! `bench_passes … PNG 1`): docs/performance.md.

use std::io::Write;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let (Some(image), Some(reference)) = (args.first(), args.get(1)) else {
        return Err("usage: compare_images IMAGE REFERENCE [FLOOR_ROW]".into());
    };
    let open = |path: &str| {
        image::open(path)
            .map(|i| i.to_rgb8())
            .map_err(|err| format!("{path}: {err}"))
    };
    let (a, b) = (open(image)?, open(reference)?);
    if a.dimensions() != b.dimensions() {
        return Err(format!(
            "{image} is {:?} but {reference} is {:?}",
            a.dimensions(),
            b.dimensions()
        )
        .into());
    }
    let floor_row: u32 = args.get(2).map(|r| r.parse()).transpose()?.unwrap_or(a.height() / 2);
    let difference = |from_row: u32| {
        let (mut sum, mut squares, mut count) = (0.0f64, 0.0f64, 0u64);
        for (x, y, pixel) in a.enumerate_pixels() {
            if y < from_row {
                continue;
            }
            for (p, q) in pixel.0.iter().zip(b.get_pixel(x, y).0) {
                let d = f64::from(*p) - f64::from(q);
                sum += d;
                squares += d * d;
                count += 1;
            }
        }
        let n = count.max(1) as f64;
        ((squares / n).sqrt(), sum / n)
    };
    let (rmse, bias) = difference(0);
    let (floor_rmse, floor_bias) = difference(floor_row);
    let mut out = std::io::stdout().lock();
    writeln!(out, "frame: RMSE {rmse:.1}/255, bias {bias:+.1}")?;
    writeln!(
        out,
        "rows from {floor_row}: RMSE {floor_rmse:.1}/255, bias {floor_bias:+.1}"
    )?;
    Ok(())
}
