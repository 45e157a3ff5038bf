//! Issue 34 diagnosis harness (research branch): torque and power balances of the flowing and
//! nodal belts, friction regularisation sweeps. Run:
//! `cargo run --release -p drives --example issue34 -- <command> [args]`.
//!
//! Research code (not part of the library): index loops over nodal vectors read like the
//! equations they evaluate.
#![allow(clippy::needless_range_loop, clippy::field_reassign_with_default)]

use drives::model::span_states;
use drives::speed_loss::{SpeedLossConfig, speed_loss_sweep};
use fe_model::element::{Element, Frame2d, Frame2dSection};
use flowing::belt::model::{chord_turn_rate, corotational_rate_block};
use flowing::belt::nodal::NodalBelt;
use flowing::belt::{BeltDriveConfig, BeltFe, FlowingBelt, Schedule};
use mbd_core::integrators::State;

type B6 = [[f64; 6]; 6];

/// One element of the loop between reference nodes i → j.
struct Elem {
    i: usize,
    j: usize,
    u: [f64; 2],
    k: B6,
    ke: B6,
    kj: B6,
    /// The co-rotated axial force's bar (exact model) and EA.
    bar: Option<(flowing::belt::model::Bar, f64)>,
}

fn to_b6(m: &impl std::ops::Index<(usize, usize), Output = f64>) -> B6 {
    std::array::from_fn(|a| std::array::from_fn(|b| m[(a, b)]))
}

fn elements(
    pos: &[[f64; 2]],
    tan: &[[f64; 2]],
    sec: Frame2dSection,
    t0: f64,
    exact: bool,
) -> Vec<Elem> {
    let n = pos.len();
    let bars = flowing::belt::model::Bar::loop_of(pos);
    (0..n)
        .map(|i| {
            let j = (i + 1) % n;
            let e = Frame2d::new([0, 1, 2, 3, 4, 5], pos[i], pos[j], sec, t0).unwrap();
            let ke = to_b6(&e.stiffness());
            let kg = to_b6(&e.geometric_stiffness().unwrap());
            let mut k = ke;
            for a in 0..6 {
                for b in 0..6 {
                    k[a][b] += kg[a][b];
                }
            }
            let turn = chord_turn_rate(pos[i], pos[j], tan[i], tan[j]);
            let mut kj = corotational_rate_block(&ke);
            kj.iter_mut().flatten().for_each(|x| *x *= turn);
            Elem {
                i,
                j,
                u: [e.c, e.s],
                k,
                ke,
                kj,
                bar: exact.then_some((bars[i], sec.ea)),
            }
        })
        .collect()
}

/// Force of element `e` on its two nodes (6: x, y, m at i then j), split into
/// (pretension + stiffness, damping): f0 − K δ, −β (K_e δ̇_m − v ψ' K_e J δ).
fn elem_force(
    e: &Elem,
    t0: f64,
    beta: f64,
    vb: f64,
    d: &[f64],
    dm: &[f64],
) -> ([f64; 6], [f64; 6]) {
    let dofs = [
        3 * e.i,
        3 * e.i + 1,
        3 * e.i + 2,
        3 * e.j,
        3 * e.j + 1,
        3 * e.j + 2,
    ];
    let mut fs = [0.0; 6];
    let mut fd = [0.0; 6];
    fs[0] = t0 * e.u[0];
    fs[1] = t0 * e.u[1];
    fs[3] = -t0 * e.u[0];
    fs[4] = -t0 * e.u[1];
    for a in 0..6 {
        for b in 0..6 {
            fs[a] -= e.k[a][b] * d[dofs[b]];
            fd[a] -= beta * (e.ke[a][b] * dm[dofs[b]] - vb * e.kj[a][b] * d[dofs[b]]);
        }
    }
    if let Some((bar, ea)) = &e.bar {
        let (c, _) = bar.correction(d, t0, *ea, false);
        fs[3] += c[0];
        fs[4] += c[1];
        fs[0] -= c[0];
        fs[1] -= c[1];
    }
    (fs, fd)
}

fn cross(a: [f64; 2], b: [f64; 2]) -> f64 {
    a[0] * b[1] - a[1] * b[0]
}

/// Steady state of a two-pulley drive model at (omega, torque) through the speed-loss
/// procedure; returns the last state.
fn steady<M: drives::DriveModel>(model: &mut M, omega: f64, torque: f64, step: f64) -> State {
    let cfg = SpeedLossConfig {
        omega_driver: omega,
        torques: vec![torque],
        step,
        max_hold: 6.0,
        spin_up: 0.5,
        torque_ramp: std::env::var("RAMP")
            .ok()
            .and_then(|s| s.parse().ok())
            .unwrap_or(0.1),
        ..Default::default()
    };
    let mut last = None;
    let (pts, stats) = speed_loss_sweep(model, &cfg, |s, _| last = Some(s.clone()))
        .unwrap_or_else(|f| panic!("sweep failed: {}", f.error));
    let p = &pts[0];
    eprintln!(
        "steady: torque {} dω {:.5} ω2 {:.4} t {:.3} steps {} newton {} gross slip {:?}",
        p.torque,
        p.delta_omega,
        p.omega_driven,
        p.time,
        stats.steps,
        stats.newton_iterations,
        p.gross_slip
    );
    last.unwrap()
}

/// Torque-balance figures of one pulley at one instant (travel-sense moments \[N m\]).
#[derive(Debug, Clone, Copy, Default)]
struct Bal {
    /// Contact torque on the pulley (`−F_T·R_contact` summed).
    tau: f64,
    /// Moment of the contact forces on the belt about the centre, reversed.
    tau_belt: f64,
    /// Span tensions (the model's element force measure), middle half: in, out.
    t_in: f64,
    t_out: f64,
    /// Moments of the cut forces (elastic, damping) at the middle element of each span.
    cut_s: f64,
    cut_d: f64,
    /// Moment the wrap's internal elements do not balance (elastic, damping).
    int_s: f64,
    int_d: f64,
    /// Σ N1·Δv over the wrap's internal elements.
    n1dv: f64,
    /// Arms of the cut forces in and out \[m\].
    arm_in: f64,
    arm_out: f64,
    /// Range of the tangential deflection on the wrap \[m\].
    ut_min: f64,
    ut_max: f64,
    r: f64,
}

impl Bal {
    fn add(&mut self, o: &Bal, w: f64) {
        self.tau += w * o.tau;
        self.tau_belt += w * o.tau_belt;
        self.t_in += w * o.t_in;
        self.t_out += w * o.t_out;
        self.cut_s += w * o.cut_s;
        self.cut_d += w * o.cut_d;
        self.int_s += w * o.int_s;
        self.int_d += w * o.int_d;
        self.n1dv += w * o.n1dv;
        self.arm_in += w * o.arm_in;
        self.arm_out += w * o.arm_out;
        self.ut_min += w * o.ut_min;
        self.ut_max += w * o.ut_max;
        self.r = o.r;
    }

