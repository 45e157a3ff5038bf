//! Coupled modes of the drive: the spans' transverse motion coupled with the rotational model
//! through the tensioner arm (Beikmann, Perkins & Ulsoy 1996, "Free vibration of serpentine
//! belt drive systems", J. Vib. Acoust. 118, 406–413: the hybrid discrete–continuous model).
//!
//! # Model
//!
//! Coordinates: the rotational model's `q_r` ([`super::modes`]: the free pulleys, a
//! decoupler's accessory, the arm angle `θ_a`) and, for every span `i` of length `L_i`, the
//! amplitudes `a_ik` of a sine series. The span's transverse displacement (to the left of its
//! travel direction `d_i`, normal `n_i = (−d_y, d_x)`) at `x ∈ [0, L_i]` from the pulley it
//! leaves is
//!
//! ```text
//!   w_i(x, t) = (g_i0 (1 − x/L_i) + g_i1 x/L_i) θ_a(t) + Σ_{k=1..N} a_ik(t) sin(kπx/L_i)
//! ```
//!
//! where `g = c'(θ_a) · n_i` \[m/rad\] at an end on the tensioner's idler (its centre moves by
//! `c'(θ_a) δθ_a`, which moves the tangent line by the normal component of that displacement;
//! Beikmann et al. (1996) boundary condition at the idler) and `g = 0` at every other end
//! (fixed centres). Each span is a travelling string of tension `T_i` (the steady span tension,
//! centrifugal part included), mass per length `m = ρA` and speed `v` (Wickert & Mote 1990,
//! Lagrangian `½∫ m (w_t + v w_x)² − T w_x² dx`), which with the Galerkin shapes `N(x)` gives
//!
//! ```text
//!   M = m∫NNᵀ,  G = B − Bᵀ with B = m v ∫N N'ᵀ,  K_s = ∫(T − m v²) N'N'ᵀ
//!   (M_r ⊕ M_s) q̈ + G q̇ + (K_r' ⊕ K_s) q = 0
//! ```
//!
//! The arm's own stiffness in `K_r'` is the rotational model's `k_t + k_g` less the spans'
//! share of `k_g`, `Σ_i (T_i − ρA v²) g_i²/L_i` (the geometric stiffness of the span
//! directions turning with the idler, `−ℓ × ∂F/∂θ` with `ℓ × n_i = g_i`): the boundary shapes
//! restore it exactly through `K_s`, so that at zero string mass the arm's row is the
//! rotational model's. What the arm sees from the spans — the moment of their transverse force
//! `T w'(end)` about the pivot (lever `g`) — is the coupling of `θ_a` with the sines in `M`,
//! `G` and `K_s` (weak form; Beikmann et al. (1996) eqs. for the arm). The pulleys couple to
//! the spans only through the arm (the linear theory: a pulley's rotation moves no span end
//! transversely).
//!
//! **Included**: the gyroscopic (Coriolis) terms of the travelling spans, the centrifugal
//! softening `−m v²`, the arm's inertia, spring and geometric stiffness, the whole rotational
//! model. **Not included**: damping, bending stiffness, the belt's mass on the wraps,
//! nonlinear (tension-fluctuation) coupling of transverse and longitudinal motion.
//!
//! # Eigen solution
//!
//! The gyroscopic system `M q̈ + G q̇ + K q = 0` (`M`, `K` symmetric positive definite, `G`
//! skew) in first-order form (Meirovitch 1974) `A ẋ + B x = 0`, `x = [q̇; q]`,
//! `A = diag(M, K)`, `B = [[G, K], [−K, 0]]`; with `A = L Lᵀ` (Cholesky) and `z = Lᵀ x`,
//! `ż = −S z` where `S = L⁻¹ B L⁻ᵀ` is real skew-symmetric. Its eigenvalues are `±iω`, so the
//! symmetric positive semi-definite `SᵀS = −S²` has each `ω²` twice; it is solved by the
//! workspace's dense symmetric eigen solver ([`fe_model::dense_modes`]) with the identity as
//! mass. A mode's two real vectors `y` and `S y/ω` are the real and imaginary parts of its
//! complex shape; their displacement parts give each part's share of the modal kinetic energy
//! (`J φ²` for a rotational coordinate, `∫ m w² dx` for a span, its moving end included).

