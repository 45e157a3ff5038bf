//! Matrix and mesh exchange: Matrix Market, ABAQUS matrix output, VTK (.vtu), sprs.

pub mod abaqus;
pub mod mtx;
#[cfg(feature = "sprs")]
pub mod sprs_conv;
pub mod vtk;

/// Read a whole text file; returns its display name (for the file/line errors of the parsers)
/// and its text, or [`crate::FeError::Io`] naming the file.
pub(crate) fn read_text(path: &std::path::Path) -> Result<(String, String), crate::FeError> {
    let name = path.display().to_string();
    let text = std::fs::read_to_string(path).map_err(|source| crate::FeError::Io {
        file: name.clone(),
        source,
    })?;
    Ok((name, text))
}