    fn print(&self, p: usize, load: f64) {
        let span = (self.t_out - self.t_in) * self.r;
        println!(
            "pulley {p}: load {load:.4} contact torque {:.5} | (T_out−T_in)·R {:.5} (T_in {:.3}, T_out {:.3}) residual {:+.3} % | cut moments {:.5} ({:+.3} %) + damping {:.5}",
            self.tau,
            span,
            self.t_in,
            self.t_out,
            100.0 * (span / self.tau - 1.0),
            self.cut_s,
            100.0 * (self.cut_s / self.tau - 1.0),
            self.cut_d
        );
        println!(
            "  contact forces' moment on the belt {:.5} ({:+.3} %); wrap elements' unbalanced moment: elastic {:.5} (Σ N1·Δv {:.5}) damping {:.5}; u_t on the wrap [{:.3}, {:.3}] mm; arms − R: in {:+.4} mm out {:+.4} mm",
            self.tau_belt,
            100.0 * (self.tau_belt / self.tau - 1.0),
            self.int_s,
            self.n1dv,
            self.int_d,
            1e3 * self.ut_min,
            1e3 * self.ut_max,
            1e3 * (self.arm_in - self.r),
            1e3 * (self.arm_out - self.r)
        );
    }
}

/// The balance of pulley `p` for a belt at reference positions `pos` (tangents `tan`) with
/// deflections `d`, material rates `dm`, belt speed `vb`, contacts `(node, pulley, force,
/// torque)`.
#[allow(clippy::too_many_arguments)]
fn balance(
    fe: &BeltFe,
    pos: &[[f64; 2]],
    tan: &[[f64; 2]],
    d: &[f64],
    dm: &[f64],
    vb: f64,
    contacts: &[(usize, usize, [f64; 2], f64)],
    p: usize,
    exact: bool,
) -> Bal {
    let b = fe.config.belt;
    let beta = fe.config.damping.beta;
    let sec = Frame2dSection {
        ea: b.ea,
        ei: b.ei,
        mass_per_length: b.mass_per_length,
    };
    let els = elements(pos, tan, sec, b.tension, exact);
    let n = pos.len();
    let pl = fe.path.pulleys()[p];
    let c = pl.center;
    let r = pl.radius;
    let turn = match pl.side {
        fe_model::generate::belt_path::WrapSide::Inside => 1.0,
        fe_model::generate::belt_path::WrapSide::Outside => -1.0,
    };
    let x: Vec<[f64; 2]> = (0..n)
        .map(|i| [pos[i][0] + d[3 * i], pos[i][1] + d[3 * i + 1]])
        .collect();
    let mut o = Bal {
        r,
        ..Default::default()
    };
    o.tau = contacts.iter().filter(|k| k.1 == p).map(|k| k.3).sum();
    o.tau_belt = contacts
        .iter()
        .filter(|k| k.1 == p)
        .map(|k| turn * cross([x[k.0][0] - c[0], x[k.0][1] - c[1]], k.2))
        .sum();
    // span tensions: T0 + EA Δl/l (linear) or T0 + EA (l − l0)/l0 (exact), middle half
    let tens: Vec<f64> = if exact {
        flowing::belt::model::Bar::loop_of(pos)
            .iter()
            .map(|e| e.force(d, b.tension, b.ea))
            .collect()
    } else {
        flowing::belt::model::chord_tensions(pos, d, b.tension, b.ea)
    };
    let spans = span_states(&fe.path, &x, &tens);
    o.t_in = spans.iter().find(|s| s.to == p).unwrap().tension;
    o.t_out = spans.iter().find(|s| s.from == p).unwrap().tension;
    let spl = fe.path.spans();
    let ki = spl.iter().position(|s| s.to == p).unwrap();
    let ko = spl.iter().position(|s| s.from == p).unwrap();
    // the middle element of a span
    let cut = |k: usize| -> usize {
        let sp = &spl[k];
        let mut best = (f64::INFINITY, 0);
        for e in &els {
            let mid = [0.5 * (x[e.i][0] + x[e.j][0]), 0.5 * (x[e.i][1] + x[e.j][1])];
            let (a, t) = sp.local(mid);
            if t.abs() < 0.01 && a > 0.0 && a < sp.length {
                let dd = (a - 0.5 * sp.length).abs();
                if dd < best.0 {
                    best = (dd, e.i);
                }
            }
        }
        best.1
    };
    let (ein, eout) = (cut(ki), cut(ko));
    let mut nodes = Vec::new();
    let mut i = (ein + 1) % n;
    loop {
        nodes.push(i);
        if i == eout {
            break;
        }
        i = (i + 1) % n;
    }
    let mom = |i: usize, f: [f64; 3]| {
        -turn * (cross([x[i][0] - c[0], x[i][1] - c[1]], [f[0], f[1]]) + f[2])
    };
    let (fs, fd) = elem_force(&els[ein], b.tension, beta, vb, d, dm);
    let j = els[ein].j;
    o.cut_s += mom(j, [fs[3], fs[4], fs[5]]);
    o.cut_d += mom(j, [fd[3], fd[4], fd[5]]);
    o.arm_in = cross([x[j][0] - c[0], x[j][1] - c[1]], [fs[3], fs[4]]).abs() / fs[3].hypot(fs[4]);
    let (fs, fd) = elem_force(&els[eout], b.tension, beta, vb, d, dm);
    let i0 = els[eout].i;
    o.cut_s += mom(i0, [fs[0], fs[1], fs[2]]);
    o.cut_d += mom(i0, [fd[0], fd[1], fd[2]]);
    o.arm_out =
        cross([x[i0][0] - c[0], x[i0][1] - c[1]], [fs[0], fs[1]]).abs() / fs[0].hypot(fs[1]);
    // the wrap's internal elements
    o.ut_min = f64::INFINITY;
    o.ut_max = f64::NEG_INFINITY;
    for &i in &nodes {
        let ut = d[3 * i] * tan[i][0] + d[3 * i + 1] * tan[i][1];
        o.ut_min = o.ut_min.min(ut);
        o.ut_max = o.ut_max.max(ut);
    }
    for w in nodes.windows(2) {
        let e = &els[w[0]];
        let dd = [d[3 * e.j] - d[3 * e.i], d[3 * e.j + 1] - d[3 * e.i + 1]];
        let l = (pos[e.j][0] - pos[e.i][0]).hypot(pos[e.j][1] - pos[e.i][1]);
        let n1 = b.ea * (e.u[0] * dd[0] + e.u[1] * dd[1]) / l;
        let dv = -e.u[1] * dd[0] + e.u[0] * dd[1];
        o.n1dv += -turn * n1 * dv;
        let (fs, fd) = elem_force(e, b.tension, beta, vb, d, dm);
        o.int_s += mom(e.i, [fs[0], fs[1], fs[2]]) + mom(e.j, [fs[3], fs[4], fs[5]]);
        o.int_d += mom(e.i, [fd[0], fd[1], fd[2]]) + mom(e.j, [fd[3], fd[4], fd[5]]);
    }
    o
}

/// Continue `model` from `st` for `window` \[s\] at step `h`, calling `f` every `every` steps.
fn window<M: drives::DriveModel>(
    model: &M,
    st: State,
    h: f64,
    window: f64,
    every: usize,
    mut f: impl FnMut(&State),
) -> State {
    use mbd_core::integrators::{AlphaConfig, GeneralizedAlpha};
    let alpha = GeneralizedAlpha::new(AlphaConfig {
        h,
        rho_inf: 0.6,
        ..Default::default()
    });
    let mut stepper = alpha.stepper(model, st).unwrap();
    let n = (window / h).round() as usize;
    for k in 0..n {
        drives::speed_loss::robust_step(&mut stepper, model, h, 4).unwrap();
        if (k + 1) % every == 0 {
            f(stepper.state());
        }
    }
    stepper.state().clone()
}

