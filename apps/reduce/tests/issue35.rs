//! Issue 35 reproducers for `flowmbd-reduce`: counts and run lengths from input are refused
//! before anything is allocated or stepped (`reduce --method mc --modes 99999999999` allocated
//! 800 GB; `lin-beam` with `length_m = 1e9` or `area_m2 = 1e-300` hit an index assertion;
//! `lin-slab` with `step_s = 1e-15` ran without end); non-regular and absurdly sized matrix
//! files are refused before reading, also with `--allow-large`; text from a file is echoed
//! escaped; `reduce` prints and reads its configuration.

use crate::common;
use common::{bin, tmp};
use std::path::Path;
use std::process::Output;
use std::time::{Duration, Instant};

fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

/// Exit 2, one line containing every needle, within 20 s.
fn bad_input(o: &Output, t0: Instant, needles: &[&str]) {
    let err = stderr(o);
    assert_eq!(o.status.code(), Some(2), "{err}");
    assert_eq!(err.trim().lines().count(), 1, "{err}");
    for n in needles {
        assert!(err.contains(n), "{n} not in: {err}");
    }
    assert!(t0.elapsed() < Duration::from_secs(20), "{:?}", t0.elapsed());
}

/// `study`'s default configuration with the line `key = ...` replaced by `key = value`.
fn config_with(dir: &Path, study: &str, key: &str, value: &str) -> std::path::PathBuf {
    let o = bin().args([study, "--print-config"]).output().unwrap();
    assert!(o.status.success(), "{}", stderr(&o));
    let text = String::from_utf8_lossy(&o.stdout);
    let mut n = 0;
    let text: Vec<String> = text
        .lines()
        .map(|l| {
            if l.split('=').next().map(str::trim) == Some(key) {
                n += 1;
                format!("{key} = {value}")
            } else {
                l.to_string()
            }
        })
        .collect();
    assert_eq!(n, 1, "{study}: key {key}");
    let f = dir.join(format!("{study}-{key}.toml"));
    std::fs::write(&f, text.join("\n")).unwrap();
    f
}

// issue 35: an eigen solution of a beam whose axial and bending stiffness differ by more than
// 1/eps loses every digit (flowmbd_cases::lin::beam::SLENDERNESS_RANGE)
#[test]
fn lin_beam_with_absurd_proportions_is_refused() {
    let dir = tmp("i35", "linbeam");
    for (key, value, field) in [
        ("length_m", "1e9", "beam.length_m"),
        ("area_m2", "1e-300", "beam.area_m2"),
    ] {
        let f = config_with(&dir, "lin-beam", key, value);
        let t0 = Instant::now();
        let o = bin()
            .args(["lin-beam", "--quiet", "--config", f.to_str().unwrap()])
            .arg("--out")
            .arg(dir.join("out"))
            .output()
            .unwrap();
        bad_input(&o, t0, &[field, "A L^2 / I"]);
    }
    let _ = std::fs::remove_dir_all(dir);
}

// issue 35: step_s = 1e-15 over 1 s is 10^15 RK4 steps (ceiling MAX_SLAB_STEPS = 10^7)
#[test]
fn lin_slab_refuses_endless_runs() {
    let dir = tmp("i35", "linslab");
    let f = config_with(&dir, "lin-slab", "step_s", "1e-15");
    let t0 = Instant::now();
    let o = bin()
        .args([
            "lin-slab",
            "--config",
            f.to_str().unwrap(),
            "--print-config",
        ])
        .output()
        .unwrap();
    bad_input(&o, t0, &["params.step_s", "--allow-large"]);
    let f = config_with(&dir, "lin-slab", "step_s", "2.0");
    let o = bin()
        .args([
            "lin-slab",
            "--config",
            f.to_str().unwrap(),
            "--print-config",
        ])
        .output()
        .unwrap();
    bad_input(&o, t0, &["params.step_s", "longer than the run"]);
    let _ = std::fs::remove_dir_all(dir);
}

// issue 35: `--modes 99999999999` allocated 800 GB (reduction/src/basis.rs)
#[test]
fn huge_mode_counts_are_refused_before_reading() {
    let dir = tmp("i35", "modes");
    let t0 = Instant::now();
    let o = bin()
        .args(["reduce", "--method", "mc", "--modes", "99999999999"])
        .args(["--mass", "M.mtx", "--stiffness", "K.mtx", "--boundary", "1"])
        .arg("--out")
        .arg(dir.join("r.json"))
        .output()
        .unwrap();
    bad_input(&o, t0, &["--modes", "99999999999"]);
    let _ = std::fs::remove_dir_all(dir);
}

