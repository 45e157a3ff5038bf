//! Magic Formula fit of the pure-slip steady-state characteristics of one load (issue 38 item 3).
//!
//! From a [`SteadyResult`] (one vertical load, zero camber) this fits, by Levenberg–Marquardt
//! least squares ([`mbd_core::least_squares`]):
//!
//! - the side force with Pacejka's sine form (Pacejka, *Tire and Vehicle Dynamics*, 3rd ed.,
//!   eq. 4.49, and eq. 4.E19 of MF 6.1 §4.3.2):
//!   `F_y = D sin(C atan(B u − E(B u − atan(B u)))) + S_v`, `u = α* + S_h`, with
//!   `α* = tan α` (eq. 4.E3) \[N\];
//! - the aligning moment through the pneumatic trail (eqs. 4.E31–4.E33 with the residual moment
//!   `M_zr` left at zero): `M_z = −t F_y`, `t = D_t cos(C_t atan(B_t u_t − E_t(B_t u_t −
//!   atan(B_t u_t)))) cos α`, `u_t = α* + S_ht` \[m\], \[N·m\];
//! - the longitudinal force with the same sine form in `u = κ + S_h` (eq. 4.E9) \[N\], when the
//!   sweep has at least [`MIN_TORQUE_POINTS`] torque points.
//!
//! The free-rolling point (α = 0, κ = 0) is one of the data points of each curve. With few
//! points not all coefficients can be fitted: the coefficients are freed in the order listed in
//! [`FY_FREE_ORDER`] / [`TRAIL_FREE_ORDER`] up to one fewer than the number of points (at most
//! all); the others keep their starting values (`C = 1.3` lateral, `1.65` longitudinal, typical
//! values, Pacejka §4.3.2; `E = 0`, `S_h = 0`). `E` is kept ≤ 1 (the MF's condition, eq. 4.E24
//! and 4.E14) and the force curves' shape factor `C ≥ 1` (below 1 the sine form never reaches
//! its peak `D`, and a fit can trade `C → 0` for an unbounded `D`: data that rise more steeply
//! than linearly near zero slip do that): a fit outside a bound is repeated with that
//! coefficient held at the bound.

use crate::steady::SteadyResult;
use mbd_core::least_squares::{LeastSquares, LmSettings, levenberg_marquardt};
use serde::Serialize;

/// Least number of torque and prescribed-spin points for the `F_x(κ)` fit (with the free-rolling point, four points
/// for at least three coefficients).
pub const MIN_TORQUE_POINTS: usize = 3;
/// Least number of slip-angle points for the `F_y(α)`, `M_z(α)` fits.
pub const MIN_SLIP_POINTS: usize = 3;

/// Typical shape factor of the side force (Pacejka §4.3.2: `C_y ≈ 1.3`), the starting value.
pub const C_LATERAL: f64 = 1.3;
/// Typical shape factor of the longitudinal force (Pacejka §4.3.2: `C_x ≈ 1.65`).
pub const C_LONGITUDINAL: f64 = 1.65;

/// Order in which the force curve's coefficients `[B, C, D, E, S_h, S_v]` (indices) are freed.
pub const FY_FREE_ORDER: [usize; 6] = [0, 2, 5, 1, 3, 4];
/// Order in which the trail's coefficients `[B_t, C_t, D_t, E_t, S_ht]` are freed.
pub const TRAIL_FREE_ORDER: [usize; 5] = [2, 0, 1, 3, 4];

/// Errors of the fit.
#[derive(Debug, thiserror::Error, PartialEq)]
pub enum MfFitError {
    /// Too few points for a curve.
    #[error("magic formula fit of {curve}: {points} points in `{field}`, need at least {needed}")]
    TooFewPoints {
        /// The curve (`Fy(alpha)`, `Fx(kappa)`).
        curve: &'static str,
        /// The sweep field of the steady study config supplying the points.
        field: &'static str,
        /// Points given.
        points: usize,
        /// Points needed.
        needed: usize,
    },
    /// A data value is not finite.
    #[error("magic formula fit of {curve}: non-finite data point")]
    NonFinite {
        /// The curve.
        curve: &'static str,
    },
    /// The least-squares solver failed.
    #[error("magic formula fit of {curve} failed: {reason}")]
    Solver {
        /// The curve.
        curve: &'static str,
        /// The solver's termination reason.
        reason: String,
    },
}