fn table_cfg(modes: Option<usize>) -> BeltDriveConfig {
    let mut cfg = BeltDriveConfig::default();
    let env = |k: &str, d: usize| {
        std::env::var(k)
            .ok()
            .and_then(|s| s.parse().ok())
            .unwrap_or(d)
    };
    cfg.mesh.span_elements = env("SPAN_EL", 10);
    cfg.mesh.arc_elements = env("ARC_EL", 18);
    let envf = |k: &str, d: f64| {
        std::env::var(k)
            .ok()
            .and_then(|s| s.parse().ok())
            .unwrap_or(d)
    };
    cfg.belt.ei *= envf("EI_SCALE", 1.0);
    cfg.contact.kappa = envf("KAPPA", cfg.contact.kappa);
    cfg.contact.penalty_linear *= envf("PEN_SCALE", 1.0);
    cfg.contact.penalty_quadratic *= envf("PEN_SCALE", 1.0);
    cfg.damping.beta *= envf("BETA_SCALE", 1.0);
    cfg.reduction.free_modes = modes;
    cfg
}

/// The Pechstein–Gerstmayr (2013) drive of issue 34 (Exudyn's beltDriveReevingSystem.py,
/// "improvedBelt") as a two-pulley Table-6-1-style drive; the driven pulley's 2 N m s damper is
/// replaced by its steady torque (25 + 2·11.35 ≈ 47.69 N m, Exudyn's applied torque).
fn pg_cfg(modes: Option<usize>, kappa: f64) -> BeltDriveConfig {
    let mut cfg = BeltDriveConfig::default();
    cfg.geometry.center_distance = 0.1 * std::f64::consts::PI;
    cfg.geometry.radius_driver = 0.09995;
    cfg.geometry.radius_driven = 0.09995;
    cfg.belt.ea = 8000.0
        * std::env::var("EA_SCALE")
            .ok()
            .and_then(|s| s.parse::<f64>().ok())
            .unwrap_or(1.0);
    cfg.belt.ei = 0.02 * 1e7 * 0.08 * 1e-6 / 12.0;
    cfg.belt.mass_per_length = 0.8288;
    cfg.belt.tension = 400.0;
    cfg.contact.mu = 0.5;
    cfg.contact.kappa = kappa;
    cfg.driven_inertia = 0.25;
    let env = |k: &str, d: usize| {
        std::env::var(k)
            .ok()
            .and_then(|s| s.parse().ok())
            .unwrap_or(d)
    };
    cfg.mesh.span_elements = env("SPAN_EL", 12);
    cfg.mesh.arc_elements = env("ARC_EL", 24);
    cfg.reduction.free_modes = modes;
    cfg
}

fn flowing_balance(cfg: &BeltDriveConfig, omega: f64, torque: f64) {
    let fe = BeltFe::new(cfg).unwrap();
    let mut belt =
        FlowingBelt::new(fe, Schedule::constant(omega), Schedule::constant(0.0)).unwrap();
    belt.exact_axial = std::env::var("LINEAR").is_err();
    let h = 2.5e-4;
    let st = steady(&mut belt, omega, torque, h);
    let m = belt.n_modes();
    let mut acc = [Bal::default(), Bal::default()];
    let mut k = 0usize;
    let win = std::env::var("WINDOW")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(0.1);
    window(&belt, st, h, win, 4, |st| {
        let (z, zd, vb) = (&st.q[1..=m], &st.v[1..=m], st.v[0]);
        let d = belt.deflection(z);
        let nd = belt.fe.n_dofs();
        let mut dm = vec![0.0; nd];
        for r in 0..nd {
            for kk in 0..m {
                dm[r] += belt.basis.t[(r, kk)] * zd[kk] + vb * belt.basis.ts[(r, kk)] * z[kk];
            }
        }
        let contacts: Vec<_> = belt
            .contact_report(st.t, &st.q, &st.v)
            .into_iter()
            .map(|r| (r.node, r.pulley, r.contact.force, r.contact.torque))
            .collect();
        for (p, a) in acc.iter_mut().enumerate() {
            let b = balance(
                &belt.fe,
                &belt.fe.position,
                &belt.fe.tangent,
                &d,
                &dm,
                vb,
                &contacts,
                p,
                belt.exact_axial,
            );
            a.add(&b, 1.0);
        }
        k += 1;
    });
    println!(
        "flowing, ω1 = {omega}, load {torque}, modes {m}, exact axial {}, mean of {k} samples over {win} s",
        belt.exact_axial
    );
    for (p, a) in acc.iter_mut().enumerate() {
        let mut mean = Bal::default();
        mean.add(a, 1.0 / k as f64);
        mean.print(p, if p == 1 { torque } else { f64::NAN });
    }
}

/// Power balance terms of the flowing model at one instant \[W\] (see the report): the pulleys'
/// contact power, slip loss, normal (penalty) power, the belt's physical dissipation and the
/// e_t-row terms of the model's belt-speed equation.
#[derive(Debug, Clone, Copy, Default)]
struct Pow {
    /// Σ τ_k ω_k over all pulleys (−input + loads in a steady state).
    pulleys: f64,
    /// −τ_0 ω_0: the driver's input.
    input: f64,
    /// Σ load_k ω_k.
    loads: f64,
    /// Σ −F_T u ≥ 0.
    slip: f64,
    /// Σ F_N n·ḋ.
    normal: f64,
    /// Σ F·ḋ (contact power on the belt at the material velocity).
    contact_phys: f64,
    /// v e_tᵀ f_c (contact power as the model's belt-speed row sees it).
    contact_model: f64,
    /// v bᵀ f_c (b = T_,s z): the difference.
    contact_b: f64,
    /// v e_tᵀ (f0 − K δ).
    elastic: f64,
    /// v e_tᵀ g_damping.
    damping_row: f64,
    /// −v e_tᵀ M (v² ε_n + v² T_ss z + 2 v T_s ż).
    inertia_row: f64,
    /// Dissipation α|Tż|²_M + β r_mᵀ K_e r_m, r_m = δ̇_m − v ψ' J δ.
    dissipation: f64,
    /// Tensioner arm: damper + dry friction dissipation −(M_d + M_f) θ̇ ≥ 0.
    arm: f64,
    /// Kinetic energy of the pulleys and arm (for the change over a window) \[J\].
    kinetic: f64,
    /// ḋᵀ g_el, ḋᵀ g_d, −ḋᵀ M d̈ (physical powers of the belt's forces on the material).
    el_phys: f64,
    d_phys: f64,
    in_phys: f64,
}

impl Pow {
    fn add(&mut self, o: &Pow, w: f64) {
        self.pulleys += w * o.pulleys;
        self.input += w * o.input;
        self.loads += w * o.loads;
        self.slip += w * o.slip;
        self.normal += w * o.normal;
        self.contact_phys += w * o.contact_phys;
        self.contact_model += w * o.contact_model;
        self.contact_b += w * o.contact_b;
        self.elastic += w * o.elastic;
        self.damping_row += w * o.damping_row;
        self.inertia_row += w * o.inertia_row;
        self.dissipation += w * o.dissipation;
        self.el_phys += w * o.el_phys;
        self.arm += w * o.arm;
        self.kinetic += w * o.kinetic;
        self.d_phys += w * o.d_phys;
        self.in_phys += w * o.in_phys;
    }
    fn print(&self) {
        let created = self.loads + self.slip + self.dissipation + self.arm - self.input;
        println!(
            "power: input {:.4} W, loads {:.4}, slip {:.4}, belt dissipation {:.4}, tensioner arm {:.4} → created {:+.4} W ({:+.3} % of input)",
            self.input,
            self.loads,
            self.slip,
            self.dissipation,
            self.arm,
            created,
            100.0 * created / self.input
        );
        println!(
            "  contact power on the belt: physical F·ḋ {:.4} = model row v e_tᵀf_c {:.4} + v bᵀ f_c {:.4}; normal F_N n·ḋ {:.4}; check −Σ τω − slip + normal = {:.4}",
            self.contact_phys,
            self.contact_model,
            self.contact_b,
            self.normal,
            -self.pulleys - self.slip + self.normal
        );
        println!(
            "  belt-speed row × v: contact {:.4} + elastic v e_tᵀ(f0 − Kδ) {:.4} + damping {:.4} + inertia {:.4} = {:.4}",
            self.contact_model,
            self.elastic,
            self.damping_row,
            self.inertia_row,
            self.contact_model + self.elastic + self.damping_row + self.inertia_row
        );
        println!(
            "  physical powers on the material ḋ = v(e_t + δ_,s) + Tż: elastic {:.4} damping {:.4} (−dissipation {:.4}) inertia {:.4}; contact + these = {:.4}",
            self.el_phys,
            self.d_phys,
            -self.dissipation,
            self.in_phys,
            self.contact_phys + self.el_phys + self.d_phys + self.in_phys
        );
    }
}

