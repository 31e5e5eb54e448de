//! `lightpaint study --quick`: the whole pipeline (reference, grid, metrics, report) runs
//! on the GPU in CI and its outputs are complete and sane.

mod common;

use std::ffi::OsStr;

/// The CSV's rows as maps from column name to value.
fn read_csv(text: &str) -> Vec<std::collections::HashMap<String, String>> {
    let mut lines = text.lines();
    let header: Vec<String> = lines.next().expect("a header").split(',').map(String::from).collect();
    lines
        .map(|line| header.iter().cloned().zip(line.split(',').map(String::from)).collect())
        .collect()
}

/// Runs `lightpaint study --quick` with `extra` arguments into a new directory; returns it
/// and the standard output, once the run has succeeded (None without a GPU).
fn quick_study(extra: &[&str]) -> Option<(tempfile::TempDir, String)> {
    common::gpu()?;
    let dir = tempfile::tempdir().unwrap();
    let mut args = vec![OsStr::new("study"), OsStr::new("--quick")];
    args.extend(extra.iter().map(OsStr::new));
    args.extend([OsStr::new("-o"), dir.path().as_os_str()]);
    let out = common::run_lightpaint(&args);
    let stdout = String::from_utf8_lossy(&out.stdout).into_owned();
    assert!(out.status.success(), "{stdout}{}", String::from_utf8_lossy(&out.stderr));
    Some((dir, stdout))
}

