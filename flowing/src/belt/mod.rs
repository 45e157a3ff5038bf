//! The flowing-material belt drive (Ribaric ch. 5–6): a belt loop whose FE mesh stays in place
//! while the material flows through it, reduced to contact-node static modes plus truncated
//! free-node modes, on two rigid pulleys with penalty contact and tanh friction.
//!
//! - [`BeltDriveConfig`]: Table 6-1 parameters;
//! - [`BeltFe`], [`FlowingBasis`]: the loop, its matrices and the reduction basis (5.9)–(5.13);
//! - [`FlowingBelt`]: the flowing-material equations (5.14) as a [`mbd_core::SecondOrderSystem`];
//! - [`analytical_speed_loss`]: Bechtel's formula (6.3).

pub mod config;
pub mod contact;
pub mod flowing_system;
pub mod model;
pub mod nodal;
pub mod schedule;
mod statics;
pub mod study;
pub mod wave;

pub use config::BeltDriveConfig;
pub use flowing_system::{FlowingBelt, NodeReport};
pub use model::{BeltFe, FlowingBasis};
pub use schedule::Schedule;
pub use study::{DriveModel, SpeedLossPoint, SpeedLossSettings, speed_loss_sweep};

/// Angular speed loss of Bechtel et al., Ribaric (6.3):
/// `Δω = (1 − (2RT0 − M_p + 2Rk)/(2RT0 + M_p + 2Rk)) ω = 2 M_p ω / (2R(T0 + k) + M_p)` \[rad/s\],
/// with `k = EA` \[N\] (the dimensionally consistent reading, seed-000 note U13), pulley radius
/// `R` \[m\], pre-tension `T0` \[N\], load torque `M_p` \[N m\] and driver speed `ω` \[rad/s\].
pub fn analytical_speed_loss(radius: f64, tension: f64, ea: f64, torque: f64, omega: f64) -> f64 {
    let a = 2.0 * radius * tension + 2.0 * radius * ea;
    (1.0 - (a - torque) / (a + torque)) * omega
}

#[cfg(test)]
mod tests {
    use super::*;

    // seed-000 note §2.3 table: Δω = 2 M_p ω / (15231 + M_p) for Table 6-1
    #[test]
    fn bechtel_line_matches_the_note_table() {
        let d = analytical_speed_loss(0.05, 310.0, 152_000.0, 10.0, 62.8);
        assert!((d - 0.08241).abs() < 5e-6, "{d}");
        let d = analytical_speed_loss(0.05, 310.0, 152_000.0, 20.0, 22.6);
        assert!((d - 0.05927).abs() < 5e-6, "{d}");
    }
}
