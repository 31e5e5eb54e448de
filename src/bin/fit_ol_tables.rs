//! Regenerates `src/sh/ol_tables.rs`, the OL exponentiation coefficients for every
//! supported order: `cargo run --bin fit-ol-tables [OUT.rs]`.

use std::fmt::Write;

use lightpaint::sh::ol_fit::{OL_TABLE_ENTRIES, OL_TABLE_ORDERS, OL_TRAINING_SHAPES, fit_ol_table};
use lightpaint::sh::ol_tables::NORM_STEP;

fn main() -> std::process::ExitCode {
    let out = std::env::args().nth(1).unwrap_or_else(|| "src/sh/ol_tables.rs".into());
    let mut text = String::new();
    let _ = writeln!(
        text,
        "//! OL exponentiation coefficients (a, b) per order, fitted by\n\
         //! `cargo run --bin fit-ol-tables` (see `ol_fit.rs`; {OL_TRAINING_SHAPES} training shapes per order).\n\
         //! Generated: do not edit.\n\n\
         /// Spacing of the table in ‖f̂‖.\n\
         pub const NORM_STEP: f64 = {NORM_STEP:?};\n"
    );
    for order in OL_TABLE_ORDERS {
        let table = fit_ol_table(order, OL_TABLE_ENTRIES, NORM_STEP);
        let _ = writeln!(text, "const ORDER_{order}: [(f64, f64); {}] = [", table.len());
        for (a, b) in table {
            let _ = writeln!(text, "    ({a:?}, {b:?}),");
        }
        let _ = writeln!(text, "];\n");
        eprintln!("order {order} fitted");
    }
    let _ = writeln!(
        text,
        "/// (a, b) at ‖f̂‖ = k · NORM_STEP for orders {}..={}.\n\
         pub fn table(order: usize) -> Option<&'static [(f64, f64)]> {{\n    match order {{",
        OL_TABLE_ORDERS.start(),
        OL_TABLE_ORDERS.end()
    );
    for order in OL_TABLE_ORDERS {
        let _ = writeln!(text, "        {order} => Some(&ORDER_{order}),");
    }
    let _ = writeln!(text, "        _ => None,\n    }}\n}}");
    match std::fs::write(&out, text) {
        Ok(()) => {
            println!("wrote {out}");
            std::process::ExitCode::SUCCESS
        }
        Err(e) => {
            eprintln!("error: {out}: {e}");
            std::process::ExitCode::FAILURE
        }
    }
}
