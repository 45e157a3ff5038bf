//! Helpers shared by the end-to-end tests of `flowmbd-tire`: the binary, scratch folders, JSON
//! summaries and a small generated tire (the coarse 96 × 8 truck tire of the library tests in
//! `tests/tests/tire_*.rs`, 33 contact nodes, 50 free-node modes: reduced in about a second).

#![allow(dead_code)]

pub mod export;

use std::path::{Path, PathBuf};
use std::process::{Command, Output};
use std::sync::OnceLock;

/// The binary under test.
pub fn bin() -> Command {
    Command::new(env!("CARGO_BIN_EXE_flowmbd-tire"))
}

/// A fresh scratch folder `flowmbd-tire-<test>-<pid>` in Cargo's scratch folder for integration
/// tests (`target/tmp`).
pub fn tmp(test: &str) -> PathBuf {
    let d = Path::new(env!("CARGO_TARGET_TMPDIR"))
        .join(format!("flowmbd-tire-{test}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

/// Run the binary with `args` (all `--quiet` unless a test needs the messages).
pub fn run(args: &[&str]) -> Output {
    bin().args(args).output().expect("the binary runs")
}

/// Run `study` with the flags `flags`, then `--config cfg --out out`: the set-up shared by the
/// tests that run a study on a written configuration.
pub fn run_study(study: &str, flags: &[&str], cfg: &Path, out: &Path) -> Output {
    let (cfg, out) = (cfg.to_str().unwrap(), out.to_str().unwrap());
    let mut args = vec![study];
    args.extend_from_slice(flags);
    args.extend_from_slice(&["--config", cfg, "--out", out]);
    run(&args)
}

/// Exit code, stdout and stderr of a run.
pub fn outcome(out: &Output) -> (i32, String, String) {
    (
        out.status.code().unwrap_or(-1),
        String::from_utf8_lossy(&out.stdout).into_owned(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

/// The JSON summary printed by a successful `--json` run (panics with the run's stderr
/// otherwise).
pub fn json_of(out: &Output) -> serde_json::Value {
    assert!(
        out.status.success(),
        "exit {:?}: {}",
        out.status.code(),
        String::from_utf8_lossy(&out.stderr)
    );
    serde_json::from_slice(&out.stdout).expect("stdout is the JSON summary")
}

/// Circumferential divisions, section divisions and thickness divisions of the small tire.
pub const CIRC: usize = 96;
/// Section divisions of the small tire.
pub const SECTION: usize = 8;
/// Contact nodes of the small tire's reduction.
pub const CONTACT: usize = 33;
/// Free-node modes of the small tire's reduction.
pub const MODES: usize = 50;

/// The `[tire]` tables of the small tire, with its reduced-tire file at `reduced`: the isotropic
/// materials of earlier versions (tread 150 MPa, no carcass cords), as the library's rolling
/// tests (`tests/tests/common`, which says why).
pub fn tire_tables(reduced: &Path) -> String {
    format!(
        "[tire]\nreduced_file = {:?}\n\
         [tire.generator]\ncircumferential_divisions = {CIRC}\nsection_divisions = {SECTION}\n\
         thickness_divisions = 1\nbead_elements = 1\npatch_half_angle_deg = 20.0\n\
         [tire.generator.tread]\nyoung = 150e6\npoisson = 0.45\ndensity = 1500.0\n\
         [tire.generator.carcass]\nmodulus = 0.0\n\
         [tire.reduction]\ncontact_nodes = {CONTACT}\nfree_modes = {MODES}\n",
        reduced.display().to_string()
    )
}

/// Write a configuration file `name` in `dir`: top-level keys `top`, the small tire's tables
/// (reduced file `reduced`), then further tables `tables`.
pub fn config(dir: &Path, name: &str, top: &str, reduced: &Path, tables: &str) -> PathBuf {
    let p = dir.join(name);
    std::fs::write(&p, format!("{top}\n{}{tables}", tire_tables(reduced))).unwrap();
    p
}

/// The small tire reduced once per test binary by `flowmbd-tire reduce`: (reduced file,
/// reduce summary).
pub fn shared_reduced() -> &'static (PathBuf, serde_json::Value) {
    static R: OnceLock<(PathBuf, serde_json::Value)> = OnceLock::new();
    R.get_or_init(|| {
        let dir = tmp("shared");
        let file = dir.join("reduced.json");
        let cfg = config(&dir, "tire.toml", "", &file, "");
        let out = run_study("reduce", &["--quiet", "--json"], &cfg, &dir.join("reduce"));
        let s = json_of(&out);
        assert!(file.is_file(), "reduce wrote {}", file.display());
        (file, s)
    })
}

/// Numeric column `col` of a CSV file with a header row.
pub fn csv_column(path: &Path, col: &str) -> Vec<f64> {
    let text = std::fs::read_to_string(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    let mut lines = text.lines();
    let header: Vec<&str> = lines.next().unwrap().split(',').collect();
    let j = header
        .iter()
        .position(|h| *h == col)
        .unwrap_or_else(|| panic!("{}: no column {col} in {header:?}", path.display()));
    lines
        .map(|l| l.split(',').nth(j).unwrap().parse::<f64>().unwrap())
        .collect()
}

/// Assert that `dir/stem.png` is a PNG and `dir/stem.svg` an SVG document.
pub fn assert_plot(dir: &Path, stem: &str) {
    let png = std::fs::read(dir.join(format!("{stem}.png")))
        .unwrap_or_else(|e| panic!("{stem}.png: {e}"));
    assert_eq!(&png[..8], b"\x89PNG\r\n\x1a\n", "{stem}.png signature");
    let svg = std::fs::read_to_string(dir.join(format!("{stem}.svg")))
        .unwrap_or_else(|e| panic!("{stem}.svg: {e}"));
    assert!(svg.contains("<svg"), "{stem}.svg is not SVG");
}
