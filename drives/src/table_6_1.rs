//! Ribaric's Table 6-1 drive (§6.1, §6.4): the embedded default of the speed-loss study.
//!
//! Two pulleys of R = 0.05 m inside the loop at (0, 0) and (0.45, 0) m; the belt of
//! EA = 152 000 N, EI = 2.6·10⁻² N m², ρA = 0.096 kg/m mounted at T0 = 310 N on the path
//! (note U8: the printed 1.2 m belt cannot be stretched onto the 1.214 m path at 310 N; the
//! path of L_c and R is taken as printed and T0 is the tension of that mounted state); penalty
//! contact (6.1) with tanh friction (6.2) μ = 1.2, κ = 40 s/m; Rayleigh damping α = 2.8 s⁻¹,
//! β = 1.8·10⁻³ s; the driven pulley's inertia 0.013 kg m². The procedure overwrites the
//! driver's speed and the driven pulley's load.

use belt::{Drive, Layout};

/// Table 6-1 as a layout (driver at rest, no load).
pub fn layout() -> Layout {
    Layout::table_6_1()
}

/// Table 6-1 resolved.
///
/// # Panics
/// Never: the embedded layout is valid (tested).
pub fn drive() -> Drive {
    layout()
        .resolve()
        .expect("Ribaric Table 6-1 is a valid layout")
}
