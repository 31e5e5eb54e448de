//! Terrain in the scene: where its heights come from (a grayscale or float image, or
//! generated hills), how it is placed in the world (stored in project files), and its
//! render mesh. The shading math of height fields lives in `crate::terrain`.

use std::path::{Path, PathBuf};

use super::SceneError;
use crate::random::SplitMix64;
use crate::terrain::HeightField;

/// A terrain as the project file stores it.
#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize)]
#[serde(deny_unknown_fields)]
pub struct TerrainSpec {
    pub source: TerrainSource,
    /// World x and z of the footprint's centre and the world y of height 0, metres.
    pub center_m: [f32; 3],
    /// Footprint along world x and z, metres.
    pub size_m: [f32; 2],
    /// World height of a full-scale sample (white, or 1.0 in a float image), metres.
    pub height_scale_m: f32,
    /// Linear base colour of the ground.
    pub color: [f32; 3],
}

/// The heights' origin.
#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize)]
#[serde(tag = "kind", rename_all = "snake_case", deny_unknown_fields)]
pub enum TerrainSource {
    /// A grayscale image: 8- or 16-bit PNG, JPEG, or a float Radiance .hdr (a colour image
    /// gives its luminance), rows along +z and columns along +x. The path is relative to
    /// the project.
    Image { path: PathBuf },
    /// Rolling hills, the same for the same seed: a sum of sinusoids of random direction
    /// and phase whose amplitude falls as 1/frequency (spectral synthesis), normalised to
    /// heights 0..1, on a `resolution`² grid.
    Hills { seed: u64, resolution: u32 },
}

/// Sample counts beyond this per side are refused (a 4k² map is 16M samples).
pub const MAX_TERRAIN_SAMPLES_PER_SIDE: u32 = 4096;

impl TerrainSpec {
    /// Generated hills over `size_m` with `height_scale_m` relief.
    pub fn hills(seed: u64, resolution: u32, size_m: f32, height_scale_m: f32) -> TerrainSpec {
        TerrainSpec {
            source: TerrainSource::Hills { seed, resolution },
            center_m: [0.0; 3],
            size_m: [size_m, size_m],
            height_scale_m,
            color: [0.36, 0.33, 0.27],
        }
    }

    /// This spec with an image path made absolute against `directory` (the project's).
    pub fn with_absolute_image(&self, directory: &Path) -> TerrainSpec {
        self.with_image_path(|path| directory.join(path))
    }

    /// This spec with `map` applied to its image path, if it has one.
    pub fn with_image_path(&self, map: impl Fn(&Path) -> PathBuf) -> TerrainSpec {
        let mut spec = self.clone();
        if let TerrainSource::Image { path } = &mut spec.source {
            *path = map(path);
        }
        spec
    }

    /// The problems that make this spec unusable ("" joined), checked before any work.
    pub fn problems(&self) -> Vec<String> {
        let mut problems = Vec::new();
        if !self.center_m.iter().all(|v| v.is_finite()) {
            problems.push("terrain centre is not finite".to_string());
        }
        if !self.size_m.iter().all(|v| v.is_finite() && *v > 0.0) {
            problems.push(format!("terrain size {:?} m must be finite and positive", self.size_m));
        }
        if !self.height_scale_m.is_finite() || self.height_scale_m.abs() > 1e5 {
            problems.push(format!(
                "terrain height scale {} m must be finite and at most 1e5 in size",
                self.height_scale_m
            ));
        }
        if !self.color.iter().all(|v| v.is_finite() && *v >= 0.0) {
            problems.push("terrain colour must be finite and non-negative".to_string());
        }
        if let TerrainSource::Hills { resolution, .. } = self.source
            && !(2..=MAX_TERRAIN_SAMPLES_PER_SIDE).contains(&resolution)
        {
            problems.push(format!(
                "terrain resolution {resolution} must be 2..={MAX_TERRAIN_SAMPLES_PER_SIDE}"
            ));
        }
        problems
    }