#[test]
fn the_quick_study_writes_its_table_plot_and_images_with_sane_numbers() {
    let Some((dir, stdout)) = quick_study(&[]) else {
        return;
    };
    for file in ["study.csv", "study.md", "pareto.png", "images/sample-o4-hyb-e0.1.png"] {
        assert!(dir.path().join(file).is_file(), "{file} was written");
    }
    let plot = image::open(dir.path().join("pareto.png")).expect("the plot is a PNG");
    // One panel of at least 500 × 500 pixels per scene.
    assert!(plot.width() >= 500 && plot.height() >= 500, "the plot is readable");
    let rows = read_csv(&std::fs::read_to_string(dir.path().join("study.csv")).unwrap());
    assert!(rows.len() >= 15, "{} rows", rows.len());
    let number = |row: &std::collections::HashMap<String, String>, column: &str| -> f64 {
        row[column]
            .parse()
            .unwrap_or_else(|_| panic!("{column} = {:?} is a number", row[column]))
    };
    for row in &rows {
        let (ms, rmse, ssim) = (number(row, "ms_per_frame"), number(row, "rmse"), number(row, "ssim"));
        assert!(ms.is_finite() && ms > 0.0, "{row:?}");
        assert!((0.0..0.5).contains(&rmse), "{row:?}");
        assert!((0.0..=1.0).contains(&ssim), "{row:?}");
    }
    let find = |knobs: &str| {
        rows.iter()
            .find(|r| r["knobs"] == knobs)
            .unwrap_or_else(|| panic!("a {knobs} row"))
    };
    let (none, default) = (find("no-shadows"), find("o4-hyb-e0.1"));
    // The BRDF carried in the SH is measured beside the default separate shading.
    find("o4-hyb-e0.1-log-brdf");
    find("o4-hyb-e0.1-product-brdf");
    // Where the reference is in shadow, the log-SH shadows must bring the image closer to it
    // than no shadows at all.
    assert!(
        number(default, "shadow_rmse") < number(none, "shadow_rmse"),
        "shadowed pixels: default {} vs no shadows {}",
        default["shadow_rmse"],
        none["shadow_rmse"]
    );
    // The CPU's exact exponential bounds what the GPU's approximations can reach at the
    // same order (up to f32 and the reference's noise).
    let exact = number(find("o4-ref-e0.1"), "rmse");
    for method in ["dc", "ol", "hyb"] {
        let rmse = number(find(&format!("o4-{method}-e0.1")), "rmse");
        assert!(
            rmse >= exact - 0.003,
            "{method}: {rmse} vs the exact exponential's {exact}"
        );
    }
    // Against the reference with one bounce, the baked maps' indirect light must bring the
    // frame closer than the direct light alone.
    let (gi, baked) = (find("o4-hyb-e0.1-gi"), find("o4-hyb-e0.1-gi-baked"));
    assert!(
        number(baked, "rmse") < number(gi, "rmse"),
        "against the one-bounce reference: baked indirect {} vs none {}",
        baked["rmse"],
        gi["rmse"]
    );
    assert_eq!(baked["reference_bounces"], "1");
    let table = std::fs::read_to_string(dir.path().join("study.md")).unwrap();
    // Small lights: the exact path's penumbra error is under the SH path's at every size,
    // and no path lights a pixel beyond its unshadowed light.
    let penumbra_rows: Vec<Vec<String>> = table
        .lines()
        .skip_while(|l| !l.starts_with("## Small lights"))
        .filter(|l| l.starts_with("| ") && (l.contains("| SH |") || l.contains("| exact |")))
        .map(|l| l.split('|').map(|c| c.trim().to_string()).collect())
        .collect();
    assert_eq!(penumbra_rows.len(), 11, "five light sizes × two paths, and the sky");
    for pair in penumbra_rows.chunks(2).filter(|p| p.len() == 2) {
        let (sh, exact) = (&pair[0], &pair[1]);
        let rms = |row: &Vec<String>| row[4].parse::<f64>().expect("penumbra RMS");
        assert!(
            rms(exact) < rms(sh),
            "{} light: exact {} vs SH {}",
            exact[1],
            exact[4],
            sh[4]
        );
        for row in pair {
            assert!(row[6].parse::<f64>().unwrap() <= 1.001, "overshoot: {row:?}");
        }
    }
    // The defaults fit one sphere to each ball and, those spheres being the balls, take
    // the exact path for every light size: within the exact path's own error.
    let defaults_rows: Vec<Vec<String>> = table
        .lines()
        .skip_while(|l| !l.starts_with("## Small lights"))
        .filter(|l| l.starts_with("| ") && l.contains("| defaults: "))
        .map(|l| l.split('|').map(|c| c.trim().to_string()).collect())
        .collect();
    assert_eq!(defaults_rows.len(), 5, "one per light size: {defaults_rows:?}");
    for row in &defaults_rows {
        assert_eq!(row[2], "defaults: exact", "{row:?}");
        let rms: f64 = row[4].parse().expect("penumbra RMS");
        assert!(rms <= 0.03, "{row:?}");
    }
    // Small lights over meshes: one row per sphere budget, with the automatic fit, each
    // with a fit error in (0, 1] and finite errors.
    let fit_rows: Vec<Vec<String>> = table
        .lines()
        .skip_while(|l| !l.starts_with("## Small lights over meshes"))
        .skip(1)
        .take_while(|l| !l.starts_with("## "))
        .filter(|l| l.starts_with("| ") && !l.starts_with("| budget"))
        .map(|l| l.split('|').map(|c| c.trim().to_string()).collect())
        .collect();
    assert_eq!(fit_rows.len(), 3, "two budgets and the automatic fit: {fit_rows:?}");
    for row in &fit_rows {
        let fit_error: f64 = row[3].parse().expect("fit error");
        assert!(fit_error > 0.0 && fit_error <= 1.0, "{row:?}");
        for column in [4, 6] {
            let rms: f64 = row[column].parse().expect("penumbra RMS");
            assert!(rms.is_finite() && rms < 0.6, "{row:?}");
        }
    }
    // The path tracer's samples per pixel to match the default frame's shadow error.
    let equal_error = table
        .lines()
        .skip_while(|l| !l.starts_with("## Path tracing to the same shadow error"))
        .find(|l| l.starts_with("| sample |"));
    assert!(equal_error.is_some(), "the equal-error table has the sample: {table}");
    assert!(
        table.contains("## Stability at the extremes"),
        "the stability table is written"
    );
    assert!(table.contains("| 10,000 blockers |"), "{table}");
    assert!(!table.contains("**no**"), "every stability case holds: {table}");
    assert!(stdout.contains("study of"), "{stdout}");
}

