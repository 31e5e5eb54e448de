//! What the editor remembers between runs (in eframe's storage, beside the window's size
//! and position): recently opened files and view choices.

use std::path::{Path, PathBuf};

/// Key of the preferences in eframe's storage.
const STORAGE_KEY: &str = "lightpaint.preferences";
/// How many recent files File ▸ Open Recent lists.
pub const RECENT_FILES: usize = 10;

#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize)]
#[serde(default)]
pub struct Preferences {
    /// Projects and scenes opened, most recent first.
    pub recent_files: Vec<PathBuf>,
    /// Draw light markers and the light gizmo over the viewport.
    pub show_light_markers: bool,
    /// Outline the shadow-casting sphere blockers over the viewport.
    pub show_blockers: bool,
    /// Colour the scene by how much of the selected light reaches each vertex.
    pub show_heat_map: bool,
    pub show_outliner: bool,
    pub show_inspector: bool,
}

impl Default for Preferences {
    fn default() -> Preferences {
        Preferences {
            recent_files: Vec::new(),
            show_light_markers: true,
            show_blockers: false,
            show_heat_map: false,
            show_outliner: true,
            show_inspector: true,
        }
    }
}

impl Preferences {
    /// The preferences stored by an earlier run (defaults without storage or when they
    /// cannot be read: preferences are never worth an error).
    pub fn load(storage: Option<&dyn eframe::Storage>) -> Preferences {
        storage
            .and_then(|s| eframe::get_value(s, STORAGE_KEY))
            .unwrap_or_default()
    }

    pub fn store(&self, storage: &mut dyn eframe::Storage) {
        eframe::set_value(storage, STORAGE_KEY, self);
    }

    /// Puts `path` first in the recent files (once), keeping the newest [`RECENT_FILES`].
    pub fn remember(&mut self, path: &Path) {
        let path = std::path::absolute(path).unwrap_or_else(|_| path.to_path_buf());
        self.recent_files.retain(|p| *p != path);
        self.recent_files.insert(0, path);
        self.recent_files.truncate(RECENT_FILES);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn recent_files_are_newest_first_without_repeats_and_bounded() {
        let mut preferences = Preferences::default();
        for i in 0..15 {
            preferences.remember(Path::new(&format!("/projects/p{i}.lightpaint")));
        }
        preferences.remember(Path::new("/projects/p7.lightpaint"));
        assert_eq!(preferences.recent_files.len(), RECENT_FILES);
        assert_eq!(preferences.recent_files[0], Path::new("/projects/p7.lightpaint"));
        assert_eq!(preferences.recent_files[1], Path::new("/projects/p14.lightpaint"));
        let sevens = preferences
            .recent_files
            .iter()
            .filter(|p| p.ends_with("p7.lightpaint"))
            .count();
        assert_eq!(sevens, 1);
    }

    #[test]
    fn preferences_of_an_older_run_fill_in_missing_fields() {
        let old: Preferences = serde_json::from_str(r#"{"recent_files": ["/a.glb"]}"#).expect("reads");
        assert_eq!(old.recent_files, [PathBuf::from("/a.glb")]);
        assert!(old.show_light_markers && old.show_outliner && old.show_inspector);
    }
}
