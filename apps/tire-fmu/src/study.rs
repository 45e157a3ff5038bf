//! The FMU as a study of `flowmbd-tire` (`flowmbd-tire fmu`, issue 38 item 1): its
//! configuration ([`FmuConfig`]: the tire and the rig, as the other tire studies), where the
//! compiled shared library is found ([`find_library`]) and the summary of the written FMU
//! ([`FmuSummary`]: its variables, frame and internal step). The app only parses, calls
//! [`write_fmu`](crate::write_fmu) and writes.

use crate::{
    Causality, FmuError, INSTANTIATION_TOKEN, MODEL_IDENTIFIER, VARIABLES, platform, start_values,
};
use mbd_core::validate::{InvalidField, Validate};
use serde::{Deserialize, Serialize};
use std::path::{Path, PathBuf};
use tire::motion::WheelMotion;
use tire::{ReducedTire, RigConfig, TireSource};

/// Configuration of the tire FMU (`flowmbd-tire fmu`): the tire (the `[tire]` tables of every
/// tire study) and the rig whose damping, integration, contact, `load`, `rolling.friction` and
/// `rolling.time_step` the FMU is built with (the FMU rolls on the flat road without cleat;
/// `speed_kmh` sets the start values of the inputs, [`tire::CoSimulation::rig_start`]).
#[derive(Debug, Clone, Default, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(default, deny_unknown_fields)]
pub struct FmuConfig {
    /// The tire.
    pub tire: TireSource,
    /// The rig.
    pub rig: RigConfig,
}

impl mbd_core::config::PartialRules for FmuConfig {}

impl Validate for FmuConfig {
    /// The tire's and the rig's checks ([`tire::study::validate_rig`]), fields named from the
    /// root (`tire.…`, `rig.…`).
    fn validate(&self) -> Result<(), InvalidField> {
        self.tire.validate_within("tire")?;
        tire::study::validate_rig(&self.rig)
    }
}

/// The file name of the compiled FMU library on this platform (`libflowmbd_tire_fmu.so` on
/// Linux, `.dylib` on macOS, `flowmbd_tire_fmu.dll` on Windows: Cargo's cdylib names).
pub fn library_file_name() -> String {
    format!(
        "{}{MODEL_IDENTIFIER}{}",
        std::env::consts::DLL_PREFIX,
        std::env::consts::DLL_SUFFIX
    )
}

/// The environment variable naming the compiled FMU library (as the Python package's
/// `flowmbd.tire.fmu_library`).
pub const LIBRARY_ENV: &str = "FLOWMBD_FMU_LIB";

/// The compiled FMU library to pack: `given` (the app's `--library`) if any, else
/// `$FLOWMBD_FMU_LIB` ([`LIBRARY_ENV`]) if set, else [`library_file_name`] in `exe_dir/deps`
/// (where Cargo puts the cdylib of a dependency: the library built with the executable) or in
/// `exe_dir` (where `cargo build --release -p flowmbd-tire-fmu` puts it). Errors
/// ([`InvalidField`], field `library`): a given or named file that does not exist, or none
/// found, with the command that builds it.
pub fn find_library(
    given: Option<&Path>, env: Option<PathBuf>, exe_dir: Option<&Path>,
) -> Result<PathBuf, InvalidField> {
    let named = given
        .map(|p| (p.to_path_buf(), "--library"))
        .or_else(|| env.map(|p| (p, LIBRARY_ENV)));
    if let Some((p, from)) = named {
        return if p.is_file() {
            Ok(p)
        } else {
            Err(InvalidField::new(
                "library",
                format!(
                    "`{}` ({from}) is not a file: build the FMU library with `cargo build \
                     --release -p flowmbd-tire-fmu`",
                    p.display()
                ),
            ))
        };
    }
    let name = library_file_name();
    let dirs: Vec<PathBuf> = exe_dir
        .map(|d| vec![d.join("deps"), d.to_path_buf()])
        .unwrap_or_default();
    dirs.iter()
        .map(|d| d.join(&name))
        .find(|p| p.is_file())
        .ok_or_else(|| {
            InvalidField::new(
                "library",
                format!(
                    "{name} not found in {}: build it with `cargo build --release -p \
                     flowmbd-tire-fmu`, or give its path with --library or {LIBRARY_ENV}",
                    dirs.iter()
                        .map(|d| format!("`{}`", d.display()))
                        .collect::<Vec<_>>()
                        .join(", ")
                ),
            )
        })
}

/// One variable of the FMU in the summary.
#[derive(Debug, Clone, Serialize)]
pub struct VariableSummary {
    /// Name in `modelDescription.xml`.
    pub name: &'static str,
    /// Value reference.
    pub value_reference: u32,
    /// `parameter`, `input` or `output`.
    pub causality: &'static str,
    /// Unit (SI symbol; `1` for none).
    pub unit: &'static str,
    /// Start value of a parameter or input (in its unit), `null` for an output.
    pub start: Option<f64>,
    /// What it is.
    pub description: &'static str,
}

