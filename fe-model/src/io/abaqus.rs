//! ABAQUS matrix files written by `*MATRIX GENERATE` with
//! `*MATRIX OUTPUT, STIFFNESS=YES, MASS=YES, FORMAT=MATRIX INPUT` (files `job_STIF1.mtx`,
//! `job_MASS1.mtx`): one entry per line, `row node, row DOF, column node, column DOF, value`,
//! comma separated, one triangle of the symmetric matrix (Abaqus Analysis User's Guide,
//! "Generating matrices"). Lines starting with `*` are keywords/comments and skipped.
//!
//! Reading collects the (node, DOF) pairs of all given files, numbers them in ascending
//! (node, DOF) order — the [`AbaqusDofMap`] — and assembles every file with that common map,
//! mirroring one-triangle storage into a full symmetric matrix.

use super::{check_mirror, err, parsed};
use crate::FeError;
use crate::error::MatrixFileError as E;
use faer::sparse::{SparseColMat, Triplet};
use std::collections::{BTreeMap, HashMap};
use std::path::Path;

/// Parsed entries of one ABAQUS matrix file.
#[derive(Debug, Clone, PartialEq)]
pub struct AbaqusEntries {
    /// Source name (for errors).
    pub file: String,
    /// `(row node, row dof, col node, col dof, value, line)`.
    pub entries: Vec<(u64, u32, u64, u32, f64, usize)>,
}

/// Map between ABAQUS (node label, DOF number 1..6) and matrix row index.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct AbaqusDofMap {
    /// `(node, dof)` of each row, ascending.
    pub dofs: Vec<(u64, u32)>,
    index: HashMap<(u64, u32), usize>,
}

impl AbaqusDofMap {
    /// Row index of `(node, dof)`.
    pub fn index(&self, node: u64, dof: u32) -> Option<usize> {
        self.index.get(&(node, dof)).copied()
    }

    /// Number of rows.
    pub fn len(&self) -> usize {
        self.dofs.len()
    }

    /// Whether the map is empty.
    pub fn is_empty(&self) -> bool {
        self.dofs.is_empty()
    }
}

/// The syntax error "`shape`, found `line`" of a line `line` of the wrong shape (line `ln` of
/// `file`).
fn misshapen(shape: &str, line: &str, file: &str, ln: usize) -> FeError {
    err(
        file,
        ln,
        E::Syntax(format!(
            "{shape}, found `{}`",
            mbd_core::validate::escape(line)
        )),
    )
}

/// Parse ABAQUS matrix text; `file` names the source in errors.
pub fn parse(text: &str, file: &str) -> Result<AbaqusEntries, FeError> {
    let mut entries = Vec::new();
    for (i, l) in text.lines().enumerate() {
        let ln = i + 1;
        let t = l.trim();
        if t.is_empty() || t.starts_with('*') {
            continue;
        }
        let f: Vec<&str> = t
            .split(',')
            .map(|s| s.trim())
            .filter(|s| !s.is_empty())
            .collect();
        if f.len() != 5 {
            return Err(misshapen(
                "expected `node, dof, node, dof, value`",
                t,
                file,
                ln,
            ));
        }
        let node =
            |s: &str| -> Result<u64, FeError> { parsed(s, "a node label", E::Syntax, file, ln) };
        let dof = |s: &str| -> Result<u32, FeError> {
            let d: u32 = parsed(s, "a DOF number", E::Syntax, file, ln)?;
            if d == 0 {
                return Err(err(file, ln, E::Syntax("DOF numbers start at 1".into())));
            }
            Ok(d)
        };
        let v: f64 = parsed(f[4], "a number", E::Syntax, file, ln)?;
        if !v.is_finite() {
            return Err(err(
                file,
                ln,
                E::NonFinite(mbd_core::validate::escape(f[4])),
            ));
        }
        entries.push((node(f[0])?, dof(f[1])?, node(f[2])?, dof(f[3])?, v, ln));
    }
    Ok(AbaqusEntries {
        file: file.to_string(),
        entries,
    })
}

/// Most node labels a node-set file may list or generate: 10⁸ (raised 1000-fold by
/// `--allow-large`, [`mbd_core::validate::limits`]); a `GENERATE` line is counted before
/// anything is expanded.
pub const MAX_SET_LABELS: usize = 100_000_000;

/// Node labels of a node-set file: plain lists (labels separated by commas or white space,
/// `#` comment lines), or ABAQUS `*NSET` / `*ELSET` data lines. After a keyword line with the
/// `GENERATE` parameter (`*NSET, NSET=RIM, GENERATE`), each data line is `first, last[,
/// increment]` and stands for `first, first + increment, …, last` (Abaqus Keywords Reference,
/// `*NSET`: "GENERATE: … first node, last node, increment in node numbers between nodes in the
/// set", increment 1 by default; issue 35: the line `1, 432, 1` had been read as the three
/// labels 1, 432, 1). Other keyword lines end a `GENERATE` block. Errors name `file` and line.
pub fn parse_node_set(text: &str, file: &str) -> Result<Vec<u64>, FeError> {
    Ok(parse_node_set_lines(text, file)?
        .into_iter()
        .map(|(label, _)| label)
        .collect())
}