    /// The heights in world metres. Image paths are resolved against `directory`; errors
    /// name the image and say what is wrong with it.
    pub fn height_field(&self, directory: &Path) -> Result<HeightField, SceneError> {
        let (columns, rows, unit_heights) = match &self.source {
            TerrainSource::Image { path } => read_height_image(&directory.join(path))?,
            TerrainSource::Hills { seed, resolution } => {
                let n = *resolution as usize;
                (n, n, hills(*seed, n))
            }
        };
        let [cx, cy, cz] = self.center_m.map(f64::from);
        let [sx, sz] = self.size_m.map(f64::from);
        let scale = self.height_scale_m as f64;
        Ok(HeightField {
            columns,
            rows,
            min_xz: [cx - sx / 2.0, cz - sz / 2.0],
            spacing_m: [sx / (columns - 1) as f64, sz / (rows - 1) as f64],
            heights_m: unit_heights.iter().map(|h| (cy + scale * *h as f64) as f32).collect(),
        })
    }
}

/// An image's luminance as heights (8/16-bit scaled to 0..1, float as is).
fn read_height_image(path: &Path) -> Result<(usize, usize, Vec<f32>), SceneError> {
    if !path.exists() {
        return Err(SceneError::NotFound {
            path: path.to_path_buf(),
        });
    }
    let image = image::open(path).map_err(|e| SceneError::Malformed {
        path: path.to_path_buf(),
        reason: format!("cannot read the height map: {e}"),
    })?;
    let (width, height) = (image.width(), image.height());
    if width < 2 || height < 2 || width > MAX_TERRAIN_SAMPLES_PER_SIDE || height > MAX_TERRAIN_SAMPLES_PER_SIDE {
        return Err(SceneError::invalid(
            path,
            format!(
                "a height map must be 2..={MAX_TERRAIN_SAMPLES_PER_SIDE} pixels a side, this one is {width}×{height}"
            ),
        ));
    }
    // to_luma32f maps 8- and 16-bit samples to 0..1 and keeps float samples.
    let heights: Vec<f32> = image.to_luma32f().into_raw();
    if let Some(bad) = heights.iter().position(|h| !h.is_finite()) {
        return Err(SceneError::invalid(
            path,
            format!(
                "height map pixel ({}, {}) is not a finite number",
                bad % width as usize,
                bad / width as usize
            ),
        ));
    }
    Ok((width as usize, height as usize, heights))
}

/// Spectral synthesis: 48 sinusoids, wavelengths from the whole map down to 1/6 of it,
/// amplitude ∝ wavelength², then normalised to 0..1 (smooth, rolling relief).
fn hills(seed: u64, n: usize) -> Vec<f32> {
    let mut random = SplitMix64(seed ^ 0x7e55_a1d5_0f1e_1d00);
    let waves: Vec<(f64, f64, f64, f64)> = (0..48)
        .map(|k| {
            let frequency = 1.0 + 5.0 * (k as f64 / 47.0).powi(2);
            let angle = random.next_f64() * std::f64::consts::TAU;
            let phase = random.next_f64() * std::f64::consts::TAU;
            (
                frequency * angle.cos(),
                frequency * angle.sin(),
                phase,
                frequency.powi(-2),
            )
        })
        .collect();
    let raw: Vec<f64> = (0..n * n)
        .map(|index| {
            let (u, v) = ((index % n) as f64 / (n - 1) as f64, (index / n) as f64 / (n - 1) as f64);
            waves
                .iter()
                .map(|(fx, fz, phase, amplitude)| amplitude * (std::f64::consts::TAU * (fx * u + fz * v) + phase).sin())
                .sum()
        })
        .collect();
    let (lo, hi) = raw
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &h| (a.min(h), b.max(h)));
    let span = (hi - lo).max(1e-12);
    raw.iter().map(|h| ((h - lo) / span) as f32).collect()
}

/// The render mesh of a height field: one vertex per sample, normals from central
/// differences, uv 0..1 over the footprint, two counter-clockwise (seen from above)
/// triangles per cell.
pub struct TerrainMesh {
    pub positions: Vec<[f32; 3]>,
    pub normals: Vec<[f32; 3]>,
    pub uvs: Vec<[f32; 2]>,
    pub indices: Vec<u32>,
}

