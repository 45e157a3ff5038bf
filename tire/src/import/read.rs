//! Reading the files of an imported tire: text files are regular files of at most
//! [`MAX_IMPORT_TEXT_BYTES`] (checked before reading), matrices by fe-model's Matrix Market and
//! ABAQUS readers; every error names the import field, the file and the line.

use super::ImportFiles;
use crate::error::TireError;
use crate::files::read_text_bounded;
use mbd_core::validate::limits;
use std::collections::HashMap;

/// Largest node or node-set file of an imported tire \[bytes\] (1 GiB; a 64 000-node file is
/// about 4 MB): a documented ceiling, raised 1000-fold by `--allow-large`
/// ([`mbd_core::validate::limits`]).
pub const MAX_IMPORT_TEXT_BYTES: u64 = 1 << 30;

/// An [`TireError::Import`] error of the file named by `field`.
pub(super) fn import_err(field: &'static str, reason: impl Into<String>) -> TireError {
    TireError::Import {
        field,
        reason: reason.into(),
    }
}

/// A node named in a node-set file: its index (its label until [`labels_to_indices`]) and the
/// line \[1-based\] it is listed on.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct Listed {
    pub node: usize,
    pub line: usize,
}

/// The node file: coordinates in the wheel frame \[m\], labels (ABAQUS; empty for Matrix
/// Market) and the line of each node.
pub(super) struct Nodes {
    pub path: String,
    pub coords: Vec<[f64; 3]>,
    pub labels: Vec<u64>,
    pub lines: Vec<usize>,
}

impl Nodes {
    /// Node `i` as the user wrote it: its label (ABAQUS) or 0-based index, and its line in the
    /// node file, e.g. ``node 1008 (nodes.inp:5)``.
    pub fn name(&self, i: usize) -> String {
        let id = self.labels.get(i).map_or(i as u64, |&l| l);
        match self.lines.get(i) {
            Some(line) => format!("node {id} ({}:{line})", self.path),
            None => format!("node {id}"),
        }
    }
}

/// The text of an import file: a regular file within the ceiling in force.
fn read_text(field: &'static str, path: &str) -> Result<String, TireError> {
    let max = limits::ceiling_count(MAX_IMPORT_TEXT_BYTES as usize) as u64;
    read_text_bounded(std::path::Path::new(path), max).map_err(|reason| {
        let hint = if reason.contains("ceiling") {
            limits::raise_hint()
        } else {
            ""
        };
        import_err(field, format!("{path}: {reason}{hint}"))
    })
}

/// The data lines of a text file with their 1-based numbers (`#`, `**` and ABAQUS keyword
/// lines `*…` are skipped).
fn data_lines(text: &str) -> impl Iterator<Item = (usize, &str)> {
    text.lines().enumerate().filter_map(|(ln, line)| {
        let line = line.trim();
        (!line.is_empty() && !line.starts_with('#') && !line.starts_with('*'))
            .then_some((ln + 1, line))
    })
}

fn tokens(line: &str) -> impl Iterator<Item = &str> {
    line.split(|c: char| c == ',' || c.is_whitespace())
        .filter(|t| !t.is_empty())
}

/// The node indices (Matrix Market) or labels (ABAQUS) of a node-set file, with their lines;
/// after `*NSET, …, GENERATE` each data line is a range `first, last[, increment]` (ABAQUS):
/// fe-model's one node-set reader ([`fe_model::io::abaqus::parse_node_set_lines`]), its
/// errors naming the file and line, prefixed by the import field.
pub(super) fn read_indices(field: &'static str, path: &str) -> Result<Vec<Listed>, TireError> {
    let text = read_text(field, path)?;
    let labels = fe_model::io::abaqus::parse_node_set_lines(&text, path)
        .map_err(|e| import_err(field, e.to_string()))?;
    labels
        .into_iter()
        .map(|(label, line)| {
            let node = usize::try_from(label).map_err(|_| {
                import_err(
                    field,
                    format!("{path}:{line}: node {label} is out of range"),
                )
            })?;
            Ok(Listed { node, line })
        })
        .collect()
}

