//! The version of the code that reduces a tire, `CODE_VERSION` of the `tire` crate: the package
//! version and a digest (SHA-256) of the source of everything a reduced tire's numbers depend
//! on — the FE tire and its import (`tire/src/{mesh,model}.rs`, `tire/src/import`), the
//! reduction and the reduced-tire file (`tire/src/reduce.rs`, `tire/src/reduced`), the FE layer
//! (`fe-model/src`), the Craig–Bampton reduction (`reduction/src`), the derivative operators
//! (`flowing/src/derivative`, `flowing/src/grid.rs`) and the locked dependency versions
//! (`Cargo.lock`: faer's eigen solvers). The reduced-tire cache in the user's cache folder is
//! shared by every checkout and release, so a cached tire is reused only by the code that made
//! it (`tire::cache`). A path that does not exist (e.g. a packaged crate without the workspace)
//! enters the digest as missing.

use sha2::{Digest, Sha256};
use std::path::{Path, PathBuf};

/// Paths relative to the workspace root whose content the reduced tire depends on.
const INPUTS: [&str; 10] = [
    "tire/src/mesh.rs",
    "tire/src/model.rs",
    "tire/src/import",
    "tire/src/reduce.rs",
    "tire/src/reduced",
    "fe-model/src",
    "reduction/src",
    "flowing/src/derivative",
    "flowing/src/grid.rs",
    "Cargo.lock",
];

/// Every file under `path` (itself if a file), sorted.
fn files(path: &Path, out: &mut Vec<PathBuf>) {
    if path.is_dir() {
        let mut entries: Vec<PathBuf> = std::fs::read_dir(path)
            .map(|d| d.filter_map(|e| e.ok().map(|e| e.path())).collect())
            .unwrap_or_default();
        entries.sort();
        for e in entries {
            files(&e, out);
        }
    } else {
        out.push(path.to_path_buf());
    }
}

fn main() {
    let manifest = PathBuf::from(std::env::var("CARGO_MANIFEST_DIR").unwrap_or_default());
    let root = manifest.parent().unwrap_or(&manifest).to_path_buf();
    let mut hash = Sha256::new();
    for input in INPUTS {
        let path = root.join(input);
        println!("cargo:rerun-if-changed={}", path.display());
        let mut list = Vec::new();
        files(&path, &mut list);
        for file in list {
            let rel = file.strip_prefix(&root).unwrap_or(&file);
            hash.update(rel.to_string_lossy().as_bytes());
            hash.update([0u8]);
            match std::fs::read(&file) {
                Ok(bytes) => {
                    hash.update((bytes.len() as u64).to_le_bytes());
                    hash.update(&bytes);
                }
                Err(_) => hash.update(b"missing"),
            }
        }
    }
    let digest: String = hash
        .finalize()
        .iter()
        .take(8)
        .map(|b| format!("{b:02x}"))
        .collect();
    let version = std::env::var("CARGO_PKG_VERSION").unwrap_or_default();
    println!(
        "cargo:rustc-env=FLOWMBD_TIRE_CODE_VERSION=flowmbd {version} (reduction source {digest})"
    );
}
