//! `io::vtk::polyline` (moved from the unit tests of `fe-model/src/io/vtk.rs`).

use fe_model::io::vtk::polyline;

// definition: n points of a closed loop give n segments, the last back to the first; an
// open line gives n − 1
#[test]
fn polyline_closes_the_loop() {
    let pts = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [1.0, 1.0, 0.0]];
    let closed = polyline(&pts, true);
    assert_eq!(closed.cells.len(), 3);
    assert_eq!(closed.cells[2].nodes, vec![2, 0]);
    assert_eq!(polyline(&pts, false).cells.len(), 2);
    assert!(polyline(&pts[..1], true).cells.is_empty());
}
