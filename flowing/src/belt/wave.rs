//! Rotating vs non-rotating belt (Ribaric §6.2, Fig. 6-3; seed-000 note §2.2, example B0):
//! the flowing-material belt drive of Table 6-1 started with a deflected upper span, once at rest
//! and once running at a constant (exaggerated) belt speed.
//!
//! The stationary mesh shows the material's motion through the deflection field: at rest the
//! initial bump splits into two equal waves running to both pulleys at `±c`, `c = √(T0/ρA)`
//! (the centroid of the squared deflection stays put); on the running belt the two waves travel at
//! `v ± c` and the disturbance is carried along with the belt (the centroid of the squared deflection
//! drifts at the belt speed `v`, the two halves keeping equal amplitudes), and the span's vibration frequency falls by the factor `1 − v²/c²` of the axially
//! moving string, `ω_n = nπ (c² − v²)/(c L)` (Ribaric §4.2, Wickert & Mote).
//!
//! Initial conditions: the deflection `δ₀ = A cos²(π(x − x_m)/(2b))` (for `|x − x_m| < b`)
//! normal to the upper span, `x_m` its middle, projected on the basis (`T z₀ ≈ δ₀`, mass-weighted
//! least squares); the material points of the deflected belt have no transverse velocity — the
//! bump is a deformation *of the material*, which the running belt carries with it — so the
//! Eulerian rate is `T ż₀ = −v T_,s z₀` (projected likewise) (with `ż₀ = 0` instead, the two waves
//! would carry the amplitudes `(c ∓ v)/(2c)` and the deflection centroid would stay put). The belt
//! speed and both pulley speeds start at `v` (driver held at `v/R₁`), no load.

use super::config::FlowingSettings;
use super::flowing_system::FlowingBelt;
use crate::error::{FlowError, invalid};
use belt::{Drive, Motion, Signal};
use faer::Mat;
use faer::linalg::solvers::Solve;
use mbd_core::integrators::{AlphaConfig, GeneralizedAlpha, Recorder, State, observe_fn};
use mbd_core::validate::{InvalidField, Validate};
use serde::{Deserialize, Serialize};

/// Most generalized-α steps of one run, `t_end / step` (a documented ceiling,
/// [`mbd_core::validate::limits`]; the default run takes 2000).
pub const MAX_WAVE_STEPS: f64 = 1e7;
/// Most recorded samples of one run (every sample keeps the loop's shape: about 2 kB for
/// Table 6-1's default mesh; the default records 1000).
pub const MAX_WAVE_SAMPLES: usize = 100_000;

/// Settings of the demonstration (SI units).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(default, deny_unknown_fields)]
pub struct WaveConfig {
    /// Belt speed of the running case \[m/s\] (default 28.4 m/s = c/2 for Table 6-1, an
    /// "exaggerated" speed at which `1 − v²/c² = 0.75`).
    pub belt_speed: f64,
    /// Peak initial deflection \[m\].
    pub amplitude: f64,
    /// Half-width of the initial bump as a fraction of the upper span length \[-\].
    pub half_width: f64,
    /// Simulated time \[s\].
    pub t_end: f64,
    /// Generalized-α step \[s\].
    pub step: f64,
    /// Generalized-α spectral radius at infinity \[-\].
    pub rho_inf: f64,
    /// Number of output samples (histories and belt shapes), equally spaced in time.
    pub samples: usize,
}

impl Default for WaveConfig {
    fn default() -> Self {
        Self {
            belt_speed: 28.4,
            amplitude: 2e-3,
            half_width: 0.2,
            t_end: 0.1,
            step: 5e-5,
            rho_inf: 0.9,
            samples: 1000,
        }
    }
}

