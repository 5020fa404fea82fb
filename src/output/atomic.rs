//! Writing output files atomically, and the folder an output goes in;
//! the temporary files of writes under way, which a signal handler can
//! remove.
//!
//! A plotter program, a file watcher or a second moyo run may read an output
//! file while it is being written; they must see either the old file or the
//! new one, never half of it. So every file is written to a temporary file
//! (`.moyo-XXXX.tmp`) in the same directory (a rename is only atomic within
//! one file system) and then renamed over the target. The temporary file is
//! moyo's own business: errors name the target, or its folder, never it.
//!
//! Nothing is left behind:
//! - a command with several outputs writes every temporary file first and
//!   renames them last ([`write_all_atomic`]), so a failed write leaves all
//!   the old files;
//! - each temporary file is registered while it exists; a program that is
//!   stopped by a signal calls [`remove_temporaries`] from its handler (the
//!   library installs no handler: that is the program's business; the
//!   `moyo` command does);
//! - a temporary file left by a run that was killed outright (SIGKILL, a
//!   power cut) is removed by the first write into its folder once it is
//!   older than [`STALE_AFTER`]. The age guards a second moyo writing into
//!   the same folder at the same time, whose temporary file is seconds old.

use std::io::{self, Write as _};
use std::path::{Path, PathBuf};
use std::sync::{Mutex, MutexGuard, PoisonError};
use std::time::{Duration, SystemTime};

use crate::error::{Error, Result};

/// How old a `.moyo-*.tmp` file not written by this process must be before
/// a write into its folder removes it. A temporary file lives for the
/// seconds it takes to write the outputs of one command (they are in
/// memory before the first is written), so ten minutes leaves a
/// concurrent run alone.
pub const STALE_AFTER: Duration = Duration::from_secs(10 * 60);

/// This process's temporary files, and whether it is closing.
struct Registry {
    /// The temporary files that exist now.
    live: Vec<PathBuf>,
    /// Folders already swept for stale temporary files: once a run is
    /// enough (a folder of frames would be listed once per frame).
    swept: Vec<PathBuf>,
    /// Set by [`remove_temporaries`]: no temporary file is created after.
    closed: bool,
}

static REGISTRY: Mutex<Registry> = Mutex::new(Registry {
    live: Vec::new(),
    swept: Vec::new(),
    closed: false,
});

/// The registry; a panic while it was held leaves it usable (it is a list
/// of paths: no invariant to break).
fn registry() -> MutexGuard<'static, Registry> {
    REGISTRY.lock().unwrap_or_else(PoisonError::into_inner)
}

/// Removes the temporary files of the writes under way, and makes any
/// later write fail instead of creating one: for a program's signal
/// handler, just before it exits. A file that cannot be removed is left
/// (the next write into its folder removes it once it is stale).
pub fn remove_temporaries() {
    registry().close();
}

impl Registry {
    /// [`remove_temporaries`] on this registry.
    fn close(&mut self) {
        self.closed = true;
        for path in self.live.drain(..) {
            // Already renamed or gone: nothing to do.
            let _ = std::fs::remove_file(path);
        }
    }

    /// Creates the temporary file at `path` and registers it, unless the
    /// registry is closed.
    fn create(&mut self, path: &Path) -> io::Result<std::fs::File> {
        if self.closed {
            return Err(io::Error::new(io::ErrorKind::Interrupted, "interrupted"));
        }
        let mut options = std::fs::OpenOptions::new();
        options.write(true).create_new(true);
        // Temporary files are usually private (0600); an output file should
        // be as readable as any other file the user creates.
        #[cfg(unix)]
        std::os::unix::fs::OpenOptionsExt::mode(&mut options, 0o666);
        let file = options.open(path)?;
        self.live.push(path.to_path_buf());
        Ok(file)
    }
}

