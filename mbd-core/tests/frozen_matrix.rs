//! The frozen iteration-matrix policy of the generalized-α stepper (`NewtonUpdate::Frozen`,
//! `DriftTrigger`, the spare of another step size), its explicit inverse, the linearly
//! implicit step, the zero predictor and explicit coefficients, checked against full Newton
//! on linear models (second formulation: with constant matrices one Newton iteration with the
//! exact matrix solves the step exactly, whatever the predictor and the solver).

use faer::Mat;
use mbd_core::Workspace;
use mbd_core::integrators::{
    AlphaCoefficients, AlphaConfig, AlphaCorrection, AlphaStepper, DriftTrigger, NewtonUpdate,
    State, StepCorrection, Stepper,
};
use mbd_core::{ForceTangent, MbdError, SecondOrderSystem, SysMatrix};

/// Damped two-mass chain `M ẍ + C ẋ + K x = 0` (constant, non-diagonal K, C).
struct Chain;

const M: [[f64; 2]; 2] = [[2.0, 0.0], [0.0, 1.0]];
const K: [[f64; 2]; 2] = [[300.0, -100.0], [-100.0, 100.0]];
const C: [[f64; 2]; 2] = [[0.6, -0.2], [-0.2, 0.2]];

fn dense(a: [[f64; 2]; 2]) -> SysMatrix {
    SysMatrix::Dense(Mat::from_fn(2, 2, |i, j| a[i][j]))
}

impl SecondOrderSystem for Chain {
    fn n_q(&self) -> usize {
        2
    }
    fn mass_is_constant(&self) -> bool {
        true
    }
    fn mass(&self, _t: f64, _q: &[f64]) -> Result<SysMatrix, MbdError> {
        Ok(dense(M))
    }
    fn forces(
        &self, _t: f64, q: &[f64], v: &[f64], f: &mut [f64], _ws: &mut Workspace,
    ) -> Result<(), MbdError> {
        for i in 0..2 {
            f[i] = -(0..2).map(|j| K[i][j] * q[j] + C[i][j] * v[j]).sum::<f64>();
        }
        Ok(())
    }
    fn force_tangent(
        &self, _t: f64, _q: &[f64], _v: &[f64], _ws: &mut Workspace,
    ) -> Result<Option<ForceTangent>, MbdError> {
        Ok(Some(ForceTangent {
            stiffness: dense(K),
            damping: dense(C),
        }))
    }
}

fn start() -> State {
    State::new(0.0, vec![0.01, -0.02], vec![0.3, 0.0])
}

fn full_newton() -> AlphaConfig {
    AlphaConfig {
        h: 2e-3,
        rho_inf: 0.6,
        newton_atol: 1e-14,
        newton_rtol: 1e-14,
        ..AlphaConfig::default()
    }
}

fn frozen() -> AlphaConfig {
    AlphaConfig {
        update: NewtonUpdate::Frozen,
        linearly_implicit: true,
        explicit_inverse: true,
        ..full_newton()
    }
}

/// Runs `steps` steps of the sizes `h(k)` and returns the states.
fn run(cfg: AlphaConfig, steps: usize, h: impl Fn(usize) -> f64) -> (Vec<State>, usize) {
    let mut st = AlphaStepper::new(&Chain, start(), cfg).unwrap();
    let mut out = Vec::new();
    for k in 0..steps {
        Stepper::step(&mut st, &Chain, Some(h(k))).unwrap();
        out.push(st.state().clone());
    }
    (out, st.stats.factorizations)
}

fn max_diff(a: &[State], b: &[State]) -> f64 {
    a.iter()
        .zip(b)
        .flat_map(|(x, y)| x.q.iter().zip(&y.q).chain(x.v.iter().zip(&y.v)))
        .map(|(p, q)| (p - q).abs())
        .fold(0.0, f64::max)
}

#[test]
fn frozen_linearly_implicit_step_equals_full_newton_on_a_linear_model() {
    let (reference, n_ref) = run(full_newton(), 300, |_| 2e-3);
    let (fz, n_fz) = run(frozen(), 300, |_| 2e-3);
    let (zp, _) = run(
        AlphaConfig {
            zero_predictor: true,
            ..frozen()
        },
        300,
        |_| 2e-3,
    );
    let d = max_diff(&reference, &fz);
    assert!(d < 1e-12, "frozen differs by {d}");
    let d = max_diff(&reference, &zp);
    assert!(d < 1e-12, "zero predictor differs by {d}");
    // one factorisation of the iteration matrix (plus the start accelerations' mass solve)
    // instead of at least one per step
    assert!(n_fz <= 2, "{n_fz} factorisations");
    assert!(n_ref >= 300, "{n_ref} factorisations");
}

#[test]
fn alternating_step_sizes_keep_one_factorisation_each() {
    // sub-steps h/4 in a window, as the tire rig takes them through the cleat impact
    let h = |k: usize| if (100..140).contains(&k) { 5e-4 } else { 2e-3 };
    let (reference, _) = run(full_newton(), 300, h);
    let (fz, n_fz) = run(frozen(), 300, h);
    let d = max_diff(&reference, &fz);
    assert!(d < 1e-12, "frozen differs by {d}");
    assert!(n_fz <= 3, "{n_fz} factorisations (start, h, h/4)");
}

