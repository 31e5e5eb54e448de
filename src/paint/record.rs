//! What a stroke is, as saved in a project and replayed: the view it was painted from,
//! its dabs, the brush and the strategies. Replaying the same records from the same
//! intensities gives bit-identical intensities.

use glam::{Vec2, Vec3};

use super::brush::Brush;
use super::modify::ModificationStrategy;
use super::pick::View;
use super::select::SelectionStrategy;
use crate::scene::Camera;

/// Which importance the selection ranks lights by.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Ranking {
    /// Light the stroke receives now, P_i·T_i: "which light lights this spot".
    #[default]
    Received,
    /// Transfer over reach, T_i/R_i (R_i the light's mean transfer over the scene): also
    /// finds lights that are off (P = 0) but would reach it, whatever their unit.
    Transfer,
}

/// Whether a stroke stands alone or is solved together with every earlier one.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum SolveMode {
    /// Rozon's additive model: each stroke changes its selected lights only; a later
    /// stroke may undo an earlier one.
    #[default]
    Additive,
    /// After the additive step, every recorded stroke (its achieved mean luminance) and
    /// every constrained vertex becomes a least-squares equation, and all intensities are
    /// solved together, non-negative (`nnls`), so strokes stop undoing each other.
    Global,
}

/// Every knob of the painting engine except the brush.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct PaintSettings {
    pub selection: SelectionStrategy,
    pub modification: ModificationStrategy,
    pub ranking: Ranking,
    pub solve: SolveMode,
    /// λ of the constraint penalty: importance ÷ (1 + λ·share of the constrained light the
    /// light supplies).
    pub constraint_penalty: f64,
    /// Relative change of a constrained vertex's luminance that later strokes may cause.
    pub constraint_tolerance: f64,
}

impl Default for PaintSettings {
    fn default() -> Self {
        PaintSettings {
            selection: SelectionStrategy::default(),
            modification: ModificationStrategy::default(),
            ranking: Ranking::default(),
            solve: SolveMode::default(),
            constraint_penalty: 10.0,
            constraint_tolerance: 0.02,
        }
    }
}

impl PaintSettings {
    pub fn problems(&self) -> Vec<String> {
        let mut problems = self.selection.problems();
        problems.extend(self.modification.problems());
        if !(self.constraint_penalty.is_finite() && self.constraint_penalty >= 0.0) {
            problems.push(format!(
                "constraint_penalty must be finite and ≥ 0, not {}",
                self.constraint_penalty
            ));
        }
        if !(self.constraint_tolerance.is_finite() && self.constraint_tolerance >= 0.0) {
            problems.push(format!(
                "constraint_tolerance must be finite and ≥ 0, not {}",
                self.constraint_tolerance
            ));
        }
        problems
    }
}

/// A camera and viewport as saved with a stroke.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ViewRecord {
    pub eye: Vec3,
    pub forward: Vec3,
    pub up: Vec3,
    pub yfov_rad: f32,
    pub width_px: u32,
    pub height_px: u32,
}

impl ViewRecord {
    pub fn of(view: &View) -> ViewRecord {
        ViewRecord {
            eye: view.camera.position,
            forward: view.camera.forward,
            up: view.camera.up,
            yfov_rad: view.camera.yfov_rad,
            width_px: view.width_px,
            height_px: view.height_px,
        }
    }

    pub fn view(&self) -> View {
        View {
            camera: Camera {
                position: self.eye,
                forward: self.forward,
                up: self.up,
                yfov_rad: self.yfov_rad,
                znear: 1e-3,
                zfar: None,
            },
            width_px: self.width_px,
            height_px: self.height_px,
        }
    }

    /// What is unusable about the view, if anything.
    pub fn problems(&self) -> Vec<String> {
        let mut problems = Vec::new();
        if !(self.eye.is_finite() && self.forward.is_finite() && self.up.is_finite()) {
            problems.push("the view's eye, forward and up must be finite".to_string());
        }
        if self.forward.length_squared() < 1e-12 || self.forward.cross(self.up).length_squared() < 1e-12 {
            problems.push("the view's forward and up must be non-zero and not parallel".to_string());
        }
        if !(self.yfov_rad > 0.0 && self.yfov_rad < std::f32::consts::PI) {
            problems.push(format!("yfov_rad must be in (0, π), not {}", self.yfov_rad));
        }
        if self.width_px == 0 || self.height_px == 0 || self.width_px > 16384 || self.height_px > 16384 {
            problems.push(format!(
                "the viewport must be 1–16384 pixels on each side, not {}×{}",
                self.width_px, self.height_px
            ));
        }
        problems
    }
}

