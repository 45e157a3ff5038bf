//! Issue 36 item 2 diagnosis: the first rotational mode of the default FEAD drive in the
//! design study's rotational model against the flowing model's free ring-down about its
//! settled state (crank at constant speed, a short torque pulse on the alternator, the
//! alternator's speed fitted by the peak of its spectrum).
//!
//! The default drive with the tensioner's dry friction and damping removed and belt damping
//! β = 2e-4 s, as in `drives/tests/fead_sweep.rs`. Prints the design model's spans, wraps
//! (slip arcs), modes, the modes with the arm locked, on the installed geometry and with each
//! wrap's slip arc added to the span leaving it as compliance (`r (1 − e^{−μ φ_s})/μ`, the
//! capstan law on a sliding arc), then the flowing model's ring-down: the spectral peaks of
//! the alternator's speed and the arm's angle (Hann window, 0.05 Hz grid) and the ring-down's
//! shape at the peak (complex amplitudes of the angles per the alternator's).
//!
//! `cargo run --release -p drives --example fead_ringdown -- [key=value ...]` with keys
//! `rpm`, `kappa` (tanh law \[s/m\]; above about 400 s/m the start from rest does not
//! converge), `mu`, `k1` (penalty factor), `ei`, `rho` (belt bending stiffness and mass
//! factors), `arm` (tensioner spring factor), `jarm` (arm inertia factor), `load` (factor on
//! every load torque), `beta`, `modes` (free modes), `span` and `arc` (element lengths \[m\]),
//! `settle`, `record` \[s\], `h` (step \[s\]), `sim` (0: design only). The measurements of
//! issue 36 item 2 (module documentation of `drives/tests/fead_sweep.rs`) are its output.

use drives::fead::FeadConfig;
use drives::fead_design::modes::rotational_model;
use drives::fead_design::steady_state;
use drives::simulation::BeltSimulation;
use flowing::belt::FlowingBelt;
use mbd_core::integrators::AlphaConfig;
use std::collections::HashMap;

