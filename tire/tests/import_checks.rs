//! The checks of an imported tire that catch the easy mistakes (issue #39, item 7), one test
//! per check on a small crafted model: three rings of twelve nodes in the wheel plane (rim at
//! 0.30 m, sidewall at 0.40 m, tread at 0.50 m about the wheel axis `y`) joined by isotropic
//! springs along the rings and between them, written by hand as Matrix Market files. The
//! reference of every test is the crafted model itself: as written it imports (the first
//! test), and each test breaks exactly one thing the check is about, so the typed error
//! (`tire::ImportCheckError`) must name that file (and line or node) and nothing else fails.

use std::f64::consts::PI;
use std::path::{Path, PathBuf};
use tire::{ImportCheckError, ImportFiles, ImportFormat, TireError, imported_tire};

const PER_RING: usize = 12;
const RADII: [f64; 3] = [0.30, 0.40, 0.50];
/// Spring stiffness \[N/m\].
const K: f64 = 1e5;

/// A scratch folder of this test process.
fn scratch(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!(
        "flowmbd-tire-import-checks-{}-{name}",
        std::process::id()
    ));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

/// Node `j` of ring `r` (ring-major).
fn node(r: usize, j: usize) -> usize {
    r * PER_RING + j % PER_RING
}

/// The crafted model: node coordinates (θ from +z towards +x, Ribaric's wheel frame: node `j`
/// at θ = 30° j, so node 6 of a ring is at the road point θ = π) and the springs.
fn model() -> (Vec<[f64; 3]>, Vec<(usize, usize)>) {
    let mut x = Vec::new();
    for r in RADII {
        for j in 0..PER_RING {
            let t = 2.0 * PI * j as f64 / PER_RING as f64;
            x.push([r * t.sin(), 0.0, r * t.cos()]);
        }
    }
    let mut springs = Vec::new();
    for r in 0..RADII.len() {
        for j in 0..PER_RING {
            springs.push((node(r, j), node(r, j + 1)));
            if r + 1 < RADII.len() {
                springs.push((node(r, j), node(r + 1, j)));
            }
        }
    }
    (x, springs)
}

/// K = Σ K (e_a − e_b)(e_a − e_b)ᵀ ⊗ I₃ over the springs (positive semi-definite, the three
/// translations free) plus `extra` diagonal-only nodes, as Matrix Market `symmetric` lower
/// triangle entries; `diagonal_only` drops every off-diagonal entry.
fn stiffness_mtx(n_nodes: usize, springs: &[(usize, usize)], diagonal_only: bool) -> String {
    let mut diag = vec![0.0; n_nodes];
    let mut entries = Vec::new();
    for &(a, b) in springs {
        diag[a] += K;
        diag[b] += K;
        let (hi, lo) = (a.max(b), a.min(b));
        for d in 0..3 {
            entries.push((3 * hi + d, 3 * lo + d, -K));
        }
    }
    for (i, &k) in diag.iter().enumerate() {
        // a node without springs gets its own stiffness (a spring to the ground)
        let k = if k == 0.0 { K } else { k };
        for d in 0..3 {
            entries.push((3 * i + d, 3 * i + d, k));
        }
    }
    if diagonal_only {
        entries.retain(|(r, c, _)| r == c);
    }
    let n = 3 * n_nodes;
    let mut s = format!(
        "%%MatrixMarket matrix coordinate real symmetric\n{n} {n} {}\n",
        entries.len()
    );
    for (r, c, v) in entries {
        s += &format!("{} {} {v:e}\n", r + 1, c + 1);
    }
    s
}

/// Lumped mass, 1 kg per node.
fn mass_mtx(n_nodes: usize) -> String {
    let n = 3 * n_nodes;
    let mut s = format!("%%MatrixMarket matrix coordinate real general\n{n} {n} {n}\n");
    for i in 1..=n {
        s += &format!("{i} {i} 1.0\n");
    }
    s
}

