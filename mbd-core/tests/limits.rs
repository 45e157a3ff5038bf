//! The documented size ceilings and the one switch that raises them (issue 20, item 2). Its own
//! test binary: the switch is process-wide, so no other test may see it raised.

use mbd_core::validate::{check, limits};

// definition of the switch: every ceiling × LARGE_FACTOR (1000) when raised, restored after
#[test]
fn allow_large_raises_every_ceiling_1000_fold_and_no_further() {
    limits::set_allow_large(false);
    let e = check::size("nodes", 2001, 3, 2000).unwrap_err();
    assert_eq!(e.field, "nodes");
    assert!(
        e.reason.starts_with("must lie in [3, 2000], got 2001"),
        "{e}"
    );
    assert!(e.reason.contains("--allow-large"), "{e}");
    assert_eq!(limits::ceiling(1e8), 1e8);
    // below the floor is not a ceiling matter: no hint
    let e = check::size("nodes", 2, 3, 2000).unwrap_err();
    assert!(!e.reason.contains("--allow-large"), "{e}");

    limits::set_allow_large(true);
    assert!(limits::large_allowed());
    assert!(check::size("nodes", 2001, 3, 2000).is_ok());
    assert!(check::size("nodes", 2_000_000, 3, 2000).is_ok());
    let e = check::size("nodes", 2_000_001, 3, 2000).unwrap_err();
    assert_eq!(e.reason, "must lie in [3, 2000000], got 2000001");
    assert_eq!(limits::ceiling(1e8), 1e11);
    assert_eq!(limits::ceiling_count(usize::MAX), usize::MAX, "saturates");
    assert_eq!(limits::raise_hint(), "");

    limits::set_allow_large(false);
    assert!(check::size("nodes", 2001, 3, 2000).is_err());
}
