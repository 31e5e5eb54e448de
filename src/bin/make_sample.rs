//! Regenerates sample scenes and projects under projects/NAME/:
//! `cargo run --bin make-sample [NAME…]`, NAME one of sample, studio, interior, large, terrain,
//! lamp-room,
//! all (default: the committed ones, sample, studio and terrain).

use std::path::Path;
use std::process::ExitCode;

use lightpaint::samples::Sample;

fn main() -> ExitCode {
    let names: Vec<String> = std::env::args().skip(1).collect();
    let samples: Vec<Sample> = if names.is_empty() {
        Sample::ALL.into_iter().filter(|s| s.is_committed()).collect()
    } else if names.iter().any(|n| n == "all") {
        Sample::ALL.to_vec()
    } else {
        let mut samples = Vec::new();
        for name in &names {
            match Sample::from_name(name) {
                Some(sample) => samples.push(sample),
                None => {
                    eprintln!(
                        "error: unknown sample '{name}' (sample, studio, interior, large, terrain, lamp-room, all)"
                    );
                    return ExitCode::from(2);
                }
            }
        }
        samples
    };
    for sample in samples {
        let directory = Path::new("projects").join(sample.name());
        if let Err(e) = std::fs::create_dir_all(&directory) {
            eprintln!("error: {}: {e}", directory.display());
            return ExitCode::FAILURE;
        }
        match sample.write(&directory) {
            Ok(project) => println!("wrote {}", project.display()),
            Err(e) => {
                eprintln!("error: {e}");
                return ExitCode::FAILURE;
            }
        }
    }
    ExitCode::SUCCESS
}
