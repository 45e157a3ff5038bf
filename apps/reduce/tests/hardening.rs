//! Reproducers of issue #20 for `flowmbd-reduce` (each panicked, aborted or answered nonsense
//! before): absurd Matrix Market headers, node ranges up to 2⁶⁴ − 1, a `general` file storing
//! one triangle, all-zero and indefinite K, a directory given for a file, and `--json` /
//! `--print-config` into a closed pipe. Every one exits 0 with a correct result or 2 with one
//! line naming the file (and line) or option.

use crate::common;
use common::{bin, tmp};
use std::path::Path;
use std::process::{Command, Output, Stdio};

fn write(dir: &Path, name: &str, text: &str) -> String {
    let p = dir.join(name);
    std::fs::write(&p, text).unwrap();
    p.display().to_string()
}

/// K = [[2, −1], [−1, 2]] N/m, M = I kg: ω² = 1 and 3 rad²/s² (analytical).
const K: &str = "%%MatrixMarket matrix coordinate real symmetric\n2 2 3\n1 1 2\n2 1 -1\n2 2 2\n";
const M: &str = "%%MatrixMarket matrix coordinate real symmetric\n2 2 2\n1 1 1\n2 2 1\n";

fn run(args: &[&str]) -> Output {
    bin().args(args).output().unwrap()
}

fn expect_2(out: &Output, needles: &[&str]) {
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{err}");
    assert_eq!(err.trim_end().lines().count(), 1, "one line: {err}");
    for n in needles {
        assert!(err.contains(n), "`{n}` not in: {err}");
    }
}

