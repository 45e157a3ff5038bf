//! The FMI 3.0 C API of the tire FMU (co-simulation, `Float64` variables, no event mode),
//! declared as in the standard's `fmi3FunctionTypes.h`. Every entry point runs inside
//! `catch_unwind` (`guard`): a panic becomes `fmi3Fatal` with a logged message, never an
//! unwind across the C ABI. Errors are reported through the importer's `logMessage`
//! callback (category `logStatusError`) and the returned status. Functions of the interface
//! that this FMU does not support (other variable types, FMU state, model exchange, scheduled
//! execution, clocks) return `fmi3Error` after logging, or NULL for the other instantiate
//! functions.

use crate::{INSTANTIATION_TOKEN, RIG_FILE, TIRE_FILE, VARIABLES};
use std::ffi::{CStr, CString, c_char, c_void};
use std::panic::{AssertUnwindSafe, catch_unwind};
use std::path::PathBuf;
use std::sync::Arc;
use tire::motion::{CoSimulation, WheelMotion};
use tire::{ReducedTire, RigConfig, WheelLoads};

/// `fmi3Status`.
pub type Status = i32;
/// `fmi3OK`.
pub const OK: Status = 0;
/// `fmi3Warning`.
pub const WARNING: Status = 1;
/// `fmi3Error`.
pub const ERROR: Status = 3;
/// `fmi3Fatal`.
pub const FATAL: Status = 4;

/// `fmi3LogMessageCallback`.
pub type LogMessage =
    Option<unsafe extern "C" fn(*mut c_void, Status, *const c_char, *const c_char)>;

self_cell::self_cell!(
    /// The co-simulation with the reduced tire it borrows.
    struct Running {
        owner: Arc<ReducedTire>,
        #[not_covariant]
        dependent: CoSimulation,
    }
);

/// The state of the FMU instance (FMI 3.0 co-simulation state machine, without event mode).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Mode {
    Instantiated,
    Initialization,
    Step,
    Terminated,
    /// After an error of a step: only get, reset, terminate and free.
    Failed,
}

/// One FMU instance.
pub struct Instance {
    name: String,
    log: LogMessage,
    env: *mut c_void,
    tire: Arc<ReducedTire>,
    rig: RigConfig,
    /// Values by value reference (parameters, inputs, outputs; index = vr).
    values: [f64; 27],
    /// The start values, restored by `fmi3Reset`.
    start: [f64; 27],
    mode: Mode,
    running: Option<Running>,
    time: f64,
}

impl Instance {
    fn log(&self, status: Status, msg: &str) {
        if let Some(cb) = self.log {
            let cat = if status >= ERROR {
                c"logStatusError"
            } else {
                c"logStatusWarning"
            };
            let m = CString::new(format!("{}: {msg}", self.name).replace('\0', " "))
                .unwrap_or_default();
            // SAFETY: the callback and environment are the importer's, valid for the
            // instance's lifetime (FMI 3.0 §3.2.1); the strings live across the call.
            unsafe { cb(self.env, status, cat.as_ptr(), m.as_ptr()) };
        }
    }

    fn error(&self, msg: &str) -> Status {
        self.log(ERROR, msg);
        ERROR
    }

    fn motion(&self) -> WheelMotion {
        let v = &self.values;
        WheelMotion {
            height: v[12],
            velocity: [v[13], v[14], v[15]],
            yaw: v[16],
            camber: v[17],
            spin_rate: v[18],
        }
    }

    fn rig_with_parameters(&self) -> RigConfig {
        let mut rig = self.rig.clone();
        rig.load = self.values[1];
        rig.rolling.friction = self.values[2];
        rig.rolling.time_step = self.values[3];
        rig
    }

    fn set_outputs(&mut self, l: WheelLoads, spin_torque: f64) {
        let o = [l.fx, l.fy, l.fz, l.mx, l.my, l.mz, spin_torque];
        self.values[20..27].copy_from_slice(&o);
    }

    /// Starts the co-simulation from the parameters and inputs (exit of initialization).
    fn start(&mut self) -> Status {
        let rig = self.rig_with_parameters();
        let m = self.motion();
        let r = Running::try_new(self.tire.clone(), |red| CoSimulation::start(red, &rig, &m));
        match r {
            Ok(run) => {
                let (l, tau) =
                    run.with_dependent(|_, cs| (cs.sim.wheel_loads(), cs.sim.spin_torque()));
                self.set_outputs(l, tau);
                self.running = Some(run);
                OK
            }
            Err(e) => self.error(&format!("cannot start: {e}")),
        }
    }
}

