//! Procedural triangle meshes (counter-clockwise, outward normals, UVs in [0, 1]) for the
//! bundled samples and test scenes.

use std::f32::consts::{PI, TAU};

use glam::{Vec2, Vec3};

/// Raw mesh arrays, ready for [`super::gltf_write::GltfBuilder::add_mesh`].
#[derive(Debug, Clone, Default)]
pub struct ShapeMesh {
    pub positions: Vec<Vec3>,
    pub normals: Vec<Vec3>,
    pub uvs: Vec<Vec2>,
    pub indices: Vec<u32>,
}

impl ShapeMesh {
    /// Appends a (rows+1)×(cols+1) vertex grid produced by `vertex(u, v)` → (position,
    /// normal), triangulated so that faces are counter-clockwise seen from the normal side.
    fn grid(&mut self, cols: u32, rows: u32, vertex: impl Fn(f32, f32) -> (Vec3, Vec3)) {
        let first = self.positions.len() as u32;
        for row in 0..=rows {
            for col in 0..=cols {
                let (u, v) = (col as f32 / cols as f32, row as f32 / rows as f32);
                let (p, n) = vertex(u, v);
                self.positions.push(p);
                self.normals.push(n);
                self.uvs.push(Vec2::new(u, v));
            }
        }
        for row in 0..rows {
            for col in 0..cols {
                let a = first + row * (cols + 1) + col;
                let b = a + cols + 1;
                for tri in [[a, b, a + 1], [a + 1, b, b + 1]] {
                    // Rows that collapse to a point (poles, cap centres) make zero-area
                    // triangles: leave them out. The test is relative to the edge
                    // lengths, so shapes of any size keep their real triangles (an
                    // absolute area cut emptied a 0.4 mm plane): a sliver is a triangle whose
                    // area is tiny next to its longest edge squared.
                    let [p, q, r] = tri.map(|i| self.positions[i as usize]);
                    let (e1, e2) = (q - p, r - p);
                    let longest2 = e1
                        .length_squared()
                        .max(e2.length_squared())
                        .max((r - q).length_squared());
                    if e1.cross(e2).length_squared() > 1e-12 * longest2 * longest2 {
                        self.indices.extend(tri);
                    }
                }
            }
        }
    }

    /// This mesh moved by `transform` (normals by its inverse transpose).
    pub fn transformed(mut self, transform: glam::Affine3A) -> ShapeMesh {
        let normal_matrix = glam::Mat3::from(transform.matrix3).inverse().transpose();
        for p in &mut self.positions {
            *p = transform.transform_point3(*p);
        }
        for n in &mut self.normals {
            *n = (normal_matrix * *n).normalize_or_zero();
        }
        self
    }

    /// This mesh as a scene object named `name` with material 0.
    pub fn into_object(self, name: &str) -> super::MeshObject {
        super::MeshObject {
            name: name.into(),
            positions: self.positions,
            normals: self.normals,
            uvs: self.uvs,
            indices: self.indices,
            material: 0,
        }
    }

    /// The union of two meshes (indices of `other` offset).
    pub fn merged(mut self, other: ShapeMesh) -> ShapeMesh {
        let offset = self.positions.len() as u32;
        self.positions.extend(other.positions);
        self.normals.extend(other.normals);
        self.uvs.extend(other.uvs);
        self.indices.extend(other.indices.into_iter().map(|i| i + offset));
        self
    }
}

/// A horizontal square of side `size` centred at the origin, facing +y, split into
/// `segments`² quads. UVs repeat `uv_repeat` times across it.
pub fn plane(size: f32, segments: u32, uv_repeat: f32) -> ShapeMesh {
    let mut mesh = ShapeMesh::default();
    mesh.grid(segments, segments, |u, v| {
        (Vec3::new((u - 0.5) * size, 0.0, (v - 0.5) * size), Vec3::Y)
    });
    for uv in &mut mesh.uvs {
        *uv *= uv_repeat;
    }
    mesh
}

/// A UV sphere of `radius` around the origin.
pub fn uv_sphere(radius: f32, segments: u32, rings: u32) -> ShapeMesh {
    let mut mesh = ShapeMesh::default();
    mesh.grid(segments, rings, |u, v| {
        let (theta, phi) = (v * PI, -u * TAU);
        let n = Vec3::new(theta.sin() * phi.cos(), theta.cos(), theta.sin() * phi.sin());
        (n * radius, n)
    });
    mesh
}