/// Write the model's five files into `dir` (node indices of the patch set one per line) and
/// return them.
fn write(dir: &Path, x: &[[f64; 3]], stiffness: &str, patch: &[usize]) -> ImportFiles {
    let p = |n: &str| dir.join(n).display().to_string();
    std::fs::write(p("k.mtx"), stiffness).unwrap();
    std::fs::write(p("m.mtx"), mass_mtx(x.len())).unwrap();
    let nodes: String = x
        .iter()
        .map(|v| format!("{:e}, {:e}, {:e}\n", v[0], v[1], v[2]))
        .collect();
    std::fs::write(p("nodes.csv"), nodes).unwrap();
    let rim: Vec<String> = (0..PER_RING).map(|j| node(0, j).to_string()).collect();
    std::fs::write(p("rim.txt"), rim.join(" ")).unwrap();
    let patch: Vec<String> = patch.iter().map(|i| i.to_string()).collect();
    std::fs::write(p("patch.txt"), patch.join("\n") + "\n").unwrap();
    ImportFiles {
        format: ImportFormat::MatrixMarket,
        stiffness: p("k.mtx"),
        mass: p("m.mtx"),
        nodes: p("nodes.csv"),
        rim_nodes: p("rim.txt"),
        patch_nodes: p("patch.txt"),
    }
}

/// The tread nodes around the road point (θ = 150°, 180°, 210°).
fn road_patch() -> Vec<usize> {
    vec![node(2, 5), node(2, 6), node(2, 7)]
}

/// The crafted model's files written into a scratch folder that is removed when the case is
/// dropped (also when an assertion fails).
struct Case {
    dir: PathBuf,
    files: ImportFiles,
}

impl Case {
    /// Nodes `x`, the model's springs (`diagonal_only` drops K's coupling) and the patch set.
    fn new(name: &str, x: &[[f64; 3]], diagonal_only: bool, patch: &[usize]) -> Self {
        let dir = scratch(name);
        let (_, springs) = model();
        let files = write(
            &dir,
            x,
            &stiffness_mtx(x.len(), &springs, diagonal_only),
            patch,
        );
        Case { dir, files }
    }
}

impl Drop for Case {
    fn drop(&mut self) {
        let _ = std::fs::remove_dir_all(&self.dir);
    }
}

/// The failed check of an import that must fail one, with the field it blames.
fn check_of(files: &ImportFiles) -> (&'static str, ImportCheckError) {
    match imported_tire(files) {
        Err(TireError::ImportCheck { field, check }) => (field, check),
        Err(e) => panic!("expected a failed import check, got {e}"),
        Ok(_) => panic!("expected a failed import check, the import passed"),
    }
}

// Reference: the crafted model as written is a valid tire (connected springs, patch on the
// tread at the road point), so the checks below fail for what each test breaks, not for the
// model.
#[test]
fn the_crafted_model_imports() {
    let x = model().0;
    let case = Case::new("ok", &x, false, &road_patch());
    let files = &case.files;
    let fe = imported_tire(files).unwrap();
    assert_eq!(fe.n_nodes(), 3 * PER_RING);
}

// A K holding only its diagonal (a triangle written without its off-diagonal entries): no DOF
// is coupled to another. Reference: the same K with its coupling imports (first test).
#[test]
fn a_stiffness_without_off_diagonal_entries_is_refused() {
    let x = model().0;
    let case = Case::new("diag", &x, true, &road_patch());
    let files = &case.files;
    let (field, check) = check_of(files);
    assert_eq!(field, "stiffness");
    assert_eq!(
        check,
        ImportCheckError::DiagonalStiffness {
            file: files.stiffness.clone()
        }
    );
    let text = TireError::ImportCheck { field, check }.to_string();
    assert!(
        text.starts_with("import.stiffness: ") && text.contains("k.mtx"),
        "{text}"
    );
}