/// Runs `f` on the instance behind `ptr` inside `catch_unwind`: a null pointer is `fmi3Error`,
/// a panic `fmi3Fatal` (logged; the instance is then failed).
fn guard(ptr: *mut c_void, f: impl FnOnce(&mut Instance) -> Status) -> Status {
    if ptr.is_null() {
        return ERROR;
    }
    // SAFETY: a non-null instance pointer is one returned by fmi3InstantiateCoSimulation and
    // not yet freed (the importer's obligation, FMI 3.0 §2.3.1); calls on one instance are
    // not concurrent (§2.3.5).
    let inst = unsafe { &mut *(ptr as *mut Instance) };
    match catch_unwind(AssertUnwindSafe(|| f(inst))) {
        Ok(s) => s,
        Err(p) => {
            let msg = p
                .downcast_ref::<&str>()
                .map(|s| s.to_string())
                .or_else(|| p.downcast_ref::<String>().cloned())
                .unwrap_or_else(|| "unknown".into());
            inst.mode = Mode::Failed;
            inst.log(FATAL, &format!("internal error (panic): {msg}"));
            FATAL
        }
    }
}

/// A C string or `None` for NULL.
///
/// # Safety
/// `p` is NULL or a NUL-terminated string valid for the call.
unsafe fn text(p: *const c_char) -> Option<String> {
    if p.is_null() {
        None
    } else {
        // SAFETY: by the caller's contract.
        Some(unsafe { CStr::from_ptr(p) }.to_string_lossy().into_owned())
    }
}

/// `fmi3GetVersion`: "3.0".
#[unsafe(no_mangle)]
pub extern "C" fn fmi3GetVersion() -> *const c_char {
    c"3.0".as_ptr()
}

/// `fmi3SetDebugLogging`: errors are always logged; accepted and ignored.
#[unsafe(no_mangle)]
pub extern "C" fn fmi3SetDebugLogging(
    instance: *mut c_void, _on: bool, _n: usize, _categories: *const *const c_char,
) -> Status {
    guard(instance, |_| OK)
}

/// Reads the tire and the rig from the resources folder `dir`.
fn load_resources(dir: &str) -> Result<(ReducedTire, RigConfig), String> {
    // (FMI 3.0 passes an absolute path with a trailing separator; a file:// URI as in FMI 2
    // is also accepted)
    let dir = PathBuf::from(dir.strip_prefix("file://").unwrap_or(dir));
    let red = ReducedTire::load(&dir.join(TIRE_FILE)).map_err(|e| e.to_string())?;
    let path = dir.join(RIG_FILE);
    let text = tire::files::read_text_bounded(&path, 1 << 20)
        .map_err(|e| format!("{}: {e}", path.display()))?;
    let rig: RigConfig = toml::from_str(&text).map_err(|e| format!("{}: {e}", path.display()))?;
    mbd_core::Validate::validate(&rig).map_err(|e| format!("{}: rig.{e}", path.display()))?;
    Ok((red, rig))
}