/// The node file: `x, y, z` per line, or with `labelled` (ABAQUS `*NODE` data lines)
/// `label, x, y, z`; a label given twice is refused.
pub(super) fn read_nodes(path: &str, labelled: bool) -> Result<Nodes, TireError> {
    let text = read_text("nodes", path)?;
    let mut nodes = Nodes {
        path: path.to_string(),
        coords: Vec::new(),
        labels: Vec::new(),
        lines: Vec::new(),
    };
    let mut seen: HashMap<u64, usize> = HashMap::new();
    for (line, data) in data_lines(&text) {
        let mut v: Vec<&str> = tokens(data).collect();
        if labelled {
            let Some(label) = v.first().and_then(|t| t.parse::<u64>().ok()) else {
                return Err(import_err(
                    "nodes",
                    format!("{path}:{line}: expected `label, x, y, z`, got `{data}`"),
                ));
            };
            if let Some(first) = seen.insert(label, line) {
                return Err(import_err(
                    "nodes",
                    format!(
                        "{path}:{line}: node label {label} is given twice (also on line {first})"
                    ),
                ));
            }
            nodes.labels.push(label);
            v.remove(0);
        }
        let parse = |t: &str| t.parse::<f64>().ok().filter(|x| x.is_finite());
        match (
            v.len(),
            v.iter().map(|t| parse(t)).collect::<Option<Vec<f64>>>(),
        ) {
            (3, Some(x)) => nodes.coords.push([x[0], x[1], x[2]]),
            _ => {
                return Err(import_err(
                    "nodes",
                    format!("{path}:{line}: expected three finite coordinates, got `{data}`"),
                ));
            }
        }
        nodes.lines.push(line);
    }
    Ok(nodes)
}

/// The node labels of a set (ABAQUS) as 0-based indices in the node file's order.
pub(super) fn labels_to_indices(
    field: &'static str, path: &str, listed: &[Listed], labels: &[u64],
) -> Result<Vec<Listed>, TireError> {
    let pos: HashMap<u64, usize> = labels.iter().enumerate().map(|(i, &l)| (l, i)).collect();
    listed
        .iter()
        .map(|l| match pos.get(&(l.node as u64)) {
            Some(&node) => Ok(Listed { node, line: l.line }),
            None => Err(import_err(
                field,
                format!(
                    "{path}:{}: node label {} is not in the node file",
                    l.line, l.node
                ),
            )),
        })
        .collect()
}

/// A node listed twice in one set file is refused (a copy-and-paste slip; the reduction would
/// constrain its DOFs twice), naming both lines.
pub(super) fn unique_in_file(
    field: &'static str, path: &str, listed: &[Listed], nodes: &Nodes,
) -> Result<(), TireError> {
    let mut first: HashMap<usize, usize> = HashMap::with_capacity(listed.len());
    for l in listed {
        if let Some(&line) = first.get(&l.node) {
            let id = nodes.labels.get(l.node).map_or(l.node as u64, |&x| x);
            return Err(import_err(
                field,
                format!(
                    "{path}:{}: node {id} is listed twice (also on line {line})",
                    l.line
                ),
            ));
        }
        first.insert(l.node, l.line);
    }
    Ok(())
}

/// A stiffness or mass matrix (`field`) from Matrix Market: square and symmetric (a `general`
/// file storing one triangle is refused, see `fe_model::io::mtx`), default size ceiling unless
/// raised (`mbd_core::validate::limits`).
pub(super) fn read_mtx(
    field: &'static str, path: &str,
) -> Result<faer::sparse::SparseColMat<usize, f64>, TireError> {
    // `--allow-large` (mbd_core::validate::limits) lifts the reader's size ceiling too
    let opts = fe_model::io::mtx::ReadOptions::symmetric()
        .allow_large(mbd_core::validate::limits::large_allowed());
    fe_model::io::mtx::read_sparse_with(path, &opts).map_err(|e| import_err(field, e.to_string()))
}

pub(super) type Sparse = faer::sparse::SparseColMat<usize, f64>;

