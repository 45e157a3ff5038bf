//! The checks of an imported tire (issue #35 "wrong exit class", issue #39 item 7): a patch
//! node listed twice, node coordinates all equal, a K holding only its diagonal, a node that no
//! stiffness entry connects, a patch set off the tread or away from the road point, and a
//! reduced-tire file that is a device all exit 2 with one line naming the field, the file and
//! (where it applies) the line, instead of a numerical failure (exit 1) or a silent reduction.
//! The reference model is the coarse generated tire exported to Matrix Market files, which
//! imports and reduces cleanly (the first case).

use crate::common;
use common::export::{Export, lines, mtx, refused};
use common::{outcome, run, tmp};
use std::fmt::Write as _;
use std::path::Path;
use tire::mesh::node_angle;

#[test]
fn bad_imports_exit_2_naming_field_file_and_line() {
    let e = Export::new("import-checks");
    // the reference: the export as it is imports and reduces
    let (code, err) = e.reduce("ok", "K.mtx", "M.mtx", "nodes.txt", "patch.txt");
    assert_eq!(code, 0, "{err}");

    // a patch node listed twice (its first node again on a last line)
    let mut patch = lines(&e.fe.candidates);
    writeln!(patch, "{}", e.fe.candidates[0]).unwrap();
    e.write("patch2.txt", &patch);
    let last = e.fe.candidates.len() + 1;
    refused(
        "patch twice",
        e.reduce("twice", "K.mtx", "M.mtx", "nodes.txt", "patch2.txt"),
        &[
            "tire.import.patch_nodes",
            &format!("patch2.txt:{last}:"),
            &format!(
                "node {} is listed twice (also on line 1)",
                e.fe.candidates[0]
            ),
        ],
    );

    // every node at the same point
    let same = vec![[0.3, 0.1, -0.2]; e.fe.n_nodes()];
    e.write("same.txt", &e.nodes_text(&same));
    refused(
        "coordinates equal",
        e.reduce("same", "K.mtx", "M.mtx", "same.txt", "patch.txt"),
        &["tire.import.nodes", "same.txt", "have the same coordinates"],
    );

    // two tire nodes at the same point: the second named with its line
    let mut two = e.fe.nodes.clone();
    let (a, b) = (e.fe.candidates[0], e.fe.candidates[1]);
    two[b] = two[a];
    e.write("two.txt", &e.nodes_text(&two));
    refused(
        "coincident nodes",
        e.reduce("two", "K.mtx", "M.mtx", "two.txt", "patch.txt"),
        &[
            "tire.import.nodes",
            &format!("node {} (", a.min(b)),
            &format!("two.txt:{})", a.max(b) + 1),
            "same point",
        ],
    );

    // K holding only its diagonal (e.g. one triangle of a matrix lost its other half)
    let diag: Vec<_> = e
        .stiffness()
        .into_iter()
        .filter(|&(r, c, _)| r == c)
        .collect();
    e.write("Kdiag.mtx", &mtx(e.n(), &diag));
    refused(
        "diagonal K",
        e.reduce("diag", "Kdiag.mtx", "M.mtx", "nodes.txt", "patch.txt"),
        &[
            "tire.import.stiffness",
            "Kdiag.mtx",
            "no off-diagonal entry",
        ],
    );

    // a node in the node file that no element uses: its own diagonal stiffness, no coupling
    let n1 = e.n() + 3;
    let mut k = e.stiffness();
    k.extend((e.n()..n1).map(|d| (d, d, 1e6)));
    e.write("Kextra.mtx", &mtx(n1, &k));
    e.write("Mextra.mtx", &e.mass(n1));
    let mut extra = e.fe.nodes.clone();
    extra.push([0.9, 0.0, 0.9]);
    e.write("extra.txt", &e.nodes_text(&extra));
    refused(
        "disconnected node",
        e.reduce(
            "extra",
            "Kextra.mtx",
            "Mextra.mtx",
            "extra.txt",
            "patch.txt",
        ),
        &[
            "tire.import.stiffness",
            &format!("node {} (", e.fe.n_nodes()),
            &format!("extra.txt:{})", e.fe.n_nodes() + 1),
            "is not connected",
        ],
    );

    // a patch set on the inner side of the section (the non-rim nodes nearest the axle)
    let rho = |i: usize| e.fe.nodes[i][0].hypot(e.fe.nodes[i][2]);
    let rim = e.fe.rim_mask();
    let mut inner: Vec<usize> = (0..e.fe.n_nodes()).filter(|&i| !rim[i]).collect();
    inner.sort_by(|&a, &b| rho(a).total_cmp(&rho(b)));
    inner.truncate(e.fe.candidates.len());
    e.write("inner.txt", &lines(&inner));
    refused(
        "patch off the tread",
        e.reduce("inner", "K.mtx", "M.mtx", "nodes.txt", "inner.txt"),
        &[
            "tire.import.patch_nodes",
            "inner.txt:1:",
            "tread's outer surface",
        ],
    );

    // the patch at the top of the tire (θ near 0), not at the road point
    let top: Vec<usize> =
        e.fe.candidates
            .iter()
            .map(|&i| {
                // the node on the same ring diametrically opposite (θ + π), found by position
                let x = e.fe.nodes[i];
                (0..e.fe.n_nodes())
                    .min_by(|&a, &b| {
                        let d = |j: usize| {
                            let y = e.fe.nodes[j];
                            (y[0] + x[0]).hypot(y[2] + x[2]) + (y[1] - x[1]).abs()
                        };
                        d(a).total_cmp(&d(b))
                    })
                    .unwrap()
            })
            .collect();
    assert!(top.iter().all(|&i| {
        let deg = node_angle(&e.fe.nodes[i]).to_degrees();
        !(45.0..=315.0).contains(&deg)
    }));
    e.write("top.txt", &lines(&top));
    refused(
        "patch at the top",
        e.reduce("top", "K.mtx", "M.mtx", "nodes.txt", "top.txt"),
        &["tire.import.patch_nodes", "top.txt", "road point"],
    );
    std::fs::remove_dir_all(&e.dir).ok();
}

/// A reduced-tire file that is a device (`/dev/zero`) or a folder is refused before reading
/// (exit 2 naming `tire.reduced_file`), instead of being read without end.
#[cfg(unix)]
#[test]
fn reduced_file_that_is_a_device_is_refused() {
    let dir = tmp("reduced-device");
    let cfg = dir.join("c.toml");
    for (i, file) in ["/dev/zero", dir.to_str().unwrap()].iter().enumerate() {
        std::fs::write(&cfg, common::tire_tables(Path::new(file))).unwrap();
        let out = dir.join(format!("o{i}"));
        let (code, _, err) = outcome(&run(&[
            "cleat",
            "--quiet",
            "--config",
            cfg.to_str().unwrap(),
            "--out",
            out.to_str().unwrap(),
        ]));
        refused(
            file,
            (code, err),
            &[
                "tire.reduced_file",
                if i == 0 {
                    "not a regular file"
                } else {
                    "directory"
                },
            ],
        );
    }
    std::fs::remove_dir_all(&dir).ok();
}