/// `fmi3InstantiateCoSimulation`: checks the token, reads `resources/` (the reduced tire and
/// the rig); NULL on failure (logged).
///
/// # Safety
/// The strings are NULL or NUL-terminated; `log_message` and `environment` are the
/// importer's (FMI 3.0 §3.2.1).
#[unsafe(no_mangle)]
#[allow(clippy::too_many_arguments)]
pub unsafe extern "C" fn fmi3InstantiateCoSimulation(
    instance_name: *const c_char, token: *const c_char, resource_path: *const c_char,
    _visible: bool, _logging_on: bool, _event_mode_used: bool, _early_return_allowed: bool,
    _required_intermediate: *const u32, _n_required: usize, environment: *mut c_void,
    log_message: LogMessage, _intermediate_update: *mut c_void,
) -> *mut c_void {
    let r = catch_unwind(AssertUnwindSafe(|| {
        // SAFETY: by the caller's contract.
        let (name, token, res) = unsafe { (text(instance_name), text(token), text(resource_path)) };
        let name = name.unwrap_or_else(|| "flowmbd_tire_fmu".into());
        let fail = |msg: String| {
            if let Some(cb) = log_message {
                let m =
                    CString::new(format!("{name}: {msg}").replace('\0', " ")).unwrap_or_default();
                // SAFETY: as in Instance::log.
                unsafe { cb(environment, ERROR, c"logStatusError".as_ptr(), m.as_ptr()) };
            }
            std::ptr::null_mut::<c_void>()
        };
        if token.as_deref() != Some(INSTANTIATION_TOKEN) {
            return fail(format!(
                "instantiation token {token:?} is not this FMU's {INSTANTIATION_TOKEN}"
            ));
        }
        let Some(res) = res else {
            return fail("no resource path (the tire and rig are in resources/)".into());
        };
        let (red, rig) = match load_resources(&res) {
            Ok(x) => x,
            Err(e) => return fail(e),
        };
        let start = match CoSimulation::rig_start(&red, &rig) {
            Ok(m) => m,
            Err(e) => return fail(format!("the rig does not start: {e}")),
        };
        let mut values = [0.0; 27];
        for (vr, v) in crate::start_values(&rig, &start) {
            values[vr as usize] = v;
        }
        let inst = Box::new(Instance {
            name,
            log: log_message,
            env: environment,
            tire: Arc::new(red),
            rig,
            values,
            start: values,
            mode: Mode::Instantiated,
            running: None,
            time: 0.0,
        });
        Box::into_raw(inst) as *mut c_void
    }));
    r.unwrap_or(std::ptr::null_mut())
}

/// `fmi3FreeInstance`.
///
/// # Safety
/// `instance` is NULL or an instance of this FMU not yet freed.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi3FreeInstance(instance: *mut c_void) {
    if instance.is_null() {
        return;
    }
    let _ = catch_unwind(AssertUnwindSafe(|| {
        // SAFETY: by the caller's contract, created by Box::into_raw.
        drop(unsafe { Box::from_raw(instance as *mut Instance) });
    }));
}

/// `fmi3EnterInitializationMode`.
#[unsafe(no_mangle)]
pub extern "C" fn fmi3EnterInitializationMode(
    instance: *mut c_void, _tolerance_defined: bool, _tolerance: f64, start_time: f64,
    _stop_time_defined: bool, _stop_time: f64,
) -> Status {
    guard(instance, |i| {
        if i.mode != Mode::Instantiated {
            return i.error(&format!("enter initialization mode in mode {:?}", i.mode));
        }
        if !start_time.is_finite() {
            return i.error(&format!("start time {start_time} is not finite"));
        }
        i.time = start_time;
        i.mode = Mode::Initialization;
        OK
    })
}

/// `fmi3ExitInitializationMode`: starts the tire from the parameters and inputs.
#[unsafe(no_mangle)]
pub extern "C" fn fmi3ExitInitializationMode(instance: *mut c_void) -> Status {
    guard(instance, |i| {
        if i.mode != Mode::Initialization {
            return i.error(&format!("exit initialization mode in mode {:?}", i.mode));
        }
        let s = i.start();
        if s == OK {
            i.mode = Mode::Step;
        }
        s
    })
}

/// `fmi3EnterEventMode`: no event mode.
#[unsafe(no_mangle)]
pub extern "C" fn fmi3EnterEventMode(instance: *mut c_void) -> Status {
    guard(instance, |i| i.error("this FMU has no event mode"))
}

/// `fmi3EnterStepMode`: already in step mode after initialization (no event mode).
#[unsafe(no_mangle)]
pub extern "C" fn fmi3EnterStepMode(instance: *mut c_void) -> Status {
    guard(instance, |i| {
        if i.mode == Mode::Step {
            OK
        } else {
            i.error(&format!("enter step mode in mode {:?}", i.mode))
        }
    })
}

/// `fmi3Terminate`.
#[unsafe(no_mangle)]
pub extern "C" fn fmi3Terminate(instance: *mut c_void) -> Status {
    guard(instance, |i| {
        i.mode = Mode::Terminated;
        OK
    })
}

/// `fmi3Reset`: back to the instantiated state with the start values.
#[unsafe(no_mangle)]
pub extern "C" fn fmi3Reset(instance: *mut c_void) -> Status {
    guard(instance, |i| {
        i.running = None;
        i.values = i.start;
        i.time = 0.0;
        i.mode = Mode::Instantiated;
        OK
    })
}