/// One sine-form Magic Formula curve (Pacejka eq. 4.49):
/// `y = D sin(C atan(B u − E(B u − atan(B u)))) + S_v`, `u = x + S_h`.
/// Units: `x` \[-\] (`tan α` or κ), `D`, `S_v` \[N\], `B` \[-\], `C`, `E`, `S_h` \[-\].
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct MfCurve {
    /// Stiffness factor `B` \[-\].
    pub b: f64,
    /// Shape factor `C` \[-\].
    pub c: f64,
    /// Peak factor `D` \[N\].
    pub d: f64,
    /// Curvature factor `E` \[-\].
    pub e: f64,
    /// Horizontal shift `S_h` \[-\].
    pub sh: f64,
    /// Vertical shift `S_v` \[N\].
    pub sv: f64,
}

impl MfCurve {
    /// From the fitted parameters `[B, C, D, E, S_h, S_v]` (at least six).
    fn from_params(p: &[f64]) -> Self {
        let &[b, c, d, e, sh, sv, ..] = p else {
            unreachable!("the fit has six parameters")
        };
        Self { b, c, d, e, sh, sv }
    }
    /// `y(x)` (Pacejka eq. 4.49) \[N\].
    pub fn eval(&self, x: f64) -> f64 {
        self.d * shape_angle(self.b, self.c, self.e, x + self.sh).sin() + self.sv
    }
    /// Slope at `u = 0`, `K = B C D` (Pacejka eq. 4.50) \[N\] per unit `x`.
    pub fn stiffness(&self) -> f64 {
        self.b * self.c * self.d
    }
}

/// The argument of the Magic Formula's sine (eq. 4.49) and of the trail's cosine (eq. 4.E33),
/// `C atan(B u − E(B u − atan(B u)))` \[rad\].
fn shape_angle(b: f64, c: f64, e: f64, u: f64) -> f64 {
    let bu = b * u;
    c * (bu - e * (bu - bu.atan())).atan()
}

/// Pneumatic trail curve (Pacejka eq. 4.E33 without the `cos'α` factor):
/// `t = D_t cos(C_t atan(B_t u − E_t(B_t u − atan(B_t u))))`, `u = tan α + S_ht`.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct TrailCurve {
    /// `B_t` \[-\].
    pub b: f64,
    /// `C_t` \[-\].
    pub c: f64,
    /// Trail at `u = 0`, `D_t` \[m\].
    pub d: f64,
    /// `E_t` \[-\].
    pub e: f64,
    /// `S_ht` \[-\].
    pub sh: f64,
}

impl TrailCurve {
    /// From the fitted parameters `[B_t, C_t, D_t, E_t, S_ht]` (at least five).
    fn from_params(p: &[f64]) -> Self {
        let &[b, c, d, e, sh, ..] = p else {
            unreachable!("the fit has five parameters")
        };
        Self { b, c, d, e, sh }
    }
    /// `t(x)` \[m\] at `x = tan α` (eq. 4.E33 without `cos'α`).
    pub fn eval(&self, x: f64) -> f64 {
        self.d * shape_angle(self.b, self.c, self.e, x + self.sh).cos()
    }
}

/// Aligning moment of the fit at slip angle `alpha` \[rad\]: `M_z = −t(tan α) cos α F_y(tan α)`
/// (eqs. 4.E31–4.E33 with `M_zr = 0`, `cos'α = cos α` at free rolling) \[N·m\].
pub fn aligning_moment(fy: &MfCurve, trail: &TrailCurve, alpha: f64) -> f64 {
    let x = alpha.tan();
    -trail.eval(x) * alpha.cos() * fy.eval(x)
}

