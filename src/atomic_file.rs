//! Atomic file writing: a file is either fully replaced or left untouched.
//!
//! The content goes to a new temporary file in the target's directory (so the final rename
//! stays on one file system), which is flushed and synced, then renamed over the target. On
//! any error (or a panic while filling) the temporary file is removed and the target is not
//! touched.
//!
//! Every temporary file in progress is listed in one process-wide registry, so that a signal
//! handler can remove them as the process exits ([`exit_removing_temporaries`]; the command line
//! does so on SIGINT and SIGTERM). Creating a temporary file and renaming it over its target
//! each happen under the registry's lock, so a handler that takes the lock sees either the
//! temporary file (and removes it: the target keeps its old bytes) or the finished target.
//! SIGKILL cannot be caught: it leaves the temporary file, never a partly written target.
//!
//! A symbolic link at the target is written through: its final target is replaced, and the
//! link stays a link (as a shell's `>` and most editors do).

use std::fs::{self, File, OpenOptions};
use std::io::{self, BufWriter, Write};
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::{Mutex, MutexGuard, PoisonError};

/// Tells temporary files of one process apart.
static COUNTER: AtomicU64 = AtomicU64::new(0);

/// The bytes gathered before each write to the file (1 MiB): writers that emit many short
/// pieces (the faithful OBJ writer's lines between copied runs) then make few system calls;
/// a piece at least this long is written straight through.
const WRITE_BUFFER: usize = 1 << 20;

/// How many temporary names to try when one is taken.
const ATTEMPTS: usize = 16;

/// The most symbolic links followed from the target to the file it names (Linux's own limit).
const MAX_LINKS: usize = 40;

/// The temporary files being written now, by any thread of the process.
static TEMPORARIES: Mutex<Vec<PathBuf>> = Mutex::new(Vec::new());

/// The registry; a panic in another thread while it held the lock does not make it unusable
/// (every change to it is a single push or retain).
fn temporaries() -> MutexGuard<'static, Vec<PathBuf>> {
    TEMPORARIES.lock().unwrap_or_else(PoisonError::into_inner)
}

/// Removes every temporary file still being written and ends the process with `code`: each
/// write in progress leaves its target untouched. For a signal handler. The registry's lock is
/// held until the process ends, so no write can start or finish in between.
pub fn exit_removing_temporaries(code: i32) -> ! {
    let registry = temporaries();
    for temp in registry.iter() {
        // Nothing is left to report to: a file that cannot be removed stays.
        let _ = fs::remove_file(temp);
    }
    std::process::exit(code)
}

/// Writes `path` atomically with what `fill` writes: into a new temporary file beside the
/// file `path` names (`.<name>.<pid>-<n>.tmp`), flushed and synced, then renamed over it,
/// keeping the permissions of a file being replaced. A symbolic link at `path` is followed
/// (up to 40 links): the file it leads to is replaced, the link is kept.
///
/// # Errors
///
/// Any I/O error, from `fill` or the file system (also a chain of more than 40 links). The
/// temporary file is then removed and the target is untouched. The error does not name
/// `path`; callers add it.
pub fn write_atomically(path: &Path, fill: impl FnOnce(&mut BufWriter<File>) -> io::Result<()>) -> io::Result<()> {
    let target = follow_links(path)?;
    let (temp, file) = Temporary::create(&target)?;
    if let Ok(meta) = fs::metadata(&target) {
        // Keep the permissions of the file being replaced; not fatal if the platform refuses.
        let _ = file.set_permissions(meta.permissions());
    }
    let mut out = BufWriter::with_capacity(WRITE_BUFFER, file);
    fill(&mut out)?;
    out.flush()?;
    let file = out.into_inner().map_err(io::IntoInnerError::into_error)?;
    file.sync_all()?;
    drop(file);
    temp.rename_over(&target)
}