use super::modes::RotationalModel;
use super::statics::SteadyState;
use belt::Drive;
use faer::linalg::triangular_solve::{
    solve_lower_triangular_in_place, solve_upper_triangular_in_place,
};
use faer::{Mat, Par, Side};
use serde::Serialize;

/// Most sine terms per span.
pub const MAX_SPAN_TERMS: usize = 64;

/// Options of the coupled model.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CoupledOptions {
    /// Sine terms per span `N`.
    pub terms: usize,
    /// Hold the tensioner arm (`θ_a = 0`: every span on fixed ends, the arm's coordinate
    /// removed): the limit of an infinitely stiff arm.
    pub hold_arm: bool,
}

impl Default for CoupledOptions {
    /// 16 terms per span, the arm free.
    fn default() -> Self {
        Self {
            terms: 16,
            hold_arm: false,
        }
    }
}

/// One span's block of the coupled model.
#[derive(Debug, Clone)]
struct SpanBlock {
    /// Global index of every local coordinate (`[θ_a, a_1..a_N]`; `None` where a coordinate
    /// is absent: a span on fixed ends has no arm coordinate).
    dofs: Vec<Option<usize>>,
    /// Local mass matrix `m∫NNᵀ` \[kg\] (displacement energy `∫ m w² dx`).
    mass: Mat<f64>,
}

/// The linearised hybrid model of the drive (module documentation).
#[derive(Debug, Clone)]
pub struct CoupledModel {
    /// Name of every part: the rotational coordinates, then `"span a → b"` for every span.
    pub parts: Vec<String>,
    /// Mass `M` \[SI per coordinate\].
    pub mass: Mat<f64>,
    /// Gyroscopic matrix `G` (skew).
    pub gyroscopic: Mat<f64>,
    /// Stiffness `K`.
    pub stiffness: Mat<f64>,
    /// Number of rotational coordinates (the first of `M`, `G`, `K`).
    rotational: usize,
    /// Rotational mass `J_i` of every rotational coordinate.
    inertia: Vec<f64>,
    /// Span blocks.
    spans: Vec<SpanBlock>,
}

/// One coupled mode.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct CoupledMode {
    /// Natural frequency \[Hz\].
    pub frequency_hz: f64,
    /// The part with the largest share of the modal kinetic energy (a rotational coordinate
    /// such as `"tensioner arm"`, or `"span a → b"`).
    pub dominant: String,
    /// Share of the modal kinetic energy of every part (sums to 1), in the order of
    /// [`CoupledModel::parts`].
    pub energy_share: Vec<f64>,
}

/// Build the coupled model of `drive` about the steady state `s` with the rotational model
/// `rot` (module documentation).
pub fn coupled_model(
    drive: &Drive, s: &SteadyState, rot: &RotationalModel, options: &CoupledOptions,
) -> CoupledModel {
    coupled_model_with(drive, s, rot, options, drive.belt().mass_per_length)
}