/// One stroke: a polyline of dab centres painted from one view.
#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize)]
#[serde(deny_unknown_fields)]
pub struct StrokeRecord {
    pub view: ViewRecord,
    /// Dab centres in pixels (top-left origin, y down).
    pub dabs_px: Vec<Vec2>,
    pub brush: Brush,
    pub settings: PaintSettings,
    /// Seed of the stroke's random choices (Russian roulette).
    pub seed: u64,
    /// Objects hidden in the viewport while the stroke was painted (indices into the
    /// scene's objects): the brush neither paints them nor is stopped by them.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub hidden_objects: Vec<u32>,
    /// Lights locked while the stroke was painted (indices into the scene's lights,
    /// `Light::locked`): the stroke left them as they were.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub locked_lights: Vec<u32>,
}

impl StrokeRecord {
    pub fn problems(&self) -> Vec<String> {
        let mut problems = self.view.problems();
        problems.extend(self.brush.problems());
        problems.extend(self.settings.problems());
        if self.dabs_px.iter().any(|d| !d.is_finite()) {
            problems.push("every dab position must be finite".to_string());
        }
        problems
    }
}

/// Most dabs one stroke is cut into: a 4k screen's diagonal is under 5000 px, so a stroke
/// this long in dabs has left the screen many times over; a longer one gets its dabs
/// spread wider instead of taking time and memory in proportion to its length.
pub const MAX_DABS_PER_STROKE: usize = 100_000;

/// Dab centres every `spacing_px` along a screen polyline (its first point always, its
/// last too when the spacing leaves it over a quarter spacing away), at most
/// [`MAX_DABS_PER_STROKE`] of them (a longer polyline's spacing is widened to fit).
/// Distances are measured in f64, so the walk advances along segments of any length.
pub fn dabs_along(points_px: &[Vec2], spacing_px: f32) -> Vec<Vec2> {
    let finite: Vec<Vec2> = points_px.iter().copied().filter(|p| p.is_finite()).collect();
    let total: f64 = finite
        .windows(2)
        .map(|s| s[0].as_dvec2().distance(s[1].as_dvec2()))
        .sum();
    let spacing = (spacing_px.max(0.5) as f64).max(total / MAX_DABS_PER_STROKE as f64);
    let mut dabs: Vec<Vec2> = finite.first().copied().into_iter().collect();
    // How far past the last dab the previous segment ended.
    let mut carried = 0.0f64;
    for segment in finite.windows(2) {
        let (a, b) = (segment[0].as_dvec2(), segment[1].as_dvec2());
        let length = a.distance(b);
        let first = spacing - carried;
        if first <= length {
            let count = ((length - first) / spacing).floor() as usize + 1;
            dabs.extend((0..count).map(|k| a.lerp(b, (first + k as f64 * spacing) / length).as_vec2()));
        }
        carried = (carried + length) % spacing;
    }
    if let Some(&last) = finite.last()
        && dabs.last().is_some_and(|d| d.distance(last) as f64 > 0.25 * spacing)
    {
        dabs.push(last);
    }
    dabs
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn dabs_are_spaced_along_the_polyline_and_end_at_its_end() {
        let dabs = dabs_along(&[Vec2::ZERO, Vec2::new(10.0, 0.0), Vec2::new(10.0, 10.0)], 4.0);
        for pair in dabs.windows(2) {
            assert!(pair[0].distance(pair[1]) <= 4.0 + 1e-4);
        }
        assert_eq!(dabs.first(), Some(&Vec2::ZERO));
        assert_eq!(dabs.last(), Some(&Vec2::new(10.0, 10.0)));
        assert_eq!(dabs_along(&[Vec2::ONE], 4.0), vec![Vec2::ONE]);
        assert!(dabs_along(&[], 4.0).is_empty());
    }

    /// A segment of 10⁸ px (past where f32 stops advancing by a few pixels) ends at once,
    /// its dabs bounded and spread evenly from start to end; one of 10⁴ px keeps its
    /// spacing exactly.
    #[test]
    fn a_stroke_of_any_length_is_walked_in_bounded_time_and_memory() {
        let end = Vec2::new(1e8, 0.0);
        let dabs = dabs_along(&[Vec2::ZERO, end], 3.0);
        assert!(dabs.len() <= MAX_DABS_PER_STROKE + 1, "{}", dabs.len());
        assert_eq!(dabs.last(), Some(&end));
        let gaps: Vec<f32> = dabs.windows(2).map(|p| p[1].x - p[0].x).collect();
        let widest = gaps.iter().copied().fold(0.0, f32::max);
        assert!(widest <= 1e8 / MAX_DABS_PER_STROKE as f32 * 1.01, "{widest}");
        let short = dabs_along(&[Vec2::ZERO, Vec2::new(1e4, 0.0)], 4.0);
        assert_eq!(short.len(), 2501);
        assert!(short.windows(2).all(|p| (p[1].x - p[0].x - 4.0).abs() < 1e-3));
        // Points that are not finite are left out rather than walked.
        assert_eq!(dabs_along(&[Vec2::ZERO, Vec2::splat(f32::NAN)], 4.0), vec![Vec2::ZERO]);
    }
}