/// The file that `path` names once every symbolic link at its final component is followed
/// (the link's target need not exist yet); `path` itself when it is not a link.
fn follow_links(path: &Path) -> io::Result<PathBuf> {
    let mut current = path.to_path_buf();
    for _ in 0..MAX_LINKS {
        match fs::symlink_metadata(&current) {
            Ok(meta) if meta.file_type().is_symlink() => {
                let link = fs::read_link(&current)?;
                current = match current.parent() {
                    Some(dir) if link.is_relative() => dir.join(link),
                    _ => link,
                };
            }
            _ => return Ok(current),
        }
    }
    Err(io::Error::new(io::ErrorKind::InvalidInput, format!("more than {MAX_LINKS} symbolic links to follow")))
}

/// The bytes of the target's name kept in its temporary file's name: file systems allow 255,
/// and the rest of the temporary name takes at most 38.
const TEMPORARY_NAME_BYTES: usize = 200;

/// `name` cut on a character boundary to at most [`TEMPORARY_NAME_BYTES`] bytes.
fn cut(name: &str) -> &str {
    let mut end = name.len().min(TEMPORARY_NAME_BYTES);
    while !name.is_char_boundary(end) {
        end -= 1;
    }
    &name[..end]
}

/// A registered temporary file: removed (and unregistered) when dropped unless renamed.
struct Temporary {
    path: PathBuf,
}

impl Temporary {
    /// Creates and registers a new, empty temporary file beside `path`:
    /// `.<name>.<pid>-<n>.tmp`, the name cut to [`TEMPORARY_NAME_BYTES`] so that a target
    /// whose own name is as long as a file system allows still has a temporary sibling.
    fn create(path: &Path) -> io::Result<(Temporary, File)> {
        let name = path
            .file_name()
            .ok_or_else(|| io::Error::new(io::ErrorKind::InvalidInput, "the path does not name a file"))?;
        let dir = match path.parent() {
            Some(dir) if !dir.as_os_str().is_empty() => dir,
            _ => Path::new("."),
        };
        let mut last = None;
        for _ in 0..ATTEMPTS {
            let n = COUNTER.fetch_add(1, Ordering::Relaxed);
            let temp_name = format!(".{}.{}-{n}.tmp", cut(&name.to_string_lossy()), std::process::id());
            let temp = dir.join(temp_name);
            // Created and listed under the lock: a signal handler never misses it.
            let mut registry = temporaries();
            match OpenOptions::new().write(true).create_new(true).open(&temp) {
                Ok(file) => {
                    registry.push(temp.clone());
                    return Ok((Temporary { path: temp }, file));
                }
                Err(e) if e.kind() == io::ErrorKind::AlreadyExists => last = Some(e),
                Err(e) => return Err(e),
            }
        }
        Err(last.unwrap_or_else(|| io::Error::other("no temporary file name was free")))
    }

    /// Renames the file over `target` and unregisters it, under the registry's lock. On
    /// error the temporary file is removed (by the drop).
    fn rename_over(self, target: &Path) -> io::Result<()> {
        let mut registry = temporaries();
        let renamed = fs::rename(&self.path, target);
        if renamed.is_ok() {
            // Unregistered: the drop leaves the renamed file alone.
            registry.retain(|p| *p != self.path);
        }
        drop(registry);
        renamed
    }
}

impl Drop for Temporary {
    /// Removes the file if it is still registered (not renamed over its target).
    fn drop(&mut self) {
        let mut registry = temporaries();
        if let Some(at) = registry.iter().position(|p| *p == self.path) {
            // The temporary file is ours; failing to remove it must not hide the first error.
            let _ = fs::remove_file(&self.path);
            registry.swap_remove(at);
        }
    }
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

