//! Migrations of older project formats to [`super::FORMAT_VERSION`], one step per version,
//! applied to the parsed JSON before it is read into [`super::ProjectFile`].
//!
//! Format history:
//! - 1 (lightpaint 0.1): scene reference, lights, render settings (exposure, background),
//!   camera.
//!
//! A new format adds a `vN_to_vN+1` step here, applied in sequence, and a test that a
//! committed file of every older format opens.

use serde_json::Value;

/// Brings `value`, a project of format `version` (1 ≤ version ≤ current), to the current
/// format. Format 1 is the first, so there is nothing to migrate yet.
pub fn to_current(value: Value, version: u64) -> Value {
    debug_assert!((1..=super::FORMAT_VERSION).contains(&version));
    value
}