/// Fit error of one curve.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct FitError {
    /// Root mean square of the residuals \[N\] or \[N·m\].
    pub rms: f64,
    /// Largest absolute residual \[N\] or \[N·m\].
    pub max: f64,
    /// Largest absolute data value (the peak) \[N\] or \[N·m\].
    pub peak: f64,
    /// `rms / peak` \[-\].
    pub rms_fraction: f64,
    /// `max / peak` \[-\].
    pub max_fraction: f64,
    /// Data points.
    pub points: usize,
    /// Coefficients fitted (the others held).
    pub free_coefficients: usize,
}

impl FitError {
    fn new(data: &[(f64, f64)], model: impl Fn(f64) -> f64, free: usize) -> Self {
        let r: Vec<f64> = data.iter().map(|(x, y)| model(*x) - y).collect();
        let rms = (r.iter().map(|v| v * v).sum::<f64>() / r.len() as f64).sqrt();
        let max = r.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        let peak = data.iter().fold(0.0f64, |m, p| m.max(p.1.abs()));
        Self {
            rms,
            max,
            peak,
            rms_fraction: rms / peak,
            max_fraction: max / peak,
            points: data.len(),
            free_coefficients: free,
        }
    }
}

/// Lateral fit: `F_y(α)` and the trail of `M_z(α)`.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct LateralFit {
    /// `F_y(tan α)` \[N\].
    pub fy: MfCurve,
    /// Fit error of `F_y` \[N\].
    pub fy_error: FitError,
    /// The pneumatic trail \[m\].
    pub trail: TrailCurve,
    /// Fit error of `M_z` \[N·m\].
    pub mz_error: FitError,
}

/// Longitudinal fit `F_x(κ)`.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct LongitudinalFit {
    /// `F_x(κ)` \[N\].
    pub fx: MfCurve,
    /// Fit error \[N\].
    pub fx_error: FitError,
}

/// The Magic Formula fit of a steady result at its one load.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct MfFit {
    /// Vertical load of the fit (the study's load, `FNOMIN` of the `.tir`) \[N\].
    pub fz_n: f64,
    /// `F_y(α)`, `M_z(α)`.
    pub lateral: LateralFit,
    /// `F_x(κ)`, `None` with fewer than [`MIN_TORQUE_POINTS`] torque points.
    pub longitudinal: Option<LongitudinalFit>,
}

/// The least-squares problem: residuals `model(p, x_i) − y_i` over the free coefficients
/// (the others held at `p`).
struct Problem<'a> {
    data: &'a [(f64, f64)],
    model: &'a dyn Fn(&[f64], f64) -> f64,
    p: Vec<f64>,
    free: Vec<usize>,
}

impl LeastSquares for Problem<'_> {
    fn residual_count(&self) -> usize {
        self.data.len()
    }

    fn residuals(&self, x: &[f64], r: &mut [f64]) {
        let mut p = self.p.clone();
        for (k, &i) in self.free.iter().enumerate() {
            p[i] = x[k];
        }
        for (ri, (xi, yi)) in r.iter_mut().zip(self.data) {
            *ri = (self.model)(&p, *xi) - yi;
        }
    }
}

/// Least-squares fit of `model(p, x)` to `data` over the coefficients `free` (indices into
/// `p0`), starting from `p0`; returns all coefficients.
fn least_squares(
    curve: &'static str, data: &[(f64, f64)], model: &dyn Fn(&[f64], f64) -> f64, p0: &[f64],
    free: &[usize],
) -> Result<Vec<f64>, MfFitError> {
    let problem = Problem {
        data,
        model,
        p: p0.to_vec(),
        free: free.to_vec(),
    };
    let x0: Vec<f64> = free.iter().map(|&i| p0[i]).collect();
    let fit = levenberg_marquardt(&problem, &x0, &LmSettings::default()).map_err(|e| {
        MfFitError::Solver {
            curve,
            reason: e.to_string(),
        }
    })?;
    let mut p = p0.to_vec();
    for (k, &i) in free.iter().enumerate() {
        p[i] = fit.p[k];
    }
    if p.iter().any(|v| !v.is_finite()) || !fit.cost.is_finite() {
        return Err(MfFitError::Solver {
            curve,
            reason: format!(
                "non-finite coefficients after {} iterations",
                fit.iterations
            ),
        });
    }
    Ok(p)
}

