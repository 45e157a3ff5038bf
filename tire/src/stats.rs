//! Work counters of the rolling tire's time integration ([`StepStats`]), kept by the time step
//! ([`crate::rolling`]) and the contact step ([`crate::contact_step`]).

use serde::Serialize;

/// Work counters of the time integration (for benchmarks and diagnostics).
#[derive(Debug, Clone, Copy, Default, PartialEq, Serialize)]
pub struct StepStats {
    /// Time steps taken.
    pub steps: usize,
    /// Sum over the steps of the contact candidates.
    pub candidates: usize,
    /// Sum over the steps of the nodes in contact.
    pub active: usize,
    /// Normal LCP solves (of the fallback alternation).
    pub lcp_solves: usize,
    /// Friction Gauss–Seidel sweeps (of the fallback alternation).
    pub friction_sweeps: usize,
    /// Newton iterations (LU factorisations) of the coupled contact solve.
    pub contact_newton: usize,
    /// Chord iterations (solves with an earlier Newton matrix) of the contact solve.
    pub contact_chord: usize,
    /// Steps whose contact solve fell back to the normal/friction alternation.
    pub contact_fallbacks: usize,
    /// Steps whose contact solve missed `contact_tolerance` (forces kept).
    pub contact_unconverged: usize,
    /// Contact-node column sets computed (`S⁻¹` columns of one node).
    pub columns: usize,
    /// Re-formings of the spin-dependent force matrix `R` (drift beyond `spin_tolerance`).
    pub force_matrix_updates: usize,
    /// Nodes whose free end-of-step gap is below −`contact_margin` although they were not
    /// candidates in the previous step: impacts begun within one step. They are part of this
    /// step's contact problem (candidates are chosen from the current free gaps), so no contact
    /// is lost; a large count says that the step resolves the approach coarsely (e.g. the
    /// cleat's faces at high speed, or a lightly damped tread).
    pub late_contacts: usize,
    /// Seconds spent in: free step (products with `R` and `S⁻¹`), candidate search,
    /// re-forming `R`, contact problem, inverting `S` (with the contact-node columns).
    pub seconds: [f64; 5],
}
