//! The one bounded reader of input files (issue 33): a file is read whole only if it is a
//! regular file (not a directory, FIFO, socket or device such as `/dev/zero`, which would be
//! read without end) whose size, checked before reading, is at most a ceiling; the read itself
//! stops one byte past the ceiling, so a file that grows while it is read is refused too.
//! Every error is an [`InputError`] that names the file and says what was wrong; crates map it
//! into their own error types ([`InputError::reason`] is the message without the path).
//!
//! ```
//! let path = std::env::temp_dir().join(format!("mbd-core-input-doc-{}.txt", std::process::id()));
//! std::fs::write(&path, "a,b\n1,2\n").unwrap();
//! assert_eq!(mbd_core::input::read_text(&path, 1024).unwrap(), "a,b\n1,2\n");
//! let e = mbd_core::input::read_text(&path, 4).unwrap_err();
//! assert!(e.reason().contains("has 8 bytes, more than the ceiling of 4 bytes"), "{e}");
//! std::fs::remove_file(&path).unwrap();
//! ```

use std::io::Read;
use std::path::{Path, PathBuf};
use thiserror::Error;

/// Why an input file could not be read (every variant names the file, its display form made
/// safe for one line by [`crate::validate::escape`]).
#[derive(Debug, Error)]
pub enum InputError {
    /// Nothing at the path.
    #[error("{}: does not exist", shown(path))]
    NotFound {
        /// The file.
        path: PathBuf,
        /// The operating system's error.
        source: std::io::Error,
    },
    /// The path is a directory.
    #[error("{}: is a directory, expected a file", shown(path))]
    Directory {
        /// The path.
        path: PathBuf,
    },
    /// The path is a device, FIFO or socket.
    #[error(
        "{}: is not a regular file (a device, FIFO or socket), expected a file",
        shown(path)
    )]
    NotRegular {
        /// The path.
        path: PathBuf,
    },
    /// The file is larger than the ceiling (seen before reading, or while reading a file that
    /// grew).
    #[error(
        "{}: has {size} bytes, more than the ceiling of {max} bytes",
        shown(path)
    )]
    TooLarge {
        /// The file.
        path: PathBuf,
        /// Its size \[bytes\] (while reading: at least this many).
        size: u64,
        /// The ceiling \[bytes\].
        max: u64,
    },
    /// The file's bytes are not UTF-8 text ([`read_text`]).
    #[error("{}: is not UTF-8 text (invalid byte at offset {offset})", shown(path))]
    NotUtf8 {
        /// The file.
        path: PathBuf,
        /// Offset of the first invalid byte \[bytes\].
        offset: usize,
    },
    /// Any other failure to inspect, open or read the file (permissions, I/O).
    #[error("{}: cannot read: {source}", shown(path))]
    Io {
        /// The file.
        path: PathBuf,
        /// The operating system's error.
        source: std::io::Error,
    },
}

fn shown(path: &Path) -> String {
    crate::validate::escape(&path.display().to_string())
}

impl InputError {
    fn io(path: &Path, source: std::io::Error) -> Self {
        let path = path.to_path_buf();
        if source.kind() == std::io::ErrorKind::NotFound {
            Self::NotFound { path, source }
        } else {
            Self::Io { path, source }
        }
    }

    /// The file the error is about.
    pub fn path(&self) -> &Path {
        match self {
            Self::NotFound { path, .. }
            | Self::Directory { path }
            | Self::NotRegular { path }
            | Self::TooLarge { path, .. }
            | Self::NotUtf8 { path, .. }
            | Self::Io { path, .. } => path,
        }
    }

    /// What was wrong, without the path (`"is a directory, expected a file"`), for callers
    /// whose own error names the file in another place.
    pub fn reason(&self) -> String {
        let text = self.to_string();
        let prefix = format!("{}: ", shown(self.path()));
        match text.strip_prefix(&prefix) {
            Some(reason) => reason.to_string(),
            None => text,
        }
    }
}

/// An input file opened for a bounded read: a regular file whose size was at most the ceiling
/// when it was opened ([`open`]).
#[derive(Debug)]
pub struct BoundedFile {
    path: PathBuf,
    file: std::fs::File,
    len: u64,
    max: u64,
}

/// Open the regular file `path` if its size is at most `max_bytes`.
///
/// # Errors
/// [`InputError`]: missing, a directory, not a regular file, larger than `max_bytes`,
/// unreadable.
pub fn open(path: &Path, max_bytes: u64) -> Result<BoundedFile, InputError> {
    let meta = std::fs::metadata(path).map_err(|e| InputError::io(path, e))?;
    if meta.is_dir() {
        return Err(InputError::Directory {
            path: path.to_path_buf(),
        });
    }
    if !meta.is_file() {
        return Err(InputError::NotRegular {
            path: path.to_path_buf(),
        });
    }
    if meta.len() > max_bytes {
        return Err(InputError::TooLarge {
            path: path.to_path_buf(),
            size: meta.len(),
            max: max_bytes,
        });
    }
    let file = std::fs::File::open(path).map_err(|e| InputError::io(path, e))?;
    Ok(BoundedFile {
        path: path.to_path_buf(),
        file,
        len: meta.len(),
        max: max_bytes,
    })
}

impl BoundedFile {
    /// The file's size when it was opened \[bytes\].
    pub fn len(&self) -> u64 {
        self.len
    }