/// Removes `.moyo-*.tmp` files in `dir` older than `older_than` that this
/// process is not writing, once per folder and run. Errors are ignored: a
/// stale file that stays is harmless, and the write goes on.
fn remove_stale_temporaries(dir: &Path, older_than: Duration) {
    let mut registry = registry();
    let key = dir.canonicalize().unwrap_or_else(|_| dir.to_path_buf());
    if registry.swept.contains(&key) {
        return;
    }
    registry.swept.push(key);
    let Ok(entries) = std::fs::read_dir(dir) else {
        return;
    };
    let now = SystemTime::now();
    for entry in entries.flatten() {
        let name = entry.file_name();
        let Some(name) = name.to_str() else { continue };
        if !(name.starts_with(".moyo-") && name.ends_with(".tmp")) {
            continue;
        }
        let path = entry.path();
        // A regular file only (not a symlink), and old enough.
        let stale = entry.metadata().ok().is_some_and(|meta| {
            meta.file_type().is_file()
                && meta
                    .modified()
                    .ok()
                    .and_then(|at| now.duration_since(at).ok())
                    .is_some_and(|age| age >= older_than)
        });
        if stale && !registry.live.contains(&path) {
            let _ = std::fs::remove_file(&path);
        }
    }
}

/// The folder a file at `path` is written in (`.` for a bare name).
fn folder_of(path: &Path) -> &Path {
    match path.parent() {
        Some(dir) if !dir.as_os_str().is_empty() => dir,
        _ => Path::new("."),
    }
}

/// Checks that the folder an output file at `path` goes in is there, so
/// that a command can refuse a mistyped folder before it computes
/// anything. Folders are not created.
///
/// # Errors
/// [`Error::Io`] naming the folder: "no such folder", or "not a folder"
/// when a file has its name. A folder that cannot be looked into passes:
/// writing says what is wrong.
pub fn check_output_folder(path: &Path) -> Result<()> {
    let dir = folder_of(path);
    let refuse = |kind, message| Err(Error::io(dir, io::Error::new(kind, message)));
    match std::fs::metadata(dir) {
        Ok(meta) if !meta.is_dir() => refuse(io::ErrorKind::NotADirectory, "not a folder"),
        Err(e) if e.kind() == io::ErrorKind::NotFound => {
            refuse(io::ErrorKind::NotFound, "no such folder")
        }
        _ => Ok(()),
    }
}

/// `e` without the temporary file's name, which tempfile adds to its
/// errors (`… at path "/out/.moyo-JoZUqq.tmp"`): the user never asked for
/// that file.
fn without_temporary_name(e: io::Error) -> io::Error {
    let message = e.to_string();
    match message.split_once(" at path \"") {
        Some((cause, _)) => io::Error::new(e.kind(), cause),
        None => e,
    }
}

/// Writes `bytes` to `path`, replacing any existing file in one step.
///
/// On error, [`Error::Io`] names `path` (its folder when that is missing
/// or not a folder, as [`check_output_folder`] says), the previous file
/// (if any) is left untouched and no temporary file remains. Missing
/// parent directories are not created. The new file gets the permissions
/// of a newly created file (subject to the umask on Unix), not those of
/// the file it replaces.
pub fn write_atomic(path: &Path, bytes: &[u8]) -> Result<()> {
    write_all_atomic(&[(path, bytes)])
}

/// Writes several files, all of them or none: every file goes to its
/// temporary file first, and only when all are written are they renamed
/// over their targets, in order. Each is written as by [`write_atomic`].
///
/// # Errors
/// [`Error::Io`] naming the first target that could not be written (or
/// its folder; or the target, when it is a folder); then no target is
/// touched and no temporary file remains.
/// A rename can still fail after earlier ones succeeded (a folder removed
/// or made read-only in the instant between them): the targets before it
/// are then new, the one named and those after it old.
pub fn write_all_atomic(files: &[(&Path, &[u8])]) -> Result<()> {
    // Every target checked before any file is written.
    for (path, _) in files {
        check_target(path)?;
    }
    let mut staged = Staged::default();
    for (path, bytes) in files {
        staged.stage(path, bytes)?;
    }
    staged.commit()
}

/// [`check_output_folder`], and a target that is not a folder: a rename
/// over a folder fails, and is refused before any file is written rather
/// than after the renames before it.
fn check_target(path: &Path) -> Result<()> {
    check_output_folder(path)?;
    if path.is_dir() {
        let e = io::Error::new(io::ErrorKind::IsADirectory, "a folder, not a file");
        return Err(Error::io(path, e));
    }
    Ok(())
}

