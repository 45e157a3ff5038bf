//! `flowmbd-tire fmu` (issue 38 item 1): the written `.fmu` is a ZIP archive (read here with a
//! reader of its own written from PKWARE's APPNOTE.TXT 6.3, §4.3: end of central directory,
//! central directory, local headers; CRC-32 by `crc32fast`) holding `modelDescription.xml`, the
//! compiled library under `binaries/<platform>/` and the reduced tire and rig under
//! `resources/` (the layout of FMI 3.0 §2.5); bad input exits 2 with one line naming the field.

use crate::common::{config, outcome, run_study, shared_reduced, tire_tables, tmp};
use std::collections::BTreeMap;
use std::path::Path;

fn u16_at(b: &[u8], i: usize) -> usize {
    u16::from_le_bytes([b[i], b[i + 1]]) as usize
}

fn u32_at(b: &[u8], i: usize) -> u32 {
    u32::from_le_bytes([b[i], b[i + 1], b[i + 2], b[i + 3]])
}

/// The entries of the ZIP archive `zip` (name → bytes), stored entries only (method 0), each
/// entry's CRC-32 and sizes checked against the central directory.
fn unzip(zip: &[u8]) -> BTreeMap<String, Vec<u8>> {
    // end of central directory record: signature 0x06054b50, found from the end (no comment)
    let eocd = (0..=zip.len() - 22)
        .rev()
        .find(|&i| u32_at(zip, i) == 0x0605_4b50)
        .expect("end of central directory record");
    let count = u16_at(zip, eocd + 10);
    let mut at = u32_at(zip, eocd + 16) as usize;
    let mut out = BTreeMap::new();
    for _ in 0..count {
        assert_eq!(u32_at(zip, at), 0x0201_4b50, "central directory header");
        let method = u16_at(zip, at + 10);
        let crc = u32_at(zip, at + 16);
        let size = u32_at(zip, at + 20) as usize;
        assert_eq!(size, u32_at(zip, at + 24) as usize, "stored: sizes agree");
        let (n, extra, comment) = (
            u16_at(zip, at + 28),
            u16_at(zip, at + 30),
            u16_at(zip, at + 32),
        );
        let local = u32_at(zip, at + 42) as usize;
        let name = String::from_utf8(zip[at + 46..at + 46 + n].to_vec()).unwrap();
        assert_eq!(method, 0, "{name}: stored");
        assert_eq!(u32_at(zip, local), 0x0403_4b50, "{name}: local header");
        let data = local + 30 + u16_at(zip, local + 26) + u16_at(zip, local + 28);
        let bytes = zip[data..data + size].to_vec();
        assert_eq!(crc32fast::hash(&bytes), crc, "{name}: CRC-32");
        out.insert(name, bytes);
        at += 46 + n + extra + comment;
    }
    out
}

/// The FMU of the small tire: a ZIP with the model description naming every variable of the
/// summary, the library packed byte for byte under `binaries/x86_64-linux/`, the reduced tire
/// (JSON) and the rig (TOML, with the configured load) under `resources/`; the summary states the
/// frame, the internal step (= `rig.rolling.time_step`) and the start values.
#[test]
fn fmu_is_a_zip_with_description_binary_and_resources() {
    let (file, _) = shared_reduced();
    let dir = tmp("fmu");
    let cfg = config(
        &dir,
        "fmu.toml",
        "",
        file,
        "[rig]\nload = 4000.0\nspeed_kmh = 30.0\n[rig.rolling]\ntime_step = 2.5e-4\n",
    );
    let out = dir.join("out");
    let o = run_study("fmu", &["--quiet", "--json"], &cfg, &out);
    let s = crate::common::json_of(&o);
    let zip = std::fs::read(out.join("tire.fmu")).expect("tire.fmu written");
    assert_eq!(s["fmu_bytes"].as_u64(), Some(zip.len() as u64));
    let on_disk: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap()).unwrap();
    assert_eq!(on_disk["internal_step_s"], s["internal_step_s"]);
    let entries = unzip(&zip);
    let names: Vec<&str> = entries.keys().map(String::as_str).collect();
    // the model description: FMI 3.0 co-simulation, every variable of the summary
    let xml = String::from_utf8(entries["modelDescription.xml"].clone()).unwrap();
    assert!(xml.contains("fmiVersion=\"3.0\""), "{xml}");
    assert!(xml.contains("<CoSimulation modelIdentifier=\"flowmbd_tire_fmu\""));
    assert!(xml.contains("fixedInternalStepSize=\"2.5e-4\""), "{xml}");
    let vars = s["variables"].as_array().unwrap();
    assert_eq!(vars.len(), 19);
    for v in vars {
        let tag = format!(
            "name=\"{}\" valueReference=\"{}\"",
            v["name"].as_str().unwrap(),
            v["value_reference"]
        );
        assert!(xml.contains(&tag), "{tag} not in the model description");
    }
    let start = |name: &str| {
        vars.iter()
            .find(|v| v["name"] == name)
            .and_then(|v| v["start"].as_f64())
    };
    assert_eq!(start("load"), Some(4000.0));
    assert_eq!(start("time_step"), Some(2.5e-4));
    assert_eq!(start("vx"), Some(30.0 / 3.6));
    assert_eq!(start("z"), s["start"]["height"].as_f64());
    assert_eq!(start("Fx"), None, "outputs have no start");
    assert_eq!(s["internal_step_s"].as_f64(), Some(2.5e-4));
    assert!(s["frame"].as_str().unwrap().contains("ISO 8855"));
    // the deflected start: below the unloaded radius by a positive deflection
    let height = s["start"]["height"].as_f64().unwrap();
    assert!(height > 0.4 && height < 0.522, "start height {height} m");
    // the binary: the packed library, byte for byte, an ELF shared object
    let lib = std::fs::read(s["library"].as_str().unwrap()).unwrap();
    let bin = "binaries/x86_64-linux/flowmbd_tire_fmu.so";
    #[cfg(all(target_arch = "x86_64", target_os = "linux"))]
    {
        assert!(entries.contains_key(bin), "{bin} not in {names:?}");
        assert_eq!(&entries[bin][..4], b"\x7fELF");
        assert!(entries[bin] == lib, "{bin} is not the library");
    }
    let _ = (bin, lib);
    // the resources: the reduced tire and the rig with the configured load
    let tire: serde_json::Value = serde_json::from_slice(&entries["resources/tire.json"]).unwrap();
    assert!(tire.is_object(), "{names:?}");
    let rig: toml::Value =
        toml::from_str(std::str::from_utf8(&entries["resources/rig.toml"]).unwrap()).unwrap();
    assert_eq!(rig["load"].as_float(), Some(4000.0));
    assert_eq!(
        s["contact_nodes"].as_u64(),
        Some(crate::common::CONTACT as u64)
    );
    assert_eq!(names.len(), 4, "{names:?}");
    std::fs::remove_dir_all(&dir).ok();
}

