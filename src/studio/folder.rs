//! The one folder the studio may touch: the files a description names,
//! what the page saves and what it opens are all paths inside the folder
//! the studio was started in. A path that leaves it — absolute, with
//! `..`, or through a link that points outside — is refused. And the
//! studio reads and writes regular files only: a FIFO, a device or a
//! socket in the folder would block a read, or never end it.

use std::path::{Component, Path, PathBuf};

use crate::error::{Error, Result};
use crate::input::{read_regular_file, utf8};

/// [`crate::input::read_regular_file`] as UTF-8 text. Blocking: call it
/// off the server's threads.
///
/// # Errors
/// As [`crate::input::read_regular_file`], and
/// [`std::io::ErrorKind::InvalidData`]
/// for text that is not UTF-8.
pub(crate) fn read_text(path: &Path) -> std::io::Result<String> {
    utf8(read_regular_file(path)?)
}

/// The folder, made absolute and with its links resolved.
#[derive(Debug, Clone)]
pub(crate) struct Folder {
    root: PathBuf,
}

impl Folder {
    /// The folder at `root`.
    ///
    /// # Errors
    /// [`Error::Io`] when it does not exist.
    pub(crate) fn new(root: &Path) -> Result<Folder> {
        let root = root.canonicalize().map_err(|e| Error::io(root, e))?;
        Ok(Folder { root })
    }

    /// The folder's own path.
    pub(crate) fn root(&self) -> &Path {
        &self.root
    }

    /// Where `name` (relative, `/`-separated) is inside the folder.
    ///
    /// # Errors
    /// [`Error::Invalid`] at `field` for a name that is empty, absolute,
    /// steps out with `..`, or leads out through a link.
    pub(crate) fn resolve(&self, name: &str, field: &str) -> Result<PathBuf> {
        let refuse = |why: &str| {
            Err(Error::invalid(
                field,
                format!("'{name}' {why}: the studio reads and writes only inside its folder"),
            ))
        };
        let relative = Path::new(name);
        if name.is_empty() {
            return refuse("is empty");
        }
        if relative
            .components()
            .any(|c| !matches!(c, Component::Normal(_) | Component::CurDir))
        {
            return refuse("is absolute or steps up with '..'");
        }
        let path = self.root.join(relative);
        // A link inside the folder may point out of it: what exists of
        // the path is resolved and must still be inside.
        let mut existing = path.as_path();
        while !existing.exists() {
            match existing.parent() {
                Some(parent) => existing = parent,
                None => break,
            }
        }
        match existing.canonicalize() {
            Ok(real) if real.starts_with(&self.root) => Ok(path),
            Ok(_) => refuse("leads out of the folder through a link"),
            Err(e) => Err(Error::io(existing, e)),
        }
    }
}

/// Refuses to write over `path` when something other than a regular file
/// is there (a folder, a FIFO, a device): a write replaces a file, nothing
/// else.
///
/// # Errors
/// [`Error::Invalid`] at `field` for something that is not a regular file.
pub(crate) fn check_writable(path: &Path, field: &str) -> Result<()> {
    match std::fs::metadata(path) {
        Ok(metadata) if !metadata.file_type().is_file() => Err(Error::invalid(
            field,
            format!(
                "{}: not a regular file: the studio writes only files",
                path.display()
            ),
        )),
        _ => Ok(()),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_inside_resolve_and_names_that_leave_are_refused() {
        let dir = tempfile::tempdir().unwrap();
        std::fs::create_dir(dir.path().join("sub")).unwrap();
        let folder = Folder::new(dir.path()).unwrap();
        let inside = folder.resolve("sub/new.toml", "path").unwrap();
        assert!(inside.starts_with(folder.root()));
        assert!(folder.resolve("./a.svg", "path").is_ok());
        for bad in ["", "../x.toml", "sub/../../x", "/etc/passwd"] {
            let e = folder.resolve(bad, "path").unwrap_err().to_string();
            assert!(e.starts_with("path: "), "{bad}: {e}");
        }
        #[cfg(unix)]
        {
            std::os::unix::fs::symlink("/tmp", dir.path().join("out")).unwrap();
            let e = folder.resolve("out/x.toml", "path").unwrap_err();
            assert!(e.to_string().contains("through a link"), "{e}");
        }
    }

    #[test]
    fn only_regular_files_are_read_or_written_over() {
        let dir = tempfile::tempdir().unwrap();
        let file = dir.path().join("a.toml");
        std::fs::write(&file, "version = 1\n").unwrap();
        assert_eq!(read_text(&file).unwrap(), "version = 1\n");
        assert!(check_writable(&file, "path").is_ok());
        assert!(check_writable(&dir.path().join("new.toml"), "path").is_ok());
        let e = read_text(dir.path()).unwrap_err();
        assert_eq!(e.kind(), std::io::ErrorKind::InvalidInput);
        assert!(check_writable(dir.path(), "path").is_err());
        #[cfg(unix)]
        {
            // A FIFO with no writer: refused at once, never waited on.
            let fifo = dir.path().join("pipe.toml");
            let made = std::process::Command::new("mkfifo")
                .arg(&fifo)
                .status()
                .unwrap();
            assert!(made.success());
            let e = read_text(&fifo).unwrap_err();
            assert!(e.to_string().contains("not a regular file"), "{e}");
            assert!(check_writable(&fifo, "path").is_err());
        }
    }
}
