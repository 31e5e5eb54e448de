//! The painting engine (Rozon 2009, shading-model.md §4 "Light painting"): brushes, picking,
//! per-light stroke importance from the transfer (baked maps or the direct estimate),
//! selection and modification strategies, constraints, a global non-negative solve, and
//! an undo/redo history of replayable strokes. No GPU or UI code: the editor, the CLI and
//! the tests all call this module.

pub mod brush;
pub mod constraint;
mod global_solve;
pub mod light_reach;
pub mod modify;
pub mod nnls;
pub mod pick;
pub mod record;
mod report;
pub mod script;
pub mod select;
pub mod session;
pub mod transfer;
mod transfer_ranking;

pub use brush::{Brush, BrushKind, Falloff};
pub use modify::ModificationStrategy;
pub use pick::{Hits, PaintedPoint, VertexRef, View, pick_dab};
pub use record::{PaintSettings, Ranking, SolveMode, StrokeRecord, ViewRecord, dabs_along};
pub use select::SelectionStrategy;
pub use session::{Edit, LightChange, Outcome, Painter, StrokeReport, changes_in_words};
pub use transfer::{BakedTransfer, Transfer};
