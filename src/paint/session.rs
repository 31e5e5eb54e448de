//! The painting engine's state: the applied strokes (each with the intensity changes it
//! made, the vertices it constrained and, for the global solve, its equation) and the
//! undone ones. Intensities live with the caller (the scene's lights); a stroke reads them
//! and writes the new ones back.
//!
//! One stroke: pick the hit vertices → their transfer → importance per light (penalised
//! by constraints) → selection → modification → constraint guard → (global solve) →
//! intensities, always finite and ≥ 0.

use rayon::prelude::*;

use super::BrushKind;
use super::constraint::{ConstrainedVertex, allowed_fraction, penalty_shares};
pub use super::global_solve::MAX_GLOBAL_CHANGE;
use super::global_solve::{Equation, solve_globally};
use super::modify::{self, Step, mean_luminance};
use super::pick::{Hits, VertexRef, pick_dab};
use super::record::{Ranking, SolveMode, StrokeRecord};
pub use super::report::{LightChange, Outcome, StrokeReport, changes_in_words};
use super::select::select;
use super::transfer::Transfer;
use crate::bake::scene_bvh::SceneBvh;
use crate::scene::Scene;

/// An applied stroke, enough to undo and redo it exactly.
#[derive(Debug, Clone, PartialEq)]
pub struct Edit {
    pub record: StrokeRecord,
    pub changes: Vec<LightChange>,
    constrained: Vec<ConstrainedVertex>,
    /// The kept vertices a release stroke let go (sorted), kept no longer by the strokes
    /// after it.
    released: Vec<VertexRef>,
    equation: Option<Equation>,
}

impl Edit {
    /// An edit that changed no light: a Keep's constrained vertices, a release's freed
    /// ones, or an earlier session's stroke carried over with its equation.
    fn unchanging(
        record: StrokeRecord,
        constrained: Vec<ConstrainedVertex>,
        released: Vec<VertexRef>,
        equation: Option<Equation>,
    ) -> Edit {
        Edit {
            record,
            changes: Vec::new(),
            constrained,
            released,
            equation,
        }
    }
}

/// A painted vertex: brush weight, fixed luminance and (light, transfer) entries.
struct PaintedVertex {
    vertex: VertexRef,
    weight: f64,
    fixed: f64,
    transfer: Vec<(u32, f64)>,
}

/// The stroke's transfer reduced to means, and its painted vertices' own (a Keep's).
struct StrokeTransfer {
    vertices: Vec<PaintedVertex>,
    /// Σ w·t_i / Σ w for every light, over the painted points (or vertices).
    mean: Vec<f64>,
    fixed: f64,
}

/// The stroke's transfer: its means over the painted points (over the painted vertices
/// when it met no surface point), and each painted vertex's own when `is_keep` (a Keep
/// holds its vertices; no other stroke reads them, and they are most of a dab's cost).
fn stroke_transfer(transfer: &dyn Transfer, hits: &Hits, eye: glam::Vec3, is_keep: bool) -> StrokeTransfer {
    let per_vertex = is_keep || hits.points.is_empty();
    let listed: Vec<(VertexRef, f32)> = if per_vertex {
        hits.weights.iter().map(|(v, w)| (*v, *w)).collect()
    } else {
        Vec::new()
    };
    let vertices: Vec<PaintedVertex> = listed
        .par_iter()
        .map(|&(vertex, w)| {
            let (fixed, mut entries) = transfer.vertex_shading(vertex, eye);
            // The frame shows the light through the base-colour texture.
            let texture = hits.texture_factor(vertex);
            if texture != 1.0 {
                entries.iter_mut().for_each(|(_, t)| *t *= texture);
            }
            PaintedVertex {
                vertex,
                weight: w as f64,
                fixed,
                transfer: entries,
            }
        })
        .collect();
    // The stroke's mean is the frame's over the pixels under the brush: read at the
    // surface points there when the dabs met the surface, else at the painted vertices.
    let (mean, fixed) = if hits.points.is_empty() {
        weighted_means(
            transfer.light_count(),
            vertices.iter().map(|v| (v.weight, v.fixed, v.transfer.as_slice())),
        )
    } else {
        let shaded: Vec<(f64, Vec<(u32, f64)>)> = hits
            .points
            .par_iter()
            .map(|point| transfer.point_shading(point, eye))
            .collect();
        weighted_means(
            transfer.light_count(),
            hits.points
                .iter()
                .zip(&shaded)
                .map(|(point, (fixed, entries))| (point.weight as f64, *fixed, entries.as_slice())),
        )
    };
    StrokeTransfer { vertices, mean, fixed }
}

