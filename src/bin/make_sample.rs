//! Regenerates the bundled sample scene and project: `cargo run --bin make-sample [DIR]`
//! (default: projects/sample).

use std::path::PathBuf;

fn main() -> std::process::ExitCode {
    let directory = std::env::args_os()
        .nth(1)
        .map(PathBuf::from)
        .unwrap_or_else(|| PathBuf::from("projects/sample"));
    match lightpaint::samples::write_sample_project(&directory) {
        Ok(()) => {
            println!("wrote {}/sample.glb and sample.lightpaint", directory.display());
            std::process::ExitCode::SUCCESS
        }
        Err(e) => {
            eprintln!("error: {e}");
            std::process::ExitCode::FAILURE
        }
    }
}