/// Files written one at a time to their temporary files, as they are
/// made, and renamed over their targets all at once by
/// [`Staged::commit`]: [`write_all_atomic`] for outputs too many or too
/// large to hold in memory together (the frames of a growth). Dropped
/// without a commit, it removes its temporary files and no target is
/// touched.
#[derive(Default)]
pub struct Staged {
    pending: Vec<(PathBuf, Pending)>,
}

impl Staged {
    /// Writes `bytes` to a temporary file beside `path`, to be renamed
    /// over it by [`Staged::commit`].
    ///
    /// # Errors
    /// As [`write_all_atomic`], for this file; the files staged before
    /// stay staged (drop the batch to remove them).
    pub fn stage(&mut self, path: &Path, bytes: &[u8]) -> Result<()> {
        check_target(path)?;
        let file = Pending::write(path, bytes)?;
        self.pending.push((path.to_path_buf(), file));
        Ok(())
    }

    /// Renames every staged file over its target, in the order staged.
    ///
    /// # Errors
    /// As [`write_all_atomic`]'s renames.
    pub fn commit(self) -> Result<()> {
        for (path, file) in self.pending {
            file.rename(&path)?;
        }
        Ok(())
    }
}

/// A temporary file written, synced and closed (a run may write hundreds
/// of frames at once: no file stays open), registered until it is renamed
/// or dropped (dropping deletes it).
struct Pending {
    // Declared first, so dropped first: the file is deleted, then
    // unregistered.
    file: tempfile::TempPath,
    _live: Live,
}

/// A registered temporary file's path, unregistered when dropped.
struct Live(PathBuf);

impl Drop for Live {
    fn drop(&mut self) {
        registry().live.retain(|p| *p != self.0);
    }
}

impl Pending {
    /// Writes `bytes` to a new temporary file beside `target`.
    fn write(target: &Path, bytes: &[u8]) -> Result<Pending> {
        let dir = folder_of(target);
        let io = |e| Error::io(target, without_temporary_name(e));
        remove_stale_temporaries(dir, STALE_AFTER);
        let mut builder = tempfile::Builder::new();
        builder.prefix(".moyo-").suffix(".tmp");
        let mut file = builder.make_in(dir, create_registered).map_err(io)?;
        // Registered from here on: `Live` unregisters it when dropped, and
        // `file` deletes it (dropped first).
        let live = Live(file.path().to_path_buf());
        file.write_all(bytes).map_err(io)?;
        file.flush().map_err(io)?;
        // Without a sync the rename can reach the disk before the data, and a
        // crash would leave an empty file under the target name.
        file.as_file().sync_all().map_err(io)?;
        Ok(Pending {
            file: file.into_temp_path(),
            _live: live,
        })
    }

    /// Renames the temporary file over `target`.
    fn rename(self, target: &Path) -> Result<()> {
        let Pending { file, _live } = self;
        // On failure `PersistError` hands back the temporary file, which is
        // deleted when dropped here (before `_live` unregisters it).
        file.persist(target)
            .map_err(|e| Error::io(target, without_temporary_name(e.error)))?;
        Ok(())
    }
}

