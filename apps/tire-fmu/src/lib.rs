//! The rolling reduced tire as an FMI 3.0 co-simulation FMU (issue 38, item 4).
//!
//! The model is [`tire::motion::CoSimulation`] (one implementation with the Python
//! `flowmbd.tire.CoSimulation`): the tire on the cleat rig's road, driven by the wheel-centre
//! motion, its spin prescribed; see that module for frames, signs and the internal stepping.
//! This crate is its FMI shell only: the C API ([`ffi`], exported by the cdylib
//! `flowmbd_tire_fmu`), the packaging of the `.fmu` ([`write_fmu`]) and the study of
//! `flowmbd-tire fmu` ([`study`]: configuration, library search, summary).
//!
//! # Variables ([`VARIABLES`])
//! - parameters (fixed): `load` \[N\] (the preload the tire starts from), `friction` μ \[-\],
//!   `time_step` (the largest internal step) \[s\];
//! - inputs (continuous): wheel-centre position `x`, `y` (unused on the flat road), `z`
//!   (height above the road) \[m\]; velocity `vx`, `vy`, `vz` over the road, road frame
//!   \[m/s\]; orientation as yaw ψ and camber γ angles \[rad\] (wheel frame = road frame turned
//!   by ψ about z, then γ about x; the rig's camber, [`tire::motion`]); spin rate Ω \[rad/s\];
//! - outputs (continuous): `Fx`, `Fy`, `Fz` \[N\], `Mx`, `My`, `Mz` \[N·m\], the loads of the
//!   tire on the wheel in the ISO 8855 wheel frame at the wheel centre (x forward in the wheel
//!   plane, y left along the spin axis, z up; with camber in the W-axis orientation, z along
//!   the road normal; `Fz` > 0 is the carried load,
//!   [`tire::WheelLoads`]), and `spin_torque` \[N·m\], the torque that holds the prescribed spin
//!   about +y.
//!
//! # Why the C API is written here, not with `fmi-export`
//! `fmi-export` 0.3 (rust-fmi) was evaluated and not used: its exported functions call the
//! model without `catch_unwind`, so a panic would unwind into (and abort) the importer; its
//! `fmi3InstantiateCoSimulation` ignores the `logMessage` callback (the parameter is unused), so
//! errors could not reach the importer's logger; it reads `instanceName`/`resourcePath` with
//! `CStr::from_ptr` without a null check; and its `modelDescription.xml` is extracted from a
//! Rust-ABI symbol of the library by the separate `cargo-fmi` tool. The FMI 3.0 C API needed
//! here is small (one `Float64` variable type, co-simulation without event mode), so it is
//! written against the standard's header declarations (`fmi3FunctionTypes.h`) in [`ffi`],
//! with `catch_unwind` around every entry point.

pub mod ffi;
pub mod study;

pub use study::{FmuConfig, FmuSummary, find_library, fmu_summary};

use std::path::Path;
use tire::motion::{CoSimulation, WheelMotion};
use tire::{ReducedTire, RigConfig};

/// The FMU's model identifier: the name of its shared library and of the `.fmu`.
pub const MODEL_IDENTIFIER: &str = "flowmbd_tire_fmu";

/// The instantiation token of the model description (checked by
/// `fmi3InstantiateCoSimulation`): changes with the variables' layout.
pub const INSTANTIATION_TOKEN: &str = "{6f1f3a0e-38a4-4c2e-9d1b-flowmbd-tire-3}";

/// The reduced tire file in the FMU's `resources/` ([`tire::ReducedTire::save`]).
pub const TIRE_FILE: &str = "tire.json";

/// The rig settings in the FMU's `resources/` (TOML of [`tire::RigConfig`]: damping,
/// integration and contact; the parameters override `load`, `rolling.friction`,
/// `rolling.time_step`).
pub const RIG_FILE: &str = "rig.toml";