/// Fit with bounds `(index, lower, upper)` on free coefficients: each coefficient the free fit
/// puts outside its bound is held at the bound and the others refitted, until none is outside
/// (at most once per bound). Returns the coefficients and the number fitted.
fn fit_bounded(
    curve: &'static str, data: &[(f64, f64)], model: &dyn Fn(&[f64], f64) -> f64, p0: &[f64],
    free: &[usize], bounds: &[(usize, f64, f64)],
) -> Result<(Vec<f64>, usize), MfFitError> {
    let mut start = p0.to_vec();
    let mut free = free.to_vec();
    loop {
        let p = least_squares(curve, data, model, &start, &free)?;
        let outside: Vec<(usize, f64)> = bounds
            .iter()
            .filter(|(i, _, _)| free.contains(i))
            .filter_map(|&(i, lo, hi)| {
                (p[i] < lo)
                    .then_some((i, lo))
                    .or((p[i] > hi).then_some((i, hi)))
            })
            .collect();
        if outside.is_empty() || free.len() <= outside.len() {
            return Ok((p, free.len()));
        }
        start = p;
        for (i, v) in outside {
            start[i] = v;
            free.retain(|&k| k != i);
        }
    }
}

/// Least-squares line `y = a + k x` through the `n` points of smallest `|x|` → `(a, k)`.
fn initial_line(data: &[(f64, f64)], n: usize) -> (f64, f64) {
    let mut d = data.to_vec();
    d.sort_by(|a, b| a.0.abs().total_cmp(&b.0.abs()));
    let d = &d[..n.min(d.len())];
    let m = d.len() as f64;
    let (sx, sy) = d.iter().fold((0.0, 0.0), |s, p| (s.0 + p.0, s.1 + p.1));
    let (mx, my) = (sx / m, sy / m);
    let sxx: f64 = d.iter().map(|p| (p.0 - mx).powi(2)).sum();
    let sxy: f64 = d.iter().map(|p| (p.0 - mx) * (p.1 - my)).sum();
    let k = if sxx > 0.0 { sxy / sxx } else { 0.0 };
    (my - k * mx, k)
}

fn mf_model(p: &[f64], x: f64) -> f64 {
    MfCurve::from_params(p).eval(x)
}

/// Fit the sine-form curve `y(x)` to `data` (`x` \[-\], `y` \[N\]) with the starting shape factor
/// `c0`; coefficients freed in [`FY_FREE_ORDER`] up to `min(6, points − 1)`.
pub fn fit_curve(
    curve: &'static str, data: &[(f64, f64)], c0: f64,
) -> Result<(MfCurve, FitError), MfFitError> {
    if data.iter().any(|p| !p.0.is_finite() || !p.1.is_finite()) {
        return Err(MfFitError::NonFinite { curve });
    }
    let (sv0, k0) = initial_line(data, 3);
    let d0 = 1.1 * data.iter().fold(0.0f64, |m, p| m.max((p.1 - sv0).abs()));
    let d0 = if d0 > 0.0 { d0 } else { 1.0 };
    let p0 = [k0 / (c0 * d0), c0, d0, 0.0, 0.0, sv0];
    let nfree = (data.len() - 1).clamp(1, 6);
    let free = &FY_FREE_ORDER[..nfree];
    // C ≥ 1 (index 1), E ≤ 1 (index 3): module documentation
    let bounds = [(1, 1.0, f64::INFINITY), (3, f64::NEG_INFINITY, 1.0)];
    let (p, nf) = fit_bounded(curve, data, &mf_model, &p0, free, &bounds)?;
    let c = MfCurve::from_params(&p);
    let err = FitError::new(data, |x| c.eval(x), nf);
    Ok((c, err))
}