#[test]
fn drift_trigger_and_refactor_request_factor_again() {
    // the velocity of mass 1 swings through ±0.3 m/s: a 5 % drift trigger fires repeatedly
    let cfg = AlphaConfig {
        refactor_drift: Some(DriftTrigger {
            dof: 0,
            tolerance: 0.05,
        }),
        ..frozen()
    };
    let (reference, _) = run(full_newton(), 300, |_| 2e-3);
    let (fz, n_fz) = run(cfg, 300, |_| 2e-3);
    assert!(max_diff(&reference, &fz) < 1e-12);
    assert!(n_fz > 5, "{n_fz} factorisations");
    let mut st = AlphaStepper::new(&Chain, start(), frozen()).unwrap();
    Stepper::step(&mut st, &Chain, None).unwrap();
    let n0 = st.stats.factorizations;
    assert_eq!(st.frozen_reference(2e-3), Some(0.0));
    st.refactor();
    assert_eq!(st.frozen_reference(2e-3), None);
    Stepper::step(&mut st, &Chain, None).unwrap();
    assert_eq!(st.stats.factorizations, n0 + 1);
}

#[test]
fn newmark_coefficients_equal_unit_spectral_radius() {
    // ρ∞ = 1 gives α_m = α_f = ½, β = ¼, γ = ½: algebraically the trapezoidal rule, the plain
    // Newmark coefficients α_m = α_f = 0 (Arnold & Brüls 2007)
    let (ga, _) = run(
        AlphaConfig {
            rho_inf: 1.0,
            ..full_newton()
        },
        300,
        |_| 2e-3,
    );
    let (nm, _) = run(
        AlphaConfig {
            coefficients: Some(AlphaCoefficients {
                alpha_m: 0.0,
                alpha_f: 0.0,
                beta: 0.25,
                gamma: 0.5,
            }),
            ..frozen()
        },
        300,
        |_| 2e-3,
    );
    let d = max_diff(&ga, &nm);
    assert!(d < 1e-11, "{d}");
    let bad = AlphaConfig {
        coefficients: Some(AlphaCoefficients {
            alpha_m: 1.0,
            alpha_f: 0.0,
            beta: 0.25,
            gamma: 0.5,
        }),
        ..frozen()
    };
    assert!(AlphaStepper::new(&Chain, start(), bad).is_err());
}

/// Checks `solve_columns` against `solve` column by column on every step.
struct ColumnCheck {
    worst: f64,
    ids: Vec<usize>,
}

impl StepCorrection<Chain> for ColumnCheck {
    fn correct(&mut self, _sys: &Chain, step: &mut AlphaCorrection<'_>) -> Result<(), MbdError> {
        let f = Mat::from_fn(2, 2, |i, j| if i == j { 1.0 } else { 0.5 });
        let mut out = Mat::<f64>::zeros(2, 2);
        step.solve_columns(f.as_ref(), out.as_mut())?;
        for j in 0..2 {
            let col: Vec<f64> = (0..2).map(|i| f[(i, j)]).collect();
            let mut x = vec![0.0; 2];
            step.solve(&col, &mut x, &mut [])?;
            for i in 0..2 {
                self.worst = self.worst.max((x[i] - out[(i, j)]).abs());
            }
        }
        self.ids.push(step.factor_id());
        Ok(())
    }
}

#[test]
fn solve_columns_equals_single_solves_and_factor_id_tracks_the_spare() {
    for explicit in [false, true] {
        let cfg = AlphaConfig {
            explicit_inverse: explicit,
            ..frozen()
        };
        let mut st = AlphaStepper::new(&Chain, start(), cfg)
            .unwrap()
            .with_correction(ColumnCheck {
                worst: 0.0,
                ids: Vec::new(),
            });
        for k in 0..6 {
            let h = if k % 2 == 0 { 2e-3 } else { 1e-3 };
            Stepper::step(&mut st, &Chain, Some(h)).unwrap();
        }
        let c = st.correction();
        assert!(c.worst < 1e-15, "{}", c.worst);
        // two factorisations, swapped in turn
        assert_eq!(c.ids[0], c.ids[2]);
        assert_eq!(c.ids[1], c.ids[3]);
        assert_ne!(c.ids[0], c.ids[1]);
    }
}

/// A mass on a spring dragged by a belt at `V = 1 m/s` through the saturating creep-rate law
/// `f = −sat(ν (v − V))` (slope ν = 10⁴ N·s/m, bound 5 N; Kerkkänen Fig. 3.3): stick–slip, a
/// piecewise-smooth force whose tangent jumps between ν and 0.
struct StickSlip;

impl StickSlip {
    fn friction(v: f64) -> (f64, f64) {
        let lin = 1e4 * (v - 1.0);
        if lin.abs() <= 5.0 {
            (-lin, -1e4)
        } else {
            (-5.0 * lin.signum(), 0.0)
        }
    }
}

