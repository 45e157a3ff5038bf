//! The constraint list of a multibody container: validation when a constraint is added, row
//! offsets, evaluation against the carriers of the markers, names of rows and the scatter of
//! the Jacobian rows into the container's velocity columns (shared by
//! [`crate::MultibodySystem`] and [`crate::floating::FloatingSystem`]).

use super::{Constraint, Equation};
use crate::MbdError;
use crate::marker::{Carrier, Marker};

/// Constraints with their row offsets in `Φ` and `λ`.
#[derive(Default)]
pub struct ConstraintSet {
    items: Vec<Box<dyn Constraint>>,
    offsets: Vec<usize>,
    n_c: usize,
}

impl ConstraintSet {
    /// Empty set.
    pub fn new() -> Self {
        Self::default()
    }

    /// Validates `c` (its parameters, each marker with `check_marker(marker, what)`, no marker
    /// pair on the same body and node, not ground to ground) and appends it; returns its index.
    pub fn add(
        &mut self, c: Box<dyn Constraint>,
        check_marker: impl Fn(&Marker, &str) -> Result<(), MbdError>,
    ) -> Result<usize, MbdError> {
        let what = format!("constraint \"{}\"", c.name());
        c.validate()?;
        let [mi, mj] = c.markers();
        check_marker(&mi, &what)?;
        check_marker(&mj, &what)?;
        if mi.body.is_some() && mi.body == mj.body && mi.node == mj.node {
            return Err(MbdError::InvalidInput {
                item: what,
                reason: if mi.node.is_some() {
                    "connects a node to itself".into()
                } else {
                    "connects a body to itself".into()
                },
            });
        }
        if mi.body.is_none() && mj.body.is_none() {
            return Err(MbdError::InvalidInput {
                item: what,
                reason: "connects the ground to the ground".into(),
            });
        }
        self.offsets.push(self.n_c);
        self.n_c += c.n_eq();
        self.items.push(c);
        Ok(self.items.len() - 1)
    }

    /// Total number of equations.
    pub fn n_c(&self) -> usize {
        self.n_c
    }

    /// The constraints.
    pub fn constraints(&self) -> &[Box<dyn Constraint>] {
        &self.items
    }

    /// First row of constraint `c`.
    pub fn offset(&self, c: usize) -> usize {
        self.offsets[c]
    }

    /// Appends the equations of every constraint at time `t` \[s\]; `carrier(marker)` gives
    /// the kinematics of the body carrying a marker.
    pub fn eval<'a>(
        &self, t: f64, carrier: impl Fn(&Marker) -> Carrier<'a>, out: &mut Vec<Equation>,
    ) {
        out.reserve(self.n_c);
        for c in &self.items {
            let [mi, mj] = c.markers();
            c.eval(t, &carrier(&mi), &carrier(&mj), out);
        }
    }

    /// Calls `push(row, column, value)` for every Jacobian entry of `eqs` (from [`Self::eval`]),
    /// rows counted from `row0`; `columns(marker)` gives the first velocity column of the
    /// marker's body frame `(ṙ, ω')` and of its elastic coordinates `ż` (`None` for the ground).
    pub fn jacobian_entries(
        &self, eqs: &[Equation], row0: usize, columns: impl Fn(&Marker) -> Option<(usize, usize)>,
        mut push: impl FnMut(usize, usize, f64),
    ) {
        let mut row = row0;
        let mut eqs = eqs.iter();
        for c in &self.items {
            let [ci, cj] = c.markers().map(|m| columns(&m));
            for e in eqs.by_ref().take(c.n_eq()) {
                for k in 0..6 {
                    if let Some((f, _)) = ci {
                        push(row, f + k, e.row.di[k]);
                    }
                    if let Some((f, _)) = cj {
                        push(row, f + k, e.row.dj[k]);
                    }
                }
                for (side, el) in [(ci, &e.row.ei), (cj, &e.row.ej)] {
                    if let Some((_, z)) = side {
                        for (m, &x) in el.iter().enumerate() {
                            push(row, z + m, x);
                        }
                    }
                }
                row += 1;
            }
        }
    }

    /// Name of row `row` of the set (`None` past the end).
    pub fn row_name(&self, row: usize) -> Option<String> {
        let c = self
            .offsets
            .partition_point(|&o| o <= row)
            .saturating_sub(1);
        let con = self.items.get(c)?;
        (row < self.n_c).then(|| format!("\"{}\" (equation {})", con.name(), row - self.offsets[c]))
    }
}