/// The weighted means of each light's transfer and of the fixed luminance over
/// (weight, fixed, transfer) samples.
fn weighted_means<'t>(
    light_count: usize,
    samples: impl Iterator<Item = (f64, f64, &'t [(u32, f64)])>,
) -> (Vec<f64>, f64) {
    let mut mean = vec![0.0; light_count];
    let mut fixed = 0.0;
    let mut weight_sum = 0.0;
    for (weight, sample_fixed, entries) in samples {
        weight_sum += weight;
        fixed += weight * sample_fixed;
        for &(i, t) in entries {
            if let Some(m) = mean.get_mut(i as usize) {
                *m += weight * t;
            }
        }
    }
    if weight_sum > 0.0 {
        mean.iter_mut().for_each(|m| *m /= weight_sum);
        fixed /= weight_sum;
    }
    (mean, fixed)
}

/// What `record`'s dabs paint on `scene` seen from its view.
fn hits_of(scene: &Scene, bvh: &SceneBvh, record: &StrokeRecord) -> Hits {
    let view = record.view.view();
    let mut hits = Hits::default();
    for &dab in &record.dabs_px {
        pick_dab(scene, bvh, &view, dab, &record.brush, &record.hidden_objects, &mut hits);
    }
    hits
}

/// The vertices of a Keep stroke, each holding the luminance `p` gives it.
fn kept_vertices(stroke: StrokeTransfer, p: &[f64]) -> Vec<ConstrainedVertex> {
    stroke
        .vertices
        .into_iter()
        .map(|v| {
            let mut c = ConstrainedVertex {
                vertex: v.vertex,
                weight: v.weight,
                luminance: 0.0,
                fixed: v.fixed,
                transfer: v.transfer,
            };
            c.luminance = c.luminance_at(p);
            c
        })
        .collect()
}

/// The strokes applied. An undone stroke is handed to the caller ([`Painter::undo`]),
/// whose history keeps it for a redo ([`Painter::redo`]): the editor keeps strokes and
/// light edits in one history (`session::history`).
#[derive(Debug, Clone, Default)]
pub struct Painter {
    done: Vec<Edit>,
    /// What the strokes of earlier sessions still ask ([`Painter::carry_over`]): their
    /// Keep areas and, for the global solve, their equations. Not undoable here: they
    /// belong to the saved log, not to this session's history.
    carried: Vec<Edit>,
}

impl Painter {
    pub fn new() -> Painter {
        Painter::default()
    }

    /// The applied strokes, oldest first: the log a project saves.
    pub fn log(&self) -> impl Iterator<Item = &StrokeRecord> {
        self.done.iter().map(|e| &e.record)
    }

    pub fn applied(&self) -> &[Edit] {
        &self.done
    }

    pub fn can_undo(&self) -> bool {
        !self.done.is_empty()
    }

    /// The vertices Keep strokes hold (this session's applied ones and those carried over),
    /// each once.
    pub fn kept_vertices(&self) -> Vec<VertexRef> {
        let mut vertices: Vec<VertexRef> = self.constrained().map(|c| c.vertex).collect();
        vertices.sort_unstable();
        vertices.dedup();
        vertices
    }

    /// The constrained vertices still kept: each Keep stroke's, less those a release
    /// stroke after it let go (a vertex kept again after its release is kept).
    fn constrained(&self) -> impl Iterator<Item = &ConstrainedVertex> + Clone {
        let mut kept: Vec<&ConstrainedVertex> = Vec::new();
        for edit in self.carried.iter().chain(&self.done) {
            if !edit.released.is_empty() {
                kept.retain(|c| edit.released.binary_search(&c.vertex).is_err());
            }
            kept.extend(&edit.constrained);
        }
        kept.into_iter()
    }

