//! Atomic file writing: a file is either fully replaced or left untouched.
//!
//! The content goes to a new temporary file in the target's directory (so the final rename
//! stays on one file system), which is flushed and synced, then renamed over the target. On
//! any error the temporary file is removed and the target is not touched.

use std::fs::{self, File, OpenOptions};
use std::io::{self, BufWriter, Write};
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicU64, Ordering};

/// Tells temporary files of one process apart.
static COUNTER: AtomicU64 = AtomicU64::new(0);

/// How many temporary names to try when one is taken.
const ATTEMPTS: usize = 16;

/// Writes `path` atomically with what `fill` writes: into a new temporary file beside `path`
/// (`.<name>.<pid>-<n>.tmp`), flushed and synced, then renamed over `path`, keeping the
/// permissions of a file being replaced.
///
/// # Errors
///
/// Any I/O error, from `fill` or the file system. The temporary file is then removed and
/// `path` is untouched. The error does not name `path`; callers add it.
pub fn write_atomically(path: &Path, fill: impl FnOnce(&mut BufWriter<File>) -> io::Result<()>) -> io::Result<()> {
    let (temp, file) = create_temporary(path)?;
    let result = finish(path, &temp, file, fill);
    if result.is_err() {
        // The temporary file is ours; failing to remove it must not hide the first error.
        let _ = fs::remove_file(&temp);
    }
    result
}

/// Fills, syncs and renames the temporary file over `path`.
fn finish(
    path: &Path,
    temp: &Path,
    file: File,
    fill: impl FnOnce(&mut BufWriter<File>) -> io::Result<()>,
) -> io::Result<()> {
    if let Ok(meta) = fs::metadata(path) {
        // Keep the permissions of the file being replaced; not fatal if the platform refuses.
        let _ = file.set_permissions(meta.permissions());
    }
    let mut out = BufWriter::new(file);
    fill(&mut out)?;
    out.flush()?;
    let file = out.into_inner().map_err(io::IntoInnerError::into_error)?;
    file.sync_all()?;
    drop(file);
    fs::rename(temp, path)
}

/// Creates a new, empty temporary file beside `path`: `.<name>.<pid>-<n>.tmp`.
fn create_temporary(path: &Path) -> io::Result<(PathBuf, File)> {
    let name =
        path.file_name().ok_or_else(|| io::Error::new(io::ErrorKind::InvalidInput, "the path does not name a file"))?;
    let dir = match path.parent() {
        Some(dir) if !dir.as_os_str().is_empty() => dir,
        _ => Path::new("."),
    };
    let mut last = None;
    for _ in 0..ATTEMPTS {
        let n = COUNTER.fetch_add(1, Ordering::Relaxed);
        let mut temp_name = std::ffi::OsString::from(".");
        temp_name.push(name);
        temp_name.push(format!(".{}-{n}.tmp", std::process::id()));
        let temp = dir.join(temp_name);
        match OpenOptions::new().write(true).create_new(true).open(&temp) {
            Ok(file) => return Ok((temp, file)),
            Err(e) if e.kind() == io::ErrorKind::AlreadyExists => last = Some(e),
            Err(e) => return Err(e),
        }
    }
    Err(last.unwrap_or_else(|| io::Error::other("no temporary file name was free")))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn entries(dir: &Path) -> Vec<String> {
        let mut names: Vec<String> =
            fs::read_dir(dir).unwrap().map(|e| e.unwrap().file_name().to_string_lossy().into_owned()).collect();
        names.sort();
        names
    }

    #[test]
    fn replaces_the_file_and_leaves_no_temporary() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("out.obj");
        fs::write(&path, b"old").unwrap();
        write_atomically(&path, |w| w.write_all(b"new")).unwrap();
        assert_eq!(fs::read(&path).unwrap(), b"new");
        assert_eq!(entries(dir.path()), vec!["out.obj"]);
    }

    #[test]
    fn failing_fill_keeps_the_old_file_and_removes_the_temporary() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("out.obj");
        fs::write(&path, b"old").unwrap();
        let err = write_atomically(&path, |w| {
            w.write_all(b"partial")?;
            Err(io::Error::other("disk on fire"))
        })
        .unwrap_err();
        assert_eq!(err.to_string(), "disk on fire");
        assert_eq!(fs::read(&path).unwrap(), b"old");
        assert_eq!(entries(dir.path()), vec!["out.obj"]);
    }

    #[test]
    fn missing_directory_is_not_found() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("nope").join("out.obj");
        let err = write_atomically(&path, |w| w.write_all(b"x")).unwrap_err();
        assert_eq!(err.kind(), io::ErrorKind::NotFound, "{err}");
        assert!(entries(dir.path()).is_empty());
    }

    #[test]
    fn path_without_file_name_is_an_error() {
        let err = write_atomically(Path::new(".."), |w| w.write_all(b"x")).unwrap_err();
        assert_eq!(err.kind(), io::ErrorKind::InvalidInput, "{err}");
    }
}