/// The power terms of the flowing belt at `st` (loads: the free pulleys' load torques).
fn flowing_power(belt: &FlowingBelt, st: &State, loads: &[f64]) -> Pow {
    let m = belt.n_modes();
    let fe = &belt.fe;
    let nd = fe.n_dofs();
    let (z, zd, vb) = (&st.q[1..=m], &st.v[1..=m], st.v[0]);
    let mul = |a: &dyn Fn(usize, usize) -> f64, x: &[f64], rows: usize| -> Vec<f64> {
        (0..rows)
            .map(|r| (0..x.len()).map(|k| a(r, k) * x[k]).sum())
            .collect()
    };
    let t = &belt.basis.t;
    let ts = &belt.basis.ts;
    let tss = &belt.basis.tss;
    let d = mul(&|r, k| t[(r, k)], z, nd);
    let ds = mul(&|r, k| ts[(r, k)], z, nd);
    let dss = mul(&|r, k| tss[(r, k)], z, nd);
    let tzd = mul(&|r, k| t[(r, k)], zd, nd);
    let tszd = mul(&|r, k| ts[(r, k)], zd, nd);
    let et = fe.stacked_tangent();
    let en = fe.stacked_curvature();
    let (alpha, beta) = (fe.config.damping.alpha, fe.config.damping.beta);
    // elastic + pretension (linear part) and the co-rotated axial correction
    let mut g_el: Vec<f64> = (0..nd)
        .map(|r| fe.pretension[r] - (0..nd).map(|c| fe.stiffness[(r, c)] * d[c]).sum::<f64>())
        .collect();
    if belt.exact_axial {
        let b = fe.config.belt;
        for bar in flowing::belt::model::Bar::loop_of(&fe.position) {
            let (c, _) = bar.correction(&d, b.tension, b.ea, false);
            for a in 0..2 {
                g_el[3 * bar.j + a] += c[a];
                g_el[3 * bar.i + a] -= c[a];
            }
        }
    }
    // co-rotated material rate r_m = Tż + v T_s z − v ψ'Jδ ; K_e = (C − αM)/β
    let turn_d = mul(&|r, c| fe.frame_turn[(r, c)], &d, nd);
    let dm: Vec<f64> = (0..nd).map(|r| tzd[r] + vb * ds[r]).collect();
    let ke = |r: usize, c: usize| {
        (fe.damping[(r, c)] - if r == c { alpha * fe.mass[r] } else { 0.0 }) / beta
    };
    let ke_dm = mul(&|r, c| ke(r, c), &dm, nd);
    let g_d: Vec<f64> = (0..nd)
        .map(|r| -alpha * fe.mass[r] * tzd[r] - beta * ke_dm[r] + beta * vb * turn_d[r])
        .collect();
    let rm: Vec<f64> = (0..nd)
        .map(|r| {
            dm[r]
                - vb * {
                    // ψ' J δ: frame_turn = Σ ψ' K_e J, so use K_e⁻¹? — use the definition r_m·(β K_e r_m)
                    0.0
                }
        })
        .collect();
    let _ = rm;
    // dissipation: α |Tż|²_M − g_d_β · r_m with g_d_β = −β K_e r_m ⇒ r_mᵀ β K_e r_m = −(g_d + αMTż)ᵀ r_m;
    // r_m is not needed explicitly: β K_e r_m = β K_e dm − β v frame_turn δ, and r_mᵀ K_e r_m
    // = dmᵀ K_e dm − 2 v dmᵀ frame_turn δ + v² (ψ'Jδ)ᵀ K_e (ψ'Jδ); the last two from the
    // per-element ψ' J δ (computed below).
    let mut diss = alpha * (0..nd).map(|r| fe.mass[r] * tzd[r] * tzd[r]).sum::<f64>();
    {
        // per element: r_e = dm_e − v ψ'_e J δ_e, dissipation β r_eᵀ K_e,e r_e
        let b = fe.config.belt;
        let sec = Frame2dSection {
            ea: b.ea,
            ei: b.ei,
            mass_per_length: b.mass_per_length,
        };
        let n = fe.n_nodes();
        for i in 0..n {
            let j = (i + 1) % n;
            let e = Frame2d::new(
                [0, 1, 2, 3, 4, 5],
                fe.position[i],
                fe.position[j],
                sec,
                b.tension,
            )
            .unwrap();
            let k = to_b6(&e.stiffness());
            let psi = chord_turn_rate(fe.position[i], fe.position[j], fe.tangent[i], fe.tangent[j]);
            let dofs = [3 * i, 3 * i + 1, 3 * i + 2, 3 * j, 3 * j + 1, 3 * j + 2];
            let mut r = [0.0; 6];
            for a in 0..6 {
                r[a] = dm[dofs[a]];
            }
            for nn in [0, 3] {
                // J (x, y) = (−y, x)
                r[nn] -= vb * psi * (-d[dofs[nn + 1]]);
                r[nn + 1] -= vb * psi * d[dofs[nn]];
            }
            for a in 0..6 {
                for bb in 0..6 {
                    diss += beta * r[a] * k[a][bb] * r[bb];
                }
            }
        }
    }
    let acc: Vec<f64> = (0..nd)
        .map(|r| fe.mass[r] * (vb * vb * en[r] + vb * vb * dss[r] + 2.0 * vb * tszd[r]))
        .collect();
    let mut o = Pow::default();
    o.elastic = vb * (0..nd).map(|r| et[r] * g_el[r]).sum::<f64>();
    o.damping_row = vb * (0..nd).map(|r| et[r] * g_d[r]).sum::<f64>();
    o.inertia_row = -vb * (0..nd).map(|r| et[r] * acc[r]).sum::<f64>();
    o.dissipation = diss;
    let mdot: Vec<f64> = (0..nd).map(|r| vb * (et[r] + ds[r]) + tzd[r]).collect();
    o.el_phys = (0..nd).map(|r| mdot[r] * g_el[r]).sum();
    if std::env::var("SPLIT").is_ok() {
        let kd = mul(&|r, c| fe.stiffness[(r, c)], &d, nd);
        let dot = |a: &[f64], b: &[f64]| a.iter().zip(b).map(|(x, y)| x * y).sum::<f64>();
        let corr: Vec<f64> = (0..nd)
            .map(|r| g_el[r] - fe.pretension[r] + kd[r])
            .collect();
        println!(
            "    v e_tᵀf0 {:.4} v δ_sᵀf0 {:.4} −v e_tᵀKδ {:.4} −v δ_sᵀKδ {:.4} v(e_t+δ_s)ᵀ(exact axial corr.) {:.4}",
            vb * dot(&et, &fe.pretension),
            vb * dot(&ds, &fe.pretension),
            -vb * dot(&et, &kd),
            -vb * dot(&ds, &kd),
            vb * (dot(&et, &corr) + dot(&ds, &corr))
        );
        // per node: v (δ_s·f0 − e_t·Kδ) split by node class
        let mut by = std::collections::BTreeMap::new();
        let pulley = fe.node_pulley();
        for i in 0..fe.n_nodes() {
            let x: f64 = (0..2)
                .map(|a| ds[3 * i + a] * fe.pretension[3 * i + a] - et[3 * i + a] * kd[3 * i + a])
                .sum();
            let key = format!("{:?}", pulley[i]);
            *by.entry(key).or_insert(0.0) += vb * x;
            if std::env::var("SPLIT").as_deref() == Ok("2") {
                let ut = d[3 * i] * fe.tangent[i][0] + d[3 * i + 1] * fe.tangent[i][1];
                println!(
                    "      node {i:3} s {:.4} {:?} u_t {:.4} mm  v(δ_s·f0 − e_t·Kδ) {:.5} W",
                    fe.s[i],
                    pulley[i],
                    1e3 * ut,
                    vb * x
                );
            }
        }
        println!("    by pulley: {by:?}");
    }
    o.d_phys = (0..nd).map(|r| mdot[r] * g_d[r]).sum();
    o.in_phys = -(0..nd).map(|r| mdot[r] * acc[r]).sum::<f64>();
    for rep in belt.contact_report(st.t, &st.q, &st.v) {
        let i = rep.node;
        let c = rep.contact;
        let vel = [
            vb * (fe.tangent[i][0] + ds[3 * i]) + tzd[3 * i],
            vb * (fe.tangent[i][1] + ds[3 * i + 1]) + tzd[3 * i + 1],
        ];
        let pw = c.force[0] * vel[0] + c.force[1] * vel[1];
        o.contact_phys += pw;
        o.contact_model += vb * (fe.tangent[i][0] * c.force[0] + fe.tangent[i][1] * c.force[1]);
        o.contact_b += vb * (ds[3 * i] * c.force[0] + ds[3 * i + 1] * c.force[1]);
        o.slip -= c.friction * c.slip;
        // normal power: the part of F·ḋ not carried by friction along the travel tangent
        o.normal += pw
            - c.friction
                * (c.slip
                    + belt.pulley_speed(rep.pulley, st.t, &st.v) * fe.contact_radius[rep.pulley]);
    }
    let tq = belt.pulley_torques(st.t, &st.q, &st.v);
    let loads: Vec<f64> = if loads.is_empty() {
        belt.motions
            .iter()
            .map(|m| match m {
                flowing::belt::PulleyMotion::Free { load, .. } => load.value(st.t),
                _ => 0.0,
            })
            .collect()
    } else {
        loads.to_vec()
    };
    for (k, (tk, lk)) in tq.iter().zip(&loads).enumerate() {
        let w = belt.pulley_speed(k, st.t, &st.v);
        o.pulleys += tk * w;
        if k == 0 {
            o.input = -tk * w;
        } else {
            o.loads += lk * w;
        }
    }
    if let (Some(tm), Some(k)) = (belt.tensioner, belt.arm_dof()) {
        let rate = st.v[k];
        let md = tm.spec.damper_moment(rate).0;
        let mf = contact::friction::coulomb_tanh::tensioner_dry_friction(&tm.spec, rate).force;
        o.arm = -(md + mf) * rate;
        o.kinetic += 0.5 * tm.spec.inertia * rate * rate;
    }
    for (k, m) in belt.motions.iter().enumerate() {
        if let (flowing::belt::PulleyMotion::Free { inertia, .. }, Some(dk)) =
            (m, belt.pulley_dof(k))
        {
            o.kinetic += 0.5 * inertia * st.v[dk] * st.v[dk];
        }
    }
    o
}