/// The checked slices of a get/set call.
///
/// # Safety
/// `vr` points to `n_vr` value references, `values` to `n_values` values (or are NULL with a
/// zero count).
unsafe fn slices<'a, T>(
    vr: *const u32, n_vr: usize, values: *mut T, n_values: usize,
) -> Result<(&'a [u32], &'a mut [T]), String> {
    if n_vr != n_values {
        return Err(format!(
            "{n_vr} value references for {n_values} values (all are scalars)"
        ));
    }
    if n_vr == 0 {
        return Ok((&[], &mut []));
    }
    if vr.is_null() || values.is_null() {
        return Err("null value references or values".into());
    }
    // SAFETY: by the caller's contract.
    Ok(unsafe {
        (
            std::slice::from_raw_parts(vr, n_vr),
            std::slice::from_raw_parts_mut(values, n_values),
        )
    })
}

/// `fmi3GetFloat64`: `time` (vr 0), parameters, inputs and outputs.
///
/// # Safety
/// As `slices`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi3GetFloat64(
    instance: *mut c_void, vr: *const u32, n_vr: usize, values: *mut f64, n_values: usize,
) -> Status {
    guard(instance, |i| {
        // SAFETY: by the caller's contract.
        let (vrs, out) = match unsafe { slices(vr, n_vr, values, n_values) } {
            Ok(x) => x,
            Err(e) => return i.error(&format!("fmi3GetFloat64: {e}")),
        };
        for (r, o) in vrs.iter().zip(out.iter_mut()) {
            *o = match *r {
                0 => i.time,
                r if VARIABLES.iter().any(|v| v.vr == r) => i.values[r as usize],
                r => {
                    return i.error(&format!(
                        "fmi3GetFloat64: no variable with value reference {r}"
                    ));
                }
            };
        }
        OK
    })
}

/// `fmi3SetFloat64`: parameters before the end of initialization, inputs at any time; the
/// values are checked when the tire starts or steps.
///
/// # Safety
/// As `slices`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi3SetFloat64(
    instance: *mut c_void, vr: *const u32, n_vr: usize, values: *const f64, n_values: usize,
) -> Status {
    guard(instance, |i| {
        // SAFETY: by the caller's contract (the values are only read).
        let (vrs, vals) = match unsafe { slices(vr, n_vr, values as *mut f64, n_values) } {
            Ok(x) => x,
            Err(e) => return i.error(&format!("fmi3SetFloat64: {e}")),
        };
        for (r, v) in vrs.iter().zip(vals.iter()) {
            let Some(var) = VARIABLES.iter().find(|x| x.vr == *r) else {
                return i.error(&format!(
                    "fmi3SetFloat64: no variable with value reference {r}"
                ));
            };
            let settable = match var.causality {
                crate::Causality::Parameter => {
                    matches!(i.mode, Mode::Instantiated | Mode::Initialization)
                }
                crate::Causality::Input => i.mode != Mode::Terminated,
                crate::Causality::Output => false,
            };
            if !settable {
                return i.error(&format!(
                    "fmi3SetFloat64: {} ({:?}) cannot be set in mode {:?}",
                    var.name, var.causality, i.mode
                ));
            }
            i.values[*r as usize] = *v;
        }
        OK
    })
}

/// `fmi3DoStep`: one communication step of the tire ([`CoSimulation::do_step`]) with the
/// inputs held; an invalid input (e.g. a camber beyond ±30°) or a failed step is
/// `fmi3Error` with the reason logged.
///
/// # Safety
/// The output pointers are NULL or valid.
#[unsafe(no_mangle)]
#[allow(clippy::too_many_arguments)]
pub unsafe extern "C" fn fmi3DoStep(
    instance: *mut c_void, current: f64, step: f64, _no_set_state_prior: bool,
    event_handling_needed: *mut bool, terminate_simulation: *mut bool, early_return: *mut bool,
    last_successful_time: *mut f64,
) -> Status {
    guard(instance, |i| {
        let put = |t: f64| {
            // SAFETY: by the caller's contract.
            unsafe {
                for p in [event_handling_needed, terminate_simulation, early_return] {
                    if !p.is_null() {
                        *p = false;
                    }
                }
                if !last_successful_time.is_null() {
                    *last_successful_time = t;
                }
            }
        };
        put(i.time);
        if i.mode != Mode::Step {
            return i.error(&format!("fmi3DoStep in mode {:?}", i.mode));
        }
        if (current - i.time).abs() > 1e-9 * (1.0 + i.time.abs()) {
            return i.error(&format!(
                "fmi3DoStep at {current} s, the FMU is at {} s",
                i.time
            ));
        }
        let m = i.motion();
        let Some(run) = i.running.as_mut() else {
            return i.error("not started");
        };
        let r =
            run.with_dependent_mut(|_, cs| cs.do_step(step, &m).map(|l| (l, cs.sim.spin_torque())));
        match r {
            Ok((l, tau)) => {
                i.set_outputs(l, tau);
                i.time = current + step;
                put(i.time);
                OK
            }
            Err(e) => {
                i.mode = Mode::Failed;
                i.error(&format!("step from {current} s by {step} s: {e}"))
            }
        }
    })
}

