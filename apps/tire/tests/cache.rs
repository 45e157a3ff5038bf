//! The reduced-tire cache keyed and verified by content (issue #35, item 4), on the imported
//! coarse tire with `reduced_file = "cache"` and the cache folder in a scratch directory
//! (`XDG_CACHE_HOME`):
//! * the reproducer "imported tire edited in place reused the old reduced tire": after K is
//!   doubled in place the tire is reduced again and its frequencies are √2 times the first
//!   (independent reference: scaling K by 2 scales every ω² by 2), the full FE model's too;
//! * the reproducer "a cache file whose `k` is doubled (valid JSON) was used": the checksum
//!   refuses it, the tire is reduced again and the file replaced (the same frequencies as the
//!   first reduction, bitwise), and the next run loads it; a truncated file likewise; a file
//!   named by the user with a doubled `k` is refused (exit 2);
//! * nothing but the finished cache files is left in the cache folder (written through a
//!   temporary file renamed on completion).

use crate::common;
use common::export::{Export, refused};
use common::{bin, outcome};
use serde_json::Value;
use std::path::{Path, PathBuf};

/// `modes --json` of the import (stiffness `k`) with the cache folder `cache`: (exit code,
/// summary, stderr).
fn modes(e: &Export, cache: &Path, case: &str, reduced_file: &str) -> (i32, Value, String) {
    let cfg = e.path(&format!("{case}.toml"));
    let tables = e.tables(reduced_file, "K.mtx", "M.mtx", "nodes.txt", "patch.txt");
    std::fs::write(&cfg, format!("count = 8\n{tables}")).unwrap();
    let out = bin()
        .env("XDG_CACHE_HOME", cache)
        .args(["modes", "--json", "--config"])
        .arg(&cfg)
        .arg("--out")
        .arg(e.path(&format!("out-{case}")))
        .output()
        .unwrap();
    let (code, stdout, err) = outcome(&out);
    let summary = serde_json::from_str(&stdout).unwrap_or(Value::Null);
    (code, summary, err)
}

fn hz(s: &Value, key: &str) -> Vec<f64> {
    s[key]
        .as_array()
        .unwrap_or_else(|| panic!("{key} in {s}"))
        .iter()
        .map(|v| v.as_f64().unwrap())
        .collect()
}

/// The files in the cache folder.
fn cached(cache: &Path) -> Vec<PathBuf> {
    let dir = cache.join("flowmbd").join("tire");
    let mut v: Vec<PathBuf> = std::fs::read_dir(dir)
        .map(|d| d.map(|e| e.unwrap().path()).collect())
        .unwrap_or_default();
    v.sort();
    v
}

/// `k` of a reduced-tire file multiplied by 2, written back as valid JSON.
fn double_k(file: &Path, to: &Path) {
    let mut doc: Value = serde_json::from_str(&std::fs::read_to_string(file).unwrap()).unwrap();
    for v in doc["tire"]["k"]["data"].as_array_mut().unwrap() {
        *v = Value::from(2.0 * v.as_f64().unwrap());
    }
    std::fs::write(to, serde_json::to_string(&doc).unwrap()).unwrap();
}

#[test]
fn cache_follows_the_content_and_replaces_bad_files() {
    let e = Export::new("cache");
    let cache = e.path("cache-home");
    // first run: reduced and cached; second: loaded, the same numbers
    let (code, first, err) = modes(&e, &cache, "a", "cache");
    assert_eq!(code, 0, "{err}");
    assert!(
        err.contains("reducing the imported tire (saved to"),
        "{err}"
    );
    let before = cached(&cache);
    assert_eq!(before.len(), 1, "{before:?}");
    let (code, again, err) = modes(&e, &cache, "b", "cache");
    assert_eq!(code, 0, "{err}");
    assert!(!err.contains("reducing"), "{err}");
    assert_eq!(hz(&again, "reduced_hz"), hz(&first, "reduced_hz"));

    // K doubled in place (same path): another tire, reduced again; ω scales by √2
    let k2: Vec<_> = e
        .stiffness()
        .into_iter()
        .map(|(r, c, v)| (r, c, 2.0 * v))
        .collect();
    e.write("K.mtx", &common::export::mtx(e.n(), &k2));
    let (code, stiff, err) = modes(&e, &cache, "c", "cache");
    assert_eq!(code, 0, "{err}");
    assert!(err.contains("reducing the imported tire"), "{err}");
    for key in ["reduced_hz", "full_hz"] {
        for (a, b) in hz(&first, key).iter().zip(hz(&stiff, key)) {
            assert!((b / a - 2f64.sqrt()).abs() < 1e-8, "{key}: {a} -> {b}");
        }
    }
    let files = cached(&cache);
    assert_eq!(files.len(), 2, "{files:?}");
    let stiff_file = files.into_iter().find(|f| !before.contains(f)).unwrap();

    // the stiff tire's cache file with `k` doubled (valid JSON): refused by its checksum,
    // replaced by a fresh reduction (the same numbers), then loaded
    double_k(&stiff_file, &stiff_file);
    let (code, redone, err) = modes(&e, &cache, "e", "cache");
    assert_eq!(code, 0, "{err}");
    assert!(
        err.contains("reducing the imported tire again") && err.contains("checksum mismatch"),
        "{err}"
    );
    assert_eq!(hz(&redone, "reduced_hz"), hz(&stiff, "reduced_hz"));
    let (code, loaded, err) = modes(&e, &cache, "f", "cache");
    assert_eq!(code, 0, "{err}");
    assert!(!err.contains("reducing"), "{err}");
    assert_eq!(hz(&loaded, "reduced_hz"), hz(&stiff, "reduced_hz"));

    // a truncated cache file (a run killed while writing it in place, before this version)
    let text = std::fs::read(&stiff_file).unwrap();
    std::fs::write(&stiff_file, &text[..text.len() / 2]).unwrap();
    let (code, redone, err) = modes(&e, &cache, "g", "cache");
    assert_eq!(code, 0, "{err}");
    assert!(err.contains("reducing the imported tire again"), "{err}");
    assert_eq!(hz(&redone, "reduced_hz"), hz(&stiff, "reduced_hz"));

    // a file named by the user is never replaced: a doubled `k` is refused (exit 2)
    let mine = e.path("mine.json");
    double_k(&stiff_file, &mine);
    let (code, _, err) = modes(&e, &cache, "h", mine.to_str().unwrap());
    refused(
        "user file with doubled k",
        (code, err),
        &["tire.reduced_file", "mine.json", "checksum mismatch"],
    );

    // only the two finished cache files: no temporary file left behind
    let files = cached(&cache);
    assert_eq!(files.len(), 2, "{files:?}");
    assert!(
        files
            .iter()
            .all(|f| f.extension().is_some_and(|x| x == "json"))
    );
    std::fs::remove_dir_all(&e.dir).ok();
}
