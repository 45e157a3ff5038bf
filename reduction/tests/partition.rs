//! `DofPartition` (moved from the unit tests of `reduction/src/partition.rs`).

use reduction::DofPartition;

#[test]
fn three_sets_cover_every_dof_once() {
    // invariant: boundary ∪ interior ∪ fixed = 0..n, disjoint; user order of the boundary
    let p = DofPartition::from_nodes(12, 2, &[4, 1], &[0]).unwrap();
    assert_eq!(p.boundary(), &[8, 9, 2, 3]);
    assert_eq!(p.fixed(), &[0, 1]);
    assert_eq!(p.interior(), &[4, 5, 6, 7, 10, 11]);
    assert_eq!(p.unfixed(), vec![2, 3, 4, 5, 6, 7, 8, 9, 10, 11]);
    let e = DofPartition::new(6, &[1, 2], &[2]).unwrap_err().to_string();
    assert!(e.contains("fixed") && e.contains("DOF 2"), "{e}");
    let e = DofPartition::new(6, &[1], &[7]).unwrap_err().to_string();
    assert!(e.contains("fixed DOF set") && e.contains("7"), "{e}");
    let e = DofPartition::new(6, &[1], &[3, 3]).unwrap_err().to_string();
    assert!(e.contains("twice"), "{e}");
    // files written before the fixed set existed still load
    let old: DofPartition =
        serde_json::from_str(r#"{"n":3,"boundary":[0],"interior":[1,2]}"#).unwrap();
    assert_eq!(old, DofPartition::from_boundary_dofs(3, &[0]).unwrap());
}