/// Bad input: exit 2 and one line on stderr naming the field (the library option or variable,
/// the rig's keys); no FMU written.
#[test]
fn fmu_bad_input_exits_2_naming_the_field() {
    let (file, _) = shared_reduced();
    let dir = tmp("fmu-bad");
    let missing = dir.join("none.so").display().to_string();
    // (extra args, FLOWMBD_FMU_LIB, rig tables, expected in the message)
    let cases: Vec<(Vec<&str>, Option<&str>, &str, &str)> = vec![
        (vec!["--library", &missing], None, "", "--library"),
        (vec![], Some(&missing), "", "FLOWMBD_FMU_LIB"),
        (vec![], None, "[rig]\nload = -1.0\n", "rig.load"),
        (
            vec![],
            None,
            "[rig.rolling]\ntime_step = 0.0\n",
            "rig.rolling.time_step",
        ),
        (vec![], None, "[rig]\nsped_kmh = 30.0\n", "sped_kmh"),
        (vec![], None, "cleat_phases = 2\n", "cleat_phases"),
    ];
    for (i, (extra, env, tables, want)) in cases.iter().enumerate() {
        let cfg = dir.join(format!("bad{i}.toml"));
        let text = if tables.starts_with('[') {
            format!("{}{tables}", tire_tables(file))
        } else {
            format!("{tables}{}", tire_tables(file))
        };
        std::fs::write(&cfg, text).unwrap();
        let out = dir.join(format!("o{i}"));
        let mut cmd = crate::common::bin();
        cmd.args(["fmu", "--quiet", "--config"])
            .arg(&cfg)
            .arg("--out")
            .arg(&out)
            .args(extra);
        match env {
            Some(v) => cmd.env("FLOWMBD_FMU_LIB", v),
            None => cmd.env_remove("FLOWMBD_FMU_LIB"),
        };
        let (code, _, err) = outcome(&cmd.output().unwrap());
        assert_eq!(code, 2, "case {i}: exit {code}: {err}");
        assert_eq!(err.trim_end().lines().count(), 1, "case {i}: {err}");
        assert!(err.contains(want), "case {i}: `{want}` not in: {err}");
        assert!(
            !out.join("tire.fmu").exists(),
            "case {i}: an FMU was written"
        );
    }
    std::fs::remove_dir_all(&dir).ok();
}

/// The executable away from its build folder (a copy in a folder of its own) finds no library:
/// exit 2, naming `library` and the command that builds it.
#[test]
fn fmu_without_a_library_says_how_to_build_it() {
    let (file, _) = shared_reduced();
    let dir = tmp("fmu-nolib");
    let exe = dir.join("flowmbd-tire");
    std::fs::copy(env!("CARGO_BIN_EXE_flowmbd-tire"), &exe).unwrap();
    let cfg = config(&dir, "fmu.toml", "", file, "");
    let o = std::process::Command::new(&exe)
        .args(["fmu", "--quiet", "--config"])
        .arg(&cfg)
        .arg("--out")
        .arg(dir.join("out"))
        .env_remove("FLOWMBD_FMU_LIB")
        .output()
        .unwrap();
    let (code, _, err) = outcome(&o);
    assert_eq!(code, 2, "{err}");
    assert!(err.contains("library"), "{err}");
    assert!(
        err.contains("cargo build --release -p flowmbd-tire-fmu"),
        "{err}"
    );
    assert!(!Path::new(&dir.join("out/tire.fmu")).exists());
    std::fs::remove_dir_all(&dir).ok();
}
