//! The painting part of a project file (format 3 on), apart from the rest of the format
//! so that the migrations can write its default without reading the format they migrate.

use serde::{Deserialize, Serialize};

use crate::paint::{Brush, PaintSettings, StrokeRecord};

/// The painting state a project restores: the applied strokes (oldest first, replayable)
/// and the brush and strategies the artist had chosen.
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct PaintingState {
    pub strokes: Vec<StrokeRecord>,
    pub brush: Option<Brush>,
    pub settings: PaintSettings,
}