/// The default FEAD drive at `rpm` from rest (ramp 0.1 s as the study's first point), settled
/// `settle` s after the ramp, power terms averaged over `cycles` engine cycles (two crank
/// revolutions: whole periods of orders 2 and 4).
fn fead_power(rpm: f64, settle: f64, cycles: f64) {
    use drives::fead::{FeadConfig, crank_signal};
    use mbd_core::integrators::{AlphaConfig, GeneralizedAlpha};
    let mut cfg = FeadConfig::default();
    let envf = |k: &str, d: f64| {
        std::env::var(k)
            .ok()
            .and_then(|s| s.parse().ok())
            .unwrap_or(d)
    };
    cfg.drive.damping.beta *= envf("BETA_SCALE", 1.0);
    cfg.drive.damping.alpha *= envf("ALPHA_SCALE", 1.0);
    cfg.drive.mesh.span_element = envf("SPAN_H", cfg.drive.mesh.span_element);
    cfg.drive.mesh.arc_element = envf("ARC_H", cfg.drive.mesh.arc_element);
    if std::env::var("MODES").as_deref() == Ok("all") {
        cfg.drive.reduction.free_modes = None;
    }
    let (mut belt, _res) = cfg.drive.flowing_model().unwrap();
    belt.exact_axial = std::env::var("LINEAR").is_err();
    let omega = rpm * std::f64::consts::PI / 30.0;
    if let Some(flowing::belt::PulleyMotion::Speed(s)) = belt.motions.first_mut() {
        *s = crank_signal(&cfg.engine, 0.0, omega, cfg.run.ramp);
    }
    let h = cfg.run.step;
    let alpha = GeneralizedAlpha::new(AlphaConfig {
        h,
        rho_inf: cfg.run.rho_inf,
        ..Default::default()
    });
    let s0 = drives::DriveModel::initial_state(&belt).unwrap();
    let mut stepper = alpha.stepper(&belt, s0).unwrap();
    let t0 = cfg.run.ramp + settle;
    let period = 4.0 * std::f64::consts::PI / omega;
    let t1 = t0 + cycles * period;
    let mut acc = Pow::default();
    let mut k = 0usize;
    let mut first: Option<Pow> = None;
    let mut last = Pow::default();
    while stepper.state().t < t1 - 0.5 * h {
        drives::speed_loss::robust_step(&mut stepper, &belt, h, 4).unwrap();
        let st = stepper.state();
        if st.t < t0 - 0.5 * h {
            continue;
        }
        let p = flowing_power(&belt, st, &[]);
        if first.is_none() {
            first = Some(p);
        } else {
            acc.add(&p, 1.0);
            k += 1;
        }
        last = p;
    }
    let mut mean = Pow::default();
    mean.add(&acc, 1.0 / k as f64);
    let dke = (last.kinetic - first.unwrap().kinetic) / (t1 - t0);
    println!(
        "flowing fead {rpm} rpm, settle {settle} s, window {cycles} engine cycles ({:.4} s, {k} samples), exact axial {}; Δ(kinetic energy of pulleys, arm)/window {dke:+.4} W",
        t1 - t0,
        belt.exact_axial
    );
    mean.print();
}