/// Causality of a variable.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Causality {
    /// Fixed parameter (set before `fmi3ExitInitializationMode`).
    Parameter,
    /// Continuous input.
    Input,
    /// Continuous output.
    Output,
}

/// One `Float64` variable of the FMU.
#[derive(Debug, Clone, Copy)]
pub struct Variable {
    /// Name in `modelDescription.xml`.
    pub name: &'static str,
    /// Value reference.
    pub vr: u32,
    /// Causality.
    pub causality: Causality,
    /// Unit (SI symbol as in the XML's `unit` attribute, `""` for none).
    pub unit: &'static str,
    /// Description.
    pub description: &'static str,
}

const fn var(
    name: &'static str, vr: u32, causality: Causality, unit: &'static str,
    description: &'static str,
) -> Variable {
    Variable {
        name,
        vr,
        causality,
        unit,
        description,
    }
}

/// The FMU's variables (value reference 0 is `time`), see the crate documentation.
pub const VARIABLES: [Variable; 19] = {
    use Causality::*;
    [
        var("load", 1, Parameter, "N", "preload the tire starts from"),
        var("friction", 2, Parameter, "1", "friction coefficient mu"),
        var("time_step", 3, Parameter, "s", "largest internal step"),
        var("x", 10, Input, "m", "wheel centre x (unused: flat road)"),
        var("y", 11, Input, "m", "wheel centre y (unused: flat road)"),
        var("z", 12, Input, "m", "wheel centre height above the road"),
        var(
            "vx",
            13,
            Input,
            "m/s",
            "wheel centre velocity x, road frame",
        ),
        var(
            "vy",
            14,
            Input,
            "m/s",
            "wheel centre velocity y, road frame",
        ),
        var(
            "vz",
            15,
            Input,
            "m/s",
            "wheel centre velocity z, road frame",
        ),
        var(
            "yaw",
            16,
            Input,
            "rad",
            "yaw angle of the wheel plane about z",
        ),
        var(
            "camber",
            17,
            Input,
            "rad",
            "camber angle about the wheel x axis (ISO 8855, within the rig's +-30 deg)",
        ),
        var(
            "spin_rate",
            18,
            Input,
            "rad/s",
            "spin rate of the wheel about +y",
        ),
        var(
            "Fx",
            20,
            Output,
            "N",
            "longitudinal force on the wheel, ISO wheel frame",
        ),
        var(
            "Fy",
            21,
            Output,
            "N",
            "lateral force on the wheel, ISO wheel frame",
        ),
        var(
            "Fz",
            22,
            Output,
            "N",
            "vertical force on the wheel (carried load)",
        ),
        var(
            "Mx",
            23,
            Output,
            "N.m",
            "overturning moment about the wheel centre",
        ),
        var(
            "My",
            24,
            Output,
            "N.m",
            "moment about the spin axis at the wheel centre",
        ),
        var(
            "Mz",
            25,
            Output,
            "N.m",
            "aligning moment about the wheel centre",
        ),
        var(
            "spin_torque",
            26,
            Output,
            "N.m",
            "torque that holds the prescribed spin",
        ),
    ]
};

/// Start values of the parameters and inputs (in [`VARIABLES`] order of those): the rig's
/// `load`, μ and step, and the motion of its steady start ([`CoSimulation::rig_start`]).
pub fn start_values(rig: &RigConfig, m: &WheelMotion) -> Vec<(u32, f64)> {
    vec![
        (1, rig.load),
        (2, rig.rolling.friction),
        (3, rig.rolling.time_step),
        (10, 0.0),
        (11, 0.0),
        (12, m.height),
        (13, m.velocity[0]),
        (14, m.velocity[1]),
        (15, m.velocity[2]),
        (16, m.yaw),
        (17, m.camber),
        (18, m.spin_rate),
    ]
}

