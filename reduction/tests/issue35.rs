//! Issue 35: a mode count from input is checked against the model before anything is
//! allocated from it (`--modes 99999999999` allocated 800 GB in `ModeSelection::resolve`).

use faer::Mat;
use reduction::basis::{Method, ModeSelection, build_basis};
use reduction::{DofPartition, ReductionError};

// definition: a 4-DOF spring chain with one boundary DOF has 3 fixed-interface modes
#[test]
fn more_modes_than_the_model_has_are_refused_at_once() {
    let k = Mat::from_fn(4, 4, |i, j| match (i as i64 - j as i64).abs() {
        0 => 2.0,
        1 => -1.0,
        _ => 0.0,
    });
    let m = Mat::<f64>::identity(4, 4);
    let part = DofPartition::from_boundary_dofs(4, &[0]).unwrap();
    for method in [
        Method::ModeCondensation,
        Method::CraigBampton,
        Method::FixedInterfaceModalTruncation,
        Method::FreeFreeModalTruncation,
    ] {
        let t0 = std::time::Instant::now();
        let e = build_basis(
            k.as_ref(),
            m.as_ref(),
            &part,
            method,
            &ModeSelection::Lowest(99_999_999_999),
        )
        .unwrap_err();
        assert!(
            matches!(e, ReductionError::InvalidParameter { ref name, .. } if name == "modes"),
            "{method:?}: {e}"
        );
        assert!(e.to_string().contains("99999999999"), "{e}");
        assert!(t0.elapsed().as_secs() < 5);
    }
    // the largest valid request still works: Craig-Bampton keeps 1 static mode + 3 modes
    let b = build_basis(
        k.as_ref(),
        m.as_ref(),
        &part,
        Method::CraigBampton,
        &ModeSelection::Lowest(3),
    )
    .unwrap();
    assert_eq!(b.psi.ncols(), 4);
}
