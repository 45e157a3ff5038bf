//! A road surface given as heights on a rectilinear grid ([`HeightGrid`], read from a CSV file
//! by [`HeightGrid::parse_csv`]) and the road it describes ([`GridRoad`]).
//!
//! # The CSV format
//!
//! ```text
//! # a comment line (starts with #); blank lines are skipped too
//! x_m \ y_m, -0.15, -0.05, 0.05, 0.15
//! 0.00,       0.0,   0.0,  0.0,  0.0
//! 0.02,       0.0,   0.001, 0.001, 0.0
//! 0.04,       0.0,   0.0,  0.0,  0.0
//! ```
//!
//! Comma-separated numbers (spaces around them are allowed), in metres. The first row is the
//! header: its first cell is a free label, the others are the lateral coordinates `y_j`
//! \[m\] (along the wheel axis, left positive), strictly increasing. Every following row is
//! one longitudinal station: its first cell is `x_i` \[m\] (along the road in the travel
//! direction, strictly increasing down the file), then the heights `h(x_i, y_j)` \[m\] of the
//! road above its reference plane, one per `y_j`. At least 2 stations and 2 lateral
//! coordinates; spacings need not be uniform. Every number must be finite; the first error
//! is reported with its line and column ([`GridError`]).
//!
//! # Interpolation, normal and gap
//!
//! Between the nodes the height is bilinear in each cell,
//! `h = (1−ξ)(1−η) h₀₀ + ξ(1−η) h₁₀ + (1−ξ)η h₀₁ + ξη h₁₁`; beyond the grid it continues at
//! the nearest edge value (the road is extended by its edge profile). The normal is that of
//! the interpolated surface, `n = (−h_x, −h_y, 1)/√(1 + h_x² + h_y²)`, and the gap of a point
//! at height `Z` above the reference plane is the vertical distance projected on the normal,
//! `g = n_z (Z − h)`: the distance to the tangent plane, exact on a plane and to first order in
//! the gap elsewhere (the standard height-field contact, e.g. Wriggers, *Computational Contact
//! Mechanics*, §4.1 for the projection on the tangent plane).
//!
//! # Bounds for a candidate search
//!
//! With the slope bounds `G_x ≥ |h_x|`, `G_y ≥ |h_y|` ([`HeightGrid::slope_bounds`]: the
//! largest difference quotients between neighbouring nodes, which bound the bilinear
//! gradient in every cell) and `c = 1/√(1 + G_x² + G_y²) ≤ n_z`, the vertical gap
//! `Z − h` is `√(1 + G_x² + G_y²)`-Lipschitz in the point (Cauchy–Schwarz on
//! `(1, G_x, G_y)`), so `q = c (Z − h)` is 1-Lipschitz, and on a road moving at `u` in its
//! plane `q` changes at a fixed point by at most `c (G_x |u_x| + G_y |u_y|)` per unit time;
//! where `q ≥ 0`, `g = n_z (Z − h) ≥ q` ([`GridRoad::bound`]).

use crate::geometry::{Surface, SurfacePoint};
use mbd_core::validate::escape;
use nalgebra::{Matrix3, Point3, Vector3};

/// Largest magnitude of a grid coordinate or height \[m\] (a sanity bound that keeps every
/// difference, slope and interpolated value finite).
pub const MAX_GRID_VALUE: f64 = 1e9;

/// Default ceiling on the nodes of a [`HeightGrid`] read from a file (32 MB of heights).
pub const MAX_GRID_POINTS: usize = 4_000_000;

/// Why a height grid was refused: the line (1-based, 0 for the whole file) and column
/// (1-based) of the first offending cell, and the reason.
#[derive(Debug, Clone, PartialEq)]
pub struct GridError {
    /// Line of the file (1-based; 0 = the file as a whole).
    pub line: usize,
    /// Column (1-based cell number in the line), if one cell is at fault.
    pub column: Option<usize>,
    /// What is wrong.
    pub reason: String,
}

impl std::fmt::Display for GridError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match (self.line, self.column) {
            (0, _) => write!(f, "{}", self.reason),
            (l, Some(c)) => write!(f, "line {l}, column {c}: {}", self.reason),
            (l, None) => write!(f, "line {l}: {}", self.reason),
        }
    }
}