/// A torus around the y axis: ring radius `major`, tube radius `minor`.
pub fn torus(major: f32, minor: f32, segments: u32, sides: u32) -> ShapeMesh {
    let mut mesh = ShapeMesh::default();
    mesh.grid(segments, sides, |u, v| {
        let (phi, theta) = (-u * TAU, -v * TAU);
        let ring = Vec3::new(phi.cos(), 0.0, phi.sin());
        let n = ring * theta.cos() + Vec3::Y * theta.sin();
        (ring * major + n * minor, n)
    });
    mesh
}

/// An axis-aligned box centred at the origin with the given half extents.
pub fn cuboid(half: Vec3) -> ShapeMesh {
    let faces = [Vec3::X, -Vec3::X, Vec3::Y, -Vec3::Y, Vec3::Z, -Vec3::Z];
    faces.into_iter().fold(ShapeMesh::default(), |mesh, n| {
        // Two tangents with t1 × t2 = n, so the grid winds counter-clockwise about n.
        let t1 = if n.y.abs() > 0.5 { Vec3::Z } else { Vec3::Y };
        let t2 = n.cross(t1);
        let t1 = t2.cross(n);
        let mut face = ShapeMesh::default();
        face.grid(1, 1, |u, v| {
            let p = n + t1 * (2.0 * v - 1.0) + t2 * (2.0 * u - 1.0);
            (p * half, n)
        });
        mesh.merged(face)
    })
}

/// A tube of `radius` along the curve `point(t)`, t from 0 to 1: `segments` closed
/// cylinders of `sides` sides from one point of the curve to the next, each 5 % longer
/// than its chord so that neighbours overlap at the bends.
pub fn tube_along(point: impl Fn(f32) -> Vec3, segments: u32, radius: f32, sides: u32) -> ShapeMesh {
    (0..segments).fold(ShapeMesh::default(), |mesh, k| {
        let (a, b) = (
            point(k as f32 / segments as f32),
            point((k + 1) as f32 / segments as f32),
        );
        let length = (b - a).length();
        let turn = glam::Quat::from_rotation_arc(Vec3::Y, (b - a) / length.max(1e-12));
        mesh.merged(
            cylinder(radius, length * 1.05, sides).transformed(glam::Affine3A::from_rotation_translation(turn, a)),
        )
    })
}

/// A closed cylinder around the y axis, from y = 0 to y = `height`.
pub fn cylinder(radius: f32, height: f32, segments: u32) -> ShapeMesh {
    let mut side = ShapeMesh::default();
    side.grid(segments, 8, |u, v| {
        let phi = -u * TAU;
        let n = Vec3::new(phi.cos(), 0.0, phi.sin());
        (n * radius + Vec3::Y * ((1.0 - v) * height), n)
    });
    let cap = |y: f32, n: Vec3| {
        let mut cap = ShapeMesh::default();
        cap.grid(segments, 1, |u, v| {
            let phi = if n.y > 0.0 { u * TAU } else { -u * TAU };
            let p = Vec3::new(phi.cos(), 0.0, phi.sin()) * (radius * (1.0 - v)) + Vec3::Y * y;
            (p, n)
        });
        cap
    };
    side.merged(cap(height, Vec3::Y)).merged(cap(0.0, -Vec3::Y))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every triangle has an area and its geometric normal agrees with its vertex normals
    /// (outward, counter-clockwise).
    fn assert_consistent_winding(mesh: &ShapeMesh) {
        for tri in mesh.indices.chunks_exact(3) {
            let [a, b, c] = [0, 1, 2].map(|k| tri[k] as usize);
            let face = (mesh.positions[b] - mesh.positions[a]).cross(mesh.positions[c] - mesh.positions[a]);
            assert!(face.length() > 0.0, "degenerate triangle {tri:?}");
            let vertex_normal = mesh.normals[a] + mesh.normals[b] + mesh.normals[c];
            assert!(face.dot(vertex_normal) > 0.0, "triangle {tri:?} winds inward");
        }
    }

    #[test]
    fn all_shapes_wind_outward() {
        for mesh in [
            plane(2.0, 4, 1.0),
            uv_sphere(1.0, 16, 8),
            torus(1.0, 0.3, 16, 8),
            cuboid(Vec3::new(1.0, 2.0, 3.0)),
            cylinder(0.5, 2.0, 12),
        ] {
            assert_consistent_winding(&mesh);
            assert!(mesh.normals.iter().all(|n| (n.length() - 1.0).abs() < 1e-5));
        }
    }
}