    /// Takes up the strokes of earlier sessions (`earlier`, the saved log, oldest first)
    /// so that they still hold: each Keep stroke's area keeps the luminance `intensities`
    /// give it now, and each other stroke's area joins the global solve at its luminance
    /// now. The lights are not changed (the saved intensities are those strokes'
    /// result). Returns how many Keep areas were taken up.
    pub fn carry_over(
        &mut self,
        scene: &Scene,
        bvh: &SceneBvh,
        transfer: &dyn Transfer,
        intensities: &[f32],
        earlier: &[StrokeRecord],
    ) -> usize {
        let p: Vec<f64> = intensities.iter().map(|&v| sanitized(v as f64)).collect();
        if p.len() != transfer.light_count() {
            return 0;
        }
        let mut keeps = 0;
        for record in earlier.iter().filter(|r| r.problems().is_empty()) {
            let hits = hits_of(scene, bvh, record);
            if hits.is_empty() {
                continue;
            }
            let is_keep = record.brush.kind == BrushKind::Constraint;
            let stroke = stroke_transfer(transfer, &hits, record.view.eye, is_keep);
            if record.brush.kind == BrushKind::Release {
                let released = self.released_by(&hits);
                self.carried
                    .push(Edit::unchanging(record.clone(), Vec::new(), released, None));
                continue;
            }
            let (constrained, equation) = if record.brush.kind == BrushKind::Constraint {
                keeps += 1;
                (kept_vertices(stroke, &p), None)
            } else {
                let target = stroke.fixed + mean_luminance(&p, &stroke.mean);
                let equation = Equation {
                    transfer: stroke.mean,
                    fixed: stroke.fixed,
                    target,
                };
                (Vec::new(), Some(equation))
            };
            self.carried
                .push(Edit::unchanging(record.clone(), constrained, Vec::new(), equation));
        }
        keeps
    }

    /// Paints `record` on `scene`, reading and writing `intensities` (one per light).
    pub fn paint(
        &mut self,
        scene: &Scene,
        bvh: &SceneBvh,
        transfer: &dyn Transfer,
        intensities: &mut [f32],
        record: StrokeRecord,
    ) -> StrokeReport {
        let hits = hits_of(scene, bvh, &record);
        let vertices_per_object: Vec<usize> = scene.objects.iter().map(|o| o.positions.len()).collect();
        let mut report = self.apply(transfer, &vertices_per_object, intensities, record, &hits);
        if report.outcome == Outcome::Changed {
            report.message = format!("{}; {}", changes_in_words(&report, &scene.lights), report.message);
        }
        report
    }