/// Summary of `flowmbd-tire fmu` (`summary.json`): the written FMU and its interface.
#[derive(Debug, Clone, Serialize)]
pub struct FmuSummary {
    /// What the numbers mean.
    pub meaning: String,
    /// The written FMU (`tire.fmu` in the output folder).
    pub fmu: String,
    /// Its size \[bytes\].
    pub fmu_bytes: u64,
    /// FMI version (`3.0`, co-simulation only).
    pub fmi_version: &'static str,
    /// The model identifier (the shared library's name inside the FMU).
    pub model_identifier: &'static str,
    /// The instantiation token of `modelDescription.xml`.
    pub instantiation_token: &'static str,
    /// The platform folder of the binary (`binaries/<platform>/`, FMI 3.0 §2.5.1.4).
    pub platform: String,
    /// The compiled library that was packed.
    pub library: String,
    /// The internal step: the largest step of the rolling tire inside a communication step
    /// (`rig.rolling.time_step`, the `time_step` parameter's start value) \[s\].
    pub internal_step_s: f64,
    /// How a communication step is taken.
    pub stepping: &'static str,
    /// The frames of the inputs and outputs.
    pub frame: &'static str,
    /// The variables (parameters, inputs, outputs) with their start values.
    pub variables: Vec<VariableSummary>,
    /// The start motion (the inputs' start values: the rig's steady start).
    pub start: WheelMotion,
    /// The packed reduced tire: contact nodes `n_c`.
    pub contact_nodes: usize,
    /// The packed reduced tire: kept free-node modes `n_f` (tire coordinates `n_f + 3 n_c`).
    pub free_modes: usize,
    /// The packed reduced tire: mass without the rim nodes \[kg\].
    pub tire_mass_kg: f64,
}

/// The `meaning` of [`FmuSummary`].
pub const FMU_MEANING: &str = "An FMI 3.0 co-simulation FMU (tire.fmu) of the reduced FE tire \
    with flowing material (Ribaric 2012 ch. 7-8) rolling on a flat road, driven by its wheel-centre \
    motion (height, velocity, yaw, spin rate) and returning the six wheel loads in the ISO 8855 \
    wheel frame and the torque holding the prescribed spin. Only the start is solved here (the \
    rolling preload at rig.load, so that the FMU written starts); the summary lists the FMU's variables with their start values (the rig's steady start at \
    rig.load and rig.speed_kmh), the frames and the internal step; the FMU carries the compiled \
    library, the reduced tire and the rig settings.";

/// How a communication step is taken ([`tire::motion`]).
pub const STEPPING: &str = "a communication step H is ceil(H/h) equal internal steps of the \
    rolling tire (h = internal_step_s, generalized-alpha with the contact correction), the \
    inputs held over it (zero-order hold), the spin rate ramped to the new input over the first \
    internal step";

/// The frames of the inputs and outputs ([`tire::motion`]).
pub const FRAME: &str = "inputs: road frame, ISO 8855 earth-fixed axes on the road surface (x \
    forward, y left, z up; z = height of the wheel centre above the road), yaw about z, camber \
    about the wheel x axis (only 0); outputs: loads of the tire on the wheel in the ISO 8855 \
    wheel frame at the wheel centre (x forward in the wheel plane, y left along the spin axis, \
    z up; Fz > 0 the carried load), spin_torque about +y";

/// The summary of the FMU written to `fmu` from `library` with the reduced tire `red` on the
/// rig `rig` and the start motion `start` (as returned by [`write_fmu`](crate::write_fmu)).
pub fn fmu_summary(
    fmu: &Path, library: &Path, red: &ReducedTire, rig: &RigConfig, start: &WheelMotion,
) -> Result<FmuSummary, FmuError> {
    let fmu_bytes = std::fs::metadata(fmu)
        .map_err(|e| FmuError::Write {
            path: fmu.display().to_string(),
            reason: e.to_string(),
        })?
        .len();
    let starts = start_values(rig, start);
    let variables = VARIABLES
        .iter()
        .map(|v| VariableSummary {
            name: v.name,
            value_reference: v.vr,
            causality: match v.causality {
                Causality::Parameter => "parameter",
                Causality::Input => "input",
                Causality::Output => "output",
            },
            unit: if v.unit.is_empty() { "1" } else { v.unit },
            start: starts.iter().find(|s| s.0 == v.vr).map(|s| s.1),
            description: v.description,
        })
        .collect();
    Ok(FmuSummary {
        meaning: FMU_MEANING.to_string(),
        fmu: fmu.display().to_string(),
        fmu_bytes,
        fmi_version: "3.0",
        model_identifier: MODEL_IDENTIFIER,
        instantiation_token: INSTANTIATION_TOKEN,
        platform: platform(),
        library: library.display().to_string(),
        internal_step_s: rig.rolling.time_step,
        stepping: STEPPING,
        frame: FRAME,
        variables,
        start: *start,
        contact_nodes: red.n_contact(),
        free_modes: red.n_free_modes,
        tire_mass_kg: red.tire_mass,
    })
}
