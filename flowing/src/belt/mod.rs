//! The flowing-material belt drive (Ribaric ch. 5–6): a belt loop whose FE mesh stays in place
//! while the material flows through it, reduced to contact-node static modes plus truncated
//! free-node modes, on rigid pulleys with penalty contact and friction; and the rotating-mesh
//! nodal belt it replaces (Ribaric (5.7)). Both are built from a resolved [`belt::Drive`] and
//! implement [`belt::BeltModel`].
//!
//! - [`FlowingSettings`], [`BeltMesh`]: the models' settings (element lengths, reduction);
//! - [`BeltFe`], [`FlowingBasis`]: the loop, its matrices and the reduction basis (5.9)–(5.13);
//! - [`FlowingBelt`]: the flowing-material equations (5.14) as a [`mbd_core::SecondOrderSystem`];
//! - [`nodal::NodalBelt`]: the rotating-mesh nodal equations (5.7).
//!
//! The speed-loss procedure, Bechtel's line (6.3) and the studies live in the `drives` crate.

pub mod config;
pub mod contact;
mod coordinates;
pub mod flowing_system;
pub mod model;
pub mod nodal;
mod snapshot;
mod statics;
pub mod wave;

pub use config::{
    AxialForce, BeltEquations, BeltMesh, BeltReduction, BendingForce, FlowingSettings, ViscousForce,
};
pub use coordinates::DriveCoordinates;
pub use flowing_system::{FlowingBelt, NodeReport};
pub use model::{BeltFe, FlowingBasis};
pub use nodal::NodalBelt;
pub use snapshot::LINEAR_FORCE_MEASURE;

/// Ribaric Table 6-1's drive for the tests: driver at 0 (speed `speed` \[rad/s\]), driven
/// free with 0.013 kg m² against `load` \[N m\], T0 = 310 N, Ribaric's contact (κ = 40 s/m).
#[cfg(test)]
pub(crate) fn table_6_1(speed: f64, load: f64) -> belt::Drive {
    use belt::{Layout, Signal};
    let mut l = Layout::table_6_1();
    l.pulleys[0].motion = belt::Motion::speed(Signal::constant(speed));
    l.pulleys[1].motion = belt::Motion::load(0.013, Signal::constant(load));
    l.resolve().unwrap()
}