    /// A name of 255 bytes, the most file systems allow: the temporary name once added 37
    /// bytes to it ("File name too long").
    #[test]
    fn a_name_as_long_as_the_file_system_allows_is_written() {
        let dir = tempfile::tempdir().unwrap();
        for name in [format!("{}.obj", "a".repeat(251)), format!("{}.obj", "é".repeat(125))] {
            let path = dir.path().join(&name);
            write_atomically(&path, |w| w.write_all(b"new")).unwrap();
            assert_eq!(fs::read(&path).unwrap(), b"new");
            assert_eq!(entries(dir.path()), vec![name.clone()]);
            fs::remove_file(&path).unwrap();
        }
        assert_eq!(cut(&"é".repeat(125)).len(), 200);
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
    fn the_temporary_is_registered_while_filled_and_not_after() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("out.obj");
        let mut seen = Vec::new();
        write_atomically(&path, |w| {
            seen = temporaries().iter().filter(|p| p.starts_with(dir.path())).cloned().collect();
            w.write_all(b"new")
        })
        .unwrap();
        assert_eq!(seen.len(), 1, "{seen:?}");
        assert!(seen[0].file_name().unwrap().to_string_lossy().starts_with(".out.obj."), "{seen:?}");
        assert!(!temporaries().contains(&seen[0]));
        assert_eq!(entries(dir.path()), vec!["out.obj"]);
    }

    #[test]
    fn a_panic_while_filling_removes_the_temporary() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("out.obj");
        fs::write(&path, b"old").unwrap();
        let result = std::panic::catch_unwind(|| {
            let _ = write_atomically(&path, |w| {
                w.write_all(b"partial")?;
                panic!("fill panicked")
            });
        });
        assert!(result.is_err());
        assert_eq!(fs::read(&path).unwrap(), b"old");
        assert_eq!(entries(dir.path()), vec!["out.obj"]);
        assert!(!temporaries().iter().any(|p| p.starts_with(dir.path())));
    }

    #[cfg(unix)]
    #[test]
    fn a_symbolic_link_is_written_through() {
        let dir = tempfile::tempdir().unwrap();
        fs::create_dir(dir.path().join("assets")).unwrap();
        let target = dir.path().join("assets").join("model.obj");
        fs::write(&target, b"old").unwrap();
        let link = dir.path().join("out.obj");
        std::os::unix::fs::symlink("assets/model.obj", &link).unwrap();
        write_atomically(&link, |w| w.write_all(b"new")).unwrap();
        assert!(fs::symlink_metadata(&link).unwrap().file_type().is_symlink());
        assert_eq!(fs::read_link(&link).unwrap(), Path::new("assets/model.obj"));
        assert_eq!(fs::read(&target).unwrap(), b"new");
        assert_eq!(entries(&dir.path().join("assets")), vec!["model.obj"]);
        assert_eq!(entries(dir.path()), vec!["assets", "out.obj"]);
    }

    #[cfg(unix)]
    #[test]
    fn a_dangling_link_creates_its_target() {
        let dir = tempfile::tempdir().unwrap();
        let link = dir.path().join("out.obj");
        std::os::unix::fs::symlink(dir.path().join("new.obj"), &link).unwrap();
        write_atomically(&link, |w| w.write_all(b"new")).unwrap();
        assert_eq!(fs::read(dir.path().join("new.obj")).unwrap(), b"new");
        assert!(fs::symlink_metadata(&link).unwrap().file_type().is_symlink());
    }

    #[cfg(unix)]
    #[test]
    fn a_loop_of_links_is_an_error() {
        let dir = tempfile::tempdir().unwrap();
        let (a, b) = (dir.path().join("a.obj"), dir.path().join("b.obj"));
        std::os::unix::fs::symlink(&b, &a).unwrap();
        std::os::unix::fs::symlink(&a, &b).unwrap();
        let err = write_atomically(&a, |w| w.write_all(b"x")).unwrap_err();
        assert_eq!(err.to_string(), "more than 40 symbolic links to follow");
        assert_eq!(entries(dir.path()), vec!["a.obj", "b.obj"]);
    }

    #[test]
    fn path_without_file_name_is_an_error() {
        let err = write_atomically(Path::new(".."), |w| w.write_all(b"x")).unwrap_err();
        assert_eq!(err.kind(), io::ErrorKind::InvalidInput, "{err}");
    }
}
