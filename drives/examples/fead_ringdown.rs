//! Issue 36 item 2 diagnosis: the first rotational mode of the default FEAD drive in the
//! design study's rotational model against the flowing model's free ring-down about its
//! settled state (crank at constant speed, a short torque pulse on the alternator, the
//! alternator's speed fitted by the peak of its spectrum).
//!
//! The default drive with the tensioner's dry friction and damping removed and belt damping
//! β = 2e-4 s, as in `drives/tests/fead_sweep.rs`. Prints the design model's spans, wraps
//! (slip arcs), modes (the default wrap model: the belt held on the adhesion arcs, each span in
//! series with the slip arc it leaves, `drives::fead_design::modes`), the modes with the arm
//! locked and on the installed geometry, each slip arc's compliance as a length of belt
//! `EA c_w` against the diagnosis's estimate `r (1 − e^{−μ φ_s})/μ`, the first modes with the
//! belt held on the whole wrap and with the belt's mass added (a measurement: the spans' axial
//! mass lumped consistently to their ends, the wraps' belt to their pulleys), then the flowing
//! model's ring-down (`drives::ringdown`): the spectral peaks of the alternator's speed and the
//! arm's angle (Hann window, 0.05 Hz grid) and the ring-down's shape at the peak (complex
//! amplitudes of the angles per the alternator's).
//!
//! `cargo run --release -p drives --example fead_ringdown -- [key=value ...]` with keys
//! `rpm`, `kappa` (tanh law \[s/m\]; above about 400 s/m the start from rest does not
//! converge), `mu`, `k1` (penalty factor), `ei`, `rho` (belt bending stiffness and mass
//! factors), `arm` (tensioner spring factor), `jarm` (arm inertia factor), `load` (factor on
//! every load torque), `beta`, `modes` (free modes), `span` and `arc` (element lengths \[m\]),
//! `settle`, `record` \[s\], `h` (step \[s\]), `sim` (0: design only). The measurements of
//! issue 36 item 2 (module documentation of `drives/tests/fead_sweep.rs`) are its output.

use drives::fead::FeadConfig;
use drives::fead_design::modes::{WrapModel, rotational_model, rotational_model_with};
use drives::fead_design::steady_state;
use drives::ringdown::{RingDownSettings, ring_down, spectrum_peaks};
use flowing::belt::FlowingBelt;
use mbd_core::integrators::AlphaConfig;

mod common;