/// [`coupled_model`] with the spans' transverse mass per length `rho` \[kg/m\] (the belt's
/// `ρA` in [`coupled_model`]; the statics, hence `T_i` and `ρA v²`, keep the belt's).
pub(crate) fn coupled_model_with(
    drive: &Drive, s: &SteadyState, rot: &RotationalModel, options: &CoupledOptions, rho: f64,
) -> CoupledModel {
    let names = drive.names();
    let nt = options.terms.max(1);
    let v = s.loading.belt_speed;
    let tc = s.centrifugal;
    // rotational coordinates kept
    let arm_dof = rot.names.iter().position(|x| x == "tensioner arm");
    let keep: Vec<usize> = (0..rot.names.len())
        .filter(|&i| !(options.hold_arm && Some(i) == arm_dof))
        .collect();
    let nr = keep.len();
    let arm = if options.hold_arm {
        None
    } else {
        arm_dof.map(|a| keep.iter().position(|&i| i == a).unwrap_or(a))
    };
    let ns = s.geometry.spans.len();
    let n = nr + ns * nt;
    let mut mass = Mat::<f64>::zeros(n, n);
    let mut gyro = Mat::<f64>::zeros(n, n);
    let mut stiff = Mat::<f64>::zeros(n, n);
    for (r, &i) in keep.iter().enumerate() {
        for (c, &j) in keep.iter().enumerate() {
            mass[(r, c)] = rot.mass[(i, j)];
            stiff[(r, c)] = rot.stiffness[(i, j)];
        }
    }
    let inertia: Vec<f64> = (0..nr).map(|r| mass[(r, r)]).collect();
    // the idler's centre velocity per arm rate c'(θ)
    let idler = drive
        .arm()
        .zip(s.arm_angle)
        .map(|(a, th)| (a.tensioner.pulley, a.tensioner.center(a.length, th).1));
    let mut parts: Vec<String> = keep.iter().map(|&i| rot.names[i].clone()).collect();
    let mut spans = Vec::with_capacity(ns);
    // Gauss–Legendre rule on sub-intervals: exact for the trigonometric products up to
    // 2N half-waves to round-off
    let (gx, gw) = gauss_legendre_5();
    let intervals = 4 * nt + 8;
    for (si, sp) in s.geometry.spans.iter().enumerate() {
        parts.push(format!("span {} → {}", names[sp.from], names[sp.to]));
        let l = sp.length;
        let t = s.tensions[sp.from];
        let normal = [-sp.direction[1], sp.direction[0]];
        let g = |k: usize| -> f64 {
            match idler {
                Some((p, c)) if p == k => c[0] * normal[0] + c[1] * normal[1],
                _ => 0.0,
            }
        };
        let (g0, g1) = if arm.is_some() {
            (g(sp.from), g(sp.to))
        } else {
            (0.0, 0.0)
        };
        let moving = g0 != 0.0 || g1 != 0.0;
        let mut dofs: Vec<Option<usize>> = vec![arm.filter(|_| moving)];
        dofs.extend((0..nt).map(|k| Some(nr + si * nt + k)));
        let nl = nt + 1;
        let mut ml = Mat::<f64>::zeros(nl, nl);
        let mut bl = Mat::<f64>::zeros(nl, nl);
        let mut kl = Mat::<f64>::zeros(nl, nl);
        let h = l / intervals as f64;
        let mut shape = vec![0.0; nl];
        let mut slope = vec![0.0; nl];
        for e in 0..intervals {
            for (xi, wi) in gx.iter().zip(&gw) {
                let x = h * (e as f64 + 0.5 * (1.0 + xi));
                let w = 0.5 * h * wi;
                let u = x / l;
                shape[0] = g0 * (1.0 - u) + g1 * u;
                slope[0] = (g1 - g0) / l;
                for k in 1..=nt {
                    let a = k as f64 * std::f64::consts::PI / l;
                    let (sn, cs) = (a * x).sin_cos();
                    shape[k] = sn;
                    slope[k] = a * cs;
                }
                for r in 0..nl {
                    for c in 0..nl {
                        ml[(r, c)] += w * rho * shape[r] * shape[c];
                        bl[(r, c)] += w * rho * v * shape[r] * slope[c];
                        kl[(r, c)] += w * (t - rho * v * v) * slope[r] * slope[c];
                    }
                }
            }
        }
        // the span's share of the arm's geometric stiffness, restored by K_s (module
        // documentation)
        if let Some(a) = arm.filter(|_| moving) {
            stiff[(a, a)] -= (t - tc) * (g1 - g0) * (g1 - g0) / l;
        }
        for r in 0..nl {
            let Some(gr) = dofs[r] else { continue };
            for c in 0..nl {
                let Some(gc) = dofs[c] else { continue };
                mass[(gr, gc)] += ml[(r, c)];
                gyro[(gr, gc)] += bl[(r, c)] - bl[(c, r)];
                stiff[(gr, gc)] += kl[(r, c)];
            }
        }
        spans.push(SpanBlock { dofs, mass: ml });
    }
    CoupledModel {
        parts,
        mass,
        gyroscopic: gyro,
        stiffness: stiff,
        rotational: nr,
        inertia,
        spans,
    }
}

