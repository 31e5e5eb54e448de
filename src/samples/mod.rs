//! Sample scenes and projects, generated rather than downloaded. `cargo run --bin
//! make-sample [NAME…]` writes them under projects/; the small ones are committed and a
//! test checks they are exactly what this code produces, the big ones are generated on
//! demand (they would weigh tens of megabytes in git).

mod figure;
mod interior;
mod large;
mod studio_set;

use std::path::{Path, PathBuf};

use crate::project::{Document, ProjectError, write_atomically};

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
}

impl Sample {
    pub const ALL: [Sample; 4] = [Sample::Sample, Sample::Studio, Sample::Interior, Sample::Large];

    pub fn name(self) -> &'static str {
        match self {
            Sample::Sample => "sample",
            Sample::Studio => "studio",
            Sample::Interior => "interior",
            Sample::Large => "large",
        }
    }

    pub fn from_name(name: &str) -> Option<Sample> {
        Sample::ALL.into_iter().find(|s| s.name() == name)
    }

    /// Whether the generated files are committed under projects/ (small enough for git).
    pub fn is_committed(self) -> bool {
        matches!(self, Sample::Sample | Sample::Studio)
    }

    pub fn glb(self) -> Vec<u8> {
        match self {
            Sample::Sample => studio_set::sample_scene_glb(),
            Sample::Studio => figure::studio_glb(),
            Sample::Interior => interior::interior_glb(),
            Sample::Large => large::large_glb(),
        }
    }

    /// Writes `NAME.glb` and `NAME.lightpaint` into `directory`; returns the project path.
    pub fn write(self, directory: &Path) -> Result<PathBuf, ProjectError> {
        let scene_path = directory.join(format!("{}.glb", self.name()));
        write_atomically(&scene_path, &self.glb()).map_err(|source| ProjectError::Write {
            path: scene_path.clone(),
            source,
        })?;
        let project_path = directory.join(format!("{}.lightpaint", self.name()));
        Document::from_gltf(&scene_path)?.save(&project_path)?;
        Ok(project_path)
    }
}

/// Writes the default sample scene and project into `directory`.
pub fn write_sample_project(directory: &Path) -> Result<(), ProjectError> {
    Sample::Sample.write(directory).map(|_| ())
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