impl std::error::Error for GridError {}

/// Heights `h(x_i, y_j)` \[m\] on a rectilinear grid (module documentation).
#[derive(Debug, Clone, PartialEq)]
pub struct HeightGrid {
    x: Vec<f64>,
    y: Vec<f64>,
    /// Row-major: `h[i · n_y + j] = h(x_i, y_j)`.
    h: Vec<f64>,
    slope: [f64; 2],
}

/// The interpolated height and its derivatives at a point (module documentation).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct GridHeight {
    /// Height `h` \[m\].
    pub h: f64,
    /// `∂h/∂x` \[-\].
    pub hx: f64,
    /// `∂h/∂y` \[-\].
    pub hy: f64,
    /// `∂²h/∂x∂y` \[1/m\] (the only second derivative of a bilinear cell).
    pub hxy: f64,
}

/// The cell of `v` on the strictly increasing axis `a`: `(index i, fraction ξ, inside)`, with
/// `ξ ∈ [0, 1]` between `a[i]` and `a[i + 1]`; beyond the axis the edge node (`ξ` 0 or 1,
/// `inside = false`: the height does not depend on `v` there).
fn cell(a: &[f64], v: f64) -> (usize, f64, bool) {
    let n = a.len();
    if v <= a[0] {
        return (0, 0.0, v == a[0]);
    }
    if v >= a[n - 1] {
        return (n - 2, 1.0, v == a[n - 1]);
    }
    let i = a.partition_point(|&w| w <= v) - 1;
    (i, (v - a[i]) / (a[i + 1] - a[i]), true)
}

impl HeightGrid {
    /// A grid from its axes \[m\] and row-major heights \[m\] (`h[i · y.len() + j]`), checked as
    /// the file reader checks them: at least 2 × 2 nodes, strictly increasing axes, coordinates
    /// and heights within ±[`MAX_GRID_VALUE`], `x.len() · y.len()` heights, finite slopes and
    /// cross derivatives between the nodes.
    pub fn new(x: Vec<f64>, y: Vec<f64>, h: Vec<f64>) -> Result<Self, GridError> {
        // finite and within the bound (NaN is not)
        let within = |v: f64| v.is_finite() && v.abs() <= MAX_GRID_VALUE;
        let whole = |reason: String| GridError {
            line: 0,
            column: None,
            reason,
        };
        for (name, a) in [("x", &x), ("y", &y)] {
            if a.len() < 2 {
                return Err(whole(format!(
                    "{} {name} coordinates, at least 2 are needed",
                    a.len()
                )));
            }
            if let Some(k) = a.iter().position(|v| !within(*v)) {
                return Err(whole(format!(
                    "{name}[{k}] = {} is not a finite coordinate within ±{MAX_GRID_VALUE:e} m",
                    a[k]
                )));
            }
            if let Some(k) = a.windows(2).position(|w| w[1] <= w[0]) {
                return Err(whole(format!(
                    "{name}[{}] = {} is not above {name}[{k}] = {} (the coordinates must \
                     increase strictly)",
                    k + 1,
                    a[k + 1],
                    a[k]
                )));
            }
        }
        if h.len() != x.len() * y.len() {
            return Err(whole(format!(
                "{} heights for {} × {} nodes",
                h.len(),
                x.len(),
                y.len()
            )));
        }
        if let Some(k) = h.iter().position(|v| !within(*v)) {
            return Err(whole(format!(
                "height {k} = {} is not a finite height within ±{MAX_GRID_VALUE:e} m",
                h[k]
            )));
        }
        let ny = y.len();
        let mut slope = [0.0f64; 2];
        for i in 0..x.len() {
            for j in 0..ny {
                let v = h[i * ny + j];
                if i + 1 < x.len() {
                    slope[0] = slope[0].max((h[(i + 1) * ny + j] - v).abs() / (x[i + 1] - x[i]));
                }
                if j + 1 < ny {
                    slope[1] = slope[1].max((h[i * ny + j + 1] - v).abs() / (y[j + 1] - y[j]));
                }
            }
        }
        // the cross derivative of every cell, as `in_cell` forms it
        let twist = (0..x.len() - 1).all(|i| {
            (0..ny - 1).all(|j| {
                let d = h[(i + 1) * ny + j + 1] - h[(i + 1) * ny + j] - h[i * ny + j + 1]
                    + h[i * ny + j];
                (d / (x[i + 1] - x[i]) / (y[j + 1] - y[j])).is_finite()
            })
        });
        if !(slope[0].is_finite() && slope[1].is_finite() && twist) {
            return Err(whole(
                "the slopes between neighbouring nodes overflow (coordinates too close for \
                 the height differences)"
                    .into(),
            ));
        }
        Ok(Self { x, y, h, slope })
    }

