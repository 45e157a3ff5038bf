//! Kerkkänen Tables 2.1–2.4 (seed 001, §2.4): static beam tests of the proposed 8-DOF element
//! and of the Omar–Shabana 12-DOF element, compared to the printed digits.

use ancf::beam_mesh::BeamElementKind;
use flowmbd_cases::ancf_beams::{StaticBeamCase, cantilever_tip, simply_supported_deflection};

const NS: [usize; 6] = [2, 4, 8, 16, 32, 64];

fn check_mm(kind: BeamElementKind, nu: f64, table: &[(usize, f64)], label: &str) {
    for &(n, printed_mm) in table {
        let case = StaticBeamCase::kerkkanen(kind, n, nu, 0.1);
        let got_mm = simply_supported_deflection(&case).expect("solve") * 1e3;
        // printed with 6 decimals in mm: half a unit of the last digit (+ roundoff)
        let err = (got_mm - printed_mm).abs();
        assert!(
            err <= 0.5e-6 + 1e-9,
            "{label} n={n}: got {got_mm:.7} mm, printed {printed_mm} mm"
        );
    }
}

fn check_tip(kind: BeamElementKind, nu: f64, h: f64, table: &[(usize, [f64; 2])], label: &str) {
    // printed with 5 decimals in m: half a unit of the last digit (+ roundoff)
    let tol = 0.5e-5 + 1e-9;
    for &(n, printed) in table {
        let mut case = StaticBeamCase::kerkkanen(kind, n, nu, h);
        case.increments = 10;
        let tip = cantilever_tip(&case).expect("solve");
        for c in 0..2 {
            let err = (tip[c] - printed[c]).abs();
            assert!(
                err <= tol,
                "{label} n={n}: got ({:.6}, {:.6}) m, printed {:?}",
                tip[0],
                tip[1],
                printed
            );
        }
    }
}

// Kerkkänen Table 2.1 (ν = 0), "Proposed ANCF" column [mm].
#[test]
fn table_2_1_proposed() {
    let col = [
        -0.073043, -0.091159, -0.095688, -0.096821, -0.097104, -0.097174,
    ];
    let t: Vec<_> = NS.iter().copied().zip(col).collect();
    check_mm(BeamElementKind::Proposed, 0.0, &t, "Table 2.1 proposed");
}

// Kerkkänen Table 2.2 (ν = 0.3), "Proposed ANCF" column [mm].
#[test]
fn table_2_2_proposed() {
    let col = [
        -0.073217, -0.091333, -0.095862, -0.096995, -0.097278, -0.097348,
    ];
    let t: Vec<_> = NS.iter().copied().zip(col).collect();
    check_mm(BeamElementKind::Proposed, 0.3, &t, "Table 2.2 proposed");
}

// Kerkkänen Tables 2.1/2.2, "Omar–Shabana ANCF" columns [mm]: every row of Table 2.2 and
// n = 2…16 of Table 2.1 to the printed digits.
#[test]
fn tables_2_1_2_2_omar_shabana() {
    let t1 = [
        (2, -0.072893),
        (4, -0.091034),
        (8, -0.095578),
        (16, -0.096717),
    ];
    check_mm(
        BeamElementKind::OmarShabana,
        0.0,
        &t1,
        "Table 2.1 Omar-Shabana",
    );
    let t2 = [
        (2, -0.054388),
        (4, -0.067879),
        (8, -0.071262),
        (16, -0.072112),
        (32, -0.072327),
        (64, -0.072382),
    ];
    check_mm(
        BeamElementKind::OmarShabana,
        0.3,
        &t2,
        "Table 2.2 Omar-Shabana",
    );
}

