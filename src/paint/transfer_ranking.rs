//! The transfer ranking's weight of each light (`Ranking::Transfer`): its transfer over
//! its reach, so that lights of different units (cd, lx, nits) are weighed alike.

use rayon::prelude::*;

use super::pick::VertexRef;
use super::transfer::Transfer;

/// Most scene vertices [`per_unit_of_reach`] reads.
const REACH_SAMPLES: usize = 256;

/// The transfer ranking's weight of each light: one over its reach, the mean of its
/// transfer over an even spread of the scene's vertices and the stroke, so that a light
/// ranks by how much more it reaches the stroke than the scene at large, whatever its
/// unit (cd, lx, nits: per unit of its own unit a sun's transfer is a spot's times the
/// square of the spot's distance). Including the stroke bounds the ratio by the number
/// of vertices read; a light that reaches none of them has weight 0.
pub(super) fn per_unit_of_reach(
    transfer: &dyn Transfer,
    vertices_per_object: &[usize],
    eye: glam::Vec3,
    stroke_mean: &[f64],
) -> Vec<f64> {
    let total: usize = vertices_per_object.iter().sum();
    let stride = total.div_ceil(REACH_SAMPLES).max(1);
    let spread: Vec<VertexRef> = vertices_per_object
        .iter()
        .enumerate()
        .flat_map(|(object, &count)| {
            (0..count).map(move |vertex| VertexRef {
                object: object as u32,
                vertex: vertex as u32,
            })
        })
        .step_by(stride)
        .collect();
    let per_vertex: Vec<Vec<(u32, f64)>> = spread.par_iter().map(|&v| transfer.vertex_transfer(v, eye)).collect();
    let mut reach = stroke_mean.to_vec();
    for entries in &per_vertex {
        for &(light, t) in entries {
            if let Some(r) = reach.get_mut(light as usize) {
                *r += t.max(0.0);
            }
        }
    }
    let samples = (per_vertex.len() + 1) as f64;
    reach
        .iter()
        .map(|&r| if r > 0.0 && r.is_finite() { samples / r } else { 0.0 })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Transfer per unit of each light's unit: `scale[i]` times light i's shape over the
    /// vertices of one object (a sun reaching all alike, a spot reaching the first five).
    struct Shapes {
        scale: [f64; 2],
    }

    impl Transfer for Shapes {
        fn light_count(&self) -> usize {
            2
        }

        fn vertex_transfer(&self, vertex: VertexRef, _eye: glam::Vec3) -> Vec<(u32, f64)> {
            let spot = if vertex.vertex < 5 { 1.0 } else { 0.0 };
            vec![(0, self.scale[0]), (1, self.scale[1] * spot)]
        }

        fn fixed_luminance(&self, _vertex: VertexRef, _eye: glam::Vec3) -> f64 {
            0.0
        }
    }

    /// The transfer ranking picks the spot aimed at the stroke over the sun that lights
    /// everything alike, and the ranking does not change when either light's unit does
    /// (its transfer scaled by any factor): per unit of its own unit, the sun in lx would
    /// outrank a spot in cd whenever the spot is farther than a metre.
    #[test]
    fn the_transfer_ranking_does_not_depend_on_the_lights_units() {
        let vertices = [400];
        let stroke: Vec<VertexRef> = (0..5).map(|vertex| VertexRef { object: 0, vertex }).collect();
        let importance = |scale: [f64; 2]| -> Vec<f64> {
            let transfer = Shapes { scale };
            let mean: Vec<f64> = (0..2)
                .map(|i| {
                    stroke
                        .iter()
                        .map(|&v| transfer.vertex_transfer(v, glam::Vec3::ZERO)[i].1)
                        .sum::<f64>()
                        / stroke.len() as f64
                })
                .collect();
            let weight = per_unit_of_reach(&transfer, &vertices, glam::Vec3::ZERO, &mean);
            mean.iter().zip(weight).map(|(m, w)| m * w).collect()
        };
        for scale in [[1.0, 1.0], [1.0, 1e-3], [1e4, 0.25], [3.0, 1e6]] {
            let ranked = crate::paint::select::ranked(&importance(scale));
            assert_eq!(ranked, vec![1, 0], "scales {scale:?}");
        }
        // Exactly invariant: the importances themselves do not move.
        let (a, b) = (importance([1.0, 1.0]), importance([7.0, 1e-4]));
        for (x, y) in a.iter().zip(&b) {
            assert!((x / y - 1.0).abs() < 1e-12, "{a:?} vs {b:?}");
        }
    }
}
