//! What a stroke did, for the status bar, the CLI and tests: its outcome, the lights it
//! changed, and those changes in words.

/// One light's intensity before and after a stroke.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LightChange {
    pub light: u32,
    pub before: f32,
    pub after: f32,
}

/// Which lights a stroke changed and why, in words: "raised Rim left from 30 to 45 cd (62 % of
/// the light here)", the three largest changes (by their share of the painted area's
/// light) and how many more.
pub fn changes_in_words(report: &StrokeReport, lights: &[crate::scene::Light]) -> String {
    let mut changes = report.changes.clone();
    let share = |c: &LightChange| report.shares_before.get(c.light as usize).copied().unwrap_or(0.0);
    changes.sort_by(|a, b| share(b).total_cmp(&share(a)));
    let mut words: Vec<String> = changes
        .iter()
        .take(3)
        .map(|c| {
            let light = lights.get(c.light as usize);
            let name = light.map_or_else(|| format!("light {}", c.light), |l| l.name.clone());
            let unit = light.map_or("", |l| l.kind.intensity_unit());
            let verb = if c.after > c.before { "raised" } else { "lowered" };
            format!(
                "{verb} {name} from {} to {} {unit} ({:.0} % of the light here)",
                significant(c.before),
                significant(c.after),
                100.0 * share(c)
            )
        })
        .collect();
    if changes.len() > 3 {
        words.push(format!("and {} more", changes.len() - 3));
    }
    words.join(", ")
}

/// `value` with three significant digits, as the inspector shows intensities.
fn significant(value: f32) -> String {
    let magnitude = value.abs().max(1e-30).log10().floor() as i32;
    let decimals = (2 - magnitude).clamp(0, 6) as usize;
    format!("{value:.decimals$}")
}

/// What a stroke did.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Outcome {
    /// Intensities changed.
    Changed,
    /// A constraint stroke marked vertices; no intensity changed.
    Constrained,
    /// A release stroke let kept vertices go; no intensity changed.
    Released,
    /// The stroke touched no vertex the camera sees.
    NoVisibleVertex,
    /// No light reaches the painted vertices (directly or, with a bake, by bounces).
    NoLightReaches,
    /// Lights reach the vertices but the strategy left every intensity as it was (a
    /// direct target already met, lights at 0 under "double", or the constraints).
    Unchanged,
}

/// The result of one stroke, for the status bar, the CLI and tests.
#[derive(Debug, Clone, PartialEq)]
pub struct StrokeReport {
    pub outcome: Outcome,
    pub hit_vertices: usize,
    /// Importance of every light (after the constraint penalty).
    pub importance: Vec<f64>,
    pub selected: Vec<usize>,
    /// Weighted mean luminance of the painted vertices before and after, cd/m².
    pub mean_before: f64,
    pub mean_after: f64,
    /// Whether the constraint guard shortened the step.
    pub limited_by_constraints: bool,
    /// The lights the stroke changed, in light order.
    pub changes: Vec<LightChange>,
    /// Each light's share of the painted area's light before the stroke (Σ = 1 where any
    /// light reaches it; the fixed light aside).
    pub shares_before: Vec<f64>,
    pub message: String,
}

impl StrokeReport {
    pub(super) fn without_change(outcome: Outcome, hits: usize, mean: f64, message: impl Into<String>) -> StrokeReport {
        StrokeReport {
            outcome,
            hit_vertices: hits,
            importance: Vec::new(),
            selected: Vec::new(),
            mean_before: mean,
            mean_after: mean,
            limited_by_constraints: false,
            changes: Vec::new(),
            shares_before: Vec::new(),
            message: message.into(),
        }
    }
}