// A node of the node file that belongs to no element (a 37th node on the tread, between two
// tread nodes, with only its own diagonal stiffness): K makes two parts of the 37 nodes, the
// lone node one of them, named with its line in the node file.
#[test]
fn a_node_no_stiffness_entry_connects_is_refused() {
    let mut x = model().0;
    let t = 2.0 * PI * 2.5 / PER_RING as f64;
    x.push([0.5 * t.sin(), 0.0, 0.5 * t.cos()]);
    let lone = x.len() - 1;
    let case = Case::new("lone", &x, false, &road_patch());
    let files = &case.files;
    let (field, check) = check_of(files);
    assert_eq!(field, "stiffness");
    match check {
        ImportCheckError::DisconnectedNode {
            file,
            node,
            nodes,
            parts,
            part_nodes,
        } => {
            assert_eq!(file, files.stiffness);
            assert_eq!(node, format!("node {lone} ({}:{})", files.nodes, lone + 1));
            assert_eq!((nodes, parts, part_nodes), (3 * PER_RING + 1, 2, 1));
        }
        other => panic!("{other}"),
    }
}

// A patch set on the sidewall ring (radius 0.40 m, below the tread band 0.50 − 0.25 · 0.20 =
// 0.45 m of `tire::import::TREAD_FRACTION`) at the road point: the first such node is named
// with its line in the patch file and its radius.
#[test]
fn a_patch_set_off_the_tread_is_refused() {
    let x = model().0;
    let patch = vec![node(2, 6), node(1, 5), node(1, 6)];
    let case = Case::new("sidewall", &x, false, &patch);
    let files = &case.files;
    let (field, check) = check_of(files);
    assert_eq!(field, "patch_nodes");
    let sidewall = node(1, 5);
    match check {
        ImportCheckError::PatchOffTread {
            file,
            line,
            node,
            radius_m,
            rim_radius_m,
            outer_radius_m,
        } => {
            assert_eq!(file, files.patch_nodes);
            assert_eq!(line, 2);
            assert!(node.starts_with(&format!("node {sidewall} ")), "{node}");
            assert!((radius_m - 0.40).abs() < 1e-12, "{radius_m}");
            assert!((rim_radius_m - 0.30).abs() < 1e-12);
            assert!((outer_radius_m - 0.50).abs() < 1e-12);
        }
        other => panic!("{other}"),
    }
    let floor = 0.50 - tire::import::TREAD_FRACTION * (0.50 - 0.30);
    assert!(0.40 < floor && floor < 0.50, "{floor}");
}

// A patch set on the tread but at the top of the tire (θ = 330°, 0°, 30°): 150° from the road
// point θ = π, beyond `tire::import::MAX_PATCH_OFFSET_DEG`.
#[test]
fn a_patch_set_away_from_the_road_point_is_refused() {
    let x = model().0;
    let patch = vec![node(2, 11), node(2, 0), node(2, 1)];
    let case = Case::new("top", &x, false, &patch);
    let files = &case.files;
    let (field, check) = check_of(files);
    assert_eq!(field, "patch_nodes");
    match check {
        ImportCheckError::PatchAwayFromRoad { file, nearest_deg } => {
            assert_eq!(file, files.patch_nodes);
            assert!((nearest_deg - 150.0).abs() < 1e-9, "{nearest_deg}");
        }
        other => panic!("{other}"),
    }
}

// Rim nodes outside the tread (the rim set given as the outer ring, e.g. the sets swapped):
// the rim does not lie inside the tire.
#[test]
fn a_rim_set_outside_the_tire_is_refused() {
    let x = model().0;
    let case = Case::new("rim", &x, false, &road_patch());
    let files = &case.files;
    // the outer ring as the rim, the patch on the (now outermost non-rim) sidewall ring
    let rim: Vec<String> = (0..PER_RING).map(|j| node(2, j).to_string()).collect();
    std::fs::write(&files.rim_nodes, rim.join(" ")).unwrap();
    std::fs::write(&files.patch_nodes, format!("{}\n", node(1, 6))).unwrap();
    let (field, check) = check_of(files);
    assert_eq!(field, "rim_nodes");
    match check {
        ImportCheckError::RimNotInside {
            file,
            rim_radius_m,
            outer_radius_m,
        } => {
            assert_eq!(file, files.rim_nodes);
            assert!((rim_radius_m - 0.50).abs() < 1e-12);
            assert!((outer_radius_m - 0.40).abs() < 1e-12);
        }
        other => panic!("{other}"),
    }
}
