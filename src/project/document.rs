//! An open document: a scene with its project settings, opened from a project file or a
//! bare glTF, and saved back to a project file.

use std::path::{Path, PathBuf};

use super::atomic::write_atomically;
use super::error::ProjectError;
use super::file::{EnvironmentReference, PROJECT_EXTENSION, ProjectFile, SceneReference, read_project_file};
use super::migrate::FORMAT_VERSION;
use super::painting_state::PaintingState;
use crate::scene::{Environment, OrbitCamera, Scene};
use crate::shading::RenderSettings;

#[derive(Debug, Clone)]
pub struct Document {
    /// The scene, its lights replaced by the project's.
    pub scene: Scene,
    /// The glTF file the scene came from.
    pub scene_path: PathBuf,
    pub settings: RenderSettings,
    pub camera: Option<OrbitCamera>,
    /// The project file this document was opened from or last saved to.
    pub project_path: Option<PathBuf>,
    /// Things the user should know that did not stop the document from opening.
    pub warnings: Vec<String>,
    /// What was done for the user on opening, to say once (not problems: `check` passes
    /// them), such as the default rig lighting a glTF that has no lights.
    pub notes: Vec<String>,
    /// The stroke log, brush and painting strategies as the file holds them. In the
    /// editor a `session::EditorSession` owns the live painting state and writes it back
    /// here only when the document leaves the session or is saved.
    pub painting: PaintingState,
    /// Indices of the objects hidden in the viewport (see [`ProjectFile::hidden_objects`]).
    pub hidden_objects: std::collections::BTreeSet<usize>,
    /// Names the user gave objects (see [`ProjectFile::object_names`]); already applied
    /// to the scene's objects.
    pub object_names: std::collections::BTreeMap<usize, String>,
}

/// What a glTF without lights is lit by when it opens: a warm key sun from above and in
/// front, a cool fill sun from the other side (directional lights, so they light a scene
/// of any size alike), about 3 lx in all: a white surface facing the key shows
/// mid-grey-to-light through the tone curve at exposure 0.
pub fn default_rig() -> Vec<crate::scene::Light> {
    use crate::scene::{Light, LightKind};
    use glam::Vec3;
    let sun = |name: &str, color: Vec3, lux: f32, direction: Vec3| Light {
        name: name.into(),
        kind: LightKind::Directional,
        color,
        intensity: lux,
        position: Vec3::ZERO,
        direction: direction.normalize(),
        range: None,
        locked: false,
    };
    vec![
        sun("Key sun", Vec3::new(1.0, 0.95, 0.88), 2.5, Vec3::new(-0.4, -1.0, -0.6)),
        sun("Fill sun", Vec3::new(0.85, 0.9, 1.0), 0.8, Vec3::new(0.6, -0.5, 0.4)),
    ]
}

/// The note of a glTF that opened with [`default_rig`].
pub const DEFAULT_RIG_NOTE: &str =
    "the scene has no lights: it is lit by a default rig of two suns (Key sun, Fill sun) until you change it";

/// Whether `path` names a project file (by extension) rather than a glTF scene.
pub fn is_project_path(path: &Path) -> bool {
    path.extension()
        .and_then(|e| e.to_str())
        .is_some_and(|e| e.eq_ignore_ascii_case(PROJECT_EXTENSION))
}

impl Document {
    /// The scene as shown: the hidden objects keep their place in the list (object
    /// indices, per-object bakes and fits stay valid) but lose their triangles, so they
    /// are neither drawn nor cast shadows.
    pub fn shown_scene(&self) -> crate::scene::Scene {
        let mut scene = self.scene.clone();
        for (index, object) in scene.objects.iter_mut().enumerate() {
            if self.hidden_objects.contains(&index) {
                object.indices.clear();
            }
        }
        scene
    }