/// ABAQUS matrices reordered to the node order of the node file (DOF `3 i + d − 1` for node
/// `i`, DOF `d` = 1..3).
pub(super) fn read_abaqus(
    files: &ImportFiles, labels: &[u64],
) -> Result<(Sparse, Sparse), TireError> {
    let ke = fe_model::io::abaqus::read(&files.stiffness)
        .map_err(|e| import_err("stiffness", e.to_string()))?;
    let me =
        fe_model::io::abaqus::read(&files.mass).map_err(|e| import_err("mass", e.to_string()))?;
    let (map, mats) = fe_model::io::abaqus::assemble(&[&ke, &me])
        .map_err(|e| import_err("stiffness", e.to_string()))?;
    let pos: std::collections::HashMap<u64, usize> =
        labels.iter().enumerate().map(|(i, &l)| (l, i)).collect();
    let mut new_index = Vec::with_capacity(map.len());
    for &(node, dof) in &map.dofs {
        let Some(&i) = pos.get(&node) else {
            return Err(import_err(
                "nodes",
                format!(
                    "{}: node {node} of the ABAQUS matrices has no coordinates",
                    files.nodes
                ),
            ));
        };
        if !(1..=3).contains(&dof) {
            return Err(import_err(
                "stiffness",
                format!(
                    "{}: node {node} has DOF {dof}; only translational DOFs 1-3 (solid \
                     elements) are supported",
                    files.stiffness
                ),
            ));
        }
        new_index.push(3 * i + dof as usize - 1);
    }
    let n = 3 * labels.len();
    let mut out = Vec::with_capacity(2);
    for (a, (field, name)) in mats
        .iter()
        .zip([("stiffness", &files.stiffness), ("mass", &files.mass)])
    {
        let t: Vec<faer::sparse::Triplet<usize, usize, f64>> = a
            .as_ref()
            .triplet_iter()
            .map(|e| faer::sparse::Triplet::new(new_index[e.row], new_index[e.col], *e.val))
            .collect();
        out.push(
            faer::sparse::SparseColMat::try_new_from_triplets(n, n, &t).map_err(|e| {
                import_err(
                    field,
                    format!("{name}: cannot build the sparse matrix: {e:?}"),
                )
            })?,
        );
    }
    let m = out
        .pop()
        .ok_or_else(|| import_err("mass", format!("{}: no mass matrix", files.mass)))?;
    let k = out.pop().ok_or_else(|| {
        import_err(
            "stiffness",
            format!("{}: no stiffness matrix", files.stiffness),
        )
    })?;
    Ok((k, m))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// ABAQUS `GENERATE` ranges with and without a step, `**` comments inside a generated
    /// block, plain data lines after another keyword line, `#` comments (reference: the sets
    /// written out by hand).
    #[test]
    fn node_sets_with_generate_ranges() {
        let dir = std::env::temp_dir().join(format!("flowmbd-tire-sets-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let f = dir.join("set.inp");
        std::fs::write(
            &f,
            "# a set\n*NSET, NSET=A, generate\n1, 432, 1\n** comment\n2, 8, 2\n10, 11\n\
             *NSET, NSET=B\n1, 432, 1\n",
        )
        .unwrap();
        let got = read_indices("rim_nodes", f.to_str().unwrap()).unwrap();
        let mut want: Vec<(usize, usize)> = (1..=432).map(|l| (l, 3)).collect();
        want.extend([2, 4, 6, 8].map(|l| (l, 5)));
        want.extend([(10, 6), (11, 6), (1, 8), (432, 8), (1, 8)]);
        let got: Vec<(usize, usize)> = got.iter().map(|l| (l.node, l.line)).collect();
        assert_eq!(got, want);
        std::fs::write(&f, "*NSET, NSET=A, GENERATE\n1, 2, 3, 4\n").unwrap();
        let e = read_indices("rim_nodes", f.to_str().unwrap())
            .unwrap_err()
            .to_string();
        assert!(e.contains("set.inp:2") && e.contains("first, last"), "{e}");
        std::fs::write(&f, "*NSET, NSET=A, GENERATE\n1, 99999999999, 1\n").unwrap();
        let e = read_indices("rim_nodes", f.to_str().unwrap())
            .unwrap_err()
            .to_string();
        // fe-model's ceiling on the labels of a set (fe_model::io::abaqus::MAX_SET_LABELS)
        assert!(
            e.contains("set.inp:2") && e.contains("more than the"),
            "{e}"
        );
        std::fs::remove_dir_all(&dir).ok();
    }
}