/// `modelDescription.xml` of the FMU (FMI 3.0, co-simulation only, no event mode) with the
/// start values `start` (value reference, value) of the parameters and inputs.
pub fn model_description(start: &[(u32, f64)], step: f64) -> String {
    let mut units: Vec<&str> = VARIABLES
        .iter()
        .map(|v| v.unit)
        .filter(|u| !u.is_empty())
        .collect();
    units.sort_unstable();
    units.dedup();
    let mut x = String::new();
    x.push_str("<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n");
    x.push_str(&format!(
        "<fmiModelDescription fmiVersion=\"3.0\" modelName=\"flowmbd rolling tire\" \
         instantiationToken=\"{INSTANTIATION_TOKEN}\" description=\"The reduced FE tire with \
         flowing material rolling on a flat road (Ribaric 2012 ch. 7-8), driven by its wheel \
         centre motion; loads in the ISO 8855 wheel frame\" generationTool=\"flowmbd {}\" \
         variableNamingConvention=\"flat\">\n",
        env!("CARGO_PKG_VERSION")
    ));
    x.push_str(&format!(
        "  <CoSimulation modelIdentifier=\"{MODEL_IDENTIFIER}\" \
         canHandleVariableCommunicationStepSize=\"true\" fixedInternalStepSize=\"{step:e}\" \
         canGetAndSetFMUState=\"false\" canSerializeFMUState=\"false\" \
         hasEventMode=\"false\" providesIntermediateUpdate=\"false\"/>\n"
    ));
    x.push_str("  <UnitDefinitions>\n");
    for u in &units {
        x.push_str(&format!("    <Unit name=\"{u}\"/>\n"));
    }
    x.push_str("  </UnitDefinitions>\n");
    x.push_str("  <LogCategories>\n    <Category name=\"logStatusError\" description=\"errors\"/>\n    <Category name=\"logStatusWarning\" description=\"warnings\"/>\n  </LogCategories>\n");
    x.push_str("  <ModelVariables>\n");
    x.push_str(
        "    <Float64 name=\"time\" valueReference=\"0\" causality=\"independent\" \
         variability=\"continuous\"/>\n",
    );
    for v in VARIABLES {
        let unit = if v.unit.is_empty() {
            String::new()
        } else {
            format!(" unit=\"{}\"", v.unit)
        };
        let (c, var, extra) = match v.causality {
            Causality::Parameter => (
                "parameter",
                "fixed",
                start
                    .iter()
                    .find(|s| s.0 == v.vr)
                    .map(|s| format!(" start=\"{:e}\"", s.1))
                    .unwrap_or_default(),
            ),
            Causality::Input => (
                "input",
                "continuous",
                start
                    .iter()
                    .find(|s| s.0 == v.vr)
                    .map(|s| format!(" start=\"{:e}\"", s.1))
                    .unwrap_or_default(),
            ),
            Causality::Output => ("output", "continuous", String::new()),
        };
        x.push_str(&format!(
            "    <Float64 name=\"{}\" valueReference=\"{}\" description=\"{}\" causality=\"{c}\" \
             variability=\"{var}\"{unit}{extra}/>\n",
            v.name, v.vr, v.description
        ));
    }
    x.push_str("  </ModelVariables>\n  <ModelStructure>\n");
    for v in VARIABLES
        .iter()
        .filter(|v| v.causality == Causality::Output)
    {
        x.push_str(&format!("    <Output valueReference=\"{}\"/>\n", v.vr));
    }
    for v in VARIABLES
        .iter()
        .filter(|v| v.causality == Causality::Output)
    {
        x.push_str(&format!(
            "    <InitialUnknown valueReference=\"{}\"/>\n",
            v.vr
        ));
    }
    x.push_str("  </ModelStructure>\n</fmiModelDescription>\n");
    x
}