/// Fit `F_y(α)` and `M_z(α)` to the points `(α [rad], F_y [N], M_z [N·m])`
/// ([module docs](self)): first `F_y` over `tan α`, then the trail with that `F_y` held.
pub fn fit_lateral(points: &[(f64, f64, f64)]) -> Result<LateralFit, MfFitError> {
    let fy_data: Vec<(f64, f64)> = points.iter().map(|p| (p.0.tan(), p.1)).collect();
    let (fy, fy_error) = fit_curve("Fy(alpha)", &fy_data, C_LATERAL)?;
    if points.iter().any(|p| !p.2.is_finite()) {
        return Err(MfFitError::NonFinite { curve: "Mz(alpha)" });
    }
    // data in α [rad] → M_z; model −t(tan α) cos α F_y(tan α)
    let mz_data: Vec<(f64, f64)> = points.iter().map(|p| (p.0, p.2)).collect();
    let model = move |q: &[f64], a: f64| aligning_moment(&fy, &TrailCurve::from_params(q), a);
    // start: the largest trail −M_z/F_y among the points with |F_y| above a tenth of its peak
    let peak = fy_error.peak;
    let t0 = points
        .iter()
        .filter(|p| p.1.abs() > 0.1 * peak)
        .map(|p| -p.2 / (p.1 * p.0.cos()))
        .fold(f64::NAN, f64::max);
    let t0 = if t0.is_finite() && t0 != 0.0 {
        t0
    } else {
        0.01
    };
    let q0 = [10.0, 1.1, t0, 0.0, 0.0];
    let nfree = (points.len() - 1).clamp(1, 5);
    let free = &TRAIL_FREE_ORDER[..nfree];
    let (q, nf) = fit_bounded(
        "Mz(alpha)",
        &mz_data,
        &model,
        &q0,
        free,
        &[(3, f64::NEG_INFINITY, 1.0)],
    )?;
    let trail = TrailCurve::from_params(&q);
    let mz_error = FitError::new(&mz_data, |a| aligning_moment(&fy, &trail, a), nf);
    Ok(LateralFit {
        fy,
        fy_error,
        trail,
        mz_error,
    })
}

/// Fit a steady result at its one load `fz` \[N\] (recorded as [`MfFit::fz_n`]): the slip
/// points with the free-rolling point for `F_y`, `M_z`, the torque and prescribed-spin points
/// with it for `F_x(κ)` (skipped with fewer than [`MIN_TORQUE_POINTS`] of them together).
pub fn fit_steady(r: &SteadyResult, fz: f64) -> Result<MfFit, MfFitError> {
    if r.slip.len() < MIN_SLIP_POINTS {
        return Err(MfFitError::TooFewPoints {
            curve: "Fy(alpha)",
            field: "slip_angles_deg",
            points: r.slip.len(),
            needed: MIN_SLIP_POINTS,
        });
    }
    let lat: Vec<(f64, f64, f64)> = std::iter::once(&r.free_rolling)
        .chain(&r.slip)
        .map(|p| (p.slip_angle_deg.to_radians(), p.loads.fy, p.loads.mz))
        .collect();
    let lateral = fit_lateral(&lat)?;
    let longitudinal = if r.torque.len() + r.prescribed.len() >= MIN_TORQUE_POINTS {
        let d: Vec<(f64, f64)> = std::iter::once(&r.free_rolling)
            .chain(&r.torque)
            .chain(&r.prescribed)
            .map(|p| (p.kappa, p.loads.fx))
            .collect();
        let (fx, fx_error) = fit_curve("Fx(kappa)", &d, C_LONGITUDINAL)?;
        Some(LongitudinalFit { fx, fx_error })
    } else {
        None
    };
    Ok(MfFit {
        fz_n: fz,
        lateral,
        longitudinal,
    })
}

/// The fit in `summary.json` of `flowmbd-tire steady`: coefficients, errors, the `.tir` path,
/// and the fitted curves at the data points (for checks by other readers of the `.tir`).
#[derive(Debug, Clone, Serialize)]
pub struct MfSummary {
    /// The fit (coefficients and errors).
    pub fit: MfFit,
    /// Path of the written `.tir` (MF 6.1, [`crate::tir`]); `None` where none was written
    /// (the Python API; `tire::write_tir` gives its text).
    pub tir: Option<String>,
    /// Slip angles of the lateral data, the free-rolling point first \[deg\].
    pub slip_angle_deg: Vec<f64>,
    /// Fitted `F_y` at `slip_angle_deg` \[N\].
    pub fy_fit_n: Vec<f64>,
    /// Fitted `M_z` at `slip_angle_deg` \[N·m\].
    pub mz_fit_n_m: Vec<f64>,
    /// κ of the longitudinal data, the free-rolling point first \[-\] (empty without `F_x` fit).
    pub kappa: Vec<f64>,
    /// Fitted `F_x` at `kappa` \[N\].
    pub fx_fit_n: Vec<f64>,
    /// What limits the fit's use ([`fit_warnings`]); empty when nothing does.
    pub warnings: Vec<String>,
}

