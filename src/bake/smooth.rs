//! Denoising of the baked indirect irradiance (the value the real-time renderer adds as
//! baked indirect light): each vertex estimates it from a few dozen bounce directions, so
//! neighbouring vertices disagree by their sampling noise, which the rasteriser turns into
//! a mottle across large floors. Irradiance from bounced light varies slowly over a
//! surface, so each vertex's value is averaged with its mesh neighbours', weighted by how
//! alike their normals are (max(n_v·n_u, 0)^8: a crease or a thin wall does not mix its two
//! sides). A neighbour the light does not reach counts as 0. The SH of the maps are left
//! as baked: painting reads those, and the linearity test checks them unsmoothed.

use rayon::prelude::*;

use super::LightContribution;
use crate::scene::MeshObject;

/// Passes of neighbour averaging (each widens the kernel by one ring of vertices).
const PASSES: usize = 2;

/// Smooths the `indirect_irradiance` of every entry of `vertices` (the object's per-vertex
/// lists, sorted by light) over the object's triangle mesh.
pub fn smooth_indirect_irradiance(object: &MeshObject, vertices: &mut [Vec<LightContribution>]) {
    let neighbours = neighbours(object, vertices.len());
    for _ in 0..PASSES {
        let smoothed: Vec<Vec<f32>> = (0..vertices.len())
            .into_par_iter()
            .map(|v| {
                let n = object.normals.get(v).copied().unwrap_or_default();
                vertices[v]
                    .iter()
                    .map(|entry| {
                        let (mut sum, mut weight) = (entry.indirect_irradiance as f64, 1.0f64);
                        for &u in &neighbours[v] {
                            let u = u as usize;
                            let alike = n.dot(object.normals.get(u).copied().unwrap_or_default()).max(0.0) as f64;
                            let w = alike.powi(8);
                            let value = vertices[u]
                                .binary_search_by_key(&entry.light, |e| e.light)
                                .map_or(0.0, |k| vertices[u][k].indirect_irradiance as f64);
                            sum += w * value;
                            weight += w;
                        }
                        (sum / weight) as f32
                    })
                    .collect()
            })
            .collect();
        for (entries, values) in vertices.iter_mut().zip(smoothed) {
            for (entry, value) in entries.iter_mut().zip(values) {
                entry.indirect_irradiance = value;
            }
        }
    }
}

/// Each vertex's neighbours along triangle edges (sorted, without repeats).
fn neighbours(object: &MeshObject, vertex_count: usize) -> Vec<Vec<u32>> {
    let mut lists = vec![Vec::new(); vertex_count];
    for triangle in object.indices.chunks_exact(3) {
        for (a, b) in [(0, 1), (1, 2), (2, 0)] {
            let (a, b) = (triangle[a], triangle[b]);
            if (a as usize) < vertex_count && (b as usize) < vertex_count && a != b {
                lists[a as usize].push(b);
                lists[b as usize].push(a);
            }
        }
    }
    for list in &mut lists {
        list.sort_unstable();
        list.dedup();
    }
    lists
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::shapes;

    fn entry(light: u32, value: f32) -> Vec<LightContribution> {
        vec![LightContribution {
            light,
            sh: vec![1.0; 4],
            indirect_irradiance: value,
        }]
    }

    #[test]
    fn noise_falls_and_a_constant_stays_constant() {
        let plane = shapes::plane(2.0, 16, 1.0).into_object("plane");
        let count = plane.positions.len();
        // A constant 1 plus ±0.5 alternating noise (a checkerboard of vertex values).
        let mut noisy: Vec<Vec<LightContribution>> = (0..count)
            .map(|v| entry(0, if v % 2 == 0 { 1.5 } else { 0.5 }))
            .collect();
        let spread = |vertices: &[Vec<LightContribution>]| {
            let values: Vec<f32> = vertices.iter().map(|e| e[0].indirect_irradiance).collect();
            values.iter().fold(f32::MIN, |a, &b| a.max(b)) - values.iter().fold(f32::MAX, |a, &b| a.min(b))
        };
        let before = spread(&noisy);
        smooth_indirect_irradiance(&plane, &mut noisy);
        assert!(spread(&noisy) < 0.5 * before, "{} vs {before}", spread(&noisy));
        let mut constant: Vec<Vec<LightContribution>> = (0..count).map(|_| entry(0, 2.0)).collect();
        smooth_indirect_irradiance(&plane, &mut constant);
        assert!(constant.iter().all(|e| (e[0].indirect_irradiance - 2.0).abs() < 1e-6));
    }

    #[test]
    fn surfaces_facing_apart_do_not_mix() {
        // Two triangles sharing an edge, folded to face opposite ways (normals −y and +y).
        let object = MeshObject {
            positions: vec![
                glam::Vec3::ZERO,
                glam::Vec3::X,
                glam::Vec3::Z,
                glam::Vec3::new(1.0, 0.0, 1.0),
            ],
            normals: vec![glam::Vec3::Y, glam::Vec3::Y, glam::Vec3::NEG_Y, glam::Vec3::NEG_Y],
            indices: vec![0, 1, 2, 1, 3, 2],
            ..shapes::plane(1.0, 1, 1.0).into_object("fold")
        };
        let mut vertices = vec![entry(0, 1.0), entry(0, 1.0), entry(0, 5.0), entry(0, 5.0)];
        smooth_indirect_irradiance(&object, &mut vertices);
        assert!((vertices[0][0].indirect_irradiance - 1.0).abs() < 1e-6);
        assert!((vertices[3][0].indirect_irradiance - 5.0).abs() < 1e-6);
    }
}
