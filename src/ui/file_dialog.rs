//! Whether the system's file dialogs can open, and what to say when they cannot. rfd asks
//! the desktop portal (over the session D-Bus) and falls back to zenity; with neither it
//! returns nothing, exactly as when the user cancels, and logs the failure where an
//! artist never looks. So the editor checks before asking (no zenity and no session bus:
//! no dialog can open) and after (nothing chosen within a moment: no dialog was shown),
//! and says so in the window. `scripts/system-packages.sh` installs zenity.

use std::ffi::OsStr;
use std::path::{Path, PathBuf};
use std::time::Duration;

use crate::project::PROJECT_EXTENSION;

/// A dialog that returns nothing sooner than this never showed: nobody cancels a dialog
/// that fast.
pub const SHOWN_AT_LEAST: Duration = Duration::from_millis(150);

/// What the window says when no file dialog could open.
pub fn unavailable_message() -> String {
    "no file dialog could open: lightpaint's dialogs need zenity (sudo apt install zenity) or a \
     desktop portal; a file can also be opened from the command line: lightpaint FILE"
        .to_string()
}

/// Why no dialog can open in this environment, if none can: neither `zenity` on `path`
/// (the PATH variable) nor a session bus (`dbus`, DBUS_SESSION_BUS_ADDRESS) for a portal.
pub fn unavailable_reason(path: Option<&OsStr>, dbus: Option<&OsStr>) -> Option<String> {
    let zenity = path.is_some_and(|path| std::env::split_paths(path).any(|dir| dir.join("zenity").is_file()));
    (!zenity && !session_bus(dbus)).then(unavailable_message)
}

/// Whether a session bus address (DBUS_SESSION_BUS_ADDRESS) is given: a desktop portal
/// may answer on it.
fn session_bus(dbus: Option<&OsStr>) -> bool {
    dbus.is_some_and(|address| !address.is_empty())
}

/// [`unavailable_reason`] for this process's environment.
pub fn unavailable_here() -> Option<String> {
    unavailable_reason(
        std::env::var_os("PATH").as_deref(),
        std::env::var_os("DBUS_SESSION_BUS_ADDRESS").as_deref(),
    )
}

/// A dialog's answer after `open_for`: the path chosen, None when the user cancelled, or
/// the message to show when it returned nothing sooner than [`SHOWN_AT_LEAST`] (it never
/// showed).
pub fn outcome(picked: Option<PathBuf>, open_for: Duration) -> Result<Option<PathBuf>, String> {
    match picked {
        None if open_for < SHOWN_AT_LEAST => Err(unavailable_message()),
        picked => Ok(picked),
    }
}

/// `dialog` opening in `folder` with `name` filled in. rfd hands a portal the folder and
/// the name apart, but its zenity fallback passes only the name (`--filename`), and zenity
/// opens a path given there in its folder: so where no session bus can reach a portal, the
/// name carries the folder.
pub fn start_in(dialog: rfd::FileDialog, folder: &Path, name: &str) -> rfd::FileDialog {
    if session_bus(std::env::var_os("DBUS_SESSION_BUS_ADDRESS").as_deref()) {
        dialog.set_directory(folder).set_file_name(name)
    } else {
        dialog.set_file_name(folder.join(name).to_string_lossy())
    }
}

/// Where Save As starts for a document saved at `project` (None: never saved) on the
/// scene at `scene`: the project's folder (else the scene's) and the project's file name
/// (else the scene's name as a project).
pub fn save_as_start(project: Option<&Path>, scene: &Path) -> (PathBuf, String) {
    let named = project.unwrap_or(scene);
    let folder = named
        .parent()
        .filter(|p| !p.as_os_str().is_empty())
        .map_or_else(|| PathBuf::from("."), Path::to_path_buf);
    let stem = named
        .file_stem()
        .map_or_else(|| "untitled".to_string(), |s| s.to_string_lossy().into_owned());
    (folder, format!("{stem}.{PROJECT_EXTENSION}"))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn without_zenity_or_a_session_bus_no_dialog_can_open() {
        let empty = tempfile::tempdir().expect("temp dir");
        let path = empty.path().as_os_str();
        assert!(unavailable_reason(Some(path), None).is_some());
        assert!(unavailable_reason(None, Some(OsStr::new(""))).is_some());
        // A session bus: a portal may answer.
        assert!(unavailable_reason(Some(path), Some(OsStr::new("unix:path=/run/bus"))).is_none());
        // zenity on the PATH.
        let with_zenity = tempfile::tempdir().expect("temp dir");
        std::fs::write(with_zenity.path().join("zenity"), "").expect("write");
        let joined = std::env::join_paths([empty.path(), with_zenity.path()]).expect("join");
        assert!(unavailable_reason(Some(&joined), None).is_none());
    }

    #[test]
    fn a_dialog_that_returned_nothing_at_once_never_showed() {
        assert!(outcome(None, Duration::from_millis(5)).is_err());
        assert_eq!(outcome(None, Duration::from_secs(3)), Ok(None));
        let chosen = PathBuf::from("/tmp/a.lightpaint");
        assert_eq!(
            outcome(Some(chosen.clone()), Duration::from_millis(5)),
            Ok(Some(chosen))
        );
    }

    #[test]
    fn save_as_starts_beside_the_project_under_its_name() {
        let scene = Path::new("/scenes/hall/hall.glb");
        assert_eq!(
            save_as_start(None, scene),
            (PathBuf::from("/scenes/hall"), "hall.lightpaint".to_string())
        );
        assert_eq!(
            save_as_start(Some(Path::new("/work/shots/evening.lightpaint")), scene),
            (PathBuf::from("/work/shots"), "evening.lightpaint".to_string())
        );
        assert_eq!(
            save_as_start(Some(Path::new("bare.lightpaint")), scene),
            (PathBuf::from("."), "bare.lightpaint".to_string())
        );
    }
}