fn main() {
    let arg = common::numeric_args();
    let rpm = arg("rpm", 1482.0);
    let mut cfg = FeadConfig::default();
    let t = cfg.drive.tensioner.as_mut().unwrap();
    t.dry_friction = 0.0;
    t.damping = 0.0;
    t.stiffness *= arg("arm", 1.0);
    t.inertia *= arg("jarm", 1.0);
    cfg.drive.damping.beta = arg("beta", 2e-4);
    cfg.drive.contact.friction = contact::friction::FrictionSpec::Tanh {
        mu: arg("mu", 1.2),
        kappa: arg("kappa", 40.0),
    };
    cfg.drive.belt.ei *= arg("ei", 1.0);
    cfg.drive.belt.mass_per_length *= arg("rho", 1.0);
    cfg.drive.contact.penalty_linear *= arg("k1", 1.0);
    cfg.drive.contact.penalty_quadratic *= arg("k1", 1.0);
    let load = arg("load", 1.0);
    for p in &mut cfg.drive.pulleys {
        if let belt::Motion::Load { torque, .. } = &mut p.motion {
            *torque = belt::Signal::schedule(vec![(0.0, 0.0), (0.1, load * torque.final_value())]);
        }
    }
    let fs = &mut cfg.models.flowing;
    fs.reduction.free_modes = Some(arg("modes", 12.0) as usize);
    fs.mesh.span_element = arg("span", fs.mesh.span_element);
    fs.mesh.arc_element = arg("arc", fs.mesh.arc_element);
    let omega = rpm * std::f64::consts::PI / 30.0;
    cfg.drive.pulleys[0].motion =
        belt::Motion::speed(belt::Signal::schedule(vec![(0.0, 0.0), (0.1, omega)]));
    let drive = cfg.drive.resolve().expect("drive");
    // design model
    let s = steady_state(&drive, omega).expect("steady");
    let rm = rotational_model(&drive, &s);
    println!(
        "design at {rpm} rpm: arm {:?} rad, k_g {:?}",
        s.arm_angle, rm.arm_geometric_stiffness
    );
    let names = drive.names();
    for sp in &s.geometry.spans {
        println!(
            "  span {} -> {}: L {:.4} m, T {:.1} N, k {:.3e} N/m",
            names[sp.from],
            names[sp.to],
            sp.length,
            s.tensions[sp.from],
            drive.belt().tangent_stiffness(s.tensions[sp.from]) / sp.length
        );
    }
    for (k, w) in s.wraps.iter().enumerate() {
        println!(
            "  wrap {}: {:.1} deg, slip arc {:.1} deg, T in {:.1} out {:.1}",
            names[k],
            w.wrap.to_degrees(),
            w.slip_arc.to_degrees(),
            w.tension_in,
            w.tension_out
        );
    }
    println!("  dofs {:?}", rm.names);
    println!(
        "  K diag {:?}",
        (0..rm.names.len())
            .map(|i| rm.stiffness[(i, i)])
            .collect::<Vec<_>>()
    );
    for m in rm.modes().expect("modes") {
        println!(
            "  mode {:.2} Hz ({}), shape {:?}",
            m.frequency_hz,
            m.dominant,
            m.shape
                .iter()
                .map(|x| format!("{x:.3}"))
                .collect::<Vec<_>>()
        );
    }
    // the same model with the arm locked (its row and column removed)
    let n = rm.names.len();
    let locked = fe_model::dense_modes(
        rm.stiffness.as_ref().submatrix(0, 0, n - 1, n - 1),
        rm.mass.as_ref().submatrix(0, 0, n - 1, n - 1),
        n - 1,
    )
    .expect("locked modes");
    println!("  arm locked: {:?}", &locked.frequencies_hz[..3]);
    // the rotational model on the laid-out (installed) geometry with the operating tensions
    if let Some(a) = drive.arm() {
        let mut si = s.clone();
        si.geometry =
            drives::fead_design::statics::Geometry::at(&drive, Some(a.angle)).expect("geometry");
        si.arm_angle = Some(a.angle);
        let ri = rotational_model(&drive, &si);
        let mi = ri.modes().expect("modes");
        println!(
            "  installed arm angle {:.4} rad: modes {:?}, k_g {:?}",
            a.angle,
            mi.iter()
                .take(3)
                .map(|m| m.frequency_hz)
                .collect::<Vec<_>>(),
            ri.arm_geometric_stiffness
        );
    }
    // the wrap models (drives::fead_design::modes): the belt held on the whole wrap, and on
    // the adhesion arcs only (creep theory: each span in series with the slip arc it leaves);
    // the compliance lengths EA c_w against the diagnosis's estimate r (1 − e^{−μ φ_s})/μ
    {
        let radii: Vec<f64> = drive.pulleys().iter().map(|p| p.radius).collect();
        let held = rotational_model_with(&drive, &s, WrapModel::Held);
        let ea = drive.belt().ea;
        for (k, cw) in rm.wrap_compliance.iter().enumerate() {
            let w = &s.wraps[k];
            let mu = s.mu[k];
            println!(
                "  slip arc of {} -> span {}: EA c_w {:.2} mm (estimate {:.2} mm)",
                names[k],
                k,
                1e3 * ea * cw,
                1e3 * radii[k] * (1.0 - (-mu * w.slip_arc).exp()) / mu
            );
        }
        let f = |m: &drives::fead_design::modes::RotationalModel| -> Vec<String> {
            m.modes()
                .expect("modes")
                .iter()
                .take(3)
                .map(|m| format!("{:.2}", m.frequency_hz))
                .collect()
        };
        println!("  wrap held: {:?}; creep (default): {:?}", f(&held), f(&rm));
        // the belt's mass (measurement, issue 36 item 2): each span's axial mass lumped
        // consistently to its ends (m L/6 [2 1; 1 2] on the end displacements b_i, b_j per
        // coordinate), the belt on each wrap added to its pulley (m r³ φ)
        let mut mass = rm.mass.clone();
        let m = drive.belt().mass_per_length;
        let pulleys = s.geometry.path.pulleys();
        let dofs = |k: usize| rm.names.iter().position(|x| *x == pulleys[k].name);
        for sp in &s.geometry.spans {
            let mut ends = [vec![0.0; rm.names.len()], vec![0.0; rm.names.len()]];
            for (e, k) in [sp.from, sp.to].into_iter().enumerate() {
                if let Some(c) = dofs(k) {
                    ends[e][c] = radii[k];
                }
            }
            if let (Some(a), Some(ad)) = (
                drive.arm().zip(s.arm_angle),
                rm.names.iter().position(|x| x == "tensioner arm"),
            ) {
                let v = a.0.tensioner.center(a.0.length, a.1).1;
                for (e, k) in [sp.from, sp.to].into_iter().enumerate() {
                    if k == a.0.tensioner.pulley {
                        ends[e][ad] = sp.direction[0] * v[0] + sp.direction[1] * v[1];
                    }
                }
            }
            let ml = m * sp.length / 6.0;
            for r in 0..rm.names.len() {
                for c in 0..rm.names.len() {
                    mass[(r, c)] += ml
                        * (2.0 * ends[0][r] * ends[0][c]
                            + ends[0][r] * ends[1][c]
                            + ends[1][r] * ends[0][c]
                            + 2.0 * ends[1][r] * ends[1][c]);
                }
            }
        }
        for (k, w) in s.wraps.iter().enumerate() {
            if let Some(c) = dofs(k) {
                mass[(c, c)] += m * radii[k].powi(3) * w.wrap;
            }
        }
        let nm = rm.names.len();
        let with_mass = fe_model::dense_modes(rm.stiffness.as_ref(), mass.as_ref(), nm)
            .expect("modes with the belt's mass");
        println!(
            "  creep with the belt's mass: {:?}",
            with_mass
                .frequencies_hz
                .iter()
                .take(3)
                .map(|f| format!("{f:.2}"))
                .collect::<Vec<_>>()
        );
    }
    if arg("sim", 1.0) == 0.0 {
        return;
    }
    // flowing ring-down (drives::ringdown): a 4 ms pulse of 0.5 N m on the alternator
    let alt = 2;
    let model = FlowingBelt::new(&drive, &cfg.models.flowing).expect("model");
    let alpha = AlphaConfig {
        h: arg("h", 2.5e-4),
        rho_inf: 0.8,
        ..Default::default()
    };
    let rd = ring_down(
        model,
        alpha,
        &RingDownSettings {
            pulley: alt,
            ramp: 0.1,
            settle: arg("settle", 0.5),
            pulse_torque: 0.5,
            pulse_duration: 0.004,
            record: arg("record", 0.4),
        },
    )
    .expect("ring-down");
    let ts = &rd.times;
    let spectrum = |y: &[f64]| -> Vec<String> {
        spectrum_peaks(ts, y, [10.0, 200.0], 0.05, 0.05)
            .iter()
            .map(|(f, a)| format!("{f:.2} Hz ({a:.2})"))
            .collect()
    };
    println!(
        "flowing ring-down at {rpm} rpm: alternator speed peaks {:?}",
        spectrum(&rd.pulley_speeds[alt])
    );
    println!("  arm angle peaks {:?}", spectrum(&rd.arm_angle));
    // the ring-down's shape at the alternator's peak: complex amplitudes of the angles
    // (speeds / iω, the arm's angle) relative to the alternator's
    let fpk = spectrum_peaks(ts, &rd.pulley_speeds[alt], [10.0, 200.0], 0.05, 0.05)
        .iter()
        .copied()
        .max_by(|a, b| a.1.total_cmp(&b.1))
        .map_or(f64::NAN, |p| p.0);
    let w = 2.0 * std::f64::consts::PI * fpk;
    let dft = |y: &[f64]| {
        let mean = y.iter().sum::<f64>() / y.len() as f64;
        let (mut re, mut im) = (0.0, 0.0);
        for (&t, &v) in ts.iter().zip(y) {
            re += (v - mean) * (w * t).cos();
            im -= (v - mean) * (w * t).sin();
        }
        (re, im)
    };
    let mut amp: Vec<(f64, f64)> = (1..6)
        .map(|k| {
            let (re, im) = dft(&rd.pulley_speeds[k]);
            // speeds to angles: divide by iω
            (im / w, -re / w)
        })
        .collect();
    amp.push(dft(&rd.arm_angle));
    let (ar, ai) = amp[1];
    let d = ar * ar + ai * ai;
    println!(
        "  flowing shape at {fpk:.2} Hz (re, im per alternator): {:?}",
        amp.iter()
            .map(|&(r, i)| format!("{:.3}{:+.3}i", (r * ar + i * ai) / d, (i * ar - r * ai) / d))
            .collect::<Vec<_>>()
    );
}
