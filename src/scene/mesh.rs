use glam::{Vec2, Vec3};

use super::Aabb;

/// One triangle mesh in world space (a glTF primitive with its node transform applied).
#[derive(Debug, Clone, Default)]
pub struct MeshObject {
    pub name: String,
    pub positions: Vec<Vec3>,
    /// Unit normals, one per vertex.
    pub normals: Vec<Vec3>,
    /// Texture coordinates (set 0); zeros when the file has none.
    pub uvs: Vec<Vec2>,
    /// Triangle list, counter-clockwise front faces.
    pub indices: Vec<u32>,
    /// Index into [`super::Scene::materials`].
    pub material: usize,
}

impl MeshObject {
    pub fn bounds(&self) -> Aabb {
        Aabb::from_points(&self.positions)
    }

    /// The three vertex indices of triangle `triangle`.
    pub fn triangle_corners(&self, triangle: usize) -> [usize; 3] {
        [0, 1, 2].map(|k| self.indices[3 * triangle + k] as usize)
    }

    /// The unit shading normal at `barycentric` on triangle `triangle` (vertex normals
    /// interpolated and renormalised, as the rasteriser does; zero if they cancel).
    pub fn interpolated_normal(&self, triangle: usize, barycentric: Vec3) -> Vec3 {
        let [a, b, c] = self.triangle_corners(triangle);
        (self.normals[a] * barycentric.x + self.normals[b] * barycentric.y + self.normals[c] * barycentric.z)
            .normalize_or_zero()
    }

    /// Texture coordinates at `barycentric` on triangle `triangle` (zero where a file gave
    /// fewer coordinates than vertices).
    pub fn interpolated_uv(&self, triangle: usize, barycentric: Vec3) -> Vec2 {
        let uv = |v: usize| self.uvs.get(v).copied().unwrap_or_default();
        let [a, b, c] = self.triangle_corners(triangle);
        uv(a) * barycentric.x + uv(b) * barycentric.y + uv(c) * barycentric.z
    }

    /// The unit geometric normal of triangle `triangle` (counter-clockwise front; zero if
    /// degenerate).
    pub fn face_normal(&self, triangle: usize) -> Vec3 {
        let [a, b, c] = self.triangle_corners(triangle);
        (self.positions[b] - self.positions[a])
            .cross(self.positions[c] - self.positions[a])
            .normalize_or_zero()
    }

    /// Area-weighted vertex normals from the triangles (used when a file has none).
    /// Vertices that touch only degenerate triangles get +y, so the result is always unit.
    pub fn generate_normals(positions: &[Vec3], indices: &[u32]) -> Vec<Vec3> {
        let mut normals = vec![Vec3::ZERO; positions.len()];
        for tri in indices.chunks_exact(3) {
            let [a, b, c] = [tri[0], tri[1], tri[2]].map(|i| i as usize);
            // The cross product's length is twice the area: larger faces weigh more.
            let n = (positions[b] - positions[a]).cross(positions[c] - positions[a]);
            for v in [a, b, c] {
                normals[v] += n;
            }
        }
        normals
            .into_iter()
            .map(|n| n.try_normalize().unwrap_or(Vec3::Y))
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn generated_normals_of_a_ccw_quad_face_up() {
        let positions = [
            Vec3::new(0.0, 0.0, 0.0),
            Vec3::new(0.0, 0.0, 1.0),
            Vec3::new(1.0, 0.0, 1.0),
            Vec3::new(1.0, 0.0, 0.0),
        ];
        let normals = MeshObject::generate_normals(&positions, &[0, 1, 2, 0, 2, 3]);
        for n in normals {
            assert!((n - Vec3::Y).length() < 1e-6);
        }
    }

    #[test]
    fn degenerate_triangles_give_finite_normals() {
        let positions = [Vec3::ZERO, Vec3::ZERO, Vec3::X];
        let normals = MeshObject::generate_normals(&positions, &[0, 1, 2]);
        assert!(normals.iter().all(|n| n.is_finite() && (n.length() - 1.0).abs() < 1e-6));
    }
}