/// Creates the temporary file at `path` and registers it, both under the
/// registry's lock, so that [`remove_temporaries`] sees every file that
/// exists and none is created after it ran.
fn create_registered(path: &Path) -> io::Result<std::fs::File> {
    registry().create(path)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn entries(dir: &Path) -> Vec<String> {
        let mut names: Vec<String> = std::fs::read_dir(dir)
            .unwrap()
            .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
            .collect();
        names.sort();
        names
    }

    #[test]
    fn staged_files_are_renamed_on_commit_only() {
        let dir = tempfile::tempdir().unwrap();
        let (a, b) = (dir.path().join("a.svg"), dir.path().join("b.svg"));
        let mut staged = Staged::default();
        staged.stage(&a, b"a").unwrap();
        staged.stage(&b, b"b").unwrap();
        assert_eq!(entries(dir.path()).len(), 2, "two temporary files");
        assert!(!a.exists() && !b.exists());
        staged.commit().unwrap();
        assert_eq!(entries(dir.path()), ["a.svg", "b.svg"]);
        // Dropped without a commit: its temporary file goes, no target.
        let mut dropped = Staged::default();
        dropped.stage(&dir.path().join("c.svg"), b"c").unwrap();
        drop(dropped);
        assert_eq!(entries(dir.path()), ["a.svg", "b.svg"]);
    }

    #[test]
    fn writes_the_bytes_and_nothing_else() {
        let dir = tempfile::tempdir().unwrap();
        let target = dir.path().join("out.svg");
        write_atomic(&target, b"<svg/>\n").unwrap();
        assert_eq!(std::fs::read(&target).unwrap(), b"<svg/>\n");
        assert_eq!(entries(dir.path()), ["out.svg"]);
    }

    #[cfg(unix)]
    #[test]
    fn new_file_is_not_private() {
        use std::os::unix::fs::PermissionsExt;
        let dir = tempfile::tempdir().unwrap();
        let target = dir.path().join("out.svg");
        write_atomic(&target, b"x").unwrap();
        // The same mode as a plainly created file, whatever the umask.
        let plain = dir.path().join("plain");
        std::fs::write(&plain, b"x").unwrap();
        let mode = |p: &Path| std::fs::metadata(p).unwrap().permissions().mode();
        assert_eq!(mode(&target), mode(&plain));
    }

    #[test]
    fn overwriting_replaces_the_whole_file() {
        let dir = tempfile::tempdir().unwrap();
        let target = dir.path().join("out.png");
        std::fs::write(&target, vec![7u8; 10_000]).unwrap();
        write_atomic(&target, b"short").unwrap();
        assert_eq!(std::fs::read(&target).unwrap(), b"short");
        assert_eq!(entries(dir.path()), ["out.png"]);
    }

    #[test]
    fn a_missing_folder_is_named_not_the_temporary_file() {
        let dir = tempfile::tempdir().unwrap();
        let missing = dir.path().join("missing");
        let target = missing.join("out.svg");
        let err = write_atomic(&target, b"x").unwrap_err();
        assert!(
            matches!(&err, Error::Io { path, .. } if *path == missing),
            "{err}"
        );
        assert_eq!(
            err.to_string(),
            format!("{}: no such folder", missing.display())
        );
        assert!(entries(dir.path()).is_empty());
        // A file where the folder should be; deeper down, the first
        // folder that is missing does not matter: the one asked for is
        // named.
        std::fs::write(&missing, b"").unwrap();
        let err = write_atomic(&target, b"x").unwrap_err();
        assert_eq!(
            err.to_string(),
            format!("{}: not a folder", missing.display())
        );
        let deeper = dir.path().join("a").join("b");
        let err = check_output_folder(&deeper.join("out.svg")).unwrap_err();
        assert_eq!(
            err.to_string(),
            format!("{}: no such folder", deeper.display())
        );
        // A bare name is written in the working folder, which is there.
        check_output_folder(Path::new("out.svg")).unwrap();
        assert_eq!(entries(dir.path()), ["missing"]);
    }

    #[test]
    fn errors_never_name_the_temporary_file() {
        let e = io::Error::new(
            io::ErrorKind::PermissionDenied,
            "Permission denied (os error 13) at path \"/x/.moyo-JoZUqq.tmp\"",
        );
        let e = without_temporary_name(e);
        assert_eq!(e.kind(), io::ErrorKind::PermissionDenied);
        assert_eq!(e.to_string(), "Permission denied (os error 13)");
        let plain = without_temporary_name(io::Error::other("disk full"));
        assert_eq!(plain.to_string(), "disk full");
    }

    #[test]
    fn a_target_that_is_a_folder_is_refused_and_left_alone() {
        // Renaming a file over a directory fails: it is refused first.
        let dir = tempfile::tempdir().unwrap();
        let target = dir.path().join("taken");
        std::fs::create_dir(&target).unwrap();
        std::fs::write(target.join("keep"), b"k").unwrap();
        let err = write_atomic(&target, b"x").unwrap_err();
        assert!(
            matches!(&err, Error::Io { path, .. } if *path == target),
            "{err}"
        );
        assert_eq!(
            err.to_string(),
            format!("{}: a folder, not a file", target.display())
        );
        assert_eq!(entries(dir.path()), ["taken"]);
        assert_eq!(entries(&target), ["keep"]);
    }

    /// A folder this process cannot create files in: one without write
    /// permission, or, for root (whom permissions do not stop), `/sys`.
    fn unwritable(dir: &Path) -> Option<PathBuf> {
        let locked = dir.join("locked");
        std::fs::create_dir(&locked).unwrap();
        #[cfg(unix)]
        {
            use std::os::unix::fs::PermissionsExt;
            let mode = std::fs::Permissions::from_mode(0o555);
            std::fs::set_permissions(&locked, mode).unwrap();
        }
        [locked, PathBuf::from("/sys")]
            .into_iter()
            .find(|d| d.is_dir() && std::fs::write(d.join(".moyo-probe"), b"").is_err())
    }

    #[test]
    fn several_files_are_written_all_or_none() {
        let dir = tempfile::tempdir().unwrap();
        let first = dir.path().join("a.svg");
        let second = dir.path().join("b.png");
        std::fs::write(&first, b"old a").unwrap();
        write_all_atomic(&[(&first, b"new a"), (&second, b"new b")]).unwrap();
        assert_eq!(std::fs::read(&first).unwrap(), b"new a");
        assert_eq!(std::fs::read(&second).unwrap(), b"new b");

        // The second cannot be written: the first keeps its old bytes.
        let Some(place) = unwritable(dir.path()) else {
            return;
        };
        let blocked = place.join("c.png");
        let err = write_all_atomic(&[(&first, b"newer a"), (&blocked, b"c")]).unwrap_err();
        assert!(
            matches!(&err, Error::Io { path, .. } if *path == blocked),
            "{err}"
        );
        assert_eq!(std::fs::read(&first).unwrap(), b"new a");
        assert_eq!(entries(dir.path()), ["a.svg", "b.png", "locked"]);
        let live = registry().live.clone();
        assert!(!live.iter().any(|p| p.starts_with(dir.path())), "{live:?}");

        // A target that is a folder, or in a missing folder, is refused
        // before anything is written.
        std::fs::create_dir(dir.path().join("taken")).unwrap();
        for bad in [dir.path().join("taken"), dir.path().join("none/d.svg")] {
            write_all_atomic(&[(&first, b"x"), (&bad, b"x")]).unwrap_err();
            assert_eq!(std::fs::read(&first).unwrap(), b"new a");
        }
        assert_eq!(entries(dir.path()), ["a.svg", "b.png", "locked", "taken"]);
    }

    #[test]
    fn stale_temporary_files_are_removed_fresh_and_live_ones_kept() {
        let dir = tempfile::tempdir().unwrap();
        let long_ago = SystemTime::now() - STALE_AFTER - Duration::from_secs(60);
        let make = |name: &str, old: bool| {
            let path = dir.path().join(name);
            let file = std::fs::File::create(&path).unwrap();
            if old {
                file.set_modified(long_ago).unwrap();
            }
            path
        };
        make(".moyo-stale.tmp", true);
        make(".moyo-fresh.tmp", false);
        make("mine.tmp", true);
        make(".moyo-notes.txt", true);
        // Another write of this process, slow enough to look stale.
        let live = make(".moyo-live.tmp", true);
        registry().live.push(live.clone());
        remove_stale_temporaries(dir.path(), STALE_AFTER);
        registry().live.retain(|p| *p != live);
        assert_eq!(
            entries(dir.path()),
            [
                ".moyo-fresh.tmp",
                ".moyo-live.tmp",
                ".moyo-notes.txt",
                "mine.tmp"
            ]
        );
        // Once per folder and run: a second stale file waits for the next run.
        make(".moyo-stale.tmp", true);
        remove_stale_temporaries(dir.path(), STALE_AFTER);
        assert!(dir.path().join(".moyo-stale.tmp").exists());
    }

    #[test]
    fn closing_removes_live_temporary_files_and_refuses_new_ones() {
        let dir = tempfile::tempdir().unwrap();
        // A registry of its own: closing the process's would stop every
        // other test's writes.
        let mut registry = Registry {
            live: Vec::new(),
            swept: Vec::new(),
            closed: false,
        };
        let path = dir.path().join(".moyo-a.tmp");
        registry.create(&path).unwrap();
        assert!(path.exists());
        registry.close();
        assert!(entries(dir.path()).is_empty());
        let err = registry
            .create(&dir.path().join(".moyo-b.tmp"))
            .unwrap_err();
        assert_eq!(err.kind(), io::ErrorKind::Interrupted);
        assert!(entries(dir.path()).is_empty());
    }
}
