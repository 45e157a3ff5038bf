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

/// Read a whole file as bytes, with its display name; a directory or unreadable path is
/// [`crate::FeError::Io`] naming it (a directory is reported as such, not as missing).
pub(crate) fn read_bytes(path: &std::path::Path) -> Result<(String, Vec<u8>), crate::FeError> {
    let name = path.display().to_string();
    let io = |source| crate::FeError::Io {
        file: name.clone(),
        source,
    };
    if path.is_dir() {
        return Err(io(std::io::Error::other("is a directory, expected a file")));
    }
    let data = std::fs::read(path).map_err(io)?;
    Ok((name, data))
}

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
    if let Ok(file) = std::fs::File::open(path)
        && file.metadata().is_ok_and(|m| m.is_file() && m.len() > 0)
    {
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

/// Check that an entry `value` given in both triangles agrees with its mirror `mirror` to the
/// relative tolerance `10⁻¹²·max(|value|, |mirror|)` (symmetric storage, `A_rc = A_cr`);
/// `row`, `col` are 0-based and reported 1-based.
pub(crate) fn check_mirror(
    file: &str,
    line: usize,
    (row, col): (usize, usize),
    value: f64,
    mirror: f64,
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