// Kerkkänen Table 2.1 (ν = 0), "Omar–Shabana ANCF" rows n = 32, 64 [mm]. We get −0.0970035 and
// −0.0970761 mm against the printed −0.097005 and −0.097078 mm, i.e. 1.5e-6 and 1.9e-6 mm (two
// units of the last printed digit, 2e-5 relative). An independent numpy implementation of the
// same element (dense Newton, same 4×3 Gauss rule) gives −0.09700353618 and −0.09707608073 mm,
// equal to ours within 1e-11 mm, and the same element reproduces all Table 2.2 rows (ν = 0.3)
// and n ≤ 16 of Table 2.1 exactly, so we attribute the gap to the thesis's own solution of
// these two rows; the tolerance records it and still fails
// if the element changes (the n = 16 → 32 change is 2.9e-4 mm).
#[test]
fn table_2_1_omar_shabana_fine_meshes() {
    for (n, printed_mm) in [(32, -0.097005), (64, -0.097078)] {
        let case = StaticBeamCase::kerkkanen(BeamElementKind::OmarShabana, n, 0.0, 0.1);
        let got_mm = simply_supported_deflection(&case).expect("solve") * 1e3;
        assert!(
            (got_mm - printed_mm).abs() <= 2.5e-6,
            "Table 2.1 Omar-Shabana n={n}: got {got_mm:.7} mm, printed {printed_mm} mm"
        );
    }
}

// Kerkkänen Table 2.3 (Model 1: h = 0.1 m, ν = 0.3), "Proposed" column, tip (x, y) [m].
#[test]
fn table_2_3_proposed() {
    let col = [
        [1.88480, -0.62126],
        [1.86351, -0.66320],
        [1.85696, -0.67691],
        [1.85537, -0.68018],
        [1.85500, -0.68091],
        [1.85491, -0.68109],
    ];
    let t: Vec<_> = NS.iter().copied().zip(col).collect();
    check_tip(
        BeamElementKind::Proposed,
        0.3,
        0.1,
        &t,
        "Table 2.3 proposed",
    );
}

// Kerkkänen Table 2.4 (Model 2: h = 0.5 m, ν = 0), "Proposed" column, tip (X, Y) [m].
#[test]
fn table_2_4_proposed() {
    let col = [
        [1.87307, -0.65134],
        [1.85001, -0.69591],
        [1.84412, -0.70709],
        [1.84271, -0.70970],
        [1.84237, -0.71034],
        [1.84228, -0.71050],
    ];
    let t: Vec<_> = NS.iter().copied().zip(col).collect();
    check_tip(
        BeamElementKind::Proposed,
        0.0,
        0.5,
        &t,
        "Table 2.4 proposed",
    );
}

// Kerkkänen Table 2.3 (Model 1: h = 0.1 m, ν = 0.3), "Omar–Shabana" column, tip (x, y) [m],
// every printed row. The clamp fixes r, r_x and r_y of the root node (see
// `flowmbd_cases::ancf_beams::Cantilever`); with r_x free, as the seed note claims, the rows differ by up to
// 2.4e-5 m here and 1.0e-3 m in Table 2.4 (independent numpy oracle and this crate agree).
#[test]
fn table_2_3_omar_shabana() {
    let col = [
        [1.95536, -0.37731],
        [1.91970, -0.50932],
        [1.91344, -0.53035],
        [1.91276, -0.53267],
        [1.91264, -0.53309],
        [1.91262, -0.53319],
    ];
    let t: Vec<_> = NS.iter().copied().zip(col).collect();
    check_tip(
        BeamElementKind::OmarShabana,
        0.3,
        0.1,
        &t,
        "Table 2.3 Omar-Shabana",
    );
}

// Kerkkänen Table 2.4 (Model 2: h = 0.5 m, ν = 0), "Omar–Shabana" column, tip (X, Y) [m],
// every printed row, same clamp as Table 2.3.
#[test]
fn table_2_4_omar_shabana() {
    let col = [
        [1.86909, -0.64098],
        [1.84841, -0.69436],
        [1.84498, -0.70341],
        [1.84407, -0.70573],
        [1.84378, -0.70643],
        [1.84367, -0.70667],
    ];
    let t: Vec<_> = NS.iter().copied().zip(col).collect();
    check_tip(
        BeamElementKind::OmarShabana,
        0.0,
        0.5,
        &t,
        "Table 2.4 Omar-Shabana",
    );
}