/// `--knobs` measures only the settings it names, beside the baseline and the defaults
/// (every pixel shaded, and as shipped: one in 3 × 3, `-d3`),
/// and skips the scene-independent suites.
#[test]
fn a_study_of_some_knobs_measures_them_beside_the_defaults() {
    let Some((dir, _)) = quick_study(&["--knobs", "brdf"]) else {
        return;
    };
    let rows = read_csv(&std::fs::read_to_string(dir.path().join("study.csv")).unwrap());
    let mut knobs: Vec<&str> = rows.iter().map(|r| r["knobs"].as_str()).collect();
    knobs.sort_unstable();
    assert_eq!(
        knobs,
        [
            "no-shadows",
            "o4-hyb-e0.1",
            "o4-hyb-e0.1-d3",
            "o4-hyb-e0.1-log-brdf",
            "o4-hyb-e0.1-product-brdf"
        ]
    );
    let table = std::fs::read_to_string(dir.path().join("study.md")).unwrap();
    assert!(!table.contains("## Stability at the extremes"), "no suites: {table}");
}

/// The sphere-fit suite alone at the full study's size (128 × 128, 2048 samples per pixel,
/// sphere budgets 3 to 192): prints its table for docs/speed-accuracy.md. Minutes, so
/// not in CI: `cargo nextest run --test study --run-ignored only --no-capture sphere_fit`.
#[test]
#[ignore]
fn sphere_fit_suite_at_full_size() {
    let Some(gpu) = common::gpu() else { return };
    let rows = lightpaint::study::sphere_fit::measure_sphere_fit(&gpu, false).expect("suite runs");
    println!("{}", lightpaint::study::sphere_fit::markdown_table(&rows));
    let maps = lightpaint::study::sphere_fit::measure_mesh_maps(&gpu, false).expect("maps measured");
    println!(
        "shadow maps on the meshes: penumbra RMS {:.4}, umbra RMS {:?}, reference noise {:.4}",
        maps.penumbra_rms, maps.umbra_rms, maps.reference_noise
    );
}

/// The small lights' cost at the full study's size (8 sphere lights over 50 blockers,
/// 540 × 540, 10 frames): prints it for docs/speed-accuracy.md. Not in CI:
/// `cargo nextest run --test study --run-ignored only --no-capture eight_lights`.
#[test]
#[ignore]
fn eight_lights_cost_at_full_size() {
    let Some(gpu) = common::gpu() else { return };
    for (path, ms) in lightpaint::study::penumbra::cost_of_eight_lights(&gpu, 540, 10).expect("suite runs") {
        println!("8 small lights x 50 blockers via {path:?}: {ms:.1} ms per frame");
    }
}

/// The small-light suite alone at the full study's size (128 × 128, 2048 samples per
/// pixel): prints its rows for docs/speed-accuracy.md. Minutes, so not in CI:
/// `cargo nextest run --test study --run-ignored only --no-capture penumbra_suite`.
#[test]
#[ignore]
fn penumbra_suite_at_full_size() {
    let Some(gpu) = common::gpu() else { return };
    for row in lightpaint::study::penumbra::measure_penumbrae(&gpu, false).expect("suite runs") {
        println!(
            "| {} | {}{:?} | {} | {:.4} | {} | {:.1} | {:.4} |",
            row.light,
            if row.defaults { "defaults: " } else { "" },
            row.path,
            row.penumbra_pixels,
            row.penumbra_rms,
            row.umbra_rms.map_or("–".into(), |e| format!("{e:.4}")),
            row.ms_per_frame,
            row.reference_noise
        );
    }
}