/// The other instantiate functions: this FMU is co-simulation only (NULL).
#[unsafe(no_mangle)]
pub extern "C" fn fmi3InstantiateModelExchange() -> *mut c_void {
    std::ptr::null_mut()
}

/// Scheduled execution is not supported (NULL).
#[unsafe(no_mangle)]
pub extern "C" fn fmi3InstantiateScheduledExecution() -> *mut c_void {
    std::ptr::null_mut()
}

/// Functions of the FMI 3.0 interface that this FMU does not support: each logs and returns
/// `fmi3Error`. Declared with the instance argument only (the first of each; under the C
/// calling conventions of the supported platforms the caller's further arguments are
/// ignored).
macro_rules! unsupported {
    ($($name:ident),* $(,)?) => {$(
        #[doc = concat!("`", stringify!($name), "`: not supported by this FMU (`fmi3Error`).")]
        #[unsafe(no_mangle)]
        pub extern "C" fn $name(instance: *mut c_void) -> Status {
            guard(instance, |i| i.error(concat!(stringify!($name), " is not supported")))
        }
    )*};
}

unsupported!(
    fmi3GetFloat32,
    fmi3GetInt8,
    fmi3GetUInt8,
    fmi3GetInt16,
    fmi3GetUInt16,
    fmi3GetInt32,
    fmi3GetUInt32,
    fmi3GetInt64,
    fmi3GetUInt64,
    fmi3GetBoolean,
    fmi3GetString,
    fmi3GetBinary,
    fmi3GetClock,
    fmi3SetFloat32,
    fmi3SetInt8,
    fmi3SetUInt8,
    fmi3SetInt16,
    fmi3SetUInt16,
    fmi3SetInt32,
    fmi3SetUInt32,
    fmi3SetInt64,
    fmi3SetUInt64,
    fmi3SetBoolean,
    fmi3SetString,
    fmi3SetBinary,
    fmi3SetClock,
    fmi3GetNumberOfVariableDependencies,
    fmi3GetVariableDependencies,
    fmi3GetFMUState,
    fmi3SetFMUState,
    fmi3FreeFMUState,
    fmi3SerializedFMUStateSize,
    fmi3SerializeFMUState,
    fmi3DeserializeFMUState,
    fmi3GetDirectionalDerivative,
    fmi3GetAdjointDerivative,
    fmi3EnterConfigurationMode,
    fmi3ExitConfigurationMode,
    fmi3GetIntervalDecimal,
    fmi3GetIntervalFraction,
    fmi3GetShiftDecimal,
    fmi3GetShiftFraction,
    fmi3SetIntervalDecimal,
    fmi3SetIntervalFraction,
    fmi3SetShiftDecimal,
    fmi3SetShiftFraction,
    fmi3EvaluateDiscreteStates,
    fmi3UpdateDiscreteStates,
    fmi3EnterContinuousTimeMode,
    fmi3CompletedIntegratorStep,
    fmi3SetTime,
    fmi3SetContinuousStates,
    fmi3GetContinuousStateDerivatives,
    fmi3GetEventIndicators,
    fmi3GetContinuousStates,
    fmi3GetNominalsOfContinuousStates,
    fmi3GetNumberOfEventIndicators,
    fmi3GetNumberOfContinuousStates,
    fmi3GetOutputDerivatives,
    fmi3ActivateModelPartition,
);