    /// Applies a stroke whose hit vertices are known.
    pub fn apply(
        &mut self,
        transfer: &dyn Transfer,
        vertices_per_object: &[usize],
        intensities: &mut [f32],
        record: StrokeRecord,
        hits: &Hits,
    ) -> StrokeReport {
        let mut problems = record.problems();
        if let Some(missing) = record.locked_lights.iter().find(|&&i| i as usize >= intensities.len()) {
            problems.push(format!(
                "locked light {missing} does not exist ({} lights)",
                intensities.len()
            ));
        }
        if !problems.is_empty() || intensities.len() != transfer.light_count() {
            let message = if problems.is_empty() {
                format!(
                    "{} intensities for {} lights",
                    intensities.len(),
                    transfer.light_count()
                )
            } else {
                problems.join("; ")
            };
            return StrokeReport::without_change(Outcome::Unchanged, 0, 0.0, format!("stroke ignored: {message}"));
        }
        if hits.is_empty() {
            return StrokeReport::without_change(
                Outcome::NoVisibleVertex,
                0,
                0.0,
                "the brush touched no surface the camera sees",
            );
        }
        let p: Vec<f64> = intensities.iter().map(|&v| sanitized(v as f64)).collect();
        let is_keep = record.brush.kind == BrushKind::Constraint;
        let stroke = stroke_transfer(transfer, hits, record.view.eye, is_keep);
        let mean_before = stroke.fixed + mean_luminance(&p, &stroke.mean);
        if record.brush.kind == BrushKind::Release {
            let released = self.released_by(hits);
            let count = released.len();
            if count == 0 {
                return StrokeReport::without_change(
                    Outcome::Unchanged,
                    hits.len(),
                    mean_before,
                    "no Keep area under the brush",
                );
            }
            self.push(Edit::unchanging(record, Vec::new(), released, None));
            return StrokeReport::without_change(
                Outcome::Released,
                count,
                mean_before,
                format!("{count} kept vertices released: later strokes may change them again"),
            );
        }
        if record.brush.kind == BrushKind::Constraint {
            let constrained = kept_vertices(stroke, &p);
            let count = constrained.len();
            self.push(Edit::unchanging(record, constrained, Vec::new(), None));
            return StrokeReport::without_change(
                Outcome::Constrained,
                count,
                mean_before,
                format!("{count} vertices kept as they are"),
            );
        }
        if stroke.mean.iter().sum::<f64>() <= 0.0 {
            return StrokeReport::without_change(
                Outcome::NoLightReaches,
                hits.len(),
                mean_before,
                "no light reaches the painted area",
            );
        }
        let mut locked = vec![false; p.len()];
        record.locked_lights.iter().for_each(|&i| locked[i as usize] = true);
        let reaching_locked = (0..p.len()).filter(|&i| locked[i] && stroke.mean[i] > 0.0).count();
        if reaching_locked > 0 && (0..p.len()).all(|i| locked[i] || stroke.mean[i] <= 0.0) {
            return StrokeReport::without_change(
                Outcome::Unchanged,
                hits.len(),
                mean_before,
                format!(
                    "every light that reaches the painted area is locked ({reaching_locked}): unlock one to paint here"
                ),
            );
        }
        let settings = record.settings;
        let scale_of = |ranking: Ranking| -> Vec<f64> {
            match ranking {
                Ranking::Received => p.clone(),
                Ranking::Transfer => super::transfer_ranking::per_unit_of_reach(
                    transfer,
                    vertices_per_object,
                    record.view.eye,
                    &stroke.mean,
                ),
            }
        };
        let mut ranking = settings.ranking;
        let mut note = String::new();
        if ranking == Ranking::Received && mean_luminance(&p, &stroke.mean) <= 0.0 {
            // Every light that reaches the stroke is off: rank by what they would give.
            ranking = Ranking::Transfer;
            note = " (the lights that reach it are off: ranked by transfer)".to_string();
        }
        let scale = scale_of(ranking);
        let shares = penalty_shares(self.constrained(), vertices_per_object, &scale);
        // A locked light is ranked out: no strategy selects a light of no importance.
        let importance: Vec<f64> = (0..p.len())
            .map(|i| match locked[i] {
                true => 0.0,
                false => scale[i] * stroke.mean[i] / (1.0 + settings.constraint_penalty * shares[i]),
            })
            .collect();
        if reaching_locked > 0 {
            note.push_str(&format!(
                " ({reaching_locked} locked light(s) that reach it left as they are)"
            ));
        }
        let selected = select(settings.selection, &importance, record.seed);
        let proposed = modify::modify(&Step {
            kind: record.brush.kind,
            strategy: settings.modification,
            strength: record.brush.strength as f64,
            target_luminance: record.brush.target_luminance_nits as f64 - stroke.fixed,
            intensities: &p,
            transfer: &stroke.mean,
            selected: &selected,
        });
        // Whatever the strategy, a locked light keeps its intensity.
        let proposed: Vec<f64> = proposed
            .iter()
            .zip(&p)
            .zip(&locked)
            .map(|((&b, &a), &l)| if l { a } else { b })
            .collect();
        let fraction = allowed_fraction(self.constrained(), &p, &proposed, settings.constraint_tolerance);
        let mut new: Vec<f64> = p
            .iter()
            .zip(&proposed)
            .map(|(a, b)| if fraction >= 1.0 { *b } else { a + fraction * (b - a) })
            .collect();
        let equation = Equation {
            transfer: stroke.mean.clone(),
            fixed: stroke.fixed,
            target: stroke.fixed + mean_luminance(&new, &stroke.mean),
        };
        if settings.solve == SolveMode::Global {
            let equations = (self.carried.iter().chain(&self.done))
                .filter_map(|e| e.equation.as_ref())
                .chain([&equation]);
            let constrained: Vec<&ConstrainedVertex> = self.constrained().collect();
            let (solved, held) = solve_globally(equations, &constrained, [&p, &new], &locked);
            // Held at their intensity by the solve's bounds; exactly, not to a rounding.
            new = solved
                .iter()
                .zip(&p)
                .zip(&locked)
                .map(|((&x, &a), &l)| if l { a } else { x })
                .collect();
            if held > 0 {
                note.push_str(&format!(
                    " (the global solve held {held} light(s) within {MAX_GLOBAL_CHANGE}× of their intensity)"
                ));
            }
        }
        let changes: Vec<LightChange> = new
            .iter()
            .enumerate()
            .filter_map(|(i, &after)| {
                let after = sanitized(after) as f32;
                (after != intensities[i]).then_some(LightChange {
                    light: i as u32,
                    before: intensities[i],
                    after,
                })
            })
            .collect();
        let limited = fraction < 1.0;
        let received: Vec<f64> = p.iter().zip(&stroke.mean).map(|(p, t)| p * t).collect();
        let total = received.iter().sum::<f64>();
        let mut report = StrokeReport {
            outcome: Outcome::Changed,
            hit_vertices: hits.len(),
            importance,
            selected,
            mean_before,
            mean_after: mean_before,
            limited_by_constraints: limited,
            changes: changes.clone(),
            shares_before: received
                .iter()
                .map(|r| if total > 0.0 { r / total } else { 0.0 })
                .collect(),
            message: String::new(),
        };
        if changes.is_empty() {
            report.outcome = Outcome::Unchanged;
            report.message = if limited {
                "the constraints keep every light that reaches this area as it is".to_string()
            } else {
                format!("{} left every light as it was{note}", settings.modification.label())
            };
            return report;
        }
        for change in &changes {
            intensities[change.light as usize] = change.after;
        }
        let after: Vec<f64> = intensities.iter().map(|&v| v as f64).collect();
        report.mean_after = stroke.fixed + mean_luminance(&after, &stroke.mean);
        let limit = if limited {
            format!(
                " (the Keep areas allowed {:.0} % of the change)",
                100.0 * fraction.clamp(0.0, 1.0)
            )
        } else {
            String::new()
        };
        // An intensity that reached f32's largest value lights everything white: say so.
        let saturated = changes.iter().filter(|c| c.after >= SATURATED_INTENSITY).count();
        let saturation = if saturated > 0 {
            format!(
                "; {saturated} light(s) reached the largest intensity stored ({SATURATED_INTENSITY:e}): undo, or paint with a smaller factor or amount"
            )
        } else {
            String::new()
        };
        report.message = format!(
            "painted luminance from {:.4} to {:.4} cd/m²{limit}{note}{saturation}",
            report.mean_before, report.mean_after,
        );
        self.push(Edit {
            record,
            changes,
            constrained: Vec::new(),
            released: Vec::new(),
            equation: Some(equation),
        });
        report
    }