impl Validate for WaveConfig {
    /// Every field checked; the error names the field (path relative to this struct).
    fn validate(&self) -> Result<(), InvalidField> {
        for (name, v) in [
            ("amplitude", self.amplitude),
            ("half_width", self.half_width),
            ("t_end", self.t_end),
            ("step", self.step),
        ] {
            if !(v.is_finite() && v > 0.0) {
                return Err(InvalidField::new(
                    name,
                    format!("must be finite and > 0 (got {v})"),
                ));
            }
        }
        if !(self.belt_speed.is_finite() && self.belt_speed >= 0.0) {
            return Err(InvalidField::new("belt_speed", "must be finite and ≥ 0"));
        }
        if self.half_width >= 0.5 {
            return Err(InvalidField::new(
                "half_width",
                format!("must be < 0.5 of the span (got {})", self.half_width),
            ));
        }
        if !(0.0..=1.0).contains(&self.rho_inf) {
            return Err(InvalidField::new("rho_inf", "must lie in [0, 1]"));
        }
        if self.samples < 2 {
            return Err(InvalidField::new("samples", "must be at least 2"));
        }
        // run length and recorded samples bounded before anything runs (issue 35:
        // `t_end = 1e9` ran without end, and ignored SIGTERM)
        let steps = self.t_end / self.step;
        let max_steps = mbd_core::validate::limits::ceiling(MAX_WAVE_STEPS);
        if steps > max_steps {
            return Err(InvalidField::new(
                "t_end",
                format!(
                    "{} s at step = {} s is {steps:.3e} steps, more than the {max_steps:e} a run \
                     may take (shorten t_end or lengthen step){}",
                    mbd_core::validate::check::show(self.t_end),
                    mbd_core::validate::check::show(self.step),
                    mbd_core::validate::limits::raise_hint()
                ),
            ));
        }
        mbd_core::validate::check::count(
            "samples",
            self.samples,
            2,
            mbd_core::validate::limits::ceiling_count(MAX_WAVE_SAMPLES),
        )?;
        if self.step > self.t_end / self.samples as f64 {
            return Err(InvalidField::new(
                "step",
                "must not exceed t_end / samples (one step per sample at least)",
            ));
        }
        Ok(())
    }
}

/// History of one run.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct WaveRun {
    /// Belt speed \[m/s\].
    pub belt_speed: f64,
    /// Sample times \[s\].
    pub times: Vec<f64>,
    /// Position of the upper span's nodes along the span in the travel direction, counted from
    /// the projection of the first pulley centre on the span line \[m\] (the bump is centred at
    /// half the centre distance).
    pub span_position: Vec<f64>,
    /// Deflection normal to the upper span at its nodes, one row per sample \[m\].
    pub span_deflection: Vec<Vec<f64>>,
    /// Deflection at the node nearest the span middle, per sample \[m\].
    pub midspan: Vec<f64>,
    /// Centroid `∫x w² dx / ∫w² dx` of the span deflection, per sample \[m\] (w² rather than w:
    /// insensitive to the small background deflection of the running belt's spans).
    pub centroid: Vec<f64>,
    /// Node positions of the whole deformed loop, per sample \[m\].
    pub shapes: Vec<Vec<[f64; 2]>>,
}

/// Transverse wave speed `c = √(T0/ρA)` of the mounted belt of `drive` \[m/s\].
pub fn wave_speed(drive: &Drive) -> f64 {
    drive.belt().wave_speed(drive.tension())
}

/// Mass-weighted least squares `(Tᵀ W T) z = Tᵀ W d` (`W` the lumped mass).
fn project(t: &Mat<f64>, w: &[f64], d: &[f64]) -> Result<Vec<f64>, FlowError> {
    let (n, m) = (t.nrows(), t.ncols());
    let a = Mat::<f64>::from_fn(m, m, |i, j| {
        (0..n).map(|k| t[(k, i)] * w[k] * t[(k, j)]).sum()
    });
    let b = Mat::<f64>::from_fn(m, 1, |i, _| (0..n).map(|k| t[(k, i)] * w[k] * d[k]).sum());
    let llt = a
        .llt(faer::Side::Lower)
        .map_err(|e| FlowError::LinearAlgebra {
            what: "wave: projection of the initial deflection on the basis".into(),
            reason: format!("{e:?}"),
        })?;
    let x = llt.solve(&b);
    Ok((0..m).map(|i| x[(i, 0)]).collect())
}

