//! # tire
//!
//! The reduced FE tire with flowing material (Ribaric ch. 7–8): a domain crate above the
//! numerical layers it uses — the flowing-material derivative operators of `flowing`, the
//! Craig–Bampton reduction of `reduction`, the FE model and readers of `fe-model`, the contact
//! geometry, friction laws and the shared Alart–Curnier solver of `contact`, and the
//! generalized-α stepper of `mbd-core`. Nothing below depends on it.
//!
//! The FE tire and its reduction:
//! * [`mesh`]: the tire FE model (lumped M, K with inflation prestress, rim and patch node
//!   sets, circumferential rings) — Ribaric (7.1), (7.4); [`model`]: the generated truck tire;
//!   [`import`]: a user's tire from ABAQUS or Matrix Market files, with the checks that catch
//!   the easy mistakes;
//! * [`mod@reduce`], [`reduced`]: the reduction of §8.2 (contact-node, free-node and static
//!   modes, circumferential mode-shape derivatives) and the saved reduced tire (versioned JSON
//!   with a checksum);
//! * [`source`]: where the reduced tire comes from (generated or imported, reduction settings)
//!   and its fingerprint; [`cache`]: the reduced-tire file and the cache keyed by content and
//!   code version ([`CODE_VERSION`]); [`files`]: bounded reads, atomic writes, digests.
//!
//! The rolling tire and its studies:
//! * [`ground`]: drum or flat road with a semicircular cleat, obstacles (cleats of any section,
//!   oblique cleats, steps, potholes) and height-grid roads, tilted for camber (contact crate
//!   geometry);
//! * [`statics`]: the preload (static contact with Lagrange multipliers, Ribaric §7.3);
//! * [`mirror`]: the half model of mirror-symmetric motion (symmetric modal coordinates, one
//!   contact unknown per mirrored node pair);
//! * [`dynamics`]: the smooth wheel–tire equations (7.10)/(7.17) with the notes' corrections
//!   E15, E16, U15–U17 as a second-order system; [`contact_step`]: the contact with the ground
//!   as the step correction of the generalized-α stepper, solved by the contact crate's shared
//!   Alart–Curnier solver ([`contact::ContactSolver`]); [`rolling`]: the two stepped together,
//!   with its settings [`rolling_config`] (friction law: [`friction`]) and work counters
//!   [`stats`];
//! * [`rig`]: the cleat-test sequence of §8.3 and its outputs; [`spectrum`]: amplitude spectra;
//! * [`rotating`]: complex modes of the rotating tire in the ground frame (gyroscopic and
//!   convective terms of (7.17)), labelled by [`harmonics`] with circumferential order and
//!   forward/backward direction;
//! * [`rotating_study`]: the rotating-modes study (configuration, summary, Campbell splits);
//! * [`dips`]: the speed dips of the cleat test from the cleat's enveloping profile and the
//!   loaded vertical mode;
//! * [`dips_study`], [`pressure_study`], [`modes_study`]: the speed-dips, contact-patch and
//!   modes studies (configuration, summary, CSV tables);
//! * [`sweep_study`]: the speed sweep of the cleat test (Ribaric Figs. 8-7, 8-8, 8-14);
//! * [`study`]: the cleat study's configuration and summary and the classification of errors
//!   into bad input and numerical failures, shared by `flowmbd-tire` and the Python package.

// Dense numerical kernels index several arrays with one loop variable; iterator chains would
// obscure the equations.
#![allow(clippy::needless_range_loop)]

/// The version of the code that reduces a tire: the package version and a digest of the source
/// the reduced numbers depend on (see `build.rs`: the FE tire, its import and reduction, the
/// reduced-tire file, fe-model, reduction, the derivative operators, `Cargo.lock`). Recorded in
/// every reduced tire ([`ReducedTire::code_version`]) and part of the cache key
/// ([`TireSource::reduced_path`]), so that a cached tire is reused only by the code that made it.
pub const CODE_VERSION: &str = env!("FLOWMBD_TIRE_CODE_VERSION");

// the FE tire and its reduction
pub mod cache;
pub mod error;
pub mod files;
pub mod import;
pub mod mesh;
pub mod model;
pub mod reduce;
pub mod reduced;
pub mod source;

