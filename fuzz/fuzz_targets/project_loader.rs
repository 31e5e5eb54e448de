//! Any bytes given to the project loader parse or fail with an error; never a panic.
#![no_main]

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    // libFuzzer's hook aborts on every panic; keep that for real panics, but let the
    // loader's guard around third-party parsers turn theirs into errors, as in the app.
    static QUIET: std::sync::Once = std::sync::Once::new();
    QUIET.call_once(lightpaint::panic_guard::install_quiet_panic_hook);
    let _ = lightpaint::project::parse_project(std::path::Path::new("fuzz.lightpaint"), data);
});
