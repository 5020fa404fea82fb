//! Reading an input file whole, up to a size: the one way moyo reads the
//! files it is given (descriptions, SVGs, motifs, strokes, images,
//! meshes), so that a huge file, or a device that never ends
//! (`/dev/zero`), is refused with its size instead of filling memory.
//!
//! A file named on the command line may be anything the user points at (a
//! pipe: `moyo plot /dev/stdin`). A file a *description* names, and every
//! file the studio opens, must be a regular file ([`read_regular_file`]):
//! a FIFO would block the open until some writer came, and a device might
//! never end, so a description someone else wrote could hang moyo.

use std::fs::{File, OpenOptions};
use std::io::{Error as IoError, ErrorKind, Read};
use std::path::Path;

/// The largest file moyo reads, in bytes (256 MiB): more than any plot
/// needs. Within it, the element and segment limits of each format bound
/// the memory a file can take (see `RELIABILITY.md`).
pub const MAX_FILE_BYTES: u64 = 256 * 1024 * 1024;

/// Reads the file at `path` whole.
///
/// # Errors
/// The I/O error, or [`std::io::ErrorKind::FileTooLarge`] with a message
/// giving the limit when the file holds more than [`MAX_FILE_BYTES`].
pub fn read_file(path: &Path) -> std::io::Result<Vec<u8>> {
    read_at_most(path, MAX_FILE_BYTES)
}

fn read_at_most(path: &Path, limit: u64) -> std::io::Result<Vec<u8>> {
    read_open(File::open(path)?, limit)
}

/// Reads `file`, already open, whole up to `limit` bytes (as
/// [`read_file`], for a caller that opens it its own way).
fn read_open(file: File, limit: u64) -> std::io::Result<Vec<u8>> {
    let too_large = || {
        IoError::new(
            ErrorKind::FileTooLarge,
            format!(
                "larger than {} MiB, the largest file moyo reads",
                limit / (1024 * 1024)
            ),
        )
    };
    // The length a file claims decides at once; a device or pipe that
    // claims none is read up to one byte past the limit.
    if file.metadata()?.len() > limit {
        return Err(too_large());
    }
    let mut bytes = Vec::new();
    file.take(limit + 1).read_to_end(&mut bytes)?;
    if bytes.len() as u64 > limit {
        return Err(too_large());
    }
    Ok(bytes)
}

/// Reads the regular file at `path` whole, up to [`MAX_FILE_BYTES`],
/// without ever waiting on it (see the module documentation).
///
/// # Errors
/// The I/O error, [`ErrorKind::InvalidInput`] for anything but a regular
/// file (found so before it is opened when it can be, and checked again on
/// the open file), or what [`read_file`] refuses.
pub fn read_regular_file(path: &Path) -> std::io::Result<Vec<u8>> {
    // Not opened at all when it is plainly no file (a device's open may
    // act); the open file is checked again, for what changed between.
    regular(&std::fs::metadata(path)?)?;
    let file = open_without_waiting(path)?;
    regular(&file.metadata()?)?;
    read_open(file, MAX_FILE_BYTES)
}

/// Opens `path` for reading without waiting: opening a FIFO blocks until
/// a writer comes, unless asked not to (`O_NONBLOCK`, which changes
/// nothing for a regular file).
#[cfg(unix)]
fn open_without_waiting(path: &Path) -> std::io::Result<File> {
    use std::os::unix::fs::OpenOptionsExt;
    OpenOptions::new()
        .read(true)
        .custom_flags(libc::O_NONBLOCK)
        .open(path)
}

/// Opens `path` for reading (no FIFO is opened by a path here).
#[cfg(not(unix))]
fn open_without_waiting(path: &Path) -> std::io::Result<File> {
    OpenOptions::new().read(true).open(path)
}

fn regular(metadata: &std::fs::Metadata) -> std::io::Result<()> {
    if metadata.file_type().is_file() {
        Ok(())
    } else {
        Err(IoError::new(
            ErrorKind::InvalidInput,
            "not a regular file (a pipe, a device or a folder): moyo reads only files here",
        ))
    }
}

/// [`read_file`] as UTF-8 text.
///
/// # Errors
/// As [`read_file`], and [`std::io::ErrorKind::InvalidData`] for text that
/// is not UTF-8.
pub fn read_text(path: &Path) -> std::io::Result<String> {
    utf8(read_file(path)?)
}

/// `bytes` as UTF-8 text, or [`std::io::ErrorKind::InvalidData`] worded
/// as [`read_text`] words it.
pub(crate) fn utf8(bytes: Vec<u8>) -> std::io::Result<String> {
    String::from_utf8(bytes).map_err(|e| {
        std::io::Error::new(
            std::io::ErrorKind::InvalidData,
            format!("not UTF-8 text: {}", e.utf8_error()),
        )
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_file_is_read_up_to_the_limit_and_refused_past_it() {
        let dir = std::env::temp_dir().join(format!("moyo-read-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join("ten.txt");
        std::fs::write(&path, b"0123456789").unwrap();
        assert_eq!(read_at_most(&path, 10).unwrap(), b"0123456789");
        let e = read_at_most(&path, 9).unwrap_err();
        assert_eq!(e.kind(), std::io::ErrorKind::FileTooLarge);
        assert!(e.to_string().contains("largest file moyo reads"), "{e}");
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[cfg(unix)]
    #[test]
    fn a_device_that_never_ends_is_refused() {
        let e = read_at_most(Path::new("/dev/zero"), 1 << 20).unwrap_err();
        assert_eq!(e.kind(), std::io::ErrorKind::FileTooLarge);
    }

    #[cfg(unix)]
    #[test]
    fn a_fifo_is_refused_without_waiting_for_a_writer() {
        let dir = std::env::temp_dir().join(format!("moyo-fifo-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let fifo = dir.join("motif.svg");
        let made = std::process::Command::new("mkfifo")
            .arg(&fifo)
            .status()
            .unwrap();
        assert!(made.success());
        let e = read_regular_file(&fifo).unwrap_err();
        assert_eq!(e.kind(), ErrorKind::InvalidInput);
        assert!(e.to_string().starts_with("not a regular file"), "{e}");
        // The same when what was checked first is not what is opened.
        let opened = open_without_waiting(&fifo).unwrap();
        assert!(regular(&opened.metadata().unwrap()).is_err());
        for path in [Path::new("/dev/zero"), dir.as_path()] {
            let e = read_regular_file(path).unwrap_err();
            assert_eq!(e.kind(), ErrorKind::InvalidInput, "{}", path.display());
        }
        let file = dir.join("ok.txt");
        std::fs::write(&file, "ok").unwrap();
        assert_eq!(read_regular_file(&file).unwrap(), b"ok");
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn text_must_be_utf8() {
        let path = std::env::temp_dir().join(format!("moyo-read-{}.bin", std::process::id()));
        std::fs::write(&path, [0xff, 0xfe]).unwrap();
        let e = read_text(&path).unwrap_err();
        assert!(e.to_string().contains("not UTF-8"), "{e}");
        std::fs::remove_file(&path).unwrap();
    }
}