fn main() {
    let args: HashMap<String, f64> = std::env::args()
        .skip(1)
        .filter_map(|a| {
            let (k, v) = a.split_once('=')?;
            Some((k.to_string(), v.parse().ok()?))
        })
        .collect();
    let arg = |k: &str, d: f64| args.get(k).copied().unwrap_or(d);
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
    // the slip arcs (creep theory, at each wrap's exit) as compliance of the span leaving it:
    // tension increments along a sliding arc follow the capstan law, effective length
    // r (1 − e^{−μ φ_s})/μ
    {
        let mut ss = s.clone();
        let radii: Vec<f64> = drive.pulleys().iter().map(|p| p.radius).collect();
        for sp in &mut ss.geometry.spans {
            let w = &s.wraps[sp.from];
            let mu = s.mu[sp.from];
            sp.length += radii[sp.from] * (1.0 - (-mu * w.slip_arc).exp()) / mu;
        }
        let rs = rotational_model(&drive, &ss);
        let ms = rs.modes().expect("modes");
        println!(
            "  slip arcs as span compliance: {:?}",
            ms.iter()
                .take(3)
                .map(|m| m.frequency_hz)
                .collect::<Vec<_>>()
        );
    }
    if arg("sim", 1.0) == 0.0 {
        return;
    }
    // flowing ring-down
    let alt = 2;
    let settle = arg("settle", 0.5);
    let record = arg("record", 0.4);
    let t1 = 0.1 + settle;
    let t0 = &drive.motions()[alt];
    let torque = match t0 {
        belt::Motion::Load { torque, .. } => torque.final_value(),
        _ => 0.0,
    };
    let dt = 0.002;
    let mut model = FlowingBelt::new(&drive, &cfg.models.flowing).expect("model");
    use belt::BeltModel;
    model
        .set_signal(
            alt,
            belt::Signal::schedule(vec![
                (0.0, 0.0),
                (0.1, torque),
                (t1, torque),
                (t1 + dt, torque + 0.5),
                (t1 + 2.0 * dt, torque),
            ]),
        )
        .unwrap();
    let h = arg("h", 2.5e-4);
    let alpha = AlphaConfig {
        h,
        rho_inf: 0.8,
        ..Default::default()
    };
    let mut sim: BeltSimulation<FlowingBelt> = BeltSimulation::new(model, alpha).expect("sim");
    let mut all: Vec<Vec<f64>> = Vec::new();
    let mut ts = Vec::new();
    let mut ys = Vec::new();
    let mut arm = Vec::new();
    while sim.state().t < t1 + 2.0 * dt + record {
        sim.step().expect("step");
        let st = sim.state();
        if st.t > t1 + 2.0 * dt {
            ts.push(st.t);
            ys.push(sim.model().pulley_speed(alt, st.t, &st.v));
            arm.push(sim.model().arm_angle(&st.q).unwrap_or(0.0));
            let mut row: Vec<f64> = (1..6)
                .map(|k| sim.model().pulley_speed(k, st.t, &st.v))
                .collect();
            row.push(arm.last().copied().unwrap_or(0.0));
            all.push(row);
        }
    }
    let spectrum = |y: &[f64]| {
        let mean = y.iter().sum::<f64>() / y.len() as f64;
        let n = y.len();
        let mut best = (0.0, 0.0);
        let mut rows = Vec::new();
        let mut f = 10.0;
        while f < 200.0 {
            let w = 2.0 * std::f64::consts::PI * f;
            let (mut c, mut s) = (0.0, 0.0);
            for (i, (&t, &v)) in ts.iter().zip(y).enumerate() {
                let hann = 0.5 - 0.5 * (2.0 * std::f64::consts::PI * i as f64 / n as f64).cos();
                c += hann * (v - mean) * (w * t).cos();
                s += hann * (v - mean) * (w * t).sin();
            }
            let a = (c * c + s * s).sqrt();
            rows.push((f, a));
            if a > best.1 {
                best = (f, a);
            }
            f += 0.05;
        }
        // local maxima above 5 % of the largest
        let peaks: Vec<String> = (1..rows.len() - 1)
            .filter(|&i| rows[i].1 > rows[i - 1].1 && rows[i].1 >= rows[i + 1].1)
            .filter(|&i| rows[i].1 > 0.05 * best.1)
            .map(|i| format!("{:.2} Hz ({:.2})", rows[i].0, rows[i].1 / best.1))
            .collect();
        peaks
    };
    println!(
        "flowing ring-down at {rpm} rpm: alternator speed peaks {:?}",
        spectrum(&ys)
    );
    println!("  arm angle peaks {:?}", spectrum(&arm));
    // the ring-down's shape at the alternator's peak: complex amplitudes of the angles
    // (speeds / iω, the arm's angle) relative to the alternator's
    let fpk: f64 = spectrum(&ys)[0].split(' ').next().unwrap().parse().unwrap();
    let w = 2.0 * std::f64::consts::PI * fpk;
    let dft = |c: usize| {
        let y: Vec<f64> = all.iter().map(|r| r[c]).collect();
        let mean = y.iter().sum::<f64>() / y.len() as f64;
        let (mut re, mut im) = (0.0, 0.0);
        for (&t, &v) in ts.iter().zip(&y) {
            re += (v - mean) * (w * t).cos();
            im -= (v - mean) * (w * t).sin();
        }
        (re, im)
    };
    let amp: Vec<(f64, f64)> = (0..6)
        .map(|c| {
            let (re, im) = dft(c);
            // speeds to angles: divide by iω
            if c < 5 { (im / w, -re / w) } else { (re, im) }
        })
        .collect();
    let (ar, ai) = amp[1];
    let d = ar * ar + ai * ai;
    println!(
        "  flowing shape (re, im per alternator): {:?}",
        amp.iter()
            .map(|&(r, i)| format!("{:.3}{:+.3}i", (r * ar + i * ai) / d, (i * ar - r * ai) / d))
            .collect::<Vec<_>>()
    );
    let snap = sim.report().expect("report");
    println!(
        "  settled spans: {:?}",
        snap.spans
            .iter()
            .map(|s| format!("{:.1}", s.tension_n))
            .collect::<Vec<_>>()
    );
}
