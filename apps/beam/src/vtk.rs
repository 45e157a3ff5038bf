//! Legacy-ASCII VTK polylines of deformed beam centrelines (for ParaView).

use std::fmt::Write as _;

/// A VTK legacy file with one polyline through `points` (z = 0).
pub fn polyline(title: &str, points: &[[f64; 2]]) -> String {
    let mut s = String::new();
    let _ = writeln!(
        s,
        "# vtk DataFile Version 3.0\n{title}\nASCII\nDATASET POLYDATA"
    );
    let _ = writeln!(s, "POINTS {} double", points.len());
    for p in points {
        let _ = writeln!(s, "{:.9e} {:.9e} 0", p[0], p[1]);
    }
    let _ = writeln!(s, "LINES 1 {}", points.len() + 1);
    let _ = write!(s, "{}", points.len());
    for i in 0..points.len() {
        let _ = write!(s, " {i}");
    }
    s.push('\n');
    s
}
