//! `lightpaint check`: every problem of a project or scene file, exit 2 if there is one.

use std::path::Path;

use lightpaint::project::{Document, ProjectError};

use super::CliError;

pub fn check(file: &Path) -> Result<(), CliError> {
    let document = match Document::open(file) {
        Ok(document) => document,
        Err(ProjectError::Invalid { path, problems }) => {
            for problem in &problems {
                say!("problem: {}: {problem}", path.display());
            }
            return Err(CliError::Problems {
                path,
                count: problems.len(),
            });
        }
        Err(e) => return Err(e.into()),
    };
    for warning in &document.warnings {
        say!("problem: {}: {warning}", file.display());
    }
    let scene = &document.scene;
    say!(
        "{}: {} objects, {} vertices, {} triangles, {} materials, {} textures, {} lights, {}",
        file.display(),
        scene.objects.len(),
        scene.vertex_count(),
        scene.triangle_count(),
        scene.materials.len(),
        scene.textures.len(),
        scene.lights.len(),
        if scene.camera.is_some() { "camera" } else { "no camera" }
    );
    // Not problems: a glTF without lights opens lit by the default rig, and says so.
    for note in &document.notes {
        say!("note: {}: {note}", file.display());
    }
    if document.warnings.is_empty() {
        say!("{}: ok", file.display());
        Ok(())
    } else {
        Err(CliError::Problems {
            path: file.to_path_buf(),
            count: document.warnings.len(),
        })
    }
}
