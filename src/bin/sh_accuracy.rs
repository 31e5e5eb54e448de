//! Regenerates docs/sh-accuracy.md: `cargo run --bin sh-accuracy [OUT.md]`.

fn main() -> std::process::ExitCode {
    let out = std::env::args().nth(1).unwrap_or_else(|| "docs/sh-accuracy.md".into());
    let text = lightpaint::sh::accuracy::report(16);
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
