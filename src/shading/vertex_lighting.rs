//! Which meshes per-vertex shading lights at their vertices. Per vertex, the SH path's
//! visibility is computed at the vertices; on a mesh fine enough, the light that comes
//! through it is too (Gouraud shading, as Ren et al. 2006 shade their per-vertex frames),
//! and a fragment only multiplies the interpolated light by its material
//! (logsh_per_vertex.wgsl's cs_vertex_light and fs_vertex_lit). On a coarse mesh, a wall
//! of two triangles under a lamp, interpolating the light would lose its hot spot, so
//! such meshes keep shading each pixel through the interpolated visibility.
//!
//! A mesh is fine enough when the light varies nearly linearly across each of its
//! triangles, which three bounds say:
//! - irradiance: over a plane at distance d below a point light E(x) ∝ d/(d² + x²)^{3/2},
//!   whose second derivative is −3E/d² under the light, so interpolating across an edge
//!   of length L errs by at most L²/8 · 3E/d² = (3/8)(L/d)² E: [`MAX_EDGE_PER_LIGHT_DISTANCE`]
//!   (0.15) keeps it under 1 % (d from the mesh's bounds to the light's bounding sphere);
//! - the diffuse cosine: with the normal turning by θ across a triangle, the cosine
//!   interpolated from its corners and the cosine of the interpolated normal differ by
//!   about 1 − cos(θ/2) ≈ θ²/8: [`MAX_NORMAL_TURN_RAD`] (20°) keeps it near 1.5 %;
//! - the glossy lobe cos^r α, whose log changes by r·α·δ when its axis turns by δ: at
//!   the lobe's width α ≈ 1/√r that is √r·δ, kept under [`MAX_LOBE_CHANGE`] (0.3), with δ
//!   the normal's turn plus the angles an edge subtends from the eye and from the
//!   nearest light (a flat floor's mirrored view still turns across it).

use glam::Vec3;

use crate::scene::Aabb;
use crate::shading::cpu::area::bounding_radius_m;
use crate::shading::gpu_types::{GpuLight, LIGHT_DIRECTIONAL};

/// Largest edge length over the distance to the nearest light (irradiance bound above).
pub const MAX_EDGE_PER_LIGHT_DISTANCE: f32 = 0.15;
/// Largest angle between two vertex normals of a triangle (diffuse cosine bound above).
pub const MAX_NORMAL_TURN_RAD: f32 = 0.35;
/// Largest change of the glossy lobe's log at its width across a triangle (√r·δ).
pub const MAX_LOBE_CHANGE: f32 = 0.3;

/// How finely a mesh is tessellated: what the bounds above read of it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MeshFineness {
    /// The longest edge of its triangles, metres.
    pub longest_edge_m: f32,
    /// The widest angle between two vertex normals of one triangle, radians.
    pub widest_normal_turn_rad: f32,
}

impl MeshFineness {
    /// Of the triangles `indices` lists over `positions` and `normals` (indices past them
    /// are skipped: a loaded mesh is checked elsewhere). A normal of zero length turns by
    /// π (its light is unknown).
    pub fn of(positions: &[Vec3], normals: &[Vec3], indices: &[u32]) -> MeshFineness {
        let mut fineness = MeshFineness {
            longest_edge_m: 0.0,
            widest_normal_turn_rad: 0.0,
        };
        for triangle in indices.chunks_exact(3) {
            let [a, b, c] = [triangle[0], triangle[1], triangle[2]].map(|i| i as usize);
            let (Some(&pa), Some(&pb), Some(&pc), Some(&na), Some(&nb), Some(&nc)) = (
                positions.get(a),
                positions.get(b),
                positions.get(c),
                normals.get(a),
                normals.get(b),
                normals.get(c),
            ) else {
                continue;
            };
            for ((p, n), (q, m)) in [((pa, na), (pb, nb)), ((pb, nb), (pc, nc)), ((pc, nc), (pa, na))] {
                fineness.longest_edge_m = fineness.longest_edge_m.max(p.distance(q));
                let turn = match (n.try_normalize(), m.try_normalize()) {
                    (Some(u), Some(v)) => u.dot(v).clamp(-1.0, 1.0).acos(),
                    _ => std::f32::consts::PI,
                };
                fineness.widest_normal_turn_rad = fineness.widest_normal_turn_rad.max(turn);
            }
        }
        fineness
    }
}