fn flowing_power_table(cfg: &BeltDriveConfig, omega: f64, torque: f64) {
    let fe = BeltFe::new(cfg).unwrap();
    let mut belt =
        FlowingBelt::new(fe, Schedule::constant(omega), Schedule::constant(0.0)).unwrap();
    belt.exact_axial = std::env::var("LINEAR").is_err();
    let h = 2.5e-4;
    let st = steady(&mut belt, omega, torque, h);
    let mut acc = Pow::default();
    let mut k = 0;
    window(&belt, st, h, 0.05, 4, |st| {
        acc.add(&flowing_power(&belt, st, &[0.0, torque]), 1.0);
        k += 1;
    });
    let mut mean = Pow::default();
    mean.add(&acc, 1.0 / k as f64);
    println!(
        "flowing Table 6-1 ω1 = {omega}, load {torque}, exact axial {}",
        belt.exact_axial
    );
    mean.print();
}

/// Speed loss of a two-pulley drive model over `torques` at `omega`, one line per point.
fn speed_loss_line<M: drives::DriveModel>(
    name: &str,
    model: &mut M,
    omega: f64,
    torques: &[f64],
    step: f64,
    ramp: f64,
) {
    let cfg = SpeedLossConfig {
        omega_driver: omega,
        torques: torques.to_vec(),
        step,
        max_hold: 8.0,
        spin_up: 0.5,
        torque_ramp: ramp,
        ..Default::default()
    };
    let t = std::time::Instant::now();
    match speed_loss_sweep(model, &cfg, |_, _| {}) {
        Ok((pts, stats)) => {
            let s: Vec<String> = pts
                .iter()
                .map(|p| {
                    format!(
                        "T={} dω={:.5} ({:.3} %){}",
                        p.torque,
                        p.delta_omega,
                        100.0 * p.delta_omega / omega,
                        if p.gross_slip.is_some() { " GROSS" } else { "" }
                    )
                })
                .collect();
            println!(
                "{name}: {} | steps {} newton {} ({:.2}/step) sim {:.2} s wall {:.1} s",
                s.join(", "),
                stats.steps,
                stats.newton_iterations,
                stats.newton_iterations as f64 / stats.steps as f64,
                stats.simulated_time,
                t.elapsed().as_secs_f64()
            );
        }
        Err(f) => println!("{name}: failed {} after {} points", f.error, f.points.len()),
    }
}

/// The speed-loss procedure (spin-up, load ramps, hold until two consecutive window means of
/// the speed loss agree within `tol`) with Newton line search; returns `(dω per torque, steps,
/// Newton iterations)`.
#[allow(clippy::too_many_arguments)]
fn speed_loss_ls<M: drives::DriveModel>(
    model: &mut M,
    omega: f64,
    torques: &[f64],
    h: f64,
    ramp: f64,
    line_search: bool,
    tol: f64,
) -> Result<(Vec<f64>, usize, usize), String> {
    use mbd_core::integrators::{AlphaConfig, GeneralizedAlpha};
    let spin = 0.5;
    model.set_driver_speed(Schedule {
        knots: vec![(0.0, 0.0), (spin, omega)],
    });
    *model.load_mut() = Schedule::constant(0.0);
    let alpha = GeneralizedAlpha::new(AlphaConfig {
        h,
        rho_inf: 0.6,
        newton_line_search: line_search,
        ..Default::default()
    });
    let s0 = model.initial_state().map_err(|e| e.to_string())?;
    let mut st = alpha.stepper(&*model, s0).map_err(|e| e.to_string())?;
    let win: f64 = std::env::var("WIN")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(0.05);
    let per = (win / h).round() as usize;
    let mut out = Vec::new();
    let mut level = spin;
    let mut cur = 0.0;
    for &tq in torques {
        model.load_mut().knots.push((level, cur));
        model.load_mut().knots.push((level + ramp, tq));
        cur = tq;
        level += ramp;
        let mut means: Vec<f64> = Vec::new();
        let (mut sum, mut n) = (0.0, 0);
        loop {
            drives::speed_loss::robust_step(&mut st, &*model, h, 6).map_err(|e| e.to_string())?;
            let s = st.state();
            if s.t < level {
                continue;
            }
            sum += model.driver_speed(s.t) - model.driven_speed(&s.v);
            n += 1;
            if n == per {
                means.push(sum / n as f64);
                sum = 0.0;
                n = 0;
                let k = means.len();
                if k >= 2 && (means[k - 1] - means[k - 2]).abs() < tol {
                    out.push(means[k - 1]);
                    level = s.t;
                    break;
                }
                if s.t - level > 10.0 {
                    return Err(format!("no steady state at {tq}"));
                }
            }
        }
    }
    LAST.with(|l| *l.borrow_mut() = Some(st.state().clone()));
    Ok((out, st.stats.steps, st.stats.newton_iterations))
}

fn nodal_balance(cfg: &BeltDriveConfig, omega: f64, torque: f64, ramp: f64) {
    let fe = BeltFe::new(cfg).unwrap();
    let mut belt = NodalBelt::new(fe, Schedule::constant(omega), Schedule::constant(0.0)).unwrap();
    belt.exact_axial = std::env::var("LINEAR").is_err();
    let h = 2.5e-4;
    let tol = std::env::var("TOL")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(1e-3);
    let (dw, steps, newton) =
        speed_loss_ls(&mut belt, omega, &[torque], h, ramp, true, tol).unwrap();
    eprintln!(
        "nodal steady: dω {:.5} steps {steps} newton {newton}",
        dw[0]
    );
    // continue from the end state: re-run the last state by a short window
    let nd = belt.n_nodal();
    let mut acc = [Bal::default(), Bal::default()];
    let mut k = 0usize;
    let win = std::env::var("WINDOW")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(0.1);
    let st = LAST.with(|l| l.borrow().clone()).unwrap();
    window(&belt, st, h, win, 4, |st| {
        let pos = belt.reference_positions(st.q[0]);
        let tan: Vec<[f64; 2]> = belt
            .fe
            .s
            .iter()
            .map(|&s| belt.fe.path.point(s + st.q[0]).tangent)
            .collect();
        let d = &st.q[1..=nd];
        let dm = &st.v[1..=nd];
        let contacts: Vec<_> = belt
            .contact_report(st.t, &st.q, &st.v)
            .unwrap()
            .into_iter()
            .map(|(i, p, _, c)| (i, p, c.force, c.torque))
            .collect();
        for (p, a) in acc.iter_mut().enumerate() {
            let b = balance(
                &belt.fe,
                &pos,
                &tan,
                d,
                dm,
                st.v[0],
                &contacts,
                p,
                belt.exact_axial,
            );
            a.add(&b, 1.0);
        }
        k += 1;
    });
    println!(
        "nodal, ω1 = {omega}, load {torque}, exact axial {}, mean of {k} samples over {win} s",
        belt.exact_axial
    );
    for (p, a) in acc.iter_mut().enumerate() {
        let mut mean = Bal::default();
        mean.add(a, 1.0 / k as f64);
        mean.print(p, if p == 1 { torque } else { f64::NAN });
    }
}

thread_local! {
    static LAST: std::cell::RefCell<Option<State>> = const { std::cell::RefCell::new(None) };
}

/// What the steady-means procedure needs of a layout model.
trait Layout: drives::DriveModel {
    fn crank(&mut self, s: flowing::belt::Signal);
    fn arm(&self, q: &[f64]) -> f64;
    fn spans_now(
        &self,
        roles: &[(String, drives::PulleyRole)],
        t: f64,
        q: &[f64],
        v: &[f64],
    ) -> (Vec<f64>, Vec<f64>);
}