    /// Read the CSV text of the module documentation, with at most `max_points` nodes (checked
    /// before each row is stored). Errors name the line and column of the first offending
    /// cell.
    pub fn parse_csv(text: &str, max_points: usize) -> Result<Self, GridError> {
        let err = |line: usize, column: Option<usize>, reason: String| GridError {
            line,
            column,
            reason,
        };
        let number =
            |line: usize, column: usize, cell: &str, what: &str| -> Result<f64, GridError> {
                let t = cell.trim();
                if t.is_empty() {
                    return Err(err(
                        line,
                        Some(column),
                        format!("empty cell (expected {what})"),
                    ));
                }
                match t.parse::<f64>() {
                    Ok(v) if v.abs() <= MAX_GRID_VALUE => Ok(v),
                    Ok(v) if v.is_finite() => Err(err(
                        line,
                        Some(column),
                        format!("{what} {v:e} is beyond ±{MAX_GRID_VALUE:e} m"),
                    )),
                    Ok(_) => Err(err(
                        line,
                        Some(column),
                        format!("{what} `{}` is not finite", escape(t)),
                    )),
                    Err(_) => Err(err(
                        line,
                        Some(column),
                        format!("`{}` is not a number (expected {what})", escape(t)),
                    )),
                }
            };
        let mut y: Vec<f64> = Vec::new();
        let mut x: Vec<f64> = Vec::new();
        let mut h: Vec<f64> = Vec::new();
        let mut header = true;
        for (k, raw) in text.split('\n').enumerate() {
            let line = k + 1;
            let row = raw.strip_suffix('\r').unwrap_or(raw);
            let t = row.trim();
            if t.is_empty() || t.starts_with('#') {
                continue;
            }
            if header {
                header = false;
                for (c, cell) in row.split(',').enumerate().skip(1) {
                    let v = number(line, c + 1, cell, "a y coordinate [m]")?;
                    if let Some(&last) = y.last()
                        && v <= last
                    {
                        return Err(err(
                            line,
                            Some(c + 1),
                            format!(
                                "y = {v} m is not above the previous y = {last} m (the y \
                                 coordinates must increase strictly)"
                            ),
                        ));
                    }
                    if y.len() >= max_points {
                        return Err(err(
                            line,
                            Some(c + 1),
                            format!("more than {max_points} y coordinates"),
                        ));
                    }
                    y.push(v);
                }
                if y.len() < 2 {
                    return Err(err(
                        line,
                        None,
                        format!(
                            "the header has {} y coordinates, at least 2 are needed (first \
                             cell a label, then the y coordinates [m])",
                            y.len()
                        ),
                    ));
                }
                continue;
            }
            let ny = y.len();
            if (x.len() + 1).saturating_mul(ny) > max_points {
                return Err(err(
                    line,
                    None,
                    format!(
                        "more than {max_points} grid nodes ({} rows of {ny} heights)",
                        x.len() + 1
                    ),
                ));
            }
            let mut cells = row.split(',');
            let xv = number(line, 1, cells.next().unwrap_or(""), "an x coordinate [m]")?;
            if let Some(&last) = x.last()
                && xv <= last
            {
                return Err(err(
                    line,
                    Some(1),
                    format!(
                        "x = {xv} m is not above the previous x = {last} m (the rows must be \
                         in strictly increasing x)"
                    ),
                ));
            }
            let start = h.len();
            for (c, cell) in cells.enumerate() {
                if c >= ny {
                    return Err(err(
                        line,
                        Some(c + 2),
                        format!("the row has more than the header's {ny} heights"),
                    ));
                }
                h.push(number(line, c + 2, cell, "a height [m]")?);
            }
            if h.len() - start != ny {
                return Err(err(
                    line,
                    None,
                    format!(
                        "the row has {} heights, the header has {ny} y coordinates",
                        h.len() - start
                    ),
                ));
            }
            x.push(xv);
        }
        if header {
            return Err(err(0, None, "no header row (the file has no data)".into()));
        }
        if x.len() < 2 {
            return Err(err(
                0,
                None,
                format!("{} rows of heights, at least 2 are needed", x.len()),
            ));
        }
        Self::new(x, y, h).map_err(|mut e| {
            // (the row checks above leave only the slopes' overflow)
            e.line = 0;
            e
        })
    }