    /// The camera the document is viewed from: the project's saved one, else the scene's
    /// initial orbit. The editor, `render`, `paint` and the study all look through it.
    pub fn view(&self) -> crate::scene::OrbitCamera {
        self.camera.unwrap_or_else(|| self.scene.initial_orbit())
    }

    /// Opens a project file or, for .gltf/.glb, a new document on that scene.
    pub fn open(path: &Path) -> Result<Document, ProjectError> {
        if is_project_path(path) {
            Document::open_project(path)
        } else {
            Document::from_gltf(path)
        }
    }

    /// A new, unsaved document on a glTF scene, with default settings; a scene without
    /// lights gets `default_rig` (and a note saying so), so it opens lit rather than
    /// black.
    pub fn from_gltf(path: &Path) -> Result<Document, ProjectError> {
        let mut scene = Scene::load(path)?;
        let warnings = scene.warnings.clone();
        let mut notes = Vec::new();
        if scene.lights.is_empty() {
            scene.lights = default_rig();
            notes.push(DEFAULT_RIG_NOTE.to_string());
        }
        Ok(Document {
            scene,
            scene_path: path.to_path_buf(),
            settings: RenderSettings::default(),
            camera: None,
            project_path: None,
            warnings,
            notes,
            painting: PaintingState::default(),
            hidden_objects: Default::default(),
            object_names: Default::default(),
        })
    }

    /// Opens a project and the scene it references. A scene that changed since the
    /// project was saved is a warning (its lights and settings still apply).
    pub fn open_project(path: &Path) -> Result<Document, ProjectError> {
        let file = read_project_file(path)?;
        let directory = path.parent().unwrap_or(Path::new(""));
        let scene_path = directory.join(&file.scene.gltf);
        if !scene_path.exists() {
            return Err(ProjectError::MissingScene {
                path: path.to_path_buf(),
                scene: scene_path,
            });
        }
        let mut scene =
            Scene::load_choosing(&scene_path, file.scene.gltf_scene).map_err(|error| ProjectError::Scene {
                project: path.to_path_buf(),
                error,
            })?;
        let mut warnings = scene.warnings.clone();
        if !file.scene.blake3.is_empty() && scene.source_hash.as_deref() != Some(file.scene.blake3.as_str()) {
            warnings.push(format!(
                "{} changed since the project was saved; its lights and settings are kept",
                scene_path.display()
            ));
        }
        scene.lights = file.lights;
        scene.environment = match &file.environment {
            Some(reference) => Some(
                Environment::load(
                    &directory.join(&reference.hdr),
                    reference.intensity,
                    reference.rotation_rad,
                )
                .map_err(|error| ProjectError::Asset {
                    project: path.to_path_buf(),
                    error,
                })?,
            ),
            None => None,
        };
        if let Some(spec) = file.terrain {
            let spec = spec.with_absolute_image(directory);
            let field = spec.height_field(directory).map_err(|error| ProjectError::Asset {
                project: path.to_path_buf(),
                error,
            })?;
            scene.set_terrain(Some((spec, field)));
        }
        // A hidden or renamed object the scene no longer has (the glTF changed) is forgotten.
        let object_count = scene.objects.len();
        let (hidden_objects, gone): (Vec<usize>, Vec<usize>) =
            file.hidden_objects.iter().partition(|&&index| index < object_count);
        if !gone.is_empty() {
            warnings.push(format!(
                "hidden objects {gone:?} are not in the scene ({object_count} objects); they are shown again"
            ));
        }
        let (object_names, gone): (
            std::collections::BTreeMap<usize, String>,
            std::collections::BTreeMap<usize, String>,
        ) = file
            .object_names
            .into_iter()
            .partition(|(index, _)| *index < object_count);
        if !gone.is_empty() {
            let gone: Vec<usize> = gone.into_keys().collect();
            warnings.push(format!(
                "renamed objects {gone:?} are not in the scene ({object_count} objects); their names are dropped"
            ));
        }
        for (&index, name) in &object_names {
            scene.objects[index].name = name.clone();
        }
        Ok(Document {
            scene,
            scene_path,
            settings: file.render,
            camera: file.camera,
            project_path: Some(path.to_path_buf()),
            warnings,
            notes: Vec::new(),
            painting: file.painting,
            hidden_objects: hidden_objects.into_iter().collect(),
            object_names,
        })
    }