/// Whether the SH path's light at a mesh of `fineness` within `bounds`, of a material
/// whose glossy lobe has exponent `phong_exponent`, may be computed at its vertices and
/// interpolated, seen from `eye` and lit by `lights` (the SH path's: the other paths are
/// shaded per pixel anyway; the environment is far and smooth). NaN anywhere answers no.
pub fn lit_at_vertices(
    fineness: MeshFineness,
    bounds: &Aabb,
    phong_exponent: f32,
    lights: &[GpuLight],
    eye: Vec3,
) -> bool {
    let edge = fineness.longest_edge_m;
    let nearest_light_m = lights
        .iter()
        .filter(|light| light.kind != LIGHT_DIRECTIONAL)
        .map(|light| {
            let centre = Vec3::new(light.position[0], light.position[1], light.position[2]);
            bounds.distance_to(centre) - bounding_radius_m(light) as f32
        })
        .fold(f32::INFINITY, f32::min);
    let eye_m = bounds.distance_to(eye);
    // Written so that NaN fails every comparison: a mesh lit at its vertices only when
    // each bound holds.
    let near_enough = nearest_light_m > 0.0 && edge <= MAX_EDGE_PER_LIGHT_DISTANCE * nearest_light_m;
    let smooth_enough = fineness.widest_normal_turn_rad <= MAX_NORMAL_TURN_RAD;
    let turn_rad = fineness.widest_normal_turn_rad + edge / eye_m + edge / nearest_light_m;
    // r = 0 (a lobe the same everywhere) holds for any turn the other bounds allow.
    let lobe_holds = phong_exponent == 0.0 || phong_exponent.sqrt() * turn_rad <= MAX_LOBE_CHANGE;
    near_enough && smooth_enough && eye_m > 0.0 && lobe_holds
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::shapes;

    fn point_light(at: Vec3) -> GpuLight {
        GpuLight::new(&crate::scene::Light {
            name: "lamp".into(),
            kind: crate::scene::LightKind::Point,
            color: Vec3::ONE,
            intensity: 10.0,
            position: at,
            direction: Vec3::NEG_Y,
            range: None,
            locked: false,
        })
    }

    fn fineness_and_bounds(mesh: &shapes::ShapeMesh) -> (MeshFineness, Aabb) {
        (
            MeshFineness::of(&mesh.positions, &mesh.normals, &mesh.indices),
            Aabb::from_points(&mesh.positions),
        )
    }

    #[test]
    fn a_quad_measures_its_diagonal_and_no_turn() {
        let quad = shapes::plane(2.0, 1, 1.0);
        let (fineness, _) = fineness_and_bounds(&quad);
        assert!((fineness.longest_edge_m - 8f32.sqrt()).abs() < 1e-5, "{fineness:?}");
        assert_eq!(fineness.widest_normal_turn_rad, 0.0);
    }

    #[test]
    fn indices_past_the_mesh_are_skipped_and_a_zero_normal_turns_by_pi() {
        let positions = [Vec3::ZERO, Vec3::X, Vec3::Y];
        let normals = [Vec3::Z, Vec3::Z, Vec3::ZERO];
        let skipped = MeshFineness::of(&positions, &normals, &[0, 1, 7]);
        assert_eq!((skipped.longest_edge_m, skipped.widest_normal_turn_rad), (0.0, 0.0));
        let degenerate = MeshFineness::of(&positions, &normals, &[0, 1, 2]);
        assert_eq!(degenerate.widest_normal_turn_rad, std::f32::consts::PI);
        assert!((degenerate.longest_edge_m - 2f32.sqrt()).abs() < 1e-6);
    }

    #[test]
    fn a_sphere_turns_its_normals_by_its_segment_angle() {
        // 32 segments around: neighbouring normals 360°/32 apart along the equator.
        let sphere = shapes::uv_sphere(1.0, 32, 16);
        let (fineness, _) = fineness_and_bounds(&sphere);
        let segment = std::f32::consts::TAU / 32.0;
        assert!(fineness.widest_normal_turn_rad >= 0.99 * segment, "{fineness:?}");
        // A triangle's diagonal turns by no more than its two sides together.
        assert!(fineness.widest_normal_turn_rad <= 2.0 * segment, "{fineness:?}");
    }

    #[test]
    fn a_fine_floor_far_below_a_lamp_is_lit_at_its_vertices_and_a_quad_under_it_is_not() {
        let lamp = [point_light(Vec3::new(0.0, 3.0, 0.0))];
        let eye = Vec3::new(0.0, 2.0, 5.0);
        let (fine, bounds) = fineness_and_bounds(&shapes::plane(8.0, 96, 1.0));
        assert!(lit_at_vertices(fine, &bounds, 0.0, &lamp, eye));
        let (coarse, bounds) = fineness_and_bounds(&shapes::plane(8.0, 1, 1.0));
        assert!(!lit_at_vertices(coarse, &bounds, 0.0, &lamp, eye));
        // The fine floor with the lamp brought down to 0.3 m: its edges are too long now.
        let low_lamp = [point_light(Vec3::new(0.0, 0.3, 0.0))];
        assert!(!lit_at_vertices(fine, &bounds_of(8.0, 96), 0.0, &low_lamp, eye));
    }

    fn bounds_of(size: f32, cells: u32) -> Aabb {
        Aabb::from_points(&shapes::plane(size, cells, 1.0).positions)
    }

    #[test]
    fn a_glossy_floor_is_shaded_per_pixel() {
        let lamp = [point_light(Vec3::new(0.0, 3.0, 0.0))];
        let eye = Vec3::new(0.0, 2.0, 5.0);
        let (fine, bounds) = fineness_and_bounds(&shapes::plane(8.0, 96, 1.0));
        // Roughness 1 and 0.8 (r = 0 and about 4): lit at the vertices; 0.4 (r ≈ 76): not.
        assert!(lit_at_vertices(fine, &bounds, 4.0, &lamp, eye));
        assert!(!lit_at_vertices(fine, &bounds, 76.0, &lamp, eye));
    }

    #[test]
    fn a_faceted_tube_is_shaded_per_pixel_and_the_sun_alone_needs_no_distance() {
        // Six sides: normals 60° apart.
        let tube = shapes::torus(0.5, 0.02, 96, 6);
        let (fineness, bounds) = fineness_and_bounds(&tube);
        let sun = {
            let mut light = point_light(Vec3::ZERO);
            light.kind = LIGHT_DIRECTIONAL;
            light
        };
        let eye = Vec3::new(0.0, 2.0, 5.0);
        assert!(!lit_at_vertices(fineness, &bounds, 0.0, &[sun], eye));
        let (fine, bounds) = fineness_and_bounds(&shapes::torus(0.5, 0.1, 128, 48));
        assert!(lit_at_vertices(fine, &bounds, 0.0, &[sun], eye));
    }

    #[test]
    fn nan_and_an_eye_inside_answer_no() {
        let lamp = [point_light(Vec3::new(0.0, 3.0, 0.0))];
        let (fine, bounds) = fineness_and_bounds(&shapes::plane(8.0, 96, 1.0));
        assert!(!lit_at_vertices(
            fine,
            &bounds,
            f32::NAN,
            &lamp,
            Vec3::new(0.0, 2.0, 5.0)
        ));
        assert!(!lit_at_vertices(fine, &bounds, 0.0, &lamp, Vec3::new(0.0, 0.0, 0.0)));
        let broken = MeshFineness {
            longest_edge_m: f32::NAN,
            widest_normal_turn_rad: 0.0,
        };
        assert!(!lit_at_vertices(broken, &bounds, 0.0, &lamp, Vec3::new(0.0, 2.0, 5.0)));
    }
}