    /// The longitudinal coordinates `x_i` \[m\].
    pub fn x(&self) -> &[f64] {
        &self.x
    }

    /// The lateral coordinates `y_j` \[m\].
    pub fn y(&self) -> &[f64] {
        &self.y
    }

    /// The heights, row-major (`h[i · n_y + j]`) \[m\].
    pub fn heights(&self) -> &[f64] {
        &self.h
    }

    /// `[G_x, G_y]`: the largest `|Δh|/Δx` between neighbouring nodes along `x` and along `y`
    /// \[-\], bounds of `|h_x|` and `|h_y|` everywhere (module documentation).
    pub fn slope_bounds(&self) -> [f64; 2] {
        self.slope
    }

    /// The bilinear height and its derivatives at `(x, y)` \[m\] (module documentation). On an
    /// interior grid line the one-sided derivatives across it differ (the interpolation is
    /// continuous, not smooth): there the mean of both sides is taken, so that a grid
    /// symmetric in `y` gives a normal without lateral part on its mid-line.
    pub fn height(&self, x: f64, y: f64) -> GridHeight {
        let (i, xi, in_x) = cell(&self.x, x);
        let (j, eta, in_y) = cell(&self.y, y);
        let mid = |a: &[f64], k: usize, f: f64| k > 0 && f == 0.0 && k + 1 < a.len();
        // the cells on both sides of an interior grid line through the point
        let xs: &[(usize, f64)] = if in_x && mid(&self.x, i, xi) {
            &[(i - 1, 1.0), (i, 0.0)]
        } else {
            &[(i, xi)]
        };
        let ys: &[(usize, f64)] = if in_y && mid(&self.y, j, eta) {
            &[(j - 1, 1.0), (j, 0.0)]
        } else {
            &[(j, eta)]
        };
        let mut out = self.in_cell(i, j, xi, eta, in_x, in_y);
        if xs.len() > 1 || ys.len() > 1 {
            let (mut hx, mut hy, mut hxy) = (0.0, 0.0, 0.0);
            for &(a, f) in xs {
                for &(b, g) in ys {
                    let c = self.in_cell(a, b, f, g, in_x, in_y);
                    hx += c.hx;
                    hy += c.hy;
                    hxy += c.hxy;
                }
            }
            let n = (xs.len() * ys.len()) as f64;
            out.hx = hx / n;
            out.hy = hy / n;
            out.hxy = hxy / n;
        }
        out
    }

    /// The bilinear form of cell `(i, j)` at the fractions `(ξ, η)`; the derivative along an
    /// axis is 0 outside the grid's extent on it (`in_x`, `in_y` false).
    fn in_cell(&self, i: usize, j: usize, xi: f64, eta: f64, in_x: bool, in_y: bool) -> GridHeight {
        let ny = self.y.len();
        let at = |a: usize, b: usize| self.h[(i + a) * ny + j + b];
        let (h00, h10, h01, h11) = (at(0, 0), at(1, 0), at(0, 1), at(1, 1));
        let dx = self.x[i + 1] - self.x[i];
        let dy = self.y[j + 1] - self.y[j];
        let h = (1.0 - xi) * (1.0 - eta) * h00
            + xi * (1.0 - eta) * h10
            + (1.0 - xi) * eta * h01
            + xi * eta * h11;
        let hx = if in_x {
            ((1.0 - eta) * (h10 - h00) + eta * (h11 - h01)) / dx
        } else {
            0.0
        };
        let hy = if in_y {
            ((1.0 - xi) * (h01 - h00) + xi * (h11 - h10)) / dy
        } else {
            0.0
        };
        let hxy = if in_x && in_y {
            (h11 - h10 - h01 + h00) / dx / dy
        } else {
            0.0
        };
        GridHeight { h, hx, hy, hxy }
    }

