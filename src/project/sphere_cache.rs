//! The sphere fit kept beside a project (`NAME.lightpaint.spheres`), so reopening it does
//! not voxelise and cluster every mesh again. The file holds a key — a BLAKE3 hash of the
//! blocker settings and of every mesh's positions and triangles — and the fitted sphere
//! sets as JSON; a file whose key differs, or that cannot be read, is simply refitted
//! and rewritten (it is a cache: never an error the user has to act on).

use std::path::{Path, PathBuf};

use crate::blockers::{BlockerSettings, SceneBlockers, fit_scene};
use crate::scene::Scene;

/// Version of the file layout; a file of another version is refitted.
const VERSION: u32 = 2;

#[derive(serde::Serialize, serde::Deserialize)]
struct CacheFile {
    version: u32,
    /// Hex BLAKE3 of what the fit depends on ([`fit_key`]).
    key: String,
    blockers: SceneBlockers,
}

/// The cache file of a project.
pub fn cache_path(project: &Path) -> PathBuf {
    let mut name = project.file_name().unwrap_or_default().to_os_string();
    name.push(".spheres");
    project.with_file_name(name)
}

/// What a fit depends on: the settings and every mesh's geometry (and which object is
/// the terrain, which gets no spheres).
pub fn fit_key(scene: &Scene, settings: &BlockerSettings) -> String {
    let mut hasher = blake3::Hasher::new();
    hasher.update(format!("{settings:?}").as_bytes());
    hasher.update(format!("{:?}", scene.terrain.as_ref().map(|t| t.object)).as_bytes());
    for object in &scene.objects {
        hasher.update(&(object.positions.len() as u64).to_le_bytes());
        hasher.update(bytemuck::cast_slice(&object.positions));
        hasher.update(&(object.indices.len() as u64).to_le_bytes());
        hasher.update(bytemuck::cast_slice(&object.indices));
    }
    hasher.finalize().to_hex().to_string()
}

/// The sphere fit of `scene` stored at `path`, if it was made for exactly this scene and
/// these settings.
pub fn load(path: &Path, scene: &Scene, settings: &BlockerSettings) -> Option<SceneBlockers> {
    let bytes = std::fs::read(path).ok()?;
    let file: CacheFile = serde_json::from_slice(&bytes).ok()?;
    let fits = file.version == VERSION
        && file.key == fit_key(scene, settings)
        && file.blockers.per_object.len() == scene.objects.len();
    fits.then_some(file.blockers)
}

/// Stores `blockers`, the fit of `scene` with `settings`, at `path` (atomically).
pub fn save(path: &Path, scene: &Scene, settings: &BlockerSettings, blockers: &SceneBlockers) -> std::io::Result<()> {
    let file = CacheFile {
        version: VERSION,
        key: fit_key(scene, settings),
        blockers: blockers.clone(),
    };
    let bytes = serde_json::to_vec(&file).map_err(std::io::Error::other)?;
    super::replace_atomically(path, &bytes)
}

/// The sphere fit cached beside `project` when it is fresh, else a new fit — without
/// writing a cache (what `render` and `paint` use: the same blockers the editor draws).
pub fn cached_or_fitted(scene: &Scene, settings: &BlockerSettings, project: Option<&Path>) -> SceneBlockers {
    project
        .map(cache_path)
        .and_then(|p| load(&p, scene, settings))
        .unwrap_or_else(|| fit_scene(scene, settings))
}

/// The sphere fit of `scene`: read from the cache of `project` when it is fresh, else
/// fitted and (for a project) written there. A cache that cannot be written is left out
/// silently: the fit itself is all the caller needs.
pub fn fit_with_cache(scene: &Scene, settings: &BlockerSettings, project: Option<&Path>) -> SceneBlockers {
    let path = project.map(cache_path);
    if let Some(blockers) = path.as_deref().and_then(|p| load(p, scene, settings)) {
        return blockers;
    }
    let blockers = fit_scene(scene, settings);
    if let Some(path) = &path
        && let Err(e) = save(path, scene, settings, &blockers)
    {
        log::warn!("the sphere fit could not be cached at {}: {e}", path.display());
    }
    blockers
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::shapes;

    fn scene() -> Scene {
        let mut scene = Scene::default();
        scene.objects.push(shapes::uv_sphere(0.5, 24, 12).into_object("ball"));
        scene.objects.push(
            shapes::cuboid(glam::Vec3::new(0.4, 0.3, 0.2))
                .transformed(glam::Affine3A::from_translation(glam::Vec3::X * 2.0))
                .into_object("box"),
        );
        scene
    }

    #[test]
    fn a_cached_fit_reads_back_as_fitted_and_only_for_the_same_inputs() {
        let dir = tempfile::tempdir().expect("temp dir");
        let project = dir.path().join("p.lightpaint");
        let scene = scene();
        let settings = BlockerSettings::default();
        let fitted = fit_with_cache(&scene, &settings, Some(&project));
        assert!(fitted.sphere_count() > 0);
        let path = cache_path(&project);
        assert_eq!(path, dir.path().join("p.lightpaint.spheres"));
        assert_eq!(
            load(&path, &scene, &settings),
            Some(fitted.clone()),
            "the same fit reads back"
        );
        assert_eq!(fit_with_cache(&scene, &settings, Some(&project)), fitted);

        let other_settings = BlockerSettings {
            max_spheres_per_mesh: 3,
            ..settings
        };
        assert_eq!(load(&path, &scene, &other_settings), None, "other settings miss");
        let mut moved = scene.clone();
        moved.objects[1].positions[0].y += 0.01;
        assert_eq!(load(&path, &moved, &settings), None, "changed geometry misses");
    }

    #[test]
    fn a_damaged_cache_is_refitted_and_rewritten() {
        let dir = tempfile::tempdir().expect("temp dir");
        let project = dir.path().join("p.lightpaint");
        let scene = scene();
        let settings = BlockerSettings::default();
        let path = cache_path(&project);
        for damage in [&b"{\"version\": 1, \"key\": "[..], &b"\xff\xfe not json"[..], &[][..]] {
            std::fs::write(&path, damage).expect("write");
            assert_eq!(load(&path, &scene, &settings), None);
            let fitted = fit_with_cache(&scene, &settings, Some(&project));
            assert_eq!(fitted, fit_scene(&scene, &settings));
            assert_eq!(load(&path, &scene, &settings), Some(fitted), "rewritten");
        }
    }
}