    /// The vertices `hits` paints that are kept now (sorted): what a release stroke there
    /// lets go.
    fn released_by(&self, hits: &Hits) -> Vec<VertexRef> {
        let mut released: Vec<VertexRef> = self
            .constrained()
            .map(|c| c.vertex)
            .filter(|v| hits.weights.contains_key(v))
            .collect();
        released.sort_unstable();
        released.dedup();
        released
    }

    fn push(&mut self, edit: Edit) {
        self.done.push(edit);
    }

    /// Takes back the last stroke, restoring the exact intensities before it; the stroke,
    /// to give [`Painter::redo`] later. None if there is none.
    pub fn undo(&mut self, intensities: &mut [f32]) -> Option<Edit> {
        let edit = self.done.pop()?;
        for change in &edit.changes {
            if let Some(p) = intensities.get_mut(change.light as usize) {
                *p = change.before;
            }
        }
        Some(edit)
    }

    /// Applies again, exactly, a stroke [`Painter::undo`] took back (the last one it took
    /// back, with nothing applied since: the caller's history keeps that order).
    pub fn redo(&mut self, edit: Edit, intensities: &mut [f32]) {
        for change in &edit.changes {
            if let Some(p) = intensities.get_mut(change.light as usize) {
                *p = change.after;
            }
        }
        self.done.push(edit);
    }
}

/// An intensity this large (a tenth of f32's largest value, far beyond any real light)
/// is reported as saturated.
const SATURATED_INTENSITY: f32 = f32::MAX / 10.0;

/// Finite and ≥ 0 (NaN and negatives become 0, +∞ the largest f32).
fn sanitized(p: f64) -> f64 {
    if p.is_nan() { 0.0 } else { p.clamp(0.0, f32::MAX as f64) }
}
