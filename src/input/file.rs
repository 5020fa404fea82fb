//! Reading an input file whole, up to a size: the one way moyo reads the
//! files it is given (descriptions, SVGs, motifs, strokes, images,
//! meshes), so that a huge file, or a device that never ends
//! (`/dev/zero`), is refused with its size instead of filling memory.

use std::io::Read;
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
    read_open(std::fs::File::open(path)?, limit)
}

/// Reads `file`, already open, whole up to `limit` bytes (as
/// [`read_file`], for a caller that opens it its own way).
pub(crate) fn read_open(file: std::fs::File, limit: u64) -> std::io::Result<Vec<u8>> {
    let too_large = || {
        std::io::Error::new(
            std::io::ErrorKind::FileTooLarge,
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

    #[test]
    fn text_must_be_utf8() {
        let path = std::env::temp_dir().join(format!("moyo-read-{}.bin", std::process::id()));
        std::fs::write(&path, [0xff, 0xfe]).unwrap();
        let e = read_text(&path).unwrap_err();
        assert!(e.to_string().contains("not UTF-8"), "{e}");
        std::fs::remove_file(&path).unwrap();
    }
}