pub fn terrain_mesh(field: &HeightField) -> TerrainMesh {
    let (nx, nz) = (field.columns, field.rows);
    let [dx, dz] = field.spacing_m;
    let mut mesh = TerrainMesh {
        positions: Vec::with_capacity(nx * nz),
        normals: Vec::with_capacity(nx * nz),
        uvs: Vec::with_capacity(nx * nz),
        indices: Vec::with_capacity(6 * (nx - 1) * (nz - 1)),
    };
    for j in 0..nz as i64 {
        for i in 0..nx as i64 {
            let x = field.min_xz[0] + i as f64 * dx;
            let z = field.min_xz[1] + j as f64 * dz;
            mesh.positions.push([x as f32, field.sample(i, j) as f32, z as f32]);
            // The normal of the surface y = h(x, z) is (−∂h/∂x, 1, −∂h/∂z), normalised.
            let slope_x = (field.sample(i + 1, j) - field.sample(i - 1, j))
                / (dx * ((i + 1).min(nx as i64 - 1) - (i - 1).max(0)) as f64);
            let slope_z = (field.sample(i, j + 1) - field.sample(i, j - 1))
                / (dz * ((j + 1).min(nz as i64 - 1) - (j - 1).max(0)) as f64);
            let length = (slope_x * slope_x + 1.0 + slope_z * slope_z).sqrt();
            mesh.normals.push([
                (-slope_x / length) as f32,
                (1.0 / length) as f32,
                (-slope_z / length) as f32,
            ]);
            mesh.uvs.push([i as f32 / (nx - 1) as f32, j as f32 / (nz - 1) as f32]);
        }
    }
    for j in 0..nz - 1 {
        for i in 0..nx - 1 {
            let a = (j * nx + i) as u32;
            let (b, c, d) = (a + 1, a + nx as u32, a + nx as u32 + 1);
            // Seen from +y with x right and z down the screen, a→c→b turns counter-clockwise.
            mesh.indices.extend_from_slice(&[a, c, b, b, c, d]);
        }
    }
    mesh
}

/// A terrain placed in a scene: its spec, its heights, and the mesh object and material
/// drawing it (the scene's last ones, so other objects keep their indices).
#[derive(Debug, Clone)]
pub struct Terrain {
    pub spec: TerrainSpec,
    pub field: HeightField,
    /// Index of the terrain's mesh in `Scene::objects`.
    pub object: usize,
    /// Index of its material in `Scene::materials`.
    pub material: usize,
}

impl super::Scene {
    /// Replaces the scene's terrain (None: removes it). The terrain's mesh and material
    /// are appended after every other object and material.
    pub fn set_terrain(&mut self, terrain: Option<(TerrainSpec, HeightField)>) {
        if let Some(old) = self.terrain.take() {
            self.objects.truncate(old.object);
            self.materials.truncate(old.material);
        }
        let Some((spec, field)) = terrain else {
            return;
        };
        let mesh = terrain_mesh(&field);
        let material = self.materials.len();
        self.materials.push(super::Material {
            name: "terrain".into(),
            base_color: glam::Vec4::new(spec.color[0], spec.color[1], spec.color[2], 1.0),
            metallic: 0.0,
            roughness: 0.9,
            ..super::Material::default()
        });
        let object = self.objects.len();
        self.objects.push(super::MeshObject {
            name: "terrain".into(),
            positions: mesh.positions.into_iter().map(glam::Vec3::from).collect(),
            normals: mesh.normals.into_iter().map(glam::Vec3::from).collect(),
            uvs: mesh.uvs.into_iter().map(glam::Vec2::from).collect(),
            indices: mesh.indices,
            material,
        });
        self.terrain = Some(Terrain {
            spec,
            field,
            object,
            material,
        });
    }

