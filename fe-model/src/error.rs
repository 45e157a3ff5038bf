//! Typed errors of the fe-model crate.

use thiserror::Error;

/// Errors of model building, assembly, exchange and eigen solution.
///
/// Every message says what was wrong and where (file, line, element, DOF).
#[derive(Debug, Error)]
pub enum FeError {
    /// Two matrices (or a matrix and a vector) have incompatible shapes.
    #[error("dimension mismatch in {context}: expected {expected}, got {got}")]
    Dimension {
        /// Where the mismatch was found.
        context: String,
        /// Expected size.
        expected: usize,
        /// Actual size.
        got: usize,
    },
    /// A parameter is outside its valid range.
    #[error("invalid parameter `{name}` = {value}: {reason}")]
    InvalidParameter {
        /// Parameter (field) name.
        name: String,
        /// Offending value.
        value: f64,
        /// Why it is invalid.
        reason: String,
    },
    /// An element refers to something invalid (degenerate geometry, unknown node, ...).
    #[error("element {element}: {reason}")]
    Element {
        /// Element index.
        element: usize,
        /// What is wrong.
        reason: String,
    },
    /// A DOF or node index is out of range.
    #[error("{context}: index {index} out of range (size {size})")]
    Index {
        /// Where the index was used.
        context: String,
        /// Offending index.
        index: usize,
        /// Valid size.
        size: usize,
    },
    /// A matrix that must be symmetric positive definite is not (Cholesky failed).
    #[error("matrix `{name}` is not positive definite{detail}")]
    NotPositiveDefinite {
        /// Matrix name (e.g. "M", "K - sigma M").
        name: String,
        /// Extra information (e.g. the shift).
        detail: String,
    },
    /// An eigen solver did not converge or failed a safeguard check.
    #[error("eigen solver: {0}")]
    Eigen(String),
    /// Error while parsing an exchange file, with the 1-based line number.
    #[error("{file}:{line}: {reason}")]
    Parse {
        /// File name (or "<input>").
        file: String,
        /// 1-based line number.
        line: usize,
        /// What is wrong.
        reason: String,
    },
    /// Matrix Market / ABAQUS matrix file error, with the 1-based line number.
    #[error("{file}:{line}: {kind}")]
    Matrix {
        /// File name (or a label such as "<input>").
        file: String,
        /// 1-based line number (0 = whole file).
        line: usize,
        /// What is wrong.
        kind: MatrixFileError,
    },
    /// I/O error with the file it concerns.
    #[error("{file}: {source}")]
    Io {
        /// File name.
        file: String,
        /// Underlying error.
        #[source]
        source: std::io::Error,
    },
    /// A named item (node set, field, ...) does not exist.
    #[error("unknown {what} `{name}` (known: {known})")]
    Unknown {
        /// Kind of item.
        what: String,
        /// Requested name.
        name: String,
        /// Known names.
        known: String,
    },
    /// A matrix read from a file is physically implausible (see
    /// [`crate::plausibility::check_stiffness_mass`]).
    #[error("matrix `{matrix}`: {reason}")]
    Implausible {
        /// `K` or `M`.
        matrix: String,
        /// What is wrong, with the offending DOFs (1-based rows).
        reason: String,
    },
    /// A faer sparse structure could not be created.
    #[error("sparse matrix creation failed in {0}")]
    Sparse(String),
    /// A configuration field is rejected ([`mbd_core::Validate`]: dotted path and reason).
    #[error(transparent)]
    Invalid(#[from] mbd_core::InvalidField),
}

impl FeError {
    /// Shorthand for [`FeError::InvalidParameter`].
    pub fn param(name: &str, value: f64, reason: &str) -> Self {
        FeError::InvalidParameter {
            name: name.to_string(),
            value,
            reason: reason.to_string(),
        }
    }

    /// Check that a parameter is finite and strictly positive.
    pub fn check_positive(name: &str, value: f64) -> Result<f64, Self> {
        if value.is_finite() && value > 0.0 {
            Ok(value)
        } else {
            Err(Self::param(name, value, "must be finite and > 0"))
        }
    }

    /// Check that a parameter is finite and non-negative.
    pub fn check_non_negative(name: &str, value: f64) -> Result<f64, Self> {
        if value.is_finite() && value >= 0.0 {
            Ok(value)
        } else {
            Err(Self::param(name, value, "must be finite and >= 0"))
        }
    }
}

/// What is wrong in a matrix exchange file (see [`FeError::Matrix`]).
#[derive(Debug, Clone, PartialEq, Error)]
pub enum MatrixFileError {
    /// Missing or malformed `%%MatrixMarket` banner, or an unsupported object/format/field/symmetry.
    #[error("bad header: {0}")]
    Header(String),
    /// The size line is missing or malformed.
    #[error("bad size line: {0}")]
    Size(String),
    /// The file ended before all declared entries were read.
    #[error("truncated file: expected {expected} entries, found {found}")]
    Truncated {
        /// Declared entries.
        expected: usize,
        /// Entries found.
        found: usize,
    },
    /// More entries than declared.
    #[error("more entries than the {expected} declared")]
    TooManyEntries {
        /// Declared entries.
        expected: usize,
    },
    /// A line could not be parsed.
    #[error("syntax error: {0}")]
    Syntax(String),
    /// A 1-based index is outside `1..=size`.
    #[error("index ({row}, {col}) out of range for a {nrows}×{ncols} matrix")]
    IndexOutOfRange {
        /// Row index as written.
        row: i64,
        /// Column index as written.
        col: i64,
        /// Declared rows.
        nrows: usize,
        /// Declared columns.
        ncols: usize,
    },
    /// A value is NaN or infinite.
    #[error("non-finite value `{0}`")]
    NonFinite(String),
    /// A size in the size line exceeds the reader's ceiling (checked before allocating).
    #[error(
        "{what} = {value} exceeds the ceiling of {limit}{}",
        if *raisable { " (raise it with --allow-large)" } else { "" }
    )]
    TooLarge {
        /// `rows` or `columns`.
        what: String,
        /// Declared size.
        value: usize,
        /// The ceiling in force.
        limit: usize,
        /// Whether a larger ceiling could be requested.
        raisable: bool,
    },
    /// A `general` file of a matrix that must be symmetric stores only one triangle.
    #[error(
        "the header says `general` but only the {stored} triangle is stored ({count} off-diagonal entries, none mirrored); a stiffness or mass matrix is symmetric: write `symmetric` in the header (line 1) if the other triangle is its mirror"
    )]
    OneTriangle {
        /// `lower` or `upper`.
        stored: &'static str,
        /// Non-zero off-diagonal entries stored.
        count: usize,
    },
    /// A matrix declared symmetric is not: `a(i,j) ≠ a(j,i)`.
    #[error(
        "matrix declared symmetric but a({row},{col}) = {value} differs from a({col},{row}) = {mirror}"
    )]
    NotSymmetric {
        /// Row (1-based).
        row: usize,
        /// Column (1-based).
        col: usize,
        /// Value at (row, col).
        value: f64,
        /// Value at (col, row).
        mirror: f64,
    },
}