    /// Whether the file was empty when it was opened.
    pub fn is_empty(&self) -> bool {
        self.len == 0
    }

    /// The open file (for a reader of its own, e.g. a memory map or a digest read in blocks).
    pub fn into_file(self) -> std::fs::File {
        self.file
    }

    /// Read the whole file, at most the ceiling: a file that grew past it since it was opened
    /// is [`InputError::TooLarge`].
    ///
    /// # Errors
    /// [`InputError::TooLarge`], [`InputError::Io`].
    pub fn read(self) -> Result<Vec<u8>, InputError> {
        let mut bytes = Vec::with_capacity(self.len as usize);
        self.file
            .take(self.max.saturating_add(1))
            .read_to_end(&mut bytes)
            .map_err(|e| InputError::io(&self.path, e))?;
        if bytes.len() as u64 > self.max {
            return Err(InputError::TooLarge {
                path: self.path,
                size: bytes.len() as u64,
                max: self.max,
            });
        }
        Ok(bytes)
    }
}

/// The bytes of the regular file `path` of at most `max_bytes` bytes ([`open`], then
/// [`BoundedFile::read`]).
///
/// # Errors
/// [`InputError`]: missing, a directory, not a regular file, larger than `max_bytes` (before
/// or while reading), unreadable.
pub fn read_bounded(path: &Path, max_bytes: u64) -> Result<Vec<u8>, InputError> {
    open(path, max_bytes)?.read()
}

/// The UTF-8 text of the regular file `path` of at most `max_bytes` bytes ([`read_bounded`]).
///
/// # Errors
/// As [`read_bounded`], and [`InputError::NotUtf8`].
pub fn read_text(path: &Path, max_bytes: u64) -> Result<String, InputError> {
    String::from_utf8(read_bounded(path, max_bytes)?).map_err(|e| InputError::NotUtf8 {
        path: path.to_path_buf(),
        offset: e.utf8_error().valid_up_to(),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A scratch folder of this test process under the system's temporary folder.
    fn scratch(name: &str) -> PathBuf {
        let dir = std::env::temp_dir().join(format!(
            "mbd-core-input-{name}-{}-{:?}",
            std::process::id(),
            std::thread::current().id()
        ));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).unwrap();
        dir
    }

    /// The five cases told apart, each message naming the path (the reference is the file
    /// system's own answer: what was written is what is read back).
    #[test]
    fn refuses_what_it_must_and_reads_the_rest() {
        let dir = scratch("cases");
        let e = read_bounded(&dir, 100).unwrap_err();
        assert!(matches!(e, InputError::Directory { .. }), "{e}");
        assert_eq!(
            e.to_string(),
            format!("{}: is a directory, expected a file", dir.display())
        );
        assert_eq!(e.reason(), "is a directory, expected a file");

        #[cfg(unix)]
        {
            let e = read_bounded(Path::new("/dev/zero"), 100).unwrap_err();
            assert!(matches!(e, InputError::NotRegular { .. }), "{e}");
            assert!(
                e.to_string()
                    .starts_with("/dev/zero: is not a regular file"),
                "{e}"
            );
        }

        let missing = dir.join("none.csv");
        let e = read_text(&missing, 100).unwrap_err();
        assert!(matches!(e, InputError::NotFound { .. }), "{e}");
        assert!(e.to_string().contains("none.csv: does not exist"), "{e}");

        let big = dir.join("big.txt");
        std::fs::write(&big, [b'x'; 11]).unwrap();
        let e = read_bounded(&big, 10).unwrap_err();
        assert!(
            matches!(
                e,
                InputError::TooLarge {
                    size: 11,
                    max: 10,
                    ..
                }
            ),
            "{e}"
        );
        assert!(
            e.to_string()
                .contains("big.txt: has 11 bytes, more than the ceiling of 10 bytes"),
            "{e}"
        );
        assert_eq!(read_bounded(&big, 11).unwrap(), vec![b'x'; 11]);

        let latin1 = dir.join("latin1.txt");
        std::fs::write(&latin1, b"ab\xe9c").unwrap();
        let e = read_text(&latin1, 100).unwrap_err();
        assert!(matches!(e, InputError::NotUtf8 { offset: 2, .. }), "{e}");
        assert_eq!(read_bounded(&latin1, 100).unwrap(), b"ab\xe9c");

        let good = dir.join("good.toml");
        std::fs::write(&good, "x = 1\n").unwrap();
        let f = open(&good, 6).unwrap();
        assert_eq!(f.len(), 6);
        assert_eq!(f.read().unwrap(), b"x = 1\n");
        assert_eq!(read_text(&good, 6).unwrap(), "x = 1\n");
        std::fs::remove_dir_all(&dir).unwrap();
    }

    /// A file that grows after it was opened is cut at the ceiling and refused (the read is
    /// bounded, not only the size seen first).
    #[test]
    fn growth_after_open_is_refused() {
        let dir = scratch("grow");
        let f = dir.join("grows.txt");
        std::fs::write(&f, "12345").unwrap();
        let opened = open(&f, 8).unwrap();
        std::fs::write(&f, "123456789012").unwrap();
        let e = opened.read().unwrap_err();
        assert!(
            matches!(
                e,
                InputError::TooLarge {
                    size: 9,
                    max: 8,
                    ..
                }
            ),
            "{e}"
        );
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
