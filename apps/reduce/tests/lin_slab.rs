//! End-to-end test of `flowmbd-reduce lin-slab` simulation 3 (Lin §7.2.4): the regenerated
//! acceleration tables are written, the CB and MC histories agree to round-off (Lin §6.5.4),
//! the NR emulation follows the source run (the unreduced model it was recorded from), and bad
//! simulation-3 parameters exit with code 2 naming the field.

use crate::common;
use common::{bin, tmp};

#[test]
fn simulation3_writes_tables_and_cb_equals_mc() {
    let dir = tmp("slab", "sim3");
    let cfg = dir.join("sim3.toml");
    std::fs::write(
        &cfg,
        "simulations = [\"emulated\"]\n[params]\nduration_s = 0.2\n",
    )
    .unwrap();
    let out_dir = dir.join("out");
    let out = bin()
        .args(["lin-slab", "--quiet", "--json", "--config"])
        .arg(&cfg)
        .arg("--out")
        .arg(&out_dir)
        .output()
        .unwrap();
    let s = common::json_of(&out);
    // issue 20: the summary says what its numbers mean
    assert!(s["meaning"].as_str().unwrap().contains("Appendix B"), "{s}");
    let cbmc = s["cb_mc_max_difference_m"]["sim3"].as_f64().unwrap();
    assert!(cbmc < 1e-9, "CB vs MC {cbmc}");
    let src = &s["sim3_source"];
    // 0.2 s at 5 ms: 41 samples (t = 0 .. 0.2 s)
    assert_eq!(src["samples"], 41);
    let peak = src["peak_node8_m"].as_f64().unwrap();
    let vs = src["nr_emulation_vs_source_m"].as_f64().unwrap();
    assert!(
        peak > 1e-3 && vs < 0.02 * peak,
        "NR emulation {vs} vs peak {peak}"
    );
    let csv = std::fs::read_to_string(out_dir.join("sim3_tables.csv")).unwrap();
    let mut lines = csv.lines();
    let header = lines.next().unwrap();
    assert_eq!(
        header.split(',').count(),
        13,
        "t + 12 accelerations: {header}"
    );
    assert_eq!(lines.count(), 41);
    for f in ["sim3_node8.csv", "sim3_source_node8.csv", "sim3_eta.png"] {
        assert!(out_dir.join(f).exists(), "{f}");
    }
    // issue 39 item 3: every header in the one unit convention (accelerations `ax16_m_per_s2`)
    assert!(header.starts_with("t_s,ax16_m_per_s2,"), "{header}");
    let bad = flowmbd_cli::output::csv_violations(&out_dir);
    assert!(bad.is_empty(), "outside the CSV convention: {bad:?}");
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn bad_simulation3_parameters_exit_2_naming_the_field() {
    let dir = tmp("slab", "bad");
    for (text, field) in [
        (
            "[params.sim3]\ntable_interval_s = -0.005\n",
            "params.sim3.table_interval_s",
        ),
        ("[params.sim3]\nlink_colour = 3\n", "link_colour"),
        // serde reports an unknown enum variant by file, line and column
        ("[params.sim3]\nlink_direction = \"up\"\n", "bad.toml:2"),
    ] {
        let cfg = dir.join("bad.toml");
        std::fs::write(&cfg, text).unwrap();
        let out = bin()
            .args(["lin-slab", "--quiet", "--config"])
            .arg(&cfg)
            .arg("--out")
            .arg(dir.join("o"))
            .output()
            .unwrap();
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{text}: {err}");
        assert!(err.contains(field), "{field} not in: {err}");
    }
    std::fs::remove_dir_all(&dir).ok();
}