impl Layout for FlowingBelt {
    fn crank(&mut self, s: flowing::belt::Signal) {
        if let Some(flowing::belt::PulleyMotion::Speed(x)) = self.motions.first_mut() {
            *x = s;
        }
    }
    fn arm(&self, q: &[f64]) -> f64 {
        self.arm_angle(q).unwrap_or(f64::NAN)
    }
    fn spans_now(
        &self,
        roles: &[(String, drives::PulleyRole)],
        t: f64,
        q: &[f64],
        v: &[f64],
    ) -> (Vec<f64>, Vec<f64>) {
        let s = drives::model::flowing_layout_snapshot(self, roles, t, q, v);
        (
            s.spans.iter().map(|x| x.tension).collect(),
            s.pulleys.iter().map(|p| p.torque).collect(),
        )
    }
}

impl Layout for NodalBelt {
    fn crank(&mut self, s: flowing::belt::Signal) {
        if let Some(flowing::belt::PulleyMotion::Speed(x)) = self.motions.first_mut() {
            *x = s;
        }
    }
    fn arm(&self, q: &[f64]) -> f64 {
        self.arm_angle(q).unwrap_or(f64::NAN)
    }
    fn spans_now(
        &self,
        roles: &[(String, drives::PulleyRole)],
        t: f64,
        q: &[f64],
        v: &[f64],
    ) -> (Vec<f64>, Vec<f64>) {
        let s = drives::model::nodal_layout_snapshot(self, roles, t, q, v).unwrap();
        (
            s.spans.iter().map(|x| x.tension).collect(),
            s.pulleys.iter().map(|p| p.torque).collect(),
        )
    }
}