/// Run the demonstration on `drive` (pulley 0 speed-driven) with the flowing model's
/// `settings` (its reduction used as is), the bump on span 0 (pulley 0 → pulley 1): at rest
/// when `running` is false, at `wave.belt_speed` otherwise. Pulley 0 turns at `v/R₀`, every
/// free pulley starts at `v/R_k` without load.
pub fn wave_run(
    drive: &Drive, settings: &FlowingSettings, wave: &WaveConfig, running: bool,
) -> Result<WaveRun, FlowError> {
    wave.validate_within("wave")?;
    let v = if running { wave.belt_speed } else { 0.0 };
    let radius: Vec<f64> = drive.pulleys().iter().map(|p| p.radius).collect();
    let motions: Vec<Motion> = drive
        .motions()
        .iter()
        .enumerate()
        .map(|(k, m)| match m {
            Motion::Speed { .. } if k == 0 => Motion::speed(Signal::constant(v / radius[0])),
            Motion::Speed { .. } => Motion::speed(Signal::constant(0.0)),
            free => free.at_rest(),
        })
        .collect();
    if !matches!(motions[0], Motion::Speed { .. }) {
        return Err(invalid(
            "wave: pulleys[0].motion",
            "pulley 0 must be speed-driven (it holds the belt speed)",
        ));
    }
    let drive = drive.with_motions(motions)?;
    let belt = FlowingBelt::new(&drive, settings)?;
    let fe = &belt.fe;
    let n_nodes = fe.n_nodes();
    // span 0's nodes strictly between its tangent points, in travel order
    let piece = fe.path().pieces()[0];
    let line = fe.path().spans()[0];
    let span: Vec<usize> = (0..n_nodes)
        .filter(|&i| {
            let s = fe.s[i] - piece.s_start;
            s > 1e-9 * piece.length && s < piece.length * (1.0 - 1e-9)
        })
        .collect();
    if span.len() < 5 {
        return Err(invalid(
            "wave: span 0",
            format!("only {} nodes on the span", span.len()),
        ));
    }
    let dir = line.direction;
    let along = |p: [f64; 2]| line.local(p).0;
    let x0 = 0.0;
    let span_len = line.length;
    let xm = x0 + 0.5 * span_len;
    let b = wave.half_width * span_len;
    let normal = [-dir[1], dir[0]];
    let ndof = fe.n_dofs();
    let mut d0 = vec![0.0; ndof];
    for i in 0..n_nodes {
        let p = fe.position[i];
        if !span.contains(&i) {
            continue;
        }
        let x = along(p) - xm;
        if x.abs() < b {
            let arg = std::f64::consts::PI * x / (2.0 * b);
            let w = wave.amplitude * arg.cos().powi(2);
            // slope dw/dx = −A (π/2b) sin(2 arg)
            let slope = -wave.amplitude * std::f64::consts::PI / (2.0 * b) * (2.0 * arg).sin();
            d0[3 * i] = w * normal[0];
            d0[3 * i + 1] = w * normal[1];
            d0[3 * i + 2] = slope;
        }
    }
    let t = &belt.basis.t;
    let z0 = project(t, &fe.mass, &d0)?;
    let m = z0.len();
    // Lagrangian start: T ż₀ = −v T_,s z₀
    let zd0 = if v != 0.0 {
        let ts = &belt.basis.ts;
        let tsz: Vec<f64> = (0..ndof)
            .map(|k| -v * (0..m).map(|j| ts[(k, j)] * z0[j]).sum::<f64>())
            .collect();
        project(t, &fe.mass, &tsz)?
    } else {
        vec![0.0; m]
    };
    let nq = mbd_core::SecondOrderSystem::n_q(&belt);
    let mut q = vec![0.0; nq];
    q[1..=m].copy_from_slice(&z0);
    let mut vel = vec![0.0; nq];
    vel[0] = v;
    vel[1..=m].copy_from_slice(&zd0);
    for (k, r) in radius.iter().enumerate() {
        if let Some(j) = belt.coords.pulley_dof(k) {
            vel[j] = v / r;
        }
    }
    let state = State::new(0.0, q, vel);

    let xs: Vec<f64> = span.iter().map(|&i| along(fe.position[i]) - x0).collect();
    let mid = span
        .iter()
        .enumerate()
        .min_by(|a, b| {
            (along(fe.position[*a.1]) - xm)
                .abs()
                .total_cmp(&(along(fe.position[*b.1]) - xm).abs())
        })
        .map(|(k, _)| k)
        .unwrap_or(0);
    let mut run = WaveRun {
        belt_speed: v,
        times: Vec::new(),
        span_position: xs.clone(),
        span_deflection: Vec::new(),
        midspan: Vec::new(),
        centroid: Vec::new(),
        shapes: Vec::new(),
    };
    let mut sample = |s: &State| {
        let d = belt.deflection(&s.q[1..=m]);
        let w: Vec<f64> = span
            .iter()
            .map(|&i| d[3 * i] * normal[0] + d[3 * i + 1] * normal[1])
            .collect();
        // trapezoidal moments of w² over the span nodes
        let (mut m0, mut m1) = (0.0, 0.0);
        for k in 0..w.len().saturating_sub(1) {
            let dx = xs[k + 1] - xs[k];
            let (a, b) = (w[k] * w[k], w[k + 1] * w[k + 1]);
            m0 += 0.5 * dx * (a + b);
            m1 += 0.5 * dx * (a * xs[k] + b * xs[k + 1]);
        }
        run.times.push(s.t);
        run.midspan.push(w[mid]);
        run.centroid
            .push(if m0 != 0.0 { m1 / m0 } else { f64::NAN });
        run.span_deflection.push(w);
        run.shapes.push(
            (0..n_nodes)
                .map(|i| {
                    [
                        fe.position[i][0] + d[3 * i],
                        fe.position[i][1] + d[3 * i + 1],
                    ]
                })
                .collect(),
        );
    };
    let alpha = GeneralizedAlpha::new(AlphaConfig {
        h: wave.step,
        rho_inf: wave.rho_inf,
        ..Default::default()
    });
    let mut stepper = alpha.stepper(&belt, state)?;
    // samples at k·Δt, k = 0..=samples (the stepper is advanced to each of them)
    let dt = wave.t_end / wave.samples as f64;
    let mut rec = Recorder::new(observe_fn(&mut sample), 0.0, dt)?;
    rec.run(&mut stepper, &belt, wave.samples as f64 * dt, &mut ())?;
    Ok(run)
}

