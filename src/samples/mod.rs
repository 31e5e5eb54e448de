//! Sample scenes and projects, generated rather than downloaded. `cargo run --bin
//! make-sample [NAME…]` writes them under projects/; the small ones are committed and a
//! test checks they are exactly what this code produces, the big ones are generated on
//! demand (they would weigh tens of megabytes in git).

pub mod blocker_bench;
pub mod figure;
mod interior;
mod lamp_room;
mod large;
mod studio_set;
mod terrain;

use std::path::{Path, PathBuf};

use crate::project::{Document, ProjectError, write_atomically};
use crate::scene::Environment;

pub use studio_set::sample_scene_glb;

/// Path of the bundled sample scene, relative to the repository root.
pub const SAMPLE_SCENE: &str = "projects/sample/sample.glb";

/// Path of the bundled sample project (on [`SAMPLE_SCENE`]), relative to the repository root.
pub const SAMPLE_PROJECT: &str = "projects/sample/sample.lightpaint";

/// The samples lightpaint can generate.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Sample {
    /// A studio set: primitives on a textured floor, 4 lights (the default project).
    Sample,
    /// A figure of about 10k vertices on a floor, 9 lights.
    Studio,
    /// A furnished room, glossy and diffuse, 150k+ vertices, 17 lights.
    Interior,
    /// A field of 144 objects, 500k+ vertices, 24 lights, for scale tests.
    Large,
    /// Generated hills with a figure, standing stones and boulders, a low sun and a lantern.
    Terrain,
    /// A room at night: single-quad walls, an open shelf and card, a lattice, a box, a pole
    /// and a 100k-triangle ball under 30 lamps of 1.5 m range; no sky.
    LampRoom,
}

impl Sample {
    pub const ALL: [Sample; 6] = [
        Sample::Sample,
        Sample::Studio,
        Sample::Interior,
        Sample::Large,
        Sample::Terrain,
        Sample::LampRoom,
    ];

    pub fn name(self) -> &'static str {
        match self {
            Sample::Sample => "sample",
            Sample::Studio => "studio",
            Sample::Interior => "interior",
            Sample::Large => "large",
            Sample::Terrain => "terrain",
            Sample::LampRoom => "lamp-room",
        }
    }

    pub fn from_name(name: &str) -> Option<Sample> {
        Sample::ALL.into_iter().find(|s| s.name() == name)
    }

    /// Whether the generated files are committed under projects/ (small enough for git).
    pub fn is_committed(self) -> bool {
        matches!(self, Sample::Sample | Sample::Studio | Sample::Terrain)
    }

    pub fn glb(self) -> Vec<u8> {
        match self {
            Sample::Sample => studio_set::sample_scene_glb(),
            Sample::Studio => figure::studio_glb(),
            Sample::Interior => interior::interior_glb(),
            Sample::Large => large::large_glb(),
            Sample::Terrain => terrain::terrain_glb(&terrain_field()),
            Sample::LampRoom => lamp_room::lamp_room_glb(),
        }
    }

    /// Whether the sample is lit by the sky too ([`sky_hdr`]); the lamp room is a room at
    /// night.
    pub fn has_sky(self) -> bool {
        self != Sample::LampRoom
    }

    /// Writes `NAME.glb`, `sky.hdr` (for samples with a sky) and `NAME.lightpaint` into
    /// `directory`; returns the project path.
    pub fn write(self, directory: &Path) -> Result<PathBuf, ProjectError> {
        let write = |path: &Path, bytes: &[u8]| {
            write_atomically(path, bytes).map_err(|source| ProjectError::Write {
                path: path.to_path_buf(),
                source,
            })
        };
        let scene_path = directory.join(format!("{}.glb", self.name()));
        write(&scene_path, &self.glb())?;
        let mut document = Document::from_gltf(&scene_path)?;
        if self.has_sky() {
            let sky_path = directory.join("sky.hdr");
            write(&sky_path, &sky_hdr())?;
            document.scene.environment =
                Some(Environment::load(&sky_path, SKY_INTENSITY, 0.0).map_err(ProjectError::SceneOnly)?);
        }
        if self == Sample::Terrain {
            document.scene.lights.insert(0, terrain::sun());
            document
                .scene
                .set_terrain(Some((terrain::terrain_spec(), terrain_field())));
        }
        let project_path = directory.join(format!("{}.lightpaint", self.name()));
        document.save(&project_path)?;
        Ok(project_path)
    }
}

/// The terrain sample's heights (generated: no file is read).
fn terrain_field() -> crate::terrain::HeightField {
    terrain::terrain_spec()
        .height_field(Path::new("."))
        .expect("the sample's generated terrain is valid")
}

/// Writes the default sample scene and project into `directory`.
pub fn write_sample_project(directory: &Path) -> Result<(), ProjectError> {
    Sample::Sample.write(directory).map(|_| ())
}

/// Radiance multiplier of the samples' sky: a soft fill under the lights.
const SKY_INTENSITY: f32 = 0.15;

/// A 64 × 32 equirectangular Radiance HDR sky: blue zenith, pale horizon, warm grey ground.
pub fn sky_hdr() -> Vec<u8> {
    let (width, height) = (64usize, 32usize);
    let pixels: Vec<image::Rgb<f32>> = (0..width * height)
        .map(|i| {
            let row = i / width;
            let elevation = 1.0 - 2.0 * (row as f32 + 0.5) / height as f32; // sin of the altitude
            let rgb = if elevation > 0.0 {
                let t = elevation.sqrt();
                [0.9 + (0.35 - 0.9) * t, 0.95 + (0.5 - 0.95) * t, 1.0 + (0.9 - 1.0) * t]
            } else {
                [0.3, 0.27, 0.24]
            };
            image::Rgb(rgb)
        })
        .collect();
    let mut bytes = Vec::new();
    image::codecs::hdr::HdrEncoder::new(&mut bytes)
        .encode(&pixels, width, height)
        .expect("encoding an HDR into memory cannot fail");
    bytes
}

/// A `size`² PNG checkerboard of `squares`² squares in two sRGB colours.
pub fn checker_png(size: u32, squares: u32, light: [u8; 3], dark: [u8; 3]) -> Vec<u8> {
    let cell = (size / squares).max(1);
    let img = image::RgbaImage::from_fn(size, size, |x, y| {
        let [r, g, b] = if ((x / cell) + (y / cell)).is_multiple_of(2) {
            light
        } else {
            dark
        };
        image::Rgba([r, g, b, 255])
    });
    let mut png = Vec::new();
    img.write_to(&mut std::io::Cursor::new(&mut png), image::ImageFormat::Png)
        .expect("encoding a PNG into memory cannot fail");
    png
}