    /// Whether the grid is its own mirror image under `y ↦ −y`: `y_j = −y_{m−1−j}` and
    /// `h(x_i, y_j) = h(x_i, y_{m−1−j})` to `tol` \[m\].
    pub fn is_mirror_symmetric_in_y(&self, tol: f64) -> bool {
        let m = self.y.len();
        (0..m).all(|j| (self.y[j] + self.y[m - 1 - j]).abs() <= tol)
            && (0..self.x.len()).all(|i| {
                (0..m).all(|j| (self.h[i * m + j] - self.h[i * m + m - 1 - j]).abs() <= tol)
            })
    }
}

/// The road of a [`HeightGrid`]: the grid's `x` along the unit `along`, its `y` along
/// `up × along`, its heights along the unit road normal `up`, its node `(0, 0)` at height 0 at
/// `origin` (which moves with the road material, `velocity` in the road plane).
#[derive(Debug, Clone, Copy)]
pub struct GridRoad<'a> {
    /// The grid.
    pub grid: &'a HeightGrid,
    /// Where the grid's `(x, y) = (0, 0)` lies on the reference plane \[m\].
    pub origin: Point3<f64>,
    /// Unit direction of the grid's `x` (in the road plane).
    pub along: Vector3<f64>,
    /// Unit normal of the reference plane (heights are along it).
    pub up: Vector3<f64>,
    /// Velocity of the road material \[m/s\].
    pub velocity: Vector3<f64>,
}

impl GridRoad<'_> {
    /// `c = 1/√(1 + G_x² + G_y²)` and the lower bound `q = c (Z − h)` of the gap at `p`,
    /// 1-Lipschitz in `p` (module documentation), with its largest rate of change at a fixed
    /// point `c (G_x |u·along| + G_y |u·across|)` \[m/s\]: `(q, rate)`.
    pub fn bound(&self, p: &Point3<f64>) -> (f64, f64) {
        let [gx, gy] = self.grid.slope_bounds();
        let c = 1.0 / (1.0 + gx * gx + gy * gy).sqrt();
        let q = p - self.origin;
        let across = self.up.cross(&self.along);
        let z = q.dot(&self.up) - self.grid.height(q.dot(&self.along), q.dot(&across)).h;
        let rate =
            c * (gx * self.velocity.dot(&self.along).abs() + gy * self.velocity.dot(&across).abs());
        (c * z, rate)
    }
}

