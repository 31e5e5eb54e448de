//! Saving without ever losing the previous file: write a temporary file beside the target,
//! fsync it, keep a copy of the old file as `STEM.previous.EXT` (`studio.previous.lightpaint`:
//! still a project that opens, and not to be mistaken for the bake cache
//! `studio.lightpaint.bake`), then rename over the target (atomic on POSIX file systems)
//! and fsync the directory.

use std::io::Write;
use std::path::{Path, PathBuf};

/// The backup kept of the previous version of `path`: `STEM.previous.EXT` (or
/// `NAME.previous` without an extension).
pub fn backup_path(path: &Path) -> PathBuf {
    let mut name = path.file_stem().unwrap_or_default().to_os_string();
    name.push(".previous");
    if let Some(extension) = path.extension() {
        name.push(".");
        name.push(extension);
    }
    path.with_file_name(name)
}

/// Writes `bytes` to `path` atomically, keeping one backup of the previous file.
pub fn write_atomically(path: &Path, bytes: &[u8]) -> std::io::Result<()> {
    write_atomically_with(path, bytes, || Ok(()))
}

/// [`write_atomically`] with a hook run just before the rename (tests use it to abort a
/// save at the worst moment). Whatever fails, the previous file is untouched and the
/// temporary file is removed.
pub fn write_atomically_with(
    path: &Path,
    bytes: &[u8],
    before_rename: impl FnOnce() -> std::io::Result<()>,
) -> std::io::Result<()> {
    write(path, bytes, true, before_rename)
}

/// [`write_atomically`] without the backup: for files that can be rebuilt (the bake
/// cache), where a second copy would only double the disk used.
pub fn replace_atomically(path: &Path, bytes: &[u8]) -> std::io::Result<()> {
    write(path, bytes, false, || Ok(()))
}

fn write(
    path: &Path,
    bytes: &[u8],
    keep_backup: bool,
    before_rename: impl FnOnce() -> std::io::Result<()>,
) -> std::io::Result<()> {
    let directory = match path.parent() {
        Some(parent) if !parent.as_os_str().is_empty() => parent.to_path_buf(),
        _ => PathBuf::from("."),
    };
    let mut temporary_name = std::ffi::OsString::from(".");
    temporary_name.push(path.file_name().unwrap_or_default());
    temporary_name.push(format!(".{}.tmp", std::process::id()));
    let temporary = directory.join(temporary_name);

    let result = (|| {
        let mut file = std::fs::File::create(&temporary)?;
        file.write_all(bytes)?;
        file.sync_all()?;
        drop(file);
        if keep_backup && path.exists() {
            std::fs::copy(path, backup_path(path))?;
        }
        before_rename()?;
        std::fs::rename(&temporary, path)
    })();
    if result.is_err() {
        let _ = std::fs::remove_file(&temporary);
        return result;
    }
    // Make the rename itself durable; not every platform can open a directory, so this
    // is best effort.
    if let Ok(dir) = std::fs::File::open(&directory) {
        let _ = dir.sync_all();
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    #[test]
    fn the_backup_keeps_the_extension_after_previous() {
        use std::path::Path;
        assert_eq!(
            super::backup_path(Path::new("/p/studio.lightpaint")),
            Path::new("/p/studio.previous.lightpaint")
        );
        assert_eq!(super::backup_path(Path::new("notes")), Path::new("notes.previous"));
    }

    use super::*;

    #[test]
    fn replaces_the_file_and_keeps_a_backup() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("a.lightpaint");
        write_atomically(&path, b"one").unwrap();
        write_atomically(&path, b"two").unwrap();
        assert_eq!(std::fs::read(&path).unwrap(), b"two");
        assert_eq!(std::fs::read(backup_path(&path)).unwrap(), b"one");
        assert_eq!(backup_path(&path).file_name().unwrap(), {
            let mut name = path.file_stem().unwrap().to_os_string();
            name.push(".previous.");
            name.push(path.extension().unwrap_or_default());
            name
        });
    }

    #[test]
    fn an_interrupted_save_leaves_the_previous_file_intact() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("a.lightpaint");
        write_atomically(&path, b"precious").unwrap();
        let aborted = write_atomically_with(&path, b"half-written", || Err(std::io::Error::other("power cut")));
        assert!(aborted.is_err());
        assert_eq!(std::fs::read(&path).unwrap(), b"precious");
        let leftovers: Vec<_> = std::fs::read_dir(dir.path())
            .unwrap()
            .filter_map(|e| e.ok())
            .filter(|e| e.file_name().to_string_lossy().ends_with(".tmp"))
            .collect();
        assert!(leftovers.is_empty(), "temporary file left behind");
    }
}