/// Five-point Gauss–Legendre abscissae and weights on `[−1, 1]`.
fn gauss_legendre_5() -> ([f64; 5], [f64; 5]) {
    let a = (5.0 - 2.0 * (10.0f64 / 7.0).sqrt()).sqrt() / 3.0;
    let b = (5.0 + 2.0 * (10.0f64 / 7.0).sqrt()).sqrt() / 3.0;
    let wa = (322.0 + 13.0 * 70f64.sqrt()) / 900.0;
    let wb = (322.0 - 13.0 * 70f64.sqrt()) / 900.0;
    ([-b, -a, 0.0, a, b], [wb, wa, 128.0 / 225.0, wa, wb])
}

impl CoupledModel {
    /// Number of coordinates.
    pub fn dof(&self) -> usize {
        self.mass.nrows()
    }

    /// The `count` lowest modes, ascending (module documentation, eigen solution).
    ///
    /// # Errors
    /// [`fe_model::FeError`]: `M` or `K` not positive definite (an unstable operating point:
    /// an arm whose belt pull outweighs its spring, a span at or above its critical speed),
    /// non-finite entries.
    pub fn modes(&self, count: usize) -> Result<Vec<CoupledMode>, fe_model::FeError> {
        let n = self.dof();
        if n == 0 || count == 0 {
            return Ok(Vec::new());
        }
        let not_pd = |name: &str, e: String| fe_model::FeError::NotPositiveDefinite {
            name: name.into(),
            detail: format!(" ({e})"),
        };
        let lm = self
            .mass
            .llt(Side::Lower)
            .map_err(|e| not_pd("M", format!("{e:?}")))?;
        let lk = self
            .stiffness
            .llt(Side::Lower)
            .map_err(|e| not_pd("K", format!("{e:?}")))?;
        let (lm, lk) = (lm.L(), lk.L());
        // S11 = L_M⁻¹ G L_M⁻ᵀ, S12 = L_M⁻¹ L_K, S21 = −S12ᵀ, S22 = 0
        let mut s11 = self.gyroscopic.clone();
        solve_lower_triangular_in_place(lm, s11.as_mut(), Par::Seq);
        let mut s11 = s11.transpose().to_owned();
        solve_lower_triangular_in_place(lm, s11.as_mut(), Par::Seq);
        let s11 = s11.transpose().to_owned();
        let mut s12 = lk.to_owned();
        solve_lower_triangular_in_place(lm, s12.as_mut(), Par::Seq);
        let s = Mat::from_fn(2 * n, 2 * n, |i, j| match (i < n, j < n) {
            (true, true) => s11[(i, j)],
            (true, false) => s12[(i, j - n)],
            (false, true) => -s12[(j, i - n)],
            (false, false) => 0.0,
        });
        let h = s.transpose() * &s;
        let h = Mat::from_fn(2 * n, 2 * n, |i, j| 0.5 * (h[(i, j)] + h[(j, i)]));
        let eye = Mat::<f64>::identity(2 * n, 2 * n);
        let want = (2 * count).min(2 * n);
        let eig = fe_model::dense_modes(h.as_ref(), eye.as_ref(), want)?;
        let mut out = Vec::with_capacity(count);
        let mut c = 0;
        while c < eig.values.len() && out.len() < count {
            let omega = eig.values[c].max(0.0).sqrt();
            let y = eig.vectors.col(c).to_owned();
            let sy = &s * &y;
            let mut energy = vec![0.0; self.parts.len()];
            // ‖S y‖ = ω ‖y‖: both vectors scaled alike by 1/ω on the second
            let inv = 1.0 / omega.max(f64::MIN_POSITIVE);
            for (vec, scale) in [(&y, 1.0), (&sy, inv)] {
                // x = L⁻ᵀ z: the displacement part q = L_K⁻ᵀ z_2
                let mut q = Mat::from_fn(n, 1, |i, _| vec[n + i]);
                solve_upper_triangular_in_place(lk.transpose(), q.as_mut(), Par::Seq);
                self.part_energy(&q, scale * scale, &mut energy);
            }
            let total: f64 = energy.iter().sum();
            let share: Vec<f64> = energy
                .iter()
                .map(|e| if total > 0.0 { e / total } else { 0.0 })
                .collect();
            let dom = (0..share.len())
                .max_by(|&a, &b| share[a].total_cmp(&share[b]))
                .unwrap_or(0);
            out.push(CoupledMode {
                frequency_hz: omega / (2.0 * std::f64::consts::PI),
                dominant: self.parts[dom].clone(),
                energy_share: share,
            });
            // each ω² is an eigenvalue twice (module documentation)
            c += 2;
        }
        Ok(out)
    }