/// Peak factor `D` above this multiple of the largest data force is reported
/// ([`fit_warnings`]).
pub const D_BEYOND_DATA: f64 = 1.5;

/// What limits the use of `fit` beyond its data points: a peak factor `D` more than
/// [`D_BEYOND_DATA`] times the largest force of the data (the sweep does not reach the peak,
/// or the data are not shaped like the Magic Formula: the curve beyond the data is an
/// extrapolation), and a coefficient held at its bound (`C = 1`, `E = 1`: module
/// documentation).
pub fn fit_warnings(fit: &MfFit) -> Vec<String> {
    let mut w = Vec::new();
    let mut check = |name: &str, c: &MfCurve, e: &FitError| {
        if c.d.abs() > D_BEYOND_DATA * e.peak {
            w.push(format!(
                "{name}: the peak factor D = {:.4e} N is {:.2} times the largest force of the data \
                 ({:.4e} N): the sweep does not reach the peak or the data are not shaped like \
                 the Magic Formula; beyond the data the fit extrapolates",
                c.d,
                c.d.abs() / e.peak,
                e.peak
            ));
        }
        for (coef, v) in [("C", c.c), ("E", c.e)] {
            if v == 1.0 {
                w.push(format!(
                    "{name}: {coef} held at its bound 1 (the free fit left it; module \
                     tire::magic_formula)"
                ));
            }
        }
    };
    check("Fy(alpha)", &fit.lateral.fy, &fit.lateral.fy_error);
    if let Some(x) = &fit.longitudinal {
        check("Fx(kappa)", &x.fx, &x.fx_error);
    }
    if fit.lateral.trail.e == 1.0 {
        w.push("Mz(alpha): E_t held at its bound 1".into());
    }
    w
}

impl MfSummary {
    /// The summary of `fit` on the data of `r`, with the `.tir` written at `tir`.
    pub fn new(fit: &MfFit, r: &SteadyResult, tir: Option<String>) -> Self {
        let alpha: Vec<f64> = std::iter::once(&r.free_rolling)
            .chain(&r.slip)
            .map(|p| p.slip_angle_deg)
            .collect();
        let l = &fit.lateral;
        let (kappa, fx_fit_n) = match &fit.longitudinal {
            Some(x) => {
                let k: Vec<f64> = std::iter::once(&r.free_rolling)
                    .chain(&r.torque)
                    .chain(&r.prescribed)
                    .map(|p| p.kappa)
                    .collect();
                let f = k.iter().map(|&k| x.fx.eval(k)).collect();
                (k, f)
            }
            None => (vec![], vec![]),
        };
        Self {
            fit: *fit,
            tir,
            fy_fit_n: alpha
                .iter()
                .map(|a| l.fy.eval(a.to_radians().tan()))
                .collect(),
            mz_fit_n_m: alpha
                .iter()
                .map(|a| aligning_moment(&l.fy, &l.trail, a.to_radians()))
                .collect(),
            slip_angle_deg: alpha,
            kappa,
            fx_fit_n,
            warnings: fit_warnings(fit),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Reference: the curve's definition, Pacejka eq. 4.49 (`y(0) = D sin(0) + S_v`, slope
    /// `B C D` at `u = 0`, eq. 4.50).
    #[test]
    fn curve_value_and_slope_at_the_origin() {
        let c = MfCurve {
            b: 10.0,
            c: 1.3,
            d: 3000.0,
            e: -0.5,
            sh: 0.0,
            sv: 20.0,
        };
        assert_eq!(c.eval(0.0), 20.0);
        let h = 1e-7;
        let k = (c.eval(h) - c.eval(-h)) / (2.0 * h);
        assert!((k / c.stiffness() - 1.0).abs() < 1e-6);
    }
}
