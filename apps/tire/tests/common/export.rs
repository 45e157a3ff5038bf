//! An imported tire for the tests: the coarse generated tire (24 × 8 elements, patch ±40°)
//! exported to Matrix Market files (K, lumped M, nodes, rim and patch sets), and variants.

use super::{outcome, run, tmp};
use std::fmt::Write as _;
use std::path::PathBuf;
use tire::{TireFe, coarse_tire_config, generated_tire};

/// The coarse generated tire (24 × 8 elements, patch ±40°) and its export.
pub struct Export {
    pub fe: TireFe,
    pub dir: PathBuf,
}

/// Matrix Market text of a symmetric `n × n` matrix from its lower-triangle entries.
pub fn mtx(n: usize, entries: &[(usize, usize, f64)]) -> String {
    let mut s = format!(
        "%%MatrixMarket matrix coordinate real symmetric\n{n} {n} {}\n",
        entries.len()
    );
    for (r, c, v) in entries {
        writeln!(s, "{} {} {v:e}", r + 1, c + 1).unwrap();
    }
    s
}

pub fn lines<T: std::fmt::Display>(items: impl IntoIterator<Item = T>) -> String {
    items.into_iter().map(|i| format!("{i}\n")).collect()
}

impl Export {
    pub fn new(test: &str) -> Self {
        let fe = generated_tire(&coarse_tire_config(24, 8, 40.0)).unwrap();
        let dir = tmp(test);
        let e = Self { fe, dir };
        e.write("K.mtx", &mtx(e.n(), &e.stiffness()));
        e.write("M.mtx", &e.mass(e.n()));
        e.write("nodes.txt", &e.nodes_text(&e.fe.nodes));
        e.write("rim.txt", &lines(&e.fe.rim));
        e.write("patch.txt", &lines(&e.fe.candidates));
        e
    }
    pub fn n(&self) -> usize {
        3 * self.fe.n_nodes()
    }
    pub fn path(&self, name: &str) -> PathBuf {
        self.dir.join(name)
    }
    pub fn write(&self, name: &str, text: &str) {
        std::fs::write(self.path(name), text).unwrap();
    }
    /// The lower triangle of K.
    pub fn stiffness(&self) -> Vec<(usize, usize, f64)> {
        fe_model::sparse::triplets(self.fe.stiffness.as_ref())
            .filter(|&(r, c, _)| r >= c)
            .collect()
    }
    /// The lumped mass as a diagonal Matrix Market matrix of size `n` (1 kg beyond the tire's
    /// DOFs).
    pub fn mass(&self, n: usize) -> String {
        let e: Vec<_> = (0..n)
            .map(|d| (d, d, self.fe.mass.get(d).copied().unwrap_or(1.0)))
            .collect();
        mtx(n, &e)
    }
    pub fn nodes_text(&self, nodes: &[[f64; 3]]) -> String {
        lines(
            nodes
                .iter()
                .map(|x| format!("{:e} {:e} {:e}", x[0], x[1], x[2])),
        )
    }
    /// The `[tire]` tables importing this export's files (`stiffness`, `mass`, `nodes`,
    /// `patch` named; the rim set as exported) with 12 contact nodes and 20 free-node modes.
    pub fn tables(
        &self, reduced_file: &str, stiffness: &str, mass: &str, nodes: &str, patch: &str,
    ) -> String {
        let p = |n: &str| self.path(n).display().to_string();
        format!(
            "[tire]\nreduced_file = {reduced_file:?}\n[tire.reduction]\ncontact_nodes = 12\n\
             free_modes = 20\n[tire.import]\nformat = \"matrix_market\"\nstiffness = {:?}\n\
             mass = {:?}\nnodes = {:?}\nrim_nodes = {:?}\npatch_nodes = {:?}\n",
            p(stiffness),
            p(mass),
            p(nodes),
            p("rim.txt"),
            p(patch)
        )
    }

    /// `reduce` with the import (files of this export, the stiffness and patch files named),
    /// 12 contact nodes and 20 free-node modes: (exit code, stderr).
    pub fn reduce(
        &self, case: &str, stiffness: &str, mass: &str, nodes: &str, patch: &str,
    ) -> (i32, String) {
        let cfg = self.path(&format!("{case}.toml"));
        std::fs::write(&cfg, self.tables("", stiffness, mass, nodes, patch)).unwrap();
        let out = self.path(&format!("out-{case}"));
        let (code, _, err) = outcome(&run(&[
            "reduce",
            "--quiet",
            "--config",
            cfg.to_str().unwrap(),
            "--out",
            out.to_str().unwrap(),
        ]));
        assert!(!err.contains("panicked"), "{case}: {err}");
        (code, err)
    }
}

/// Exit 2 with one line that holds every needle.
pub fn refused(case: &str, (code, err): (i32, String), needles: &[&str]) {
    assert_eq!(code, 2, "{case}: exit {code}: {err}");
    assert_eq!(err.trim_end().lines().count(), 1, "{case}: one line: {err}");
    for n in needles {
        assert!(err.contains(n), "{case}: `{n}` not in: {err}");
    }
}
