//! A last line of defence around third-party parsers: a panic inside them (for example
//! gltf-json 1.4 indexes accessors before checking them) becomes an error for the file,
//! not a crash of the editor.

use std::cell::Cell;
use std::panic::AssertUnwindSafe;

thread_local! {
    static GUARDED: Cell<bool> = const { Cell::new(false) };
}

/// Runs `f`, turning a panic into `Err(message)`. While `f` runs, the hook installed by
/// [`install_quiet_panic_hook`] prints nothing, so the user sees one clean error.
pub fn catch_panic<T>(f: impl FnOnce() -> T) -> Result<T, String> {
    let was_guarded = GUARDED.replace(true);
    let result = std::panic::catch_unwind(AssertUnwindSafe(f));
    GUARDED.set(was_guarded);
    result.map_err(|payload| {
        payload
            .downcast_ref::<&str>()
            .map(|s| s.to_string())
            .or_else(|| payload.downcast_ref::<String>().cloned())
            .unwrap_or_else(|| "unknown panic".into())
    })
}

/// Keeps the default panic report for real bugs but silences panics that
/// [`catch_panic`] turns into errors. Call once at start-up.
pub fn install_quiet_panic_hook() {
    let default = std::panic::take_hook();
    std::panic::set_hook(Box::new(move |info| {
        if !GUARDED.get() {
            default(info);
        }
    }));
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_panic_becomes_an_error_with_its_message() {
        let result: Result<(), String> = catch_panic(|| panic!("index out of bounds"));
        assert_eq!(result, Err("index out of bounds".to_string()));
        assert_eq!(catch_panic(|| 7), Ok(7));
    }
}