/// Frequency \[Hz\] of the largest spectral peak of `y(t)` (uniform samples) between `f_lo` and
/// `f_hi`, by a scan of the discrete-time Fourier transform of the mean-free signal with a Hann
/// window, refined by golden-section search.
pub fn dominant_frequency(t: &[f64], y: &[f64], f_lo: f64, f_hi: f64) -> f64 {
    let n = y.len().min(t.len());
    if n < 4 {
        return f64::NAN;
    }
    let mean = y[..n].iter().sum::<f64>() / n as f64;
    let win: Vec<f64> = (0..n)
        .map(|k| {
            let h = 0.5 - 0.5 * (std::f64::consts::TAU * k as f64 / (n - 1) as f64).cos();
            h * (y[k] - mean)
        })
        .collect();
    let power = |f: f64| {
        let w = std::f64::consts::TAU * f;
        let (mut re, mut im) = (0.0, 0.0);
        for k in 0..n {
            re += win[k] * (w * t[k]).cos();
            im -= win[k] * (w * t[k]).sin();
        }
        re * re + im * im
    };
    let steps = 400;
    let mut best = (f_lo, f64::NEG_INFINITY);
    for k in 0..=steps {
        let f = f_lo + (f_hi - f_lo) * k as f64 / steps as f64;
        let p = power(f);
        if p > best.1 {
            best = (f, p);
        }
    }
    let df = (f_hi - f_lo) / steps as f64;
    let (mut a, mut b) = ((best.0 - df).max(f_lo), (best.0 + df).min(f_hi));
    let g = 0.5 * (5f64.sqrt() - 1.0);
    for _ in 0..60 {
        let c = b - g * (b - a);
        let d = a + g * (b - a);
        if power(c) > power(d) {
            b = d;
        } else {
            a = c;
        }
    }
    0.5 * (a + b)
}
