//! Issue 20: every table of every `flowmbd-reduce` study's configuration rejects an unknown key
//! (exit 2, one line naming it).

use crate::common;
use common::{bin, tmp};
use flowmbd_cli::config::{UNKNOWN_KEY, tables_accepting_unknown_keys_by};

#[test]
fn every_table_rejects_an_unknown_key() {
    let dir = tmp("keys", "keys");
    let file = dir.join("v.toml");
    for study in ["modes", "tire-mesh", "lin-beam", "lin-slab"] {
        let out = bin().args([study, "--print-config"]).output().unwrap();
        assert!(out.status.success(), "{study}");
        let text = String::from_utf8(out.stdout).unwrap();
        let holes = tables_accepting_unknown_keys_by(&text, |t| {
            std::fs::write(&file, t).unwrap();
            let out = bin()
                .args([study, "--print-config", "--config"])
                .arg(&file)
                .output()
                .unwrap();
            let err = String::from_utf8_lossy(&out.stderr);
            if !out.status.success() {
                assert_eq!(out.status.code(), Some(2), "{study}: {err}");
                assert!(err.contains(UNKNOWN_KEY), "{study}: {err}");
            }
            out.status.success()
        });
        assert!(holes.is_empty(), "{study}: {holes:?}");
    }
    std::fs::remove_dir_all(&dir).ok();
}
