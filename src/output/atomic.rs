//! Writing output files atomically, and the folder an output goes in.
//!
//! A plotter program, a file watcher or a second moyo run may read an output
//! file while it is being written; they must see either the old file or the
//! new one, never half of it. So every file is written to a temporary file
//! in the same directory (a rename is only atomic within one file system)
//! and then renamed over the target. The temporary file is moyo's own
//! business: errors name the target, or its folder, never it.

use std::io::{self, Write as _};
use std::path::Path;

use crate::error::{Error, Result};

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
    check_output_folder(path)?;
    let dir = folder_of(path);
    let io = |e| Error::io(path, without_temporary_name(e));
    let mut builder = tempfile::Builder::new();
    builder.prefix(".moyo-").suffix(".tmp");
    // Temporary files are private (0600) by default; an output file should
    // be as readable as any other file the user creates.
    #[cfg(unix)]
    builder.permissions(std::os::unix::fs::PermissionsExt::from_mode(0o666));
    // Dropping the temporary file on any early return deletes it.
    let mut file = builder.tempfile_in(dir).map_err(io)?;
    file.write_all(bytes).map_err(io)?;
    file.flush().map_err(io)?;
    // Without a sync the rename can reach the disk before the data, and a
    // crash would leave an empty file under the target name.
    file.as_file().sync_all().map_err(io)?;
    // On failure `PersistError` hands back the temporary file, which is
    // deleted when dropped here.
    file.persist(path).map_err(|e| io(e.error))?;
    Ok(())
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
    fn failed_rename_leaves_no_temporary_file() {
        // Renaming a file over a non-empty directory fails on every platform.
        let dir = tempfile::tempdir().unwrap();
        let target = dir.path().join("taken");
        std::fs::create_dir(&target).unwrap();
        std::fs::write(target.join("keep"), b"k").unwrap();
        let err = write_atomic(&target, b"x").unwrap_err();
        assert!(
            matches!(&err, Error::Io { path, .. } if *path == target),
            "{err}"
        );
        assert_eq!(entries(dir.path()), ["taken"]);
        assert_eq!(entries(&target), ["keep"]);
    }
}