impl Surface<3> for GridRoad<'_> {
    /// `g = n_z (Z − h)`, `n = c_n (up − h_x along − h_y across)` with `c_n = 1/√(1 + h_x² +
    /// h_y²)`, closest point `p − g n` (the foot on the tangent plane); `∇g = n + (Z − h) ∇c_n`
    /// with `∇c_n = −c_n³ h_xy (h_x across + h_y along)` and
    /// `∂n/∂p = −c_n h_xy (along acrossᵀ + across alongᵀ) + (n/c_n) ∇c_nᵀ` (within a cell,
    /// where `h_xx = h_yy = 0`).
    fn closest(&self, p: &Point3<f64>) -> SurfacePoint<3> {
        let across = self.up.cross(&self.along);
        let q = p - self.origin;
        let gh = self.grid.height(q.dot(&self.along), q.dot(&across));
        let z = q.dot(&self.up) - gh.h;
        let cn = 1.0 / (1.0 + gh.hx * gh.hx + gh.hy * gh.hy).sqrt();
        let w = self.up - self.along * gh.hx - across * gh.hy;
        let n = w * cn;
        let gap = cn * z;
        let dc = (across * gh.hx + self.along * gh.hy) * (-cn * cn * cn * gh.hxy);
        let sym = self.along * across.transpose() + across * self.along.transpose();
        let dn = sym * (-cn * gh.hxy) + w * dc.transpose();
        let t = self.along - n * n.dot(&self.along);
        SurfacePoint {
            gap,
            normal: n,
            gap_gradient: n + dc * z,
            tangent: t.try_normalize(0.0).unwrap_or(self.along),
            point: p - n * gap,
            surface_velocity: self.velocity,
            dn_dp: dn,
            dus_dp: Matrix3::zeros(),
            dus_domega: Vector3::zeros(),
            part: 0,
        }
    }
    fn center(&self) -> Point3<f64> {
        self.origin
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::spatial::geometry::HalfSpace;

    const CSV: &str = "# a test road\n\
        x_m \\ y_m, -0.2, 0.0, 0.1, 0.3\r\n\
        \n\
        -0.1, 0.0, 0.001, 0.002, 0.0\n\
        0.05, 0.003, -0.001, 0.004, 0.002\n\
        0.2,  0.001, 0.0, 0.0, 0.005\n";

    // Reference: the nodes of the file (the interpolation passes through them) and the
    // bilinear form written out for one cell.
    #[test]
    fn parses_and_interpolates() {
        let g = HeightGrid::parse_csv(CSV, 100).unwrap();
        assert_eq!(g.x(), &[-0.1, 0.05, 0.2]);
        assert_eq!(g.y(), &[-0.2, 0.0, 0.1, 0.3]);
        assert_eq!(g.height(0.05, 0.1).h, 0.004);
        assert_eq!(g.height(0.2, 0.3).h, 0.005);
        // beyond the grid: the edge values, no slope across the edge
        let e = g.height(0.5, 0.0);
        assert_eq!((e.h, e.hx, e.hxy), (0.0, 0.0, 0.0));
        // cell (0.05..0.2) × (0.0..0.1), at ξ = 0.4, η = 0.3
        let (x, y) = (0.05 + 0.4 * 0.15, 0.03);
        let (h00, h10, h01, h11) = (-0.001, 0.0, 0.004, 0.0);
        let want = 0.6 * 0.7 * h00 + 0.4 * 0.7 * h10 + 0.6 * 0.3 * h01 + 0.4 * 0.3 * h11;
        let got = g.height(x, y);
        assert!((got.h - want).abs() < 1e-17);
        assert!((got.hx - (0.7 * (h10 - h00) + 0.3 * (h11 - h01)) / 0.15).abs() < 1e-14);
        assert!((got.hy - (0.6 * (h01 - h00) + 0.4 * (h11 - h10)) / 0.1).abs() < 1e-14);
        assert!((got.hxy - (h11 - h10 - h01 + h00) / 0.015).abs() < 1e-12);
        // on an interior grid line: the mean of the one-sided slopes
        let on = g.height(0.12, 0.0);
        let left = g.height(0.12, -1e-12);
        let right = g.height(0.12, 1e-12);
        assert!((on.hy - 0.5 * (left.hy + right.hy)).abs() < 1e-9);
        assert!((on.h - left.h).abs() < 1e-13);
        // the slope bounds: the largest neighbour difference quotients
        assert!((g.slope_bounds()[0] - 0.004 / 0.15).abs() < 1e-15);
        assert!((g.slope_bounds()[1] - 0.005 / 0.1).abs() < 1e-15);
    }

    // Reference: a plane tilted in x and y is reproduced exactly by bilinear interpolation;
    // its gap is the distance to the plane (a HalfSpace with the plane's normal).
    #[test]
    fn a_plane_is_exact() {
        let (x, y) = (vec![-1.0, 0.0, 0.5, 2.0], vec![-0.4, 0.1, 0.4]);
        let plane = |x: f64, y: f64| 0.01 + 0.03 * x - 0.02 * y;
        let h: Vec<f64> = x
            .iter()
            .flat_map(|&a| y.iter().map(move |&b| plane(a, b)))
            .collect();
        let g = HeightGrid::new(x, y, h).unwrap();
        let road = GridRoad {
            grid: &g,
            origin: Point3::new(0.0, 0.0, -0.3),
            along: Vector3::x(),
            up: Vector3::z(),
            velocity: Vector3::new(-10.0, 0.5, 0.0),
        };
        let n = Vector3::new(-0.03, 0.02, 1.0).normalize();
        let half = HalfSpace {
            origin: Point3::new(0.0, 0.0, -0.3 + 0.01),
            normal: n,
            tangent: Vector3::x(),
            velocity: road.velocity,
        };
        for p in [[0.2, 0.05, -0.28], [1.3, -0.3, -0.27], [-0.6, 0.3, -0.31]] {
            let (a, b) = (
                road.closest(&Point3::from(p)),
                half.closest(&Point3::from(p)),
            );
            assert!((a.gap - b.gap).abs() < 1e-15, "{p:?}");
            assert!((a.normal - b.normal).amax() < 1e-15);
            assert!((a.point - b.point).amax() < 1e-15);
            assert!(a.dn_dp.amax() < 1e-15);
        }
    }

    // Reference: central differences of the gap, normal and the bound's Lipschitz constant and
    // rate on a rough grid inside cells, and the lower bound q ≤ g where q ≥ 0.
    #[test]
    fn derivatives_and_bounds() {
        let g = HeightGrid::parse_csv(CSV, 100).unwrap();
        let along = Vector3::new(0.96, 0.0, 0.28);
        let up = Vector3::new(-0.28, 0.0, 0.96);
        let road = GridRoad {
            grid: &g,
            origin: Point3::new(0.1, 0.2, 0.0),
            along,
            up,
            velocity: along * -12.0 + up.cross(&along) * 0.7,
        };
        let across = up.cross(&along);
        let at =
            |x: f64, y: f64, z: f64| Point3::new(0.1, 0.2, 0.0) + along * x + across * y + up * z;
        let h = 1e-7;
        for p in [
            at(0.11, 0.03, 0.004),
            at(-0.03, -0.1, 0.0),
            at(0.15, 0.2, -0.002),
        ] {
            let s = road.closest(&p);
            let mut grad = Vector3::zeros();
            for j in 0..3 {
                let mut e = Vector3::zeros();
                e[j] = h;
                let (a, b) = (road.closest(&(p + e)), road.closest(&(p - e)));
                grad[j] = (a.gap - b.gap) / (2.0 * h);
                let dn = (a.normal - b.normal) / (2.0 * h);
                for i in 0..3 {
                    assert!((dn[i] - s.dn_dp[(i, j)]).abs() < 1e-6, "dn[{i}][{j}]");
                }
            }
            assert!(
                (grad - s.gap_gradient).amax() < 1e-7,
                "{grad} {}",
                s.gap_gradient
            );
        }
        // q is 1-Lipschitz and moves at most at its rate; q ≤ g where q ≥ 0
        let mut rnd = 0x1234_5678u64;
        let mut next = move || {
            rnd ^= rnd << 13;
            rnd ^= rnd >> 7;
            rnd ^= rnd << 17;
            (rnd >> 11) as f64 / (1u64 << 53) as f64 - 0.5
        };
        let (_, rate) = road.bound(&at(0.0, 0.0, 0.0));
        for _ in 0..2000 {
            let p = at(0.6 * next(), 0.8 * next(), 0.01 * next());
            let d = Vector3::new(next(), next(), next()) * 0.02;
            let (qa, _) = road.bound(&p);
            let (qb, _) = road.bound(&(p + d));
            assert!((qa - qb).abs() <= d.norm() * (1.0 + 1e-12) + 1e-17);
            let gap = road.closest(&p).gap;
            if qa >= 0.0 {
                assert!(qa <= gap + 1e-17, "{qa} > {gap}");
            }
            // the road moved by u dt: the same as the point moved by −u dt
            let dt = 1e-3 * next().abs();
            let moved = GridRoad {
                origin: road.origin + road.velocity * dt,
                ..road
            };
            let (qm, _) = moved.bound(&p);
            assert!((qm - qa).abs() <= rate * dt * (1.0 + 1e-9) + 1e-17);
        }
    }

    // Reference: the reader's contract (module documentation) on a few thousand mutated files
    // (bytes replaced by format characters, lines cut, duplicated or dropped, huge numbers): a
    // grid with increasing axes and finite values, or an error naming a line of the text;
    // never a panic. The coverage-guided version is the `height_grid` target of fuzz/.
    #[test]
    fn mutated_files_give_a_grid_or_an_error() {
        let mut rnd = 0x9e37_79b9_7f4a_7c15u64;
        let mut next = move |n: usize| {
            rnd ^= rnd << 13;
            rnd ^= rnd >> 7;
            rnd ^= rnd << 17;
            (rnd >> 11) as usize % n.max(1)
        };
        let pieces = [
            ",", "\n", "#", " ", "-", "e", "1e308", "NaN", "inf", "0", ".", "\r", "1e-300", "9",
            "x",
        ];
        let mut accepted = 0;
        for _ in 0..4000 {
            let mut t: Vec<String> = CSV.split('\n').map(str::to_string).collect();
            for _ in 0..1 + next(4) {
                let k = next(t.len());
                match next(5) {
                    0 => {
                        let line = &mut t[k];
                        let at = next(line.len() + 1);
                        let at = (0..=at)
                            .rev()
                            .find(|&i| line.is_char_boundary(i))
                            .unwrap_or(0);
                        line.insert_str(at, pieces[next(pieces.len())]);
                    }
                    1 => {
                        let line = &mut t[k];
                        let at = next(line.len() + 1);
                        let at = (0..=at)
                            .rev()
                            .find(|&i| line.is_char_boundary(i))
                            .unwrap_or(0);
                        line.truncate(at);
                    }
                    2 => {
                        let l = t[k].clone();
                        t.insert(k, l);
                    }
                    3 if t.len() > 1 => {
                        t.remove(k);
                    }
                    _ => {
                        let (from, to) = (pieces[next(pieces.len())], pieces[next(pieces.len())]);
                        t[k] = t[k].replace(from, to);
                    }
                }
            }
            let text = t.join("\n");
            match HeightGrid::parse_csv(&text, 50) {
                Ok(g) => {
                    accepted += 1;
                    assert!(g.x().windows(2).all(|w| w[0] < w[1]));
                    assert!(g.y().windows(2).all(|w| w[0] < w[1]));
                    assert!(g.x().len() * g.y().len() <= 50);
                    let (x, y) = (g.x(), g.y());
                    for (a, b) in [
                        (x[0], y[0]),
                        (0.5 * (x[0] + x[x.len() - 1]), y[1]),
                        (x[1], -1e9),
                    ] {
                        let h = g.height(a, b);
                        assert!(h.h.is_finite() && h.hx.is_finite() && h.hy.is_finite());
                        assert!(h.hxy.is_finite(), "{text}");
                    }
                }
                Err(e) => assert!(e.line <= text.split('\n').count(), "{e}: {text}"),
            }
        }
        // the mutations must leave some files readable, else the test checks errors only
        assert!(accepted > 100, "{accepted} accepted");
    }

    fn error(text: &str) -> String {
        HeightGrid::parse_csv(text, 12).unwrap_err().to_string()
    }

    // Reference: the format's rules, one violation each, with the line and column reported.
    #[test]
    fn bad_files_name_line_and_column() {
        assert_eq!(error(""), "no header row (the file has no data)");
        assert!(error("l, 0.0\n").starts_with("line 1: the header has 1 y coordinates"));
        assert!(error("l, 0.0, -1.0\n").starts_with("line 1, column 3: y = -1 m is not above"));
        assert!(error("l, 0, 1\n0, 1\n").starts_with("line 2: the row has 1 heights"));
        assert!(error("l, 0, 1\n0, 1, 2, 3\n").starts_with("line 2, column 4: the row has more"));
        assert!(error("l, 0, 1\n0, 1, x\n").contains("line 2, column 3: `x` is not a number"));
        assert!(
            error("l, 0, 1\n0, 1, NaN\n")
                .contains("line 2, column 3: a height [m] `NaN` is not finite")
        );
        assert!(error("l, 0, 1\n0, 1, \n").contains("line 2, column 3: empty cell"));
        assert!(
            error("l, 0, 1\n0, 1, 1e300\n")
                .contains("line 2, column 3: a height [m] 1e300 is beyond")
        );
        assert!(
            error("l, 0, 1\n1, 1, 1\n1, 0, 0\n")
                .starts_with("line 3, column 1: x = 1 m is not above")
        );
        assert!(error("l, 0, 1\n0, 1, 1\n").starts_with("1 rows of heights"));
        // 7 rows of 2 exceed 12 nodes: refused at the row that would
        let big =
            "l, 0, 1\n".to_string() + &(0..7).map(|i| format!("{i}, 0, 0\n")).collect::<String>();
        assert!(
            error(&big).starts_with("line 8: more than 12 grid nodes"),
            "{}",
            error(&big)
        );
        // an escape sequence is quoted safely
        assert!(error("l, 0, 1\n0, 1, \u{1b}[31m\n").contains("\\u{1b}"));
    }
}