impl SecondOrderSystem for StickSlip {
    fn n_q(&self) -> usize {
        1
    }
    fn mass_is_constant(&self) -> bool {
        true
    }
    fn mass(&self, _t: f64, _q: &[f64]) -> Result<SysMatrix, MbdError> {
        Ok(SysMatrix::Dense(Mat::from_fn(1, 1, |_, _| 1.0)))
    }
    fn forces(
        &self, _t: f64, q: &[f64], v: &[f64], f: &mut [f64], _ws: &mut Workspace,
    ) -> Result<(), MbdError> {
        f[0] = -100.0 * q[0] + Self::friction(v[0]).0;
        Ok(())
    }
    fn force_tangent(
        &self, _t: f64, _q: &[f64], v: &[f64], _ws: &mut Workspace,
    ) -> Result<Option<ForceTangent>, MbdError> {
        let d = Self::friction(v[0]).1;
        Ok(Some(ForceTangent {
            stiffness: SysMatrix::Dense(Mat::from_fn(1, 1, |_, _| 100.0)),
            damping: SysMatrix::Dense(Mat::from_fn(1, 1, |_, _| -d)),
        }))
    }
}

// Second formulation: on the stick–slip model the frozen matrix renewed by the contraction
// trigger, with the line search and the stall exit, solves the same step equations as full
// Newton (same states to the Newton tolerance) with fewer factorisations.
#[test]
fn contraction_trigger_and_line_search_reproduce_full_newton_on_stick_slip() {
    let tight = AlphaConfig {
        h: 1e-3,
        rho_inf: 0.6,
        newton_atol: 1e-13,
        newton_rtol: 0.0,
        max_newton_iterations: 60,
        max_halvings: 0,
        ..AlphaConfig::default()
    };
    let policy = AlphaConfig {
        update: NewtonUpdate::Frozen,
        refactor_contraction: Some(0.5),
        newton_line_search: true,
        newton_stall: Some(mbd_core::newton::Stall {
            ratio: 0.9,
            iterations: 3,
            backtrack: false,
        }),
        ..tight
    };
    let go = |cfg: AlphaConfig| {
        let mut st =
            AlphaStepper::new(&StickSlip, State::new(0.0, vec![0.0], vec![1.0]), cfg).unwrap();
        let mut out = Vec::new();
        for _ in 0..1500 {
            st.step(&StickSlip, Some(1e-3)).unwrap();
            out.push(st.state().clone());
        }
        (out, st.stats)
    };
    let (reference, s_ref) = go(tight);
    let (states, s) = go(policy);
    // the motion is stick–slip: the spring force passes the friction bound
    assert!(reference.iter().any(|s| 100.0 * s.q[0] > 5.0));
    let d = max_diff(&reference, &states);
    assert!(d < 1e-8, "max difference {d:e}");
    assert!(
        s.factorizations < s_ref.factorizations,
        "{} vs {} factorisations",
        s.factorizations,
        s_ref.factorizations
    );
}

// Reference: full Newton on the linear chain (one exact iteration per step). A trust region
// (`newton_max_step`) far below the first corrections changes only the path to the step's
// solution: the same states to the tolerance, more iterations, every iteration damped until
// the last; and a trust region that is not positive is rejected as an option.
#[test]
fn newton_trust_region_reaches_the_same_steps() {
    let mut st = AlphaStepper::new(
        &Chain,
        State::new(0.0, vec![0.01, -0.02], vec![30.0, 0.0]),
        AlphaConfig {
            newton_max_step: Some(1e-7),
            max_newton_iterations: 2000,
            ..full_newton()
        },
    )
    .unwrap();
    let mut reference = AlphaStepper::new(
        &Chain,
        State::new(0.0, vec![0.01, -0.02], vec![30.0, 0.0]),
        full_newton(),
    )
    .unwrap();
    for _ in 0..50 {
        Stepper::step(&mut st, &Chain, Some(2e-3)).unwrap();
        Stepper::step(&mut reference, &Chain, Some(2e-3)).unwrap();
        for (a, b) in st.state().q.iter().zip(&reference.state().q) {
            assert!((a - b).abs() < 1e-12, "{a} vs {b}");
        }
    }
    // the predictor misses a step by about β h² ΔA ≈ 1e-5 m (ΔA ≈ K v h / M): tens of 1e-7 m
    // corrections
    assert!(
        st.stats.newton_iterations > 10 * reference.stats.newton_iterations,
        "{} vs {}",
        st.stats.newton_iterations,
        reference.stats.newton_iterations
    );
    let mut bad = AlphaStepper::new(
        &Chain,
        start(),
        AlphaConfig {
            newton_max_step: Some(0.0),
            ..full_newton()
        },
    )
    .unwrap();
    let e = Stepper::step(&mut bad, &Chain, Some(2e-3)).unwrap_err();
    assert!(e.to_string().contains("max_step"), "{e}");
}