/// Steady means of the FEAD drive at `rpm` (reached from rest by a `ramp` s ramp): windows of
/// `k` periods of the lowest engine order until two consecutive windows' means agree (span
/// tensions within `tol_t` N, accessory torques within 0.5 % of their loads, arm within 1e-4
/// rad); prints every window.
fn fead_means<M: Layout>(mut m: M, name: &str, rpm: f64, ramp: f64, line_search: bool, max_t: f64) {
    use drives::fead::{FeadConfig, crank_signal};
    use mbd_core::integrators::{AlphaConfig, GeneralizedAlpha};
    let cfg = FeadConfig::default();
    let roles = cfg.drive.roles();
    let omega = rpm * std::f64::consts::PI / 30.0;
    m.crank(crank_signal(&cfg.engine, 0.0, omega, ramp));
    let h = std::env::var("H")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(cfg.run.step);
    let alpha = GeneralizedAlpha::new(AlphaConfig {
        h,
        rho_inf: cfg.run.rho_inf,
        newton_line_search: line_search,
        ..Default::default()
    });
    let s0 = m.initial_state().unwrap();
    let mut st = alpha.stepper(&m, s0).unwrap();
    let low = cfg
        .engine
        .orders
        .iter()
        .map(|o| o.order)
        .fold(f64::INFINITY, f64::min);
    let period = 2.0 * std::f64::consts::PI / (low * omega);
    let k = (0.05 / period).ceil();
    let win = k * period;
    let loads: [f64; 6] = [0.0, 2.0, 3.0, 0.0, 1.5, 5.0];
    let mut t_next = ramp + win;
    let mut prev: Option<(Vec<f64>, Vec<f64>, f64)> = None;
    let (mut sp, mut tq, mut arm, mut n) = (vec![0.0; 6], vec![0.0; 6], 0.0, 0usize);
    let wall = std::time::Instant::now();
    loop {
        drives::speed_loss::robust_step(&mut st, &m, h, 4).unwrap();
        let s = st.state().clone();
        if s.t < ramp - 0.5 * h {
            continue;
        }
        let (a, b) = m.spans_now(&roles, s.t, &s.q, &s.v);
        for i in 0..6 {
            sp[i] += a[i];
            tq[i] += b[i];
        }
        arm += m.arm(&s.q);
        n += 1;
        if s.t >= t_next - 0.5 * h {
            let mean = |x: &[f64]| x.iter().map(|y| y / n as f64).collect::<Vec<_>>();
            let (msp, mtq, marm) = (mean(&sp), mean(&tq), arm / n as f64);
            let conv = prev.as_ref().is_some_and(|(p, q, r)| {
                msp.iter().zip(p).all(|(x, y)| (x - y).abs() < 2.0)
                    && mtq
                        .iter()
                        .zip(q)
                        .zip(&loads)
                        .skip(1)
                        .all(|((x, y), l)| (x - y).abs() < 0.005 * l.max(1.0))
                    && (marm - r).abs() < 1e-4
            });
            println!(
                "{name} {rpm} rpm t {:.4} window {win:.4} s ({k} periods): arm {marm:.5} spans {:?} torques {:?} {} (wall {:.0} s)",
                s.t,
                msp.iter()
                    .map(|x| (x * 10.0).round() / 10.0)
                    .collect::<Vec<_>>(),
                mtq.iter()
                    .map(|x| (x * 1000.0).round() / 1000.0)
                    .collect::<Vec<_>>(),
                if conv { "CONVERGED" } else { "" },
                wall.elapsed().as_secs_f64()
            );
            if conv || s.t > max_t {
                break;
            }
            prev = Some((msp, mtq, marm));
            sp.fill(0.0);
            tq.fill(0.0);
            arm = 0.0;
            n = 0;
            t_next += win;
        }
    }
}

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let arg = |i: usize, d: f64| args.get(i).and_then(|s| s.parse().ok()).unwrap_or(d);
    match args.first().map(String::as_str) {
        Some("flowing") => {
            let modes = args.get(3).and_then(|s| s.parse().ok());
            let modes = if args.get(3).map(String::as_str) == Some("all") {
                None
            } else {
                modes.or(Some(20))
            };
            flowing_balance(&table_cfg(modes), arg(1, 62.8), arg(2, 8.0));
        }
        Some("pg") => {
            let modes = if args.get(3).map(String::as_str) == Some("all") {
                None
            } else {
                Some(args.get(3).and_then(|s| s.parse().ok()).unwrap_or(20))
            };
            flowing_balance(&pg_cfg(modes, arg(4, 40.0)), arg(1, 12.0), arg(2, 47.69));
        }
        Some("sl") => {
            // sl <table|pg> <flowing|nodal> ω kappa [step]
            let kappa = arg(4, 40.0);
            let step = arg(5, 2.5e-4);
            let modes = match std::env::var("MODES").as_deref() {
                Ok("all") => None,
                Ok(s) => s.parse().ok(),
                Err(_) => Some(20),
            };
            let (cfg, torques, ramp) = match args[1].as_str() {
                "pg" => (pg_cfg(modes, kappa), vec![47.69], 1.0),
                _ => {
                    let mut c = table_cfg(modes);
                    c.contact.kappa = kappa;
                    let tq = std::env::var("TORQUES")
                        .ok()
                        .map(|s| s.split(',').filter_map(|x| x.parse().ok()).collect())
                        .unwrap_or(vec![4.0, 8.0]);
                    (c, tq, 0.1)
                }
            };
            let omega = arg(3, 62.8);
            let fe = BeltFe::new(&cfg).unwrap();
            let name = format!("{} {} ω={omega} κ={kappa} h={step}", args[1], args[2]);
            if args[2] == "nodal" {
                let mut b =
                    NodalBelt::new(fe, Schedule::constant(omega), Schedule::constant(0.0)).unwrap();
                speed_loss_line(&name, &mut b, omega, &torques, step, ramp);
            } else {
                let mut b =
                    FlowingBelt::new(fe, Schedule::constant(omega), Schedule::constant(0.0))
                        .unwrap();
                b.exact_axial = std::env::var("LINEAR").is_err();
                speed_loss_line(&name, &mut b, omega, &torques, step, ramp);
            }
        }
        Some("wrapdump") => {
            let mut cfg = table_cfg(Some(20));
            cfg.contact.kappa = arg(3, 4000.0);
            let omega = arg(1, 62.8);
            let fe = BeltFe::new(&cfg).unwrap();
            let mut b =
                FlowingBelt::new(fe, Schedule::constant(omega), Schedule::constant(0.0)).unwrap();
            let st = steady(&mut b, omega, arg(2, 8.0), 2.5e-4);
            let m = b.n_modes();
            let tens = b.element_tensions(&st.q[1..=m]);
            let d = b.deflection(&st.q[1..=m]);
            let vb = st.v[0];
            let nn = b.fe.n_nodes();
            if std::env::var("ALLT").is_ok() {
                let tz = &st.q[1..=m];
                let zd = &st.v[1..=m];
                let _ = tz;
                let line: Vec<String> = tens.iter().map(|t| format!("{t:.1}")).collect();
                println!("element tensions: {}", line.join(" "));
                let mx = zd.iter().fold(0.0f64, |a, x| a.max(x.abs()));
                println!("max |ż| {mx:.3e}");
            }
            for r in b.contact_report(st.t, &st.q, &st.v) {
                let i = r.node;
                let c = r.contact;
                let mut ds = [0.0; 2];
                for a in 0..2 {
                    for k in 0..m {
                        ds[a] += b.basis.ts[(3 * i + a, k)] * st.q[1 + k];
                    }
                }
                let t = b.fe.tangent[i];
                let eps_fd = t[0] * ds[0] + t[1] * ds[1];
                let _ = &d;
                println!(
                    "p{} node {i:3} s {:.4} T {:8.3} eps(T) {:.3e} t·δ_s {:.3e} FN {:8.3} FT {:8.3} slip {:+.3e} ω·Rc {:.5} Vt {:.5}",
                    r.pulley,
                    r.s,
                    0.5 * (tens[i] + tens[(i + nn - 1) % nn]),
                    (0.5 * (tens[i] + tens[(i + nn - 1) % nn]) - 310.0) / 152000.0,
                    eps_fd,
                    c.normal,
                    c.friction,
                    c.slip,
                    b.pulley_speed(r.pulley, st.t, &st.v) * b.fe.contact_radius[r.pulley],
                    vb * (1.0 + eps_fd)
                );
            }
        }
        Some("sl2") => {
            // sl2 <table|pg> <flowing|nodal> ω kappa [step]; env LS=0 disables line search
            let kappa = arg(4, 40.0);
            let step = arg(5, 2.5e-4);
            let ls = std::env::var("LS").as_deref() != Ok("0");
            let (cfg, torques, ramp) = match args[1].as_str() {
                "pg" => (pg_cfg(Some(20), kappa), vec![47.69], 1.0),
                _ => {
                    let mut c = table_cfg(Some(20));
                    c.contact.kappa = kappa;
                    let tq = std::env::var("TORQUES")
                        .ok()
                        .map(|s| s.split(',').filter_map(|x| x.parse().ok()).collect())
                        .unwrap_or(vec![4.0, 8.0]);
                    (c, tq, 0.1)
                }
            };
            let omega = arg(3, 62.8);
            let fe = BeltFe::new(&cfg).unwrap();
            let t = std::time::Instant::now();
            let r = if args[2] == "nodal" {
                let mut b =
                    NodalBelt::new(fe, Schedule::constant(omega), Schedule::constant(0.0)).unwrap();
                let tol = std::env::var("TOL")
                    .ok()
                    .and_then(|s| s.parse().ok())
                    .unwrap_or(1e-3);
                speed_loss_ls(&mut b, omega, &torques, step, ramp, ls, tol)
            } else {
                let mut b =
                    FlowingBelt::new(fe, Schedule::constant(omega), Schedule::constant(0.0))
                        .unwrap();
                b.exact_axial = std::env::var("EXACT").is_ok();
                speed_loss_ls(&mut b, omega, &torques, step, ramp, ls, 2e-4)
            };
            match r {
                Ok((dw, steps, newton)) => println!(
                    "{} {} ω={omega} κ={kappa} (v_s={:.2e} m/s) h={step} ls={ls}: {} | steps {steps} newton {newton} ({:.2}/step) wall {:.1} s",
                    args[1],
                    args[2],
                    1.0 / kappa,
                    torques
                        .iter()
                        .zip(&dw)
                        .map(|(t, d)| format!("T={t} dω={d:.5} ({:.4} %)", 100.0 * d / omega))
                        .collect::<Vec<_>>()
                        .join(", "),
                    newton as f64 / steps as f64,
                    t.elapsed().as_secs_f64()
                ),
                Err(e) => println!("{} {} ω={omega} κ={kappa}: failed {e}", args[1], args[2]),
            }
        }
        Some("nbal") => {
            // nbal <table|pg> ω T: nodal torque balance (uniform loop)
            let cfg = match args[1].as_str() {
                "pg" => {
                    let mut c = pg_cfg(Some(20), arg(4, 40.0));
                    c.mesh.span_elements = 24;
                    c.mesh.arc_elements = 24;
                    c
                }
                _ => {
                    let mut c = table_cfg(Some(20));
                    c.mesh.span_elements = 80;
                    c.mesh.arc_elements = 28;
                    c
                }
            };
            let ramp = if args[1] == "pg" { 1.0 } else { 0.1 };
            nodal_balance(&cfg, arg(2, 62.8), arg(3, 8.0), ramp);
        }
        Some("means") => {
            // means <flowing|nodal> rpm [ramp] [max_t]; env MODES=all, SPAN_H, ARC_H, EXACT
            let mut cfg = drives::fead::FeadConfig::default();
            let envf = |k: &str, d: f64| {
                std::env::var(k)
                    .ok()
                    .and_then(|s| s.parse().ok())
                    .unwrap_or(d)
            };
            cfg.drive.mesh.span_element = envf("SPAN_H", cfg.drive.mesh.span_element);
            cfg.drive.mesh.arc_element = envf("ARC_H", cfg.drive.mesh.arc_element);
            cfg.drive.damping.beta *= envf("BETA_SCALE", 1.0);
            if std::env::var("MODES").as_deref() == Ok("all") {
                cfg.drive.reduction.free_modes = None;
            }
            let (rpm, ramp, max_t) = (arg(2, 2500.0), arg(3, 0.5), arg(4, 2.0));
            if args[1] == "nodal" {
                let (mut b, _) = cfg.drive.uniform_mesh().nodal_model().unwrap();
                b.exact_axial = std::env::var("EXACT").is_ok();
                fead_means(b, "nodal", rpm, ramp, true, max_t);
            } else {
                let (mut b, _) = cfg.drive.flowing_model().unwrap();
                b.exact_axial = std::env::var("EXACT").is_ok();
                fead_means(b, "flowing", rpm, ramp, false, max_t);
            }
        }
        Some("fead") => fead_power(arg(1, 800.0), arg(2, 0.3), arg(3, 2.0)),
        Some("power") => {
            let modes = if args.get(3).map(String::as_str) == Some("all") {
                None
            } else {
                Some(args.get(3).and_then(|s| s.parse().ok()).unwrap_or(20))
            };
            flowing_power_table(&table_cfg(modes), arg(1, 62.8), arg(2, 8.0))
        }
        _ => eprintln!("commands: flowing ω T [modes|all]; pg ω T [modes|all] [kappa]"),
    }
    let _ = NodalBelt::new;
}
