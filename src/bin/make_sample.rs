//! Regenerates the bundled sample scene: `cargo run --bin make-sample [OUT.glb]`.

use std::path::PathBuf;

fn main() -> std::process::ExitCode {
    let out = std::env::args_os()
        .nth(1)
        .map(PathBuf::from)
        .unwrap_or_else(|| PathBuf::from(lightpaint::samples::SAMPLE_SCENE));
    let bytes = lightpaint::samples::sample_scene_glb();
    match std::fs::write(&out, &bytes) {
        Ok(()) => {
            println!("wrote {} ({} bytes)", out.display(), bytes.len());
            std::process::ExitCode::SUCCESS
        }
        Err(e) => {
            eprintln!("error: {}: {e}", out.display());
            std::process::ExitCode::FAILURE
        }
    }
}
