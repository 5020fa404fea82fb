//! Writing output files atomically.
//!
//! A plotter program, a file watcher or a second moyo run may read an output
//! file while it is being written; they must see either the old file or the
//! new one, never half of it. So every file is written to a temporary file
//! in the same directory (a rename is only atomic within one file system)
//! and then renamed over the target.

use std::io::Write as _;
use std::path::Path;

use crate::error::{Error, Result};

/// Writes `bytes` to `path`, replacing any existing file in one step.
///
/// On error, [`Error::Io`] names `path`, the previous file (if any) is left
/// untouched and no temporary file remains. Missing parent directories are
/// not created. The new file gets the permissions of a newly created file
/// (subject to the umask on Unix), not those of the file it replaces.
pub fn write_atomic(path: &Path, bytes: &[u8]) -> Result<()> {
    let dir = match path.parent() {
        Some(dir) if !dir.as_os_str().is_empty() => dir,
        _ => Path::new("."),
    };
    let io = |e| Error::io(path, e);
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
    fn missing_directory_is_an_io_error_naming_the_target() {
        let dir = tempfile::tempdir().unwrap();
        let target = dir.path().join("missing").join("out.svg");
        let err = write_atomic(&target, b"x").unwrap_err();
        assert!(
            matches!(&err, Error::Io { path, .. } if *path == target),
            "{err}"
        );
        assert!(err.to_string().contains("out.svg"));
        assert!(entries(dir.path()).is_empty());
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
