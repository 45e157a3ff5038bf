//! Matrix and mesh exchange: Matrix Market, ABAQUS matrix output, VTK (.vtu), sprs.

pub mod abaqus;
pub mod mtx;
#[cfg(feature = "sprs")]
pub mod sprs_conv;
pub mod vtk;

/// Read a whole text file; returns its display name (for the file/line errors of the parsers)
/// and its text, or [`crate::FeError::Io`] naming the file.
pub(crate) fn read_text(path: &std::path::Path) -> Result<(String, String), crate::FeError> {
    let (name, data) = read_bytes(path)?;
    let text = String::from_utf8(data).map_err(|e| crate::FeError::Io {
        file: name.clone(),
        source: std::io::Error::new(std::io::ErrorKind::InvalidData, e.utf8_error()),
    })?;
    Ok((name, text))
}

/// Largest input file read whole (Matrix Market, ABAQUS, node sets): 16 GiB, raised 1000-fold
/// by `--allow-large` ([`mbd_core::validate::limits`]). A file's size is checked before it
/// is read; its contents must also fit in the memory the machine has available
/// ([`mbd_core::validate::limits::check_memory`]).
pub const MAX_INPUT_BYTES: u64 = 16 << 30;

/// An input file that may be read whole, opened: a regular file (not a directory, FIFO,
/// socket or device such as `/dev/zero`) no larger than [`MAX_INPUT_BYTES`] (issue 35), with
/// its display name ([`mbd_core::input::open`]).
pub(crate) fn check_input(
    path: &std::path::Path,
) -> Result<(String, mbd_core::input::BoundedFile), crate::FeError> {
    let max = mbd_core::validate::limits::ceiling(MAX_INPUT_BYTES as f64);
    let file = mbd_core::input::open(path, max as u64).map_err(input_error)?;
    Ok((path.display().to_string(), file))
}

/// An [`mbd_core::input::InputError`] as [`crate::FeError::Io`] naming the file.
fn input_error(e: mbd_core::input::InputError) -> crate::FeError {
    use mbd_core::input::InputError as E;
    let file = mbd_core::validate::escape(&e.path().display().to_string());
    let source = match e {
        E::NotFound { source, .. } | E::Io { source, .. } => source,
        E::TooLarge { size, max, .. } => std::io::Error::other(format!(
            "has {size} bytes, more than the {:e} an input file may have{}",
            max as f64,
            mbd_core::validate::limits::raise_hint()
        )),
        E::NotUtf8 { .. } => std::io::Error::new(std::io::ErrorKind::InvalidData, e.reason()),
        E::Directory { .. } | E::NotRegular { .. } => std::io::Error::other(e.reason()),
    };
    crate::FeError::Io { file, source }
}

/// Read a whole file as bytes, with its display name; a directory, a non-regular or
/// oversized file ([`check_input`]) or an unreadable path is [`crate::FeError::Io`] naming it
/// (a directory is reported as such, not as missing). The file's size must fit in memory; the
/// read is bounded by the ceiling (a file that grows past it meanwhile is refused).
pub(crate) fn read_bytes(path: &std::path::Path) -> Result<(String, Vec<u8>), crate::FeError> {
    let (name, file) = check_input(path)?;
    mbd_core::validate::limits::check_memory(&name, file.len() as f64).map_err(|e| {
        crate::FeError::Io {
            file: mbd_core::validate::escape(&name),
            source: std::io::Error::other(e.reason),
        }
    })?;
    let data = file.read().map_err(input_error)?;
    Ok((name, data))
}

/// Write `bytes` to `path` through a temporary file beside it (`.NAME.part`), renamed over
/// `path` when complete: a reader never sees half a file, and a killed writer leaves the old
/// file or none (issue 35, item 3). Used by every writer of this crate
/// ([`mbd_core::output::write_atomic`]).
pub use mbd_core::output::write_atomic;

/// The bytes of a file: memory-mapped, or read into memory where mapping is not possible.
pub(crate) enum FileBytes {
    /// The file mapped read-only (no copy into a fresh buffer: for a 50 MB matrix file the
    /// copy and the page faults of its buffer took about as long as parsing it).
    Mapped(memmap2::Mmap),
    /// The file read into memory (an empty file, or one that cannot be mapped, e.g. a pipe).
    Owned(Vec<u8>),
}

impl std::ops::Deref for FileBytes {
    type Target = [u8];
    fn deref(&self) -> &[u8] {
        match self {
            Self::Mapped(m) => m,
            Self::Owned(v) => v,
        }
    }
}

/// Map a whole file read-only (populated up front), with its display name; files that cannot
/// be mapped are read ([`read_bytes`], with its errors).
///
/// The file must not be truncated by another process while it is parsed: as for any
/// memory-mapped reader, the operating system would then stop the process (`SIGBUS`).
/// Writing a matrix file while another program reads it is an error in any case.
pub(crate) fn map_bytes(path: &std::path::Path) -> Result<(String, FileBytes), crate::FeError> {
    let (_, input) = check_input(path)?;
    if !input.is_empty() {
        let file = input.into_file();
        // SAFETY: the map is read-only and private; the documented condition above (the file
        // is not truncated while mapped) is the caller's, as for every mmap-based reader.
        let map = unsafe { memmap2::MmapOptions::new().populate().map(&file) };
        if let Ok(map) = map {
            return Ok((path.display().to_string(), FileBytes::Mapped(map)));
        }
    }
    let (name, data) = read_bytes(path)?;
    Ok((name, FileBytes::Owned(data)))
}

/// A matrix-file error at `line` of `file`.
pub(crate) fn err(file: &str, line: usize, kind: crate::error::MatrixFileError) -> crate::FeError {
    crate::FeError::Matrix {
        file: file.to_string(),
        line,
        kind,
    }
}

/// The field `s` of line `ln` of `file` read as a `T`, or the error `kind` "`s` is not
/// `what`".
pub(crate) fn parsed<T: std::str::FromStr>(
    s: &str, what: &str, kind: fn(String) -> crate::error::MatrixFileError, file: &str, ln: usize,
) -> Result<T, crate::FeError> {
    s.parse().map_err(|_| {
        err(
            file,
            ln,
            kind(format!("`{}` is not {what}", mbd_core::validate::escape(s))),
        )
    })
}

/// Check that an entry `value` given in both triangles agrees with its mirror `mirror` to the
/// relative tolerance `10⁻¹²·max(|value|, |mirror|)` (symmetric storage, `A_rc = A_cr`);
/// `row`, `col` are 0-based and reported 1-based.
pub(crate) fn check_mirror(
    file: &str, line: usize, (row, col): (usize, usize), value: f64, mirror: f64,
) -> Result<(), crate::FeError> {
    let tol = 1e-12 * mirror.abs().max(value.abs());
    if (mirror - value).abs() > tol {
        return Err(err(
            file,
            line,
            crate::error::MatrixFileError::NotSymmetric {
                row: row + 1,
                col: col + 1,
                value,
                mirror,
            },
        ));
    }
    Ok(())
}
