//! Unilateral contact by Lagrange multipliers with an active set (Ribaric §7.3, seed note U4):
//! a contact node is constrained to the surface, `g(r) = 0`, while active.

use crate::geometry::Surface;
use nalgebra::{Point, SVector};

/// Constraint data of one node against an obstacle: residual, Jacobian row and acceleration
/// right-hand side of `D r̈ = γ`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct UnilateralRow<const D: usize> {
    /// Gap `g` (signed distance) \[m\].
    pub gap: f64,
    /// Gap rate `ġ = nᵀ(ṙ − u_s)` \[m/s\].
    pub gap_rate: f64,
    /// Jacobian row `∂g/∂r = nᵀ` (acts on the node's position coordinates).
    pub normal: SVector<f64, D>,
    /// `γ = −(ṙ − u_s)ᵀ (∂n/∂r) (ṙ − u_s)`: the curvature term of `g̈` for an obstacle moving
    /// with constant velocity (zero for a flat road).
    pub gamma: f64,
}

/// Constraint row of a node at `p` moving with `v` against `surface` (plane or space).
pub fn unilateral_row<const D: usize, S: Surface<D> + ?Sized>(
    surface: &S, p: &Point<f64, D>, v: &SVector<f64, D>,
) -> UnilateralRow<D> {
    let sp = surface.closest(p);
    let n = sp.normal;
    let w = v - sp.surface_velocity;
    UnilateralRow {
        gap: sp.gap,
        gap_rate: n.dot(&w),
        normal: n,
        gamma: -w.dot(&(sp.dn_dp * w)),
    }
}

/// Active set of unilateral contacts.
///
/// Rule (seed note, Ribaric U4): an inactive contact becomes active when its gap is `≤ tol`
/// and it is approaching (`ġ ≤ 0`); an active contact is released when its multiplier becomes
/// tensile (`λ_N < 0`, compressive-positive convention).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct ActiveSet {
    active: Vec<bool>,
}

impl ActiveSet {
    /// `n` inactive contacts.
    pub fn new(n: usize) -> Self {
        Self {
            active: vec![false; n],
        }
    }

    /// Whether contact `i` is active.
    pub fn is_active(&self, i: usize) -> bool {
        self.active[i]
    }

    /// Indices of active contacts.
    pub fn active(&self) -> impl Iterator<Item = usize> + '_ {
        self.active
            .iter()
            .enumerate()
            .filter_map(|(i, a)| a.then_some(i))
    }

    /// Update with the current gaps, gap rates and multipliers (multipliers of inactive
    /// contacts are ignored). Returns whether the set changed.
    pub fn update(
        &mut self, gaps: &[f64], gap_rates: &[f64], multipliers: &[f64], tol: f64,
    ) -> bool {
        let mut changed = false;
        for i in 0..self.active.len() {
            let next = if self.active[i] {
                multipliers[i] >= 0.0
            } else {
                gaps[i] <= tol && gap_rates[i] <= 0.0
            };
            changed |= next != self.active[i];
            self.active[i] = next;
        }
        changed
    }
}
