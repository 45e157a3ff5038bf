//! The reduced-tire file and the tire's fingerprint (issue #35, item 4 and the Python reader):
//! * a saved tire loads bit-identically (reference: the tire itself) and records the code
//!   version that reduced it;
//! * a file changed after it was written — `k` doubled as valid JSON, a truncated copy, an
//!   older format version — is refused with the reason (the checksum is SHA-256 of the body);
//! * a device (`/dev/zero`), a folder or a file over the size ceiling is refused before it is
//!   read;
//! * the fingerprint of an imported tire follows the files' contents, not their paths;
//! * an ABAQUS node set with `GENERATE` is read as its range, not as the three numbers.

use serde_json::Value;
use std::path::{Path, PathBuf};
use tire::{
    CODE_VERSION, ImportFiles, ImportFormat, ReducedTire, ReductionConfig, TireError, TireSource,
    coarse_tire_config, generated_tire,
};

fn scratch(test: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("flowmbd-tire-file-{test}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

fn small_tire() -> ReducedTire {
    let source = TireSource {
        generator: coarse_tire_config(24, 8, 40.0),
        reduction: ReductionConfig {
            contact_nodes: 12,
            free_modes: 20,
            ..ReductionConfig::default()
        },
        ..TireSource::default()
    };
    let fe = source.fe_model().unwrap();
    source.reduce_fe(&fe).unwrap().0
}

fn refused(path: &Path) -> String {
    match ReducedTire::load(path) {
        Err(TireError::File { reason, .. }) => reason,
        Err(e) => panic!("{}: not a file error: {e}", path.display()),
        Ok(_) => panic!("{}: accepted", path.display()),
    }
}

#[test]
fn saved_tire_round_trips_and_changed_files_are_refused() {
    let dir = scratch("round-trip");
    let red = small_tire();
    assert_eq!(red.code_version, CODE_VERSION);
    assert!(red.source.contains("\"generator\""), "{}", red.source);
    let file = dir.join("r.json");
    red.save(&file).unwrap();
    let back = ReducedTire::load(&file).unwrap();
    let bits = |m: &faer::Mat<f64>| -> Vec<u64> {
        (0..m.ncols())
            .flat_map(|j| (0..m.nrows()).map(move |i| (i, j)))
            .map(|(i, j)| m[(i, j)].to_bits())
            .collect()
    };
    for (a, b) in [
        (&red.m, &back.m),
        (&red.k, &back.k),
        (&red.g1, &back.g1),
        (&red.tc, &back.tc),
    ] {
        assert_eq!(bits(a), bits(b));
    }
    assert_eq!(
        (&back.source, &back.code_version),
        (&red.source, &red.code_version)
    );

    // k doubled, still valid JSON: the checksum refuses it
    let mut doc: Value = serde_json::from_str(&std::fs::read_to_string(&file).unwrap()).unwrap();
    for v in doc["tire"]["k"]["data"].as_array_mut().unwrap() {
        *v = Value::from(2.0 * v.as_f64().unwrap());
    }
    let doubled = dir.join("doubled.json");
    std::fs::write(&doubled, serde_json::to_string(&doc).unwrap()).unwrap();
    assert!(refused(&doubled).contains("checksum mismatch"));

    // truncated
    let text = std::fs::read_to_string(&file).unwrap();
    let cut = dir.join("cut.json");
    std::fs::write(&cut, &text[..text.len() / 3]).unwrap();
    assert!(refused(&cut).contains("not JSON"));

    // the version-2 layout (fields at the top level, no checksum)
    let mut v2 = doc["tire"].clone();
    v2["format"] = Value::from("flowmbd-reduced-tire");
    v2["version"] = Value::from(2);
    let old = dir.join("v2.json");
    std::fs::write(&old, serde_json::to_string(&v2).unwrap()).unwrap();
    let why = refused(&old);
    assert!(
        why.contains("version` is 2")
            && why.contains(&format!("version {}", tire::reduced::VERSION)),
        "{why}"
    );

    // not a regular file, refused before reading
    #[cfg(unix)]
    assert!(refused(Path::new("/dev/zero")).contains("not a regular file"));
    assert!(refused(&dir).contains("directory"));
    std::fs::remove_dir_all(&dir).ok();
}

/// Two copies of the same imported tire at different paths have one fingerprint; editing a
/// file in place changes it (the reproducer: the cache key held the paths, so an edited tire
/// reused the old reduction).
#[test]
fn fingerprint_follows_content_not_path() {
    let dir = scratch("fingerprint");
    let fe = generated_tire(&coarse_tire_config(24, 8, 40.0)).unwrap();
    let write = |sub: &str, k_scale: f64| -> ImportFiles {
        let d = dir.join(sub);
        std::fs::create_dir_all(&d).unwrap();
        let p = |n: &str| d.join(n).display().to_string();
        let n = fe.n_dofs();
        let k: Vec<String> = fe_model::sparse::triplets(fe.stiffness.as_ref())
            .filter(|&(r, c, _)| r >= c)
            .map(|(r, c, v)| format!("{} {} {:e}", r + 1, c + 1, k_scale * v))
            .collect();
        std::fs::write(
            p("K.mtx"),
            format!(
                "%%MatrixMarket matrix coordinate real symmetric\n{n} {n} {}\n{}\n",
                k.len(),
                k.join("\n")
            ),
        )
        .unwrap();
        let m: Vec<String> = (0..n)
            .map(|d| format!("{} {} {:e}", d + 1, d + 1, fe.mass[d]))
            .collect();
        std::fs::write(
            p("M.mtx"),
            format!(
                "%%MatrixMarket matrix coordinate real symmetric\n{n} {n} {n}\n{}\n",
                m.join("\n")
            ),
        )
        .unwrap();
        let lines = |v: Vec<String>| v.join("\n") + "\n";
        std::fs::write(
            p("nodes.txt"),
            lines(
                fe.nodes
                    .iter()
                    .map(|x| format!("{:e} {:e} {:e}", x[0], x[1], x[2]))
                    .collect(),
            ),
        )
        .unwrap();
        std::fs::write(
            p("rim.txt"),
            lines(fe.rim.iter().map(|i| i.to_string()).collect()),
        )
        .unwrap();
        std::fs::write(
            p("patch.txt"),
            lines(fe.candidates.iter().map(|i| i.to_string()).collect()),
        )
        .unwrap();
        ImportFiles {
            format: ImportFormat::MatrixMarket,
            stiffness: p("K.mtx"),
            mass: p("M.mtx"),
            nodes: p("nodes.txt"),
            rim_nodes: p("rim.txt"),
            patch_nodes: p("patch.txt"),
        }
    };
    let source = |files: ImportFiles| TireSource {
        import: Some(files),
        ..TireSource::default()
    };
    let a = source(write("a", 1.0));
    let b = source(write("b", 1.0));
    assert_ne!(a.import, b.import, "different paths");
    assert_eq!(a.fingerprint().unwrap(), b.fingerprint().unwrap());
    assert!(
        !a.fingerprint()
            .unwrap()
            .contains(&dir.display().to_string())
    );
    // K edited in place: another fingerprint, and another cache file
    let (fa, pa) = (a.fingerprint().unwrap(), a.reduced_path().unwrap());
    write("a", 2.0);
    assert_ne!(a.fingerprint().unwrap(), fa);
    assert_ne!(a.reduced_path().unwrap(), pa);
    std::fs::remove_dir_all(&dir).ok();
}

/// `*NSET, NSET=RIM, GENERATE` / `1, 432, 1` names the labels 1..432 (ABAQUS), not the three
/// numbers {1, 432, 1} (steps and mixed lines: the unit tests of `import::read`). Reference: the imported set equals the generated range (the rim set of a tire whose
/// labels are 1-based node numbers).
#[test]
fn abaqus_generate_sets_are_ranges() {
    let dir = scratch("generate");
    let fe = generated_tire(&coarse_tire_config(24, 8, 40.0)).unwrap();
    let p = |n: &str| dir.join(n).display().to_string();
    // labels 1..n in node order; K and M as ABAQUS *MATRIX OUTPUT lines (one triangle)
    let mut k = String::new();
    for (r, c, v) in fe_model::sparse::triplets(fe.stiffness.as_ref()) {
        if r >= c {
            k += &format!(
                "{},{},{},{},{v:e}\n",
                r / 3 + 1,
                r % 3 + 1,
                c / 3 + 1,
                c % 3 + 1
            );
        }
    }
    std::fs::write(p("K.mtx"), k).unwrap();
    let m: String = (0..fe.n_dofs())
        .map(|d| format!("{0},{1},{0},{1},{2:e}\n", d / 3 + 1, d % 3 + 1, fe.mass[d]))
        .collect();
    std::fs::write(p("M.mtx"), m).unwrap();
    let nodes: String = fe
        .nodes
        .iter()
        .enumerate()
        .map(|(i, x)| format!("{}, {:e}, {:e}, {:e}\n", i + 1, x[0], x[1], x[2]))
        .collect();
    std::fs::write(p("nodes.inp"), format!("*NODE\n{nodes}")).unwrap();
    // the rim as runs of consecutive labels written as GENERATE ranges
    let mut rim: Vec<usize> = fe.rim.iter().map(|i| i + 1).collect();
    rim.sort_unstable();
    let mut runs = Vec::new();
    for &l in &rim {
        match runs.last_mut() {
            Some((_, last)) if *last + 1 == l => *last = l,
            _ => runs.push((l, l)),
        }
    }
    let generated: String = runs.iter().map(|(a, b)| format!("{a}, {b}, 1\n")).collect();
    std::fs::write(
        p("rim.inp"),
        format!("*NSET, NSET=RIM, GENERATE\n{generated}"),
    )
    .unwrap();
    let patch: String = fe
        .candidates
        .iter()
        .map(|i| format!("{}\n", i + 1))
        .collect();
    std::fs::write(p("patch.inp"), format!("*NSET, NSET=PATCH\n{patch}")).unwrap();
    let files = ImportFiles {
        format: ImportFormat::Abaqus,
        stiffness: p("K.mtx"),
        mass: p("M.mtx"),
        nodes: p("nodes.inp"),
        rim_nodes: p("rim.inp"),
        patch_nodes: p("patch.inp"),
    };
    let imp = tire::imported_tire(&files).unwrap();
    let mut got = imp.rim.clone();
    got.sort_unstable();
    let mut want = fe.rim.clone();
    want.sort_unstable();
    assert_eq!(got, want);
    // an empty range is refused with its line
    std::fs::write(p("bad.inp"), "*NSET, NSET=S, GENERATE\n8, 2, 1\n").unwrap();
    let err = tire::imported_tire(&ImportFiles {
        patch_nodes: p("bad.inp"),
        ..files
    })
    .unwrap_err()
    .to_string();
    assert!(
        err.contains("bad.inp:2") && err.contains("last >= first"),
        "{err}"
    );
    std::fs::remove_dir_all(&dir).ok();
}
