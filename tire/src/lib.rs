//! # tire
//!
//! The reduced FE tire with flowing material (Ribaric ch. 7–8): a domain crate above the
//! numerical layers it uses — the flowing-material derivative operators of `flowing`, the
//! Craig–Bampton reduction of `reduction`, the FE model and readers of `fe-model`, the contact
//! geometry, friction laws and the shared Alart–Curnier solver of `contact`, and the
//! generalized-α stepper of `mbd-core`. Nothing below depends on it.
//!
//! * [`mesh`]: the tire FE model (lumped M, K with inflation prestress, rim and patch node
//!   sets, circumferential rings) — Ribaric (7.1), (7.4);
//! * [`mod@reduce`], [`reduced`]: the reduction of §8.2 (contact-node, free-node and static
//!   modes, circumferential mode-shape derivatives) and the saved reduced tire;
//! * [`ground`]: drum or flat road with a semicircular cleat (contact crate geometry);
//! * [`statics`]: the preload (static contact with Lagrange multipliers, Ribaric §7.3);
//! * [`mirror`]: the half model of mirror-symmetric motion (symmetric modal coordinates, one
//!   contact unknown per mirrored node pair);
//! * [`rolling`]: the wheel–tire equations (7.10)/(7.17) with the notes' corrections E15, E16,
//!   U15–U17, integrated with Lagrange contact and Coulomb slip friction;
//! * [`rig`]: the cleat-test sequence of §8.3 and its outputs; [`spectrum`]: amplitude spectra;
//! * [`rotating`]: complex modes of the rotating tire in the ground frame (gyroscopic and
//!   convective terms of (7.17)), labelled by [`harmonics`] with circumferential order and
//!   forward/backward direction;
//! * [`dips`]: the speed dips of the cleat test from the cleat's enveloping profile and the
//!   loaded vertical mode;
//! * [`study`]: the tire source (generated or imported tire and its reduction), the cleat
//!   study's configuration and summary, shared by `flowmbd-tire` and the Python package.

// Dense numerical kernels index several arrays with one loop variable; iterator chains would
// obscure the equations.
#![allow(clippy::needless_range_loop)]

pub mod error;
pub mod mesh;
pub mod reduce;
pub mod reduced;

pub use error::TireError;
pub use mesh::{Ring, TireFe};
pub use reduce::{ReductionConfig, ReductionTimings, full_frequencies_hz, reduce};
pub use reduced::{ModalTire, ReducedTire, TreadBasis, VizBasis};
pub mod harmonics;
pub mod lines;
pub use lines::{LineMode, SpindleComponent, line_modes};
pub mod rotating;
pub use harmonics::{Harmonic, WaveDirection};
pub use rotating::{
    FlowingMatrices, RotatingMode, RotatingOptions, SpeedModes, modes_at_speed, rotating_modes,
    spinning_modes,
};
pub mod contact_solve;
pub mod dips;
pub use dips::{
    DipConfig, DipPrediction, EnvelopingProfile, GroundDips, PulseShape, enveloping_profile,
    geometric_envelope_half_length, ground_dips, line_amplitude, local_minima, predict_dips,
};
pub mod friction;
pub mod ground;
pub mod lcp;
pub mod loaded;
pub mod mirror;
pub mod statics;
pub use friction::TireFriction;
pub use ground::{Ground, GroundConfig, GroundKind};
pub use loaded::{
    LoadedMode, dominant_longitudinal_mode, dominant_vertical_mode, held_nodes, loaded_modes,
    loaded_modes_at_preload,
};
pub use statics::{PatchSolution, Preload, preload, preload_rolling, solve_patch};
pub mod contact_step;
pub mod dynamics;
mod kernels;
pub mod rolling;
pub use contact_step::TireContact;
pub use dynamics::TireDynamics;
pub use mirror::{MirrorHalf, half_tire, mirror_half};
pub use rolling::{
    NormalContact, RollingConfig, RollingState, RollingTire, SpindleForce, SpindleForceMethod,
    StepStats, Symmetry, SymmetryUse,
};
pub mod model;
pub use model::{
    ImportFiles, ImportFormat, coarse_tire_config, generated_tire, imported_tire, truck_tire_config,
};
pub mod rig;
pub mod spectrum;
pub mod study;
pub use rig::{
    DampingConfig, ImpactConfig, RigConfig, RigResult, RigStart, Sample, run_cleat,
    run_cleat_observed, start_rolling,
};
pub use spectrum::{
    LINE_BAND_HZ, PEAK_BAND_HZ, Spectrum, SpectrumGrid, amplitude_spectrum, rms_fluctuation,
    spectrum_grid,
};
pub use study::{
    CleatStudyConfig, CleatSummary, MAX_CLEAT_PHASES, PhaseSpread, TireSource, cleat_summary,
    phase_spread, rig_input_error, summarize, tire_input_error,
};