    /// Add `weight ×` each part's displacement energy of the shape `q` to `energy`.
    fn part_energy(&self, q: &Mat<f64>, weight: f64, energy: &mut [f64]) {
        for r in 0..self.rotational {
            energy[r] += weight * self.inertia[r] * q[(r, 0)] * q[(r, 0)];
        }
        for (k, b) in self.spans.iter().enumerate() {
            let nl = b.dofs.len();
            let local: Vec<f64> = b
                .dofs
                .iter()
                .map(|d| d.map_or(0.0, |i| q[(i, 0)]))
                .collect();
            let mut e = 0.0;
            for r in 0..nl {
                for c in 0..nl {
                    e += local[r] * b.mass[(r, c)] * local[c];
                }
            }
            energy[self.rotational + k] += weight * e;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fead_design::{DesignConfig, modes::rotational_model, steady_state};
    use std::f64::consts::PI;

    fn default_at(rpm: f64) -> (Drive, SteadyState) {
        let drive = DesignConfig::default().drive.resolve().unwrap();
        let s = steady_state(&drive, rpm * PI / 30.0).unwrap();
        (drive, s)
    }

    fn span_modes(m: &[CoupledMode]) -> Vec<f64> {
        m.iter()
            .filter(|m| m.dominant.starts_with("span"))
            .map(|m| m.frequency_hz)
            .collect()
    }

    // (a) The arm held: every span is a travelling string on fixed ends, whose frequencies
    // are n (c² − v²)/(2 L c), c = √(T/ρA) (Wickert & Mote 1990; at rest nπ/L √(T/ρA)/(2π)).
    // The 14 lowest span-dominated coupled modes are the 14 lowest of these to 1e-3
    // (at rest the sines are the exact modes: measured 2e-15; at 3000 rpm the gyroscopic
    // coupling of the sines converges with the series: 16 terms, measured 4.0e-4 on the
    // highest of them).
    #[test]
    fn held_arm_gives_each_span_its_string_frequencies() {
        for rpm in [0.0, 3000.0] {
            let (drive, s) = default_at(rpm);
            let rot = rotational_model(&drive, &s);
            let opts = CoupledOptions {
                terms: 16,
                hold_arm: true,
            };
            let model = coupled_model(&drive, &s, &rot, &opts);
            let rho = drive.belt().mass_per_length;
            let v = s.loading.belt_speed;
            let mut exact: Vec<f64> = s
                .geometry
                .spans
                .iter()
                .flat_map(|sp| {
                    let c = (s.tensions[sp.from] / rho).sqrt();
                    (1..=8).map(move |n| n as f64 * (c * c - v * v) / (2.0 * sp.length * c))
                })
                .collect();
            exact.sort_by(f64::total_cmp);
            exact.truncate(14);
            let all = model.modes(model.dof()).unwrap();
            let mut got = span_modes(&all);
            got.truncate(14);
            assert_eq!(got.len(), exact.len(), "{rpm} rpm: {got:?} vs {exact:?}");
            let mut worst: f64 = 0.0;
            for (g, e) in got.iter().zip(&exact) {
                worst = worst.max((g / e - 1.0).abs());
                assert!((g / e - 1.0).abs() < 1e-3, "{rpm} rpm: {g} vs {e}");
            }
            eprintln!(
                "{rpm} rpm (v/c up to {:.3}): worst relative error {worst:.2e}",
                v / (s.tensions.iter().copied().fold(f64::INFINITY, f64::min) / rho).sqrt()
            );
        }
    }

    // (b) Massless spans: with the spans' transverse mass per length 1e-5 of the belt's, the
    // spans' modes go far up and the lowest coupled modes are the rotational model's (the
    // boundary shapes restore the arm's geometric stiffness exactly: module documentation),
    // the arm mode included, to 1e-3.
    #[test]
    fn massless_spans_give_the_rotational_modes() {
        let (drive, s) = default_at(0.0);
        let rot = rotational_model(&drive, &s);
        let rm = rot.modes().unwrap();
        let rho = 1e-5 * drive.belt().mass_per_length;
        let model = coupled_model_with(&drive, &s, &rot, &CoupledOptions::default(), rho);
        let cm = model.modes(rm.len()).unwrap();
        let a = rot.names.iter().position(|x| x == "tensioner arm").unwrap();
        assert!(rm.iter().any(|m| m.energy_share[a] > 0.2), "{rm:?}");
        for (a, b) in rm.iter().zip(&cm) {
            assert!(
                (b.frequency_hz / a.frequency_hz - 1.0).abs() < 1e-3,
                "{} {} vs {} {}",
                a.dominant,
                a.frequency_hz,
                b.dominant,
                b.frequency_hz
            );
            assert_eq!(a.dominant, b.dominant);
        }
    }

    // (c) Independent reference: the exact dynamic stiffness of the continuous strings at
    // rest. A string of tension T, length L, fixed at its far end and moved by g θ at the
    // idler, pulls on the arm with the moment −T g² β cot(βL) θ (β = ω/c; w = gθ sin βx/sin βL);
    // the coupled modes are the roots of det(K_r − Σ T g²/L e_a e_aᵀ − ω² M_r
    // + Σ T g² β cot(βL) e_a e_aᵀ) = 0 (multiplied by Π sin βL_i to remove the poles), and
    // the spans away from the idler keep their string frequencies. Every root below 400 Hz
    // is a coupled mode of the Galerkin model to 1e-3; 16 and 32 terms agree to 1e-3.
    #[test]
    fn coupled_modes_match_the_dynamic_stiffness_roots() {
        let (drive, s) = default_at(0.0);
        let rot = rotational_model(&drive, &s);
        let a = rot.names.iter().position(|x| x == "tensioner arm").unwrap();
        let rho = drive.belt().mass_per_length;
        let arm = drive.arm().unwrap();
        let k_idler = arm.tensioner.pulley;
        let c = arm.tensioner.center(arm.length, s.arm_angle.unwrap()).1;
        let mut adjacent = Vec::new();
        let mut others = Vec::new();
        for sp in &s.geometry.spans {
            let t = s.tensions[sp.from];
            if sp.from == k_idler || sp.to == k_idler {
                let g = -c[0] * sp.direction[1] + c[1] * sp.direction[0];
                adjacent.push((t, g, sp.length));
            } else {
                others.push((t, sp.length));
            }
        }
        assert_eq!(adjacent.len(), 2);
        let n = rot.names.len();
        let f = |hz: f64| -> f64 {
            let w = 2.0 * PI * hz;
            let mut d = 0.0;
            let mut prod = 1.0;
            for &(t, _, l) in &adjacent {
                prod *= (w / (t / rho).sqrt() * l).sin();
            }
            let mut m = Mat::from_fn(n, n, |i, j| {
                rot.stiffness[(i, j)] - w * w * rot.mass[(i, j)]
            });
            for &(t, g, l) in &adjacent {
                let beta = w / (t / rho).sqrt();
                m[(a, a)] -= t * g * g / l;
                d += t * g * g * beta * (beta * l).cos() / (beta * l).sin();
            }
            // det(A + D e eᵀ) = det A + D cof_aa (matrix determinant lemma)
            let det = m.determinant();
            let minor = Mat::from_fn(n - 1, n - 1, |i, j| {
                let (i, j) = (i + usize::from(i >= a), j + usize::from(j >= a));
                m[(i, j)]
            });
            (det + d * minor.determinant()) * prod
        };
        let fmax = 400.0;
        let mut roots = Vec::new();
        let steps = 80_000;
        let mut x0 = 1e-3;
        let mut f0 = f(x0);
        for i in 1..=steps {
            let x1 = fmax * i as f64 / steps as f64;
            let f1 = f(x1);
            if f0 * f1 < 0.0 {
                roots.push(mbd_core::roots::illinois(f, x0, x1, f0, f1, 1e-10));
            }
            (x0, f0) = (x1, f1);
        }
        for &(t, l) in &others {
            let c1 = (t / rho).sqrt() / (2.0 * l);
            let mut k = 1.0;
            while k * c1 < fmax {
                roots.push(k * c1);
                k += 1.0;
            }
        }
        roots.sort_by(f64::total_cmp);
        assert!(roots.len() >= 10, "{roots:?}");
        let model = coupled_model(&drive, &s, &rot, &CoupledOptions::default());
        let fine = coupled_model(
            &drive,
            &s,
            &rot,
            &CoupledOptions {
                terms: 32,
                hold_arm: false,
            },
        );
        let got: Vec<f64> = model
            .modes(model.dof())
            .unwrap()
            .into_iter()
            .map(|m| m.frequency_hz)
            .filter(|&x| x < fmax)
            .collect();
        let got_fine: Vec<f64> = fine
            .modes(roots.len())
            .unwrap()
            .into_iter()
            .map(|m| m.frequency_hz)
            .collect();
        assert_eq!(got.len(), roots.len(), "{got:?} vs {roots:?}");
        for ((g, r), h) in got.iter().zip(&roots).zip(&got_fine) {
            eprintln!("{g:.5} {h:.5} ref {r:.5}");
            assert!((g / r - 1.0).abs() < 1e-3, "{g} vs {r}");
            assert!((g / h - 1.0).abs() < 1e-3, "{g} vs {h}");
        }
    }

    // Convergence at speed (gyroscopic terms, 3000 rpm, v/c up to 0.41): the 12 lowest
    // coupled modes with 16 sine terms per span against 40 terms (a second discretisation of
    // the same model) to 1e-3; the arm takes part in at least one of them.
    #[test]
    fn coupled_modes_at_speed_converge_with_the_series() {
        let (drive, s) = default_at(3000.0);
        let rot = rotational_model(&drive, &s);
        let modes = |terms: usize| {
            let m = coupled_model(
                &drive,
                &s,
                &rot,
                &CoupledOptions {
                    terms,
                    hold_arm: false,
                },
            );
            m.modes(12).unwrap()
        };
        let (a, b) = (modes(16), modes(40));
        let arm = rot.names.iter().position(|x| x == "tensioner arm").unwrap();
        assert!(a.iter().any(|m| m.energy_share[arm] > 0.1), "{a:?}");
        for (x, y) in a.iter().zip(&b) {
            eprintln!("{:.4} {:.4} {}", x.frequency_hz, y.frequency_hz, x.dominant);
            assert!((x.frequency_hz / y.frequency_hz - 1.0).abs() < 1e-3);
        }
    }
}