// issue 35: `reduce` had no --print-config; the printed configuration reads back
#[test]
fn reduce_prints_and_reads_its_configuration() {
    let dir = tmp("i35", "printcfg");
    let o = bin()
        .args([
            "reduce",
            "--method",
            "guyan",
            "--boundary",
            "1-3",
            "--print-config",
        ])
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", stderr(&o));
    let text = String::from_utf8_lossy(&o.stdout).into_owned();
    assert!(text.contains("method = \"guyan\""), "{text}");
    assert!(text.contains("boundary = \"1-3\""), "{text}");
    let f = dir.join("r.toml");
    std::fs::write(&f, &text).unwrap();
    let o = bin()
        .args(["reduce", "--config", f.to_str().unwrap(), "--print-config"])
        .output()
        .unwrap();
    assert_eq!(String::from_utf8_lossy(&o.stdout), text);
    std::fs::write(&f, "methd = \"cb\"\n").unwrap();
    let t0 = Instant::now();
    let o = bin()
        .args(["reduce", "--config", f.to_str().unwrap(), "--print-config"])
        .output()
        .unwrap();
    bad_input(&o, t0, &["r.toml:1", "methd"]);
    let _ = std::fs::remove_dir_all(dir);
}

/// A symmetric Matrix Market file with the given header size line and one entry.
fn mtx(path: &Path, size_line: &str, entry: &str) {
    std::fs::write(
        path,
        format!("%%MatrixMarket matrix coordinate real symmetric\n{size_line}\n{entry}\n"),
    )
    .unwrap();
}

// issue 35: `--stiffness /dev/urandom` read without end; a 3e9 x 3e9 header with
// --allow-large grew until the machine ran out of memory
#[test]
fn matrix_files_are_bounded_before_reading() {
    let dir = tmp("i35", "mtx");
    let good = dir.join("M.mtx");
    mtx(&good, "3 3 3", "1 1 1.0\n2 2 1.0\n3 3 1.0");
    let t0 = Instant::now();
    let o = bin()
        .args(["reduce", "--boundary", "1", "--dofs-per-node", "1"])
        .arg("--mass")
        .arg(&good)
        .args(["--stiffness", "/dev/urandom", "--out"])
        .arg(dir.join("r.json"))
        .output()
        .unwrap();
    bad_input(&o, t0, &["--stiffness /dev/urandom", "not a regular file"]);
    let huge = dir.join("K.mtx");
    // (the 3e9 x 3e9 needs 24 GB; 1e12 x 1e12 is beyond any machine: 8 TB)
    mtx(&huge, "1000000000000 1000000000000 1", "1 1 1.0");
    let t0 = Instant::now();
    let o = bin()
        .args([
            "reduce",
            "--boundary",
            "1",
            "--dofs-per-node",
            "1",
            "--allow-large",
        ])
        .arg("--mass")
        .arg(&good)
        .arg("--stiffness")
        .arg(&huge)
        .arg("--out")
        .arg(dir.join("r.json"))
        .output()
        .unwrap();
    bad_input(&o, t0, &["K.mtx:2", "memory"]);
    let _ = std::fs::remove_dir_all(dir);
}

// issue 35 item 7: a bad token with a terminal escape sequence is echoed escaped
#[test]
fn tokens_from_files_are_echoed_escaped() {
    let dir = tmp("i35", "escape");
    let k = dir.join("K.mtx");
    mtx(&k, "3 3 1", "1 1 1.0\u{1b}[31mred");
    let t0 = Instant::now();
    let o = bin()
        .args(["reduce", "--boundary", "1", "--dofs-per-node", "1"])
        .arg("--mass")
        .arg(&k)
        .arg("--stiffness")
        .arg(&k)
        .arg("--out")
        .arg(dir.join("r.json"))
        .output()
        .unwrap();
    bad_input(&o, t0, &["K.mtx:3", "\\u{1b}[31mred"]);
    assert!(!stderr(&o).contains('\u{1b}'), "raw escape reached stderr");
    let _ = std::fs::remove_dir_all(dir);
}