    /// Whether object `index` is the terrain's mesh (the sphere fit leaves it out: the
    /// terrain shadows through its own horizon model).
    pub fn is_terrain_object(&self, index: usize) -> bool {
        self.terrain.as_ref().is_some_and(|t| t.object == index)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn hills_are_deterministic_normalised_and_differ_by_seed() {
        let a = hills(7, 33);
        assert_eq!(a, hills(7, 33));
        assert_ne!(a, hills(8, 33));
        let (lo, hi) = a.iter().fold((1.0f32, 0.0f32), |(l, h), &v| (l.min(v), h.max(v)));
        assert_eq!((lo, hi), (0.0, 1.0));
    }

    #[test]
    fn mesh_faces_up_and_normals_follow_the_slope() {
        let spec = TerrainSpec {
            center_m: [1.0, -2.0, 3.0],
            ..TerrainSpec::hills(1, 5, 8.0, 0.0)
        };
        let mut field = spec.height_field(Path::new(".")).expect("generated terrain");
        assert_eq!(field.min_xz, [-3.0, -1.0]);
        assert!(
            field.heights_m.iter().all(|h| *h == -2.0),
            "a zero scale is flat at the centre height"
        );
        // A slope rising 1 m per metre along x: normals lean toward −x by 45°.
        for j in 0..5 {
            for i in 0..5 {
                field.heights_m[j * 5 + i] = 2.0 * i as f32;
            }
        }
        let mesh = terrain_mesh(&field);
        for n in &mesh.normals {
            assert!(
                (n[0] + 0.5f32.sqrt()).abs() < 1e-6 && (n[1] - 0.5f32.sqrt()).abs() < 1e-6,
                "{n:?}"
            );
        }
        // Every triangle's geometric normal points up (+y): counter-clockwise from above.
        for t in mesh.indices.chunks_exact(3) {
            let [a, b, c] = [0, 1, 2].map(|k| glam::Vec3::from(mesh.positions[t[k] as usize]));
            assert!((b - a).cross(c - a).y > 0.0);
        }
    }

    #[test]
    fn bad_specs_and_images_are_named() {
        let mut spec = TerrainSpec::hills(1, 1, f32::NAN, 1.0);
        assert_eq!(spec.problems().len(), 2);
        spec = TerrainSpec {
            source: TerrainSource::Image {
                path: "missing.png".into(),
            },
            ..TerrainSpec::hills(1, 8, 4.0, 1.0)
        };
        let error = spec.height_field(Path::new("/nonexistent")).unwrap_err().to_string();
        assert!(error.contains("missing.png") && error.contains("not found"), "{error}");
        let dir = tempfile::tempdir().expect("temp dir");
        std::fs::write(dir.path().join("bad.png"), b"not a png").expect("write");
        spec.source = TerrainSource::Image { path: "bad.png".into() };
        let error = spec.height_field(dir.path()).unwrap_err().to_string();
        assert!(error.contains("bad.png") && error.contains("height map"), "{error}");
    }

    #[test]
    fn eight_bit_and_float_images_give_their_values() {
        let dir = tempfile::tempdir().expect("temp dir");
        image::GrayImage::from_fn(4, 3, |x, y| image::Luma([(x * 50 + y) as u8]))
            .save(dir.path().join("h8.png"))
            .expect("save");
        let grey: Vec<image::Rgb<f32>> = (0..12).map(|k| image::Rgb([k as f32 * 0.5; 3])).collect();
        let mut hdr = Vec::new();
        image::codecs::hdr::HdrEncoder::new(&mut hdr)
            .encode(&grey, 4, 3)
            .expect("hdr");
        std::fs::write(dir.path().join("h.hdr"), hdr).expect("write");
        let spec = |path: &str, scale: f32| TerrainSpec {
            source: TerrainSource::Image { path: path.into() },
            ..TerrainSpec::hills(1, 8, 3.0, scale)
        };
        let eight = spec("h8.png", 255.0).height_field(dir.path()).expect("8-bit map");
        assert_eq!((eight.columns, eight.rows), (4, 3));
        assert!((eight.sample(3, 2) - 152.0).abs() < 1e-3, "{}", eight.sample(3, 2));
        let float = spec("h.hdr", 1.0).height_field(dir.path()).expect("float map");
        // Radiance HDR keeps about 8 bits of mantissa: 5.5 reads back within 1 %.
        assert!((float.sample(3, 2) - 5.5).abs() < 0.06, "{}", float.sample(3, 2));
    }

    #[test]
    fn sixteen_bit_images_keep_their_precision() {
        let dir = tempfile::tempdir().expect("temp dir");
        let image = image::ImageBuffer::<image::Luma<u16>, Vec<u16>>::from_fn(3, 2, |x, y| {
            image::Luma([(x * 1000 + y) as u16])
        });
        image.save(dir.path().join("h.png")).expect("save");
        let spec = TerrainSpec {
            source: TerrainSource::Image { path: "h.png".into() },
            ..TerrainSpec::hills(1, 8, 4.0, 65535.0)
        };
        let field = spec.height_field(dir.path()).expect("16-bit map");
        assert_eq!((field.columns, field.rows), (3, 2));
        assert_eq!(field.sample(2, 1), 2001.0);
    }
}