#[test]
fn modes_refuses_absurd_headers_one_triangle_and_implausible_k() {
    let dir = tmp("hard", "modes");
    let k = write(&dir, "K.mtx", K);
    let m = write(&dir, "M.mtx", M);
    let out = dir.join("out").display().to_string();
    let modes = |mass: &str, stiff: &str, extra: &[&str]| {
        let mut a = vec!["modes", "--quiet", "--out", &out, "--count", "1"];
        a.extend_from_slice(&["--mass", mass, "--stiffness", stiff]);
        a.extend_from_slice(extra);
        run(&a)
    };
    for (name, text, needles) in [
        (
            "big.mtx",
            "%%MatrixMarket matrix array real general\n18446744073709551615 2\n1\n",
            vec!["big.mtx:2:", "--allow-large"],
        ),
        (
            "arr.mtx",
            "%%MatrixMarket matrix array real general\n1000000 1000000\n1\n",
            vec!["arr.mtx:4:", "truncated"],
        ),
        (
            "sym.mtx",
            "%%MatrixMarket matrix coordinate real symmetric\n100000000 100000000 1\n1 1 1\n",
            vec!["sym.mtx:2:", "ceiling"],
        ),
    ] {
        let p = write(&dir, name, text);
        expect_2(&modes(&p, &k, &[]), &needles);
    }
    // the lower triangle under `general`: refused at line 1 (it read as λ = 2, 2 before)
    let kg = write(&dir, "Kg.mtx", &K.replace("symmetric", "general"));
    expect_2(&modes(&m, &kg, &[]), &["Kg.mtx:1:", "lower triangle"]);
    // all-zero K (gave −7.5e-159 Hz) and indefinite K = [[1, −3], [−3, 1]] (λ = −2, 4)
    let k0 = write(
        &dir,
        "K0.mtx",
        &K.replace(" 2\n", " 0\n").replace("-1", "0"),
    );
    expect_2(&modes(&m, &k0, &[]), &["matrix `K`", "every entry is zero"]);
    let ki = write(
        &dir,
        "Ki.mtx",
        &K.replace(" 2\n", " 1\n").replace("-1", "-3"),
    );
    expect_2(&modes(&m, &ki, &[]), &["matrix `K`", "indefinite", "DOFs"]);
    // a directory for a file
    expect_2(&modes(&m, dir.to_str().unwrap(), &[]), &["is a directory"]);
    // the correct pair: f1 = √1 / 2π Hz (analytical)
    let ok = modes(&m, &k, &["--json"]);
    let s: serde_json::Value = serde_json::from_slice(&ok.stdout).unwrap();
    let f1 = s["frequencies_hz"][0].as_f64().unwrap();
    assert!(
        (f1 - 1.0 / (2.0 * std::f64::consts::PI)).abs() < 1e-12,
        "{f1}"
    );
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn reduce_refuses_huge_node_ranges_and_indefinite_k() {
    let dir = tmp("hard", "reduce");
    let k = write(&dir, "K.mtx", K);
    let m = write(&dir, "M.mtx", M);
    let o = dir.join("o.json").display().to_string();
    let reduce = |stiff: &str, boundary: &str| {
        run(&[
            "reduce",
            "--quiet",
            "--mass",
            &m,
            "--stiffness",
            stiff,
            "--out",
            &o,
            "--dofs-per-node",
            "1",
            "--boundary",
            boundary,
        ])
    };
    expect_2(
        &reduce(&k, "1-18446744073709551615"),
        &["--boundary", "18446744073709551615", "2 nodes"],
    );
    expect_2(&reduce(&k, "1-4000000000"), &["--boundary", "4000000000"]);
    expect_2(&reduce(&k, "1-18446744073709551616"), &["--boundary"]);
    let ki = write(
        &dir,
        "Ki.mtx",
        &K.replace(" 2\n", " 1\n").replace("-1", "-3"),
    );
    expect_2(&reduce(&ki, "1"), &["--stiffness", "indefinite"]);
    assert!(!Path::new(&o).exists(), "no model written on bad input");
    assert_eq!(reduce(&k, "1").status.code(), Some(0));
    std::fs::remove_dir_all(&dir).ok();
}

/// `--json` and `--print-config` into a reader that closes at once (`| true`): exit 0, no
/// "Broken pipe" panic. The reader is a child whose stdin we drop before the binary writes.
#[test]
fn closed_stdout_exits_quietly() {
    let dir = tmp("hard", "pipe");
    let k = write(&dir, "K.mtx", K);
    let m = write(&dir, "M.mtx", M);
    let out = dir.join("out").display().to_string();
    let o = dir.join("o.json").display().to_string();
    let cases: Vec<Vec<&str>> = vec![
        vec!["modes", "--print-config"],
        vec![
            "modes",
            "--quiet",
            "--json",
            "--out",
            &out,
            "--mass",
            &m,
            "--stiffness",
            &k,
            "--count",
            "1",
        ],
        vec![
            "reduce",
            "--json",
            "--mass",
            &m,
            "--stiffness",
            &k,
            "--out",
            &o,
            "--dofs-per-node",
            "1",
            "--boundary",
            "1",
        ],
    ];
    for args in cases {
        // a pipe whose read end is closed before the binary starts writing
        let (reader, writer) = std::io::pipe().unwrap();
        drop(reader);
        let res = Command::new(env!("CARGO_BIN_EXE_flowmbd-reduce"))
            .args(&args)
            .stdout(Stdio::from(writer))
            .stderr(Stdio::piped())
            .output()
            .unwrap();
        let err = String::from_utf8_lossy(&res.stderr);
        assert_eq!(res.status.code(), Some(0), "{args:?}: {err}");
        assert!(
            !err.contains("panicked") && !err.contains("Broken pipe"),
            "{err}"
        );
    }
    std::fs::remove_dir_all(&dir).ok();
}

/// Issue 20 item 5: every study's summary says what its numbers mean (`tire-mesh`, `modes` and
/// `lin-slab` are checked in their end-to-end tests, `lin-beam` and `reduce` here). The
/// reduced pair of the 2-DOF chain with DOF 1 kept and one mode (Craig–Bampton spans the whole
/// space) has the full model's ω² = 1, 3 rad²/s² (analytical).
#[test]
fn every_summary_says_what_its_numbers_mean() {
    let dir = tmp("hard", "meaning");
    let out = dir.join("lb").display().to_string();
    let lb = run(&["lin-beam", "--quiet", "--json", "--out", &out]);
    assert_eq!(lb.status.code(), Some(0));
    let s: serde_json::Value = serde_json::from_slice(&lb.stdout).unwrap();
    assert!(
        s["meaning"]
            .as_str()
            .unwrap_or_default()
            .contains("Appendix A"),
        "{s}"
    );
    let summary: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("lb/summary.json")).unwrap())
            .unwrap();
    assert_eq!(summary["meaning"], s["meaning"]);
    // issue 39 item 3: `profiles.csv` and `frequencies.csv` follow the one CSV convention, the
    // DOF, set and mode indices written as integers
    let bad = flowmbd_cli::output::csv_violations(&dir.join("lb"));
    assert!(bad.is_empty(), "outside the CSV convention: {bad:?}");
    let freqs = std::fs::read_to_string(dir.join("lb/frequencies.csv")).unwrap();
    assert!(
        freqs.starts_with("set_index,mode_index,frequency_Hz\n"),
        "{freqs}"
    );
    let k = write(&dir, "K.mtx", K);
    let m = write(&dir, "M.mtx", M);
    let o = dir.join("o.json").display().to_string();
    let r = run(&[
        "reduce",
        "--quiet",
        "--json",
        "--mass",
        &m,
        "--stiffness",
        &k,
        "--out",
        &o,
        "--dofs-per-node",
        "1",
        "--boundary",
        "1",
        "--modes",
        "1",
    ]);
    assert_eq!(
        r.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&r.stderr)
    );
    let s: serde_json::Value = serde_json::from_slice(&r.stdout).unwrap();
    assert!(
        s["meaning"]
            .as_str()
            .unwrap_or_default()
            .contains("n_reduced"),
        "{s}"
    );
    let f: Vec<f64> = s["frequencies_hz"]
        .as_array()
        .unwrap()
        .iter()
        .map(|v| v.as_f64().unwrap())
        .collect();
    let two_pi = 2.0 * std::f64::consts::PI;
    assert_eq!(f.len(), 2, "{f:?}");
    assert!((f[0] - 1.0 / two_pi).abs() < 1e-9, "{f:?}");
    assert!((f[1] - 3f64.sqrt() / two_pi).abs() < 1e-9, "{f:?}");
    std::fs::remove_dir_all(&dir).ok();
}

/// Issue 20 item 2: `--allow-large` is a flag of every study and raises the documented ceilings
/// 1000-fold: a generated tire of 8000 × 36 × 2 = 576 000 hexahedra exceeds MAX_TIRE_ELEMENTS =
/// 250 000 (refused, naming the field) and is accepted with the flag (`--print-config`
/// validates and computes nothing).
#[test]
fn allow_large_raises_the_tire_element_ceiling() {
    let dir = tmp("hard", "large");
    let cfg = write(&dir, "t.toml", "[tire]\ncircumferential_divisions = 8000\n");
    expect_2(
        &run(&["tire-mesh", "--config", &cfg, "--print-config"]),
        &["tire.circumferential_divisions", "576000", "--allow-large"],
    );
    let ok = run(&[
        "tire-mesh",
        "--config",
        &cfg,
        "--print-config",
        "--allow-large",
    ]);
    assert_eq!(
        ok.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&ok.stderr)
    );
    assert!(String::from_utf8_lossy(&ok.stdout).contains("circumferential_divisions = 8000"));
    std::fs::remove_dir_all(&dir).ok();
}