    /// The project file for saving at `project_path` (the glTF path made relative to it).
    pub fn to_project_file(&self, project_path: &Path) -> ProjectFile {
        self.to_project_file_with(project_path, self.painting.clone())
    }

    /// [`Document::to_project_file`] with `painting` as its painting state (an editor
    /// session's, which owns it while the document is open).
    pub fn to_project_file_with(&self, project_path: &Path, painting: PaintingState) -> ProjectFile {
        let directory = absolute(project_path.parent().unwrap_or(Path::new("")));
        let relative = |path: &Path| {
            let path = absolute(path);
            pathdiff::diff_paths(&path, &directory).unwrap_or(path)
        };
        let gltf = relative(&self.scene_path);
        let environment = self.scene.environment.as_ref().map(|environment| EnvironmentReference {
            hdr: relative(&environment.hdr),
            intensity: environment.intensity,
            rotation_rad: environment.rotation_rad,
        });
        ProjectFile {
            format_version: FORMAT_VERSION,
            scene: SceneReference {
                gltf,
                blake3: self.scene.source_hash.clone().unwrap_or_default(),
                gltf_scene: self.scene.gltf_scene.filter(|_| self.scene.gltf_scenes.len() > 1),
            },
            lights: self.scene.lights.clone(),
            render: self.settings,
            camera: self.camera,
            environment,
            painting,
            terrain: self.scene.terrain.as_ref().map(|t| t.spec.with_image_path(relative)),
            hidden_objects: self.hidden_objects.iter().copied().collect(),
            object_names: self.object_names.clone(),
        }
    }

    /// This document on scene `index` of the same glTF file: that scene's objects, lights
    /// and camera, with the document's render settings, environment, brush and painting
    /// strategies. The stroke log starts empty (its strokes named the other scene's
    /// lights), and the project file stays the same until it is saved.
    pub fn with_gltf_scene(&self, index: usize) -> Result<Document, ProjectError> {
        let mut scene = Scene::load_choosing(&self.scene_path, Some(index))?;
        scene.environment = self.scene.environment.clone();
        scene.set_terrain(self.scene.terrain.as_ref().map(|t| (t.spec.clone(), t.field.clone())));
        Ok(Document {
            warnings: scene.warnings.clone(),
            notes: Vec::new(),
            scene,
            scene_path: self.scene_path.clone(),
            settings: self.settings,
            camera: None,
            project_path: self.project_path.clone(),
            painting: PaintingState {
                strokes: Vec::new(),
                ..self.painting.clone()
            },
            // Another scene has other objects.
            hidden_objects: Default::default(),
            object_names: Default::default(),
        })
    }

    /// Saves atomically to `project_path` (keeping the previous file as `STEM.previous.lightpaint`) and
    /// remembers it as the document's file.
    pub fn save(&mut self, project_path: &Path) -> Result<(), ProjectError> {
        let file = self.to_project_file(project_path);
        self.save_file(project_path, &file)
    }

    /// Saves `file` (this document's, as [`Document::to_project_file`] or an editor
    /// session writes it) atomically to `project_path`, which becomes the document's file.
    pub fn save_file(&mut self, project_path: &Path, file: &ProjectFile) -> Result<(), ProjectError> {
        let text = file.to_json();
        write_atomically(project_path, text.as_bytes()).map_err(|source| ProjectError::Write {
            path: project_path.to_path_buf(),
            source,
        })?;
        self.project_path = Some(project_path.to_path_buf());
        Ok(())
    }
}

fn absolute(path: &Path) -> PathBuf {
    std::path::absolute(path).unwrap_or_else(|_| path.to_path_buf())
}
