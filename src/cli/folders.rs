//! Folders a command makes for its outputs (`--frames DIR`, the images
//! `moyo new` puts beside a description), taken away again when the
//! command writes nothing: a failed run leaves the disk as it found it.

use std::path::{Path, PathBuf};

use super::CliError;

/// The folders this run made, outermost first.
#[derive(Default)]
pub(crate) struct MadeFolders(Vec<PathBuf>);

impl MadeFolders {
    /// Makes `dir` and the folders above it that are missing, noting
    /// each one made.
    pub(crate) fn make(&mut self, dir: &Path) -> Result<(), CliError> {
        let missing: Vec<&Path> = dir
            .ancestors()
            .filter(|d| !d.as_os_str().is_empty())
            .take_while(|d| std::fs::symlink_metadata(d).is_err())
            .collect();
        std::fs::create_dir_all(dir)
            .map_err(|e| CliError::Message(format!("{}: {e}", dir.display())))?;
        self.0
            .extend(missing.into_iter().rev().map(Path::to_path_buf));
        Ok(())
    }

    /// Removes the folders made, innermost first, those still empty only
    /// (a file another program put there meanwhile stays, and so does
    /// its folder). For a run that failed before it wrote anything.
    pub(crate) fn remove(self) {
        for dir in self.0.iter().rev() {
            // Not empty, or gone: nothing to undo.
            let _ = std::fs::remove_dir(dir);
        }
    }
}