/// Errors of the FMU build.
#[derive(Debug, thiserror::Error)]
pub enum FmuError {
    /// The shared library of the FMU could not be read.
    #[error("FMU library {path}: {reason}")]
    Library {
        /// Its path.
        path: String,
        /// What went wrong.
        reason: String,
    },
    /// The tire, the rig settings or its start.
    #[error(transparent)]
    Tire(#[from] tire::TireError),
    /// Writing the FMU.
    #[error("FMU {path}: {reason}")]
    Write {
        /// The `.fmu` path.
        path: String,
        /// What went wrong.
        reason: String,
    },
}

/// The platform folder of `binaries/` for this build (FMI 3.0 §2.5.1.4: `<arch>-<sys>`).
pub fn platform() -> String {
    // (Rust's architecture names are FMI's: x86_64, aarch64, x86)
    let arch = std::env::consts::ARCH;
    let sys = match std::env::consts::OS {
        "macos" => "darwin",
        other => other,
    };
    format!("{arch}-{sys}")
}

/// The ZIP archive (FMI 3.0 §2.5; PKWARE APPNOTE.TXT) of `entries` (name, bytes), stored
/// uncompressed, written by the `zip` crate (ZIP64 records where an entry needs them).
fn stored_zip(entries: &[(String, &[u8])]) -> Result<Vec<u8>, zip::result::ZipError> {
    use std::io::Write;
    let options =
        zip::write::SimpleFileOptions::default().compression_method(zip::CompressionMethod::Stored);
    let mut w = zip::ZipWriter::new(std::io::Cursor::new(Vec::new()));
    for (name, data) in entries {
        w.start_file(
            name.as_str(),
            options.large_file(data.len() as u64 >= u32::MAX as u64),
        )?;
        w.write_all(data)?;
    }
    Ok(w.finish()?.into_inner())
}

/// Writes the FMU of the reduced tire `red` on the rig `rig` to `out` (a zip: FMI 3.0
/// §2.5): `modelDescription.xml` ([`model_description`], the start values of the rig's
/// steady start [`CoSimulation::rig_start`]), `binaries/<platform>/flowmbd_tire_fmu.<so|dylib|
/// dll>` (a copy of the compiled cdylib at `library`) and `resources/` with the reduced tire
/// ([`TIRE_FILE`]) and the rig ([`RIG_FILE`]; without a prescribed `wheel.centre_motion`, which
/// the FMU's inputs replace). The rig is validated and its start solved
/// first, so an FMU that is written starts. Written through a temporary file renamed onto
/// `out`.
pub fn write_fmu(
    library: &Path, red: &ReducedTire, rig: &RigConfig, out: &Path,
) -> Result<WheelMotion, FmuError> {
    let start = CoSimulation::rig_start(red, rig)?;
    let lib = std::fs::read(library).map_err(|e| FmuError::Library {
        path: library.display().to_string(),
        reason: e.to_string(),
    })?;
    let ext = library
        .extension()
        .and_then(|e| e.to_str())
        .unwrap_or("so")
        .to_string();
    let write = |reason: String| FmuError::Write {
        path: out.display().to_string(),
        reason,
    };
    let tire_json = red.to_json()?;
    // the FMU's inputs are the wheel-centre motion: a prescribed series is not packed
    let mut rig = rig.clone();
    rig.wheel.centre_motion = None;
    let rig = &rig;
    let rig_toml = toml::to_string(rig).map_err(|e| write(e.to_string()))?;
    let xml = model_description(&start_values(rig, &start), rig.rolling.time_step);
    let entries: Vec<(String, &[u8])> = vec![
        ("modelDescription.xml".into(), xml.as_bytes()),
        (
            format!("binaries/{}/{MODEL_IDENTIFIER}.{ext}", platform()),
            &lib,
        ),
        (format!("resources/{TIRE_FILE}"), tire_json.as_bytes()),
        (format!("resources/{RIG_FILE}"), rig_toml.as_bytes()),
    ];
    let bytes = stored_zip(&entries).map_err(|e| write(e.to_string()))?;
    tire::files::write_atomic(out, &bytes).map_err(write)?;
    Ok(start)
}
