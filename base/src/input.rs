//! Reading input files through a size cap.
//!
//! Every file the workspace reads (curves in `immerse`, tilings in
//! `immerse-mesh`, the command line's timelines) goes through
//! [`read_capped`]: a regular file longer than the cap is
//! refused from its length, without reading it, and anything else (a
//! device such as `/dev/zero`, a FIFO, a pipe, a `/proc` file, a file that
//! grows while it is read) is read through the cap, so reading stops one
//! byte past it.

use std::io::Read;
use std::path::Path;

/// Why [`read_capped`] returned no data.
///
/// Exhaustive on purpose: each reader (curves, tilings, timelines) words
/// every case in its own terms, so a new case must reach all of them.
#[derive(Debug, thiserror::Error)]
pub enum ReadError {
    /// The path could not be opened or read; the operating system's reason.
    #[error("{0}")]
    Io(#[source] std::io::Error),
    /// The path names a folder.
    #[error("a folder, not a file")]
    IsDirectory,
    /// The data is longer than the cap.
    #[error("too large ({}; the limit is {limit} bytes)", size_text(*.size, *.limit))]
    TooLarge {
        /// The length of a regular file, or `None` for data read through
        /// the cap (a device, FIFO or pipe), known only to be longer.
        size: Option<u64>,
        /// The cap, in bytes.
        limit: u64,
    },
}

impl ReadError {
    /// What was too large, as in "too large (WHAT; the limit is …)":
    /// `N bytes`, or `more than N bytes` for data read through the cap.
    pub fn size_text(&self) -> Option<String> {
        match *self {
            ReadError::TooLarge { size, limit } => Some(size_text(size, limit)),
            _ => None,
        }
    }
}

fn size_text(size: Option<u64>, limit: u64) -> String {
    match size {
        Some(n) => format!("{n} bytes"),
        None => format!("more than {limit} bytes"),
    }
}

/// Reads all of `path`, at most `limit` bytes.
///
/// A regular file longer than `limit` is refused from its length without
/// being read. Anything else is read through the cap: `/dev/zero` stops
/// after `limit + 1` bytes with [`ReadError::TooLarge`]. A FIFO is opened
/// as a file is, so the call waits for a writer and reads until the writer
/// closes it.
///
/// # Errors
///
/// [`ReadError::Io`], [`ReadError::IsDirectory`] or
/// [`ReadError::TooLarge`].
///
/// # Examples
///
/// ```
/// # fn main() -> Result<(), Box<dyn std::error::Error>> {
/// use immerse_base::input::{ReadError, read_capped};
/// let dir = std::env::temp_dir().join(format!("immerse-doc-{}", std::process::id()));
/// std::fs::create_dir_all(&dir)?;
/// let file = dir.join("four.txt");
/// std::fs::write(&file, b"1234")?;
/// assert_eq!(read_capped(&file, 4)?, b"1234");
/// assert!(matches!(read_capped(&file, 3), Err(ReadError::TooLarge { size: Some(4), limit: 3 })));
/// # std::fs::remove_dir_all(&dir)?;
/// # Ok(())
/// # }
/// ```
pub fn read_capped(path: &Path, limit: u64) -> Result<Vec<u8>, ReadError> {
    let meta = std::fs::metadata(path).map_err(ReadError::Io)?;
    if meta.is_dir() {
        return Err(ReadError::IsDirectory);
    }
    if meta.is_file() && meta.len() > limit {
        return Err(ReadError::TooLarge {
            size: Some(meta.len()),
            limit,
        });
    }
    let file = std::fs::File::open(path).map_err(ReadError::Io)?;
    // A regular file's length is known; other data grows the buffer as it
    // arrives, doubling but never past the cap (plus the one byte that
    // shows the data is longer).
    let cap = usize::try_from(limit.saturating_add(1)).unwrap_or(usize::MAX);
    let expected = if meta.is_file() { meta.len() } else { 0 };
    let mut bytes = Vec::with_capacity(usize::try_from(expected).unwrap_or(0).min(cap));
    let mut reader = file.take(limit.saturating_add(1));
    let mut chunk = vec![0_u8; 64 << 10];
    loop {
        let n = match reader.read(&mut chunk) {
            Ok(0) => break,
            Ok(n) => n,
            Err(e) if e.kind() == std::io::ErrorKind::Interrupted => continue,
            Err(e) => return Err(ReadError::Io(e)),
        };
        if bytes.len() + n > bytes.capacity() {
            let grown = (bytes.capacity() * 2).max(bytes.len() + n).min(cap);
            bytes.reserve_exact(grown - bytes.len());
        }
        bytes.extend_from_slice(&chunk[..n]);
    }
    if bytes.len() as u64 > limit {
        return Err(ReadError::TooLarge { size: None, limit });
    }
    Ok(bytes)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn devices_are_read_through_the_cap() {
        if !Path::new("/dev/zero").exists() {
            return;
        }
        let e = read_capped(Path::new("/dev/zero"), 1 << 16).unwrap_err();
        assert!(
            matches!(
                e,
                ReadError::TooLarge {
                    size: None,
                    limit: 65536
                }
            ),
            "{e}"
        );
        assert_eq!(
            e.to_string(),
            "too large (more than 65536 bytes; the limit is 65536 bytes)"
        );
        let empty = read_capped(Path::new("/dev/null"), 10).unwrap();
        assert!(empty.is_empty());
    }

    #[test]
    fn regular_files_up_to_the_cap_are_read_and_folders_refused() {
        let dir = tempfile::tempdir().unwrap();
        let f = dir.path().join("a.txt");
        std::fs::write(&f, vec![b'x'; 100]).unwrap();
        assert_eq!(read_capped(&f, 100).unwrap().len(), 100);
        let e = read_capped(&f, 99).unwrap_err();
        assert_eq!(e.size_text().as_deref(), Some("100 bytes"));
        assert!(matches!(
            read_capped(dir.path(), 100),
            Err(ReadError::IsDirectory)
        ));
        assert!(matches!(
            read_capped(&dir.path().join("missing"), 100),
            Err(ReadError::Io(_))
        ));
    }
}