pub use cache::{CacheUse, Reducing, SourcedTire, cache_dir};
pub use error::TireError;
pub use import::{ImportCheckError, ImportFiles, ImportFormat, imported_tire};
pub use mesh::{Ring, TireFe};
pub use model::{coarse_tire_config, generated_tire, truck_tire_config};
pub use reduce::{ReductionConfig, ReductionTimings, full_frequencies_hz, reduce};
pub use reduced::{ModalTire, ReducedTire, TreadBasis, VizBasis};
pub use source::{CACHE, TireSource};

// modes of the standing, loaded and rotating tire
pub mod harmonics;
pub mod lines;
pub mod loaded;
pub mod rotating;
pub mod rotating_study;

pub use harmonics::{Harmonic, WaveDirection};
pub use lines::{LineMode, SpindleComponent, line_modes};
pub use loaded::{
    LoadedMode, dominant_longitudinal_mode, dominant_vertical_mode, held_nodes, loaded_modes,
    loaded_modes_at_preload,
};
pub use rotating::{
    FlowingMatrices, RotatingMode, RotatingOptions, SpeedModes, modes_at_speed, rotating_modes,
    spinning_modes,
};
pub use rotating_study::{RotatingStudyConfig, RotatingSummary, run_rotating};

// the ground, the preload and the rolling tire
pub mod contact_step;
pub mod dynamics;
pub mod friction;
pub mod ground;
pub mod mirror;
pub mod motion;
pub mod rolling;
pub mod rolling_config;
pub mod statics;
pub mod stats;

pub use contact_step::TireContact;
pub use dynamics::TireDynamics;
pub use friction::TireFriction;
pub use ground::{CleatSection, Ground, GroundConfig, GroundKind, GroundPoint, Obstacle};
pub use mirror::{MirrorHalf, half_tire, mirror_half};
pub use motion::{CoSimulation, WheelMotion};
pub use rolling::{RollingState, RollingTire, SpindleForce, SymmetryUse, WheelLoads};
pub use rolling_config::{NormalContact, RollingConfig, SpindleForceMethod, Symmetry};
pub use statics::{
    PatchSolution, Preload, preload, preload_cambered, preload_rolling, preload_rolling_cambered,
    solve_patch, solve_patch_cambered,
};
pub use stats::StepStats;

// the studies: cleat test, spectra, speed dips
pub mod dips;
pub mod dips_study;
pub mod magic_formula;
pub mod modes_study;
pub mod pressure_study;
pub mod rig;
pub mod spectrum;
pub mod steady;
pub mod study;
pub mod sweep_study;
pub mod tir;

pub use dips::{
    DipConfig, DipPrediction, EnvelopingProfile, GroundDips, PulseShape, enveloping_profile,
    geometric_envelope_half_length, ground_dips, line_amplitude, local_minima, predict_dips,
};
pub use dips_study::{DipsStudyConfig, DipsSummary, run_dips};
pub use magic_formula::{MfCurve, MfFit, MfFitError, TrailCurve, fit_steady};
pub use modes_study::{ModesStudyConfig, ModesSummary, run_modes};
pub use pressure_study::{PressureStudyConfig, PressureSummary, pressure_meaning, run_pressure};
pub use rig::{
    DampingConfig, ImpactConfig, MAX_CAMBER_DEG, MAX_SLIP_ANGLE_DEG, RigConfig, RigResult,
    RigStart, Sample, WheelInputs, rig_step, run_cleat, run_cleat_observed, start_rolling,
};
pub use spectrum::{
    LINE_BAND_HZ, PEAK_BAND_HZ, Spectrum, SpectrumGrid, amplitude_spectrum, rms_fluctuation,
    spectrum_grid,
};
pub use steady::{
    SteadyPoint, SteadyResult, SteadyStudyConfig, SteadySummary, cornering_stiffness,
    relaxation_length, rim_moment_transfer, run_steady, slip_stiffness, steady_summary,
};
pub use study::{
    CleatStudyConfig, CleatSummary, MAX_CLEAT_PHASES, PhaseSpread, cleat_summary, phase_spread,
    rig_input_error, summarize, tire_input_error,
};
pub use sweep_study::{SweepResult, SweepStudyConfig, SweepSummary, run_sweep};
pub use tir::{TirTyre, steady_tir, write_tir};