/// The labels of a node-set file as [`parse_node_set`] reads them, each with the 1-based line
/// it is listed or generated on (for messages that point at the line naming a node; the one
/// node-set reader of the workspace, also used by the imported tire).
pub fn parse_node_set_lines(text: &str, file: &str) -> Result<Vec<(u64, usize)>, FeError> {
    let max = mbd_core::validate::limits::ceiling_count(MAX_SET_LABELS);
    let mut out: Vec<(u64, usize)> = Vec::new();
    let mut generate = false;
    let too_many = |ln: usize, n: u128| {
        err(
            file,
            ln,
            E::Syntax(format!(
                "the set has {n} labels, more than the {max} a node set may have{}",
                mbd_core::validate::limits::raise_hint()
            )),
        )
    };
    for (i, l) in text.lines().enumerate() {
        let ln = i + 1;
        let t = l.trim();
        if t.is_empty() || t.starts_with('#') || t.starts_with("**") {
            continue;
        }
        if let Some(keyword) = t.strip_prefix('*') {
            generate = keyword
                .split(',')
                .skip(1)
                .any(|p| p.trim().eq_ignore_ascii_case("generate"));
            continue;
        }
        let fields: Vec<&str> = t
            .split(|c: char| c == ',' || c.is_whitespace())
            .filter(|s| !s.is_empty())
            .collect();
        let label = |s: &str| -> Result<u64, FeError> {
            parsed(
                s,
                "a node label (a non-negative integer)",
                E::Syntax,
                file,
                ln,
            )
        };
        if generate {
            if !(2..=3).contains(&fields.len()) {
                return Err(misshapen(
                    "a GENERATE line is `first, last[, increment]`",
                    t,
                    file,
                    ln,
                ));
            }
            let (first, last) = (label(fields[0])?, label(fields[1])?);
            let inc = match fields.get(2) {
                Some(s) => label(s)?,
                None => 1,
            };
            if inc == 0 || last < first {
                return Err(err(
                    file,
                    ln,
                    E::Syntax(format!(
                        "GENERATE {first}, {last}, {inc}: needs last >= first and an \
                         increment >= 1"
                    )),
                ));
            }
            if (last - first) % inc != 0 {
                return Err(err(
                    file,
                    ln,
                    E::Syntax(format!(
                        "GENERATE {first}, {last}, {inc}: last - first is not a multiple of \
                         the increment"
                    )),
                ));
            }
            let n = u128::from((last - first) / inc) + 1;
            if out.len() as u128 + n > max as u128 {
                return Err(too_many(ln, out.len() as u128 + n));
            }
            out.extend((0..n as u64).map(|k| (first + k * inc, ln)));
        } else {
            if out.len() + fields.len() > max {
                return Err(too_many(ln, (out.len() + fields.len()) as u128));
            }
            for f in fields {
                out.push((label(f)?, ln));
            }
        }
    }
    Ok(out)
}

/// Read a node-set file ([`parse_node_set`]; a bounded read: a regular file within
/// [`super::MAX_INPUT_BYTES`]).
pub fn read_node_set(path: impl AsRef<Path>) -> Result<Vec<u64>, FeError> {
    let (name, text) = super::read_text(path.as_ref())?;
    parse_node_set(&text, &name)
}

/// Read one ABAQUS matrix file.
pub fn read(path: impl AsRef<Path>) -> Result<AbaqusEntries, FeError> {
    let (name, text) = super::read_text(path.as_ref())?;
    parse(&text, &name)
}

/// Assemble the given files with one common DOF map (full symmetric storage; one-triangle
/// files are mirrored, two-triangle files are checked for symmetry).
pub fn assemble(
    files: &[&AbaqusEntries],
) -> Result<(AbaqusDofMap, Vec<SparseColMat<usize, f64>>), FeError> {
    let mut set = BTreeMap::new();
    for f in files {
        for &(n1, d1, n2, d2, _, _) in &f.entries {
            set.insert((n1, d1), ());
            set.insert((n2, d2), ());
        }
    }
    let dofs: Vec<(u64, u32)> = set.into_keys().collect();
    let index: HashMap<(u64, u32), usize> = dofs.iter().enumerate().map(|(i, &k)| (k, i)).collect();
    let n = dofs.len();
    let mut out = Vec::with_capacity(files.len());
    for f in files {
        // key (max, min) → (value, line, stored with row < col?)
        let mut tri: HashMap<(usize, usize), (f64, usize, bool)> = HashMap::new();
        for &(n1, d1, n2, d2, v, ln) in &f.entries {
            let (r, c) = (index[&(n1, d1)], index[&(n2, d2)]);
            let upper = r < c;
            let key = if upper { (c, r) } else { (r, c) };
            match tri.get_mut(&key) {
                Some((old, _, side)) if *side != upper && r != c => {
                    check_mirror(&f.file, ln, (r, c), v, *old)?;
                }
                Some((old, _, _)) => *old += v,
                None => {
                    tri.insert(key, (v, ln, upper));
                }
            }
        }
        let mut t = Vec::with_capacity(2 * tri.len());
        for ((r, c), (v, _, _)) in tri {
            t.push(Triplet::new(r, c, v));
            if r != c {
                t.push(Triplet::new(c, r, v));
            }
        }
        out.push(
            SparseColMat::try_new_from_triplets(n, n, &t)
                .map_err(|e| FeError::Sparse(format!("ABAQUS matrix {}: {e:?}", f.file)))?,
        );
    }
    Ok((AbaqusDofMap { dofs, index }, out))
}
