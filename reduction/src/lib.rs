//! # reduction
//!
//! Reduction bases for deformable bodies (Lin 2005, Ribaric 2012 ch. 3): static condensation
//! (Guyan), fixed-interface and free-free modal truncation, Craig–Bampton, mode condensation and
//! Eitelberg's method; axis (reference) conditions (nodal-fixed, mean, principal axes) applied to
//! them; the `ReducedModel` with recovery of nodal fields, and floating-frame deformable bodies.
