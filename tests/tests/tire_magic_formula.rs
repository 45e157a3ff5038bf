//! Magic Formula fit of the steady-state characteristics and its MF 6.1 `.tir` (issue 38 item
//! 3): round trip of synthetic curves, the fit of the coarse tire's steady sweep, and the
//! written coefficients evaluated with the MF 6.1 pure-slip equations.

use tire::magic_formula::{MfFit, TrailCurve, aligning_moment, fit_curve, fit_lateral};
use tire::tir::{TirTyre, parse_tir};
use tire::*;

use crate::common;
use common::{coarse_reduced_tire as tire, rig};

const FY: MfCurve = MfCurve {
    b: 8.0,
    c: 1.35,
    d: 3300.0,
    e: -0.6,
    sh: 0.004,
    sv: 25.0,
};
const TRAIL: TrailCurve = TrailCurve {
    b: 9.0,
    c: 1.2,
    d: 0.03,
    e: -1.5,
    sh: 0.002,
};
const FX: MfCurve = MfCurve {
    b: 12.0,
    c: 1.65,
    d: 3600.0,
    e: 0.2,
    sh: 0.001,
    sv: -40.0,
};

fn close(a: f64, b: f64, rel: f64, what: &str) {
    assert!(
        (a - b).abs() <= rel * b.abs().max(1e-3),
        "{what}: fitted {a} vs known {b}"
    );
}

/// Round trip (reference: the Magic Formula itself, Pacejka eq. 4.49 for F_y and F_x, eq. 4.E33
/// for the trail of M_z): curves synthesised from known coefficients at 15 slip angles in
/// ±15° and 15 κ in ±0.3 are fitted from the module's starting values; the coefficients are
/// recovered within 1e-5 relative and the curves within 1e-6 of their peak.
#[test]
fn magic_formula_fit_recovers_known_coefficients() {
    let alphas: Vec<f64> = (0..15)
        .map(|i| (-15.0 + 30.0 * i as f64 / 14.0_f64).to_radians())
        .collect();
    let pts: Vec<(f64, f64, f64)> = alphas
        .iter()
        .map(|&a| (a, FY.eval(a.tan()), aligning_moment(&FY, &TRAIL, a)))
        .collect();
    let l = fit_lateral(&pts).unwrap();
    println!("{l:?}");
    for (f, k, n) in [
        (l.fy.b, FY.b, "B"),
        (l.fy.c, FY.c, "C"),
        (l.fy.d, FY.d, "D"),
        (l.fy.e, FY.e, "E"),
        (l.fy.sh, FY.sh, "Sh"),
        (l.fy.sv, FY.sv, "Sv"),
        (l.trail.b.abs(), TRAIL.b, "Bt"),
        (l.trail.c, TRAIL.c, "Ct"),
        (l.trail.d, TRAIL.d, "Dt"),
        (l.trail.e, TRAIL.e, "Et"),
        (l.trail.sh, TRAIL.sh, "Sht"),
    ] {
        close(f, k, 1e-5, n);
    }
    assert!(l.fy_error.max_fraction < 1e-6 && l.mz_error.max_fraction < 1e-6);
    let kd: Vec<(f64, f64)> = (0..15)
        .map(|i| -0.3 + 0.6 * i as f64 / 14.0)
        .map(|k| (k, FX.eval(k)))
        .collect();
    let (x, e) = fit_curve("Fx(kappa)", &kd, magic_formula::C_LONGITUDINAL).unwrap();
    println!("{x:?} {e:?}");
    for (f, k, n) in [
        (x.b, FX.b, "Bx"),
        (x.c, FX.c, "Cx"),
        (x.d, FX.d, "Dx"),
        (x.e, FX.e, "Ex"),
        (x.sh, FX.sh, "Shx"),
        (x.sv, FX.sv, "Svx"),
    ] {
        close(f, k, 1e-5, n);
    }
    assert!(e.max_fraction < 1e-6);
    // a fit of well-shaped data inside its bounds warns of nothing
    let fit = MfFit {
        fz_n: 4448.2,
        lateral: l,
        longitudinal: Some(magic_formula::LongitudinalFit { fx: x, fx_error: e }),
    };
    assert!(magic_formula::fit_warnings(&fit).is_empty());
}

/// MF 6.1 pure-slip side force, aligning moment and longitudinal force at `F_z = FNOMIN`,
/// γ = 0, dp_i = 0, all λ = 1, from the coefficients of a parsed `.tir` (Pacejka 3rd ed.
/// §4.3.2, eqs. 4.E9–4.E18, 4.E19–4.E30, 4.E31–4.E44 with the load, camber and pressure terms
/// that are zero in the file dropped) — written out here from the book, apart from the mapping
/// of `tire::tir`.
fn mf61(c: &[(String, String, f64)], alpha: f64, kappa: f64) -> (f64, f64, f64) {
    let g = |n: &str| {
        c.iter()
            .find(|x| x.1 == n)
            .unwrap_or_else(|| panic!("{n}"))
            .2
    };
    let fz0 = g("FNOMIN");
    let fz = fz0;
    let r0 = g("UNLOADED_RADIUS");
    let a_s = alpha.tan();
    // lateral
    let cy = g("PCY1");
    let dy = g("PDY1") * fz;
    let kya = g("PKY1") * fz0 * (g("PKY4") * (fz / (g("PKY2") * fz0)).atan()).sin();
    let by = kya / (cy * dy);
    let ay = a_s + g("PHY1");
    let ey = g("PEY1");
    let fy =
        dy * (cy * (by * ay - ey * (by * ay - (by * ay).atan())).atan()).sin() + fz * g("PVY1");
    // aligning: t = Dt cos(Ct atan(Bt at − Et(Bt at − atan(Bt at)))) cos α, Mz = −t Fy
    let at = a_s + g("QHZ1");
    let bt = g("QBZ1");
    let dt = fz * (r0 / fz0) * g("QDZ1");
    let et = g("QEZ1");
    let t =
        dt * (g("QCZ1") * (bt * at - et * (bt * at - (bt * at).atan())).atan()).cos() * alpha.cos();
    // longitudinal
    let cx = g("PCX1");
    let dx = g("PDX1") * fz;
    let bx = fz * g("PKX1") / (cx * dx);
    let kx = kappa + g("PHX1");
    let ex = g("PEX1");
    let fx =
        dx * (cx * (bx * kx - ex * (bx * kx - (bx * kx).atan())).atan()).sin() + fz * g("PVX1");
    (fy, -t * fy, fx)
}

fn tyre() -> TirTyre {
    TirTyre {
        unloaded_radius: 0.35,
        width: 0.2,
        speed: 60.0 / 3.6,
        pressure: None,
        vertical_stiffness: None,
    }
}

/// The `.tir` of a fit, parsed back, evaluated with the MF 6.1 equations ([`mf61`], reference:
/// Pacejka 3rd ed. §4.3.2) in the file's TYDEX W-axis slip angle `α_W = −α` gives the fitted
/// curves to 1e-12 of their peak (the mapping of B, C, D, E, S_h, S_v onto PCY1, PDY1, PEY1,
/// PKY1, PHY1, PVY1, QBZ1 … and PCX1 … is exact), and the file's cornering stiffness has the
/// sign of every MF-Tyre parameter set, `PKY1 < 0`, for a tire whose side force rises with
/// Pacejka's α (as the simulated tire's does).
#[test]
fn tir_coefficients_reproduce_the_fit_through_the_mf61_equations() {
    let fit = MfFit {
        fz_n: 4448.2,
        lateral: fit_lateral(&[-12.0f64, -6.0, -2.0, 0.0, 1.0, 3.0, 8.0].map(|a| {
            let a = a.to_radians();
            (a, FY.eval(a.tan()), aligning_moment(&FY, &TRAIL, a))
        }))
        .unwrap(),
        longitudinal: Some(magic_formula::LongitudinalFit {
            fx: FX,
            fx_error: fit_curve(
                "Fx",
                &[-0.2, -0.05, 0.0, 0.02, 0.1].map(|k| (k, FX.eval(k))),
                1.65,
            )
            .unwrap()
            .1,
        }),
    };
    let text = write_tir(&fit, &tyre(), "test");
    assert!(text.contains("FITTYP                   = 61"));
    let c = parse_tir(&text);
    let pky1 = c.iter().find(|x| x.1 == "PKY1").unwrap().2;
    assert!(FY.stiffness() > 0.0 && pky1 < 0.0, "PKY1 = {pky1}");
    let l = &fit.lateral;
    for a in [-14.0f64, -5.0, -0.5, 0.0, 2.0, 9.0] {
        let ar = a.to_radians();
        for k in [-0.25, 0.0, 0.03] {
            let (fy, mz, fx) = mf61(&c, -ar, k);
            let (fy0, mz0, fx0) = (
                l.fy.eval(ar.tan()),
                aligning_moment(&l.fy, &l.trail, ar),
                FX.eval(k),
            );
            assert!(
                (fy - fy0).abs() < 1e-12 * l.fy_error.peak,
                "Fy {a}: {fy} {fy0}"
            );
            assert!(
                (mz - mz0).abs() < 1e-12 * l.mz_error.peak,
                "Mz {a}: {mz} {mz0}"
            );
            assert!((fx - fx0).abs() < 1e-12 * FX.d, "Fx {k}: {fx} {fx0}");
        }
    }
}

/// The fit of the coarse tire's lateral sweep (flat road, μ = 0.85, 60 km/h, 4448.2 N; slip
/// angles ±0.1°, ±0.2°, ±0.4°, ±1° with the free-rolling point: the range where this stiff tire
/// goes from adhesion to sliding, `tests/tire_steady.rs`) reproduces the simulated points
/// (reference: the simulation's own points, `run_steady`): F_y and M_z within 5 % of their peak
/// at every point (M_z changes sign near saturation, which the MF trail's cosine form follows);
/// without torque points there is no F_x fit; the `.tir` of it has FNOMIN = the load. The
/// longitudinal fit is checked on synthetic curves above: the torque points of this rig (a
/// drive torque on the wheel's inertia, not a prescribed spin) do not settle to an F_x(κ)
/// curve within a short point time.
#[test]
fn magic_formula_fit_reproduces_the_coarse_tire_sweep() {
    let red = tire();
    let cfg = SteadyStudyConfig {
        rig: rig(GroundKind::Road, false, 0.85),
        slip_angles_deg: vec![-1.0, -0.4, -0.2, -0.1, 0.1, 0.2, 0.4, 1.0],
        drive_torques_n_m: vec![],
        slip_ratios: vec![],
        point_time: 0.3,
        average_time: 0.05,
        ..Default::default()
    };
    let r = run_steady(red, &cfg, &mut |_| {}).unwrap();
    for p in std::iter::once(&r.free_rolling).chain(&r.slip) {
        println!(
            "alpha {:+.2} deg: Fy {:.1} N, Mz {:.3} N m",
            p.slip_angle_deg, p.loads.fy, p.loads.mz
        );
    }
    let fit = fit_steady(&r, cfg.rig.load).unwrap();
    println!("{fit:#?}");
    let l = &fit.lateral;
    assert!(l.fy_error.max_fraction < 0.05, "{:?}", l.fy_error);
    assert!(l.mz_error.max_fraction < 0.05, "{:?}", l.mz_error);
    assert!(fit.longitudinal.is_none());
    // this stiff tire rises more steeply than linearly at small α (0.1° → 0.2° more than
    // doubles F_y): the sine form needs C = 1 and a D beyond the data, and says so
    let w = magic_formula::fit_warnings(&fit);
    println!("{w:#?}");
    assert_eq!(
        w.iter().any(|m| m.contains("peak factor D")),
        l.fy.d > magic_formula::D_BEYOND_DATA * l.fy_error.peak
    );
    let c = parse_tir(&write_tir(&fit, &tyre(), "coarse"));
    let fnomin = c.iter().find(|x| x.1 == "FNOMIN").unwrap().2;
    assert_eq!(fnomin, cfg.rig.load);
    // the side force rises with Pacejka's α; in the file's W-axis convention PKY1 < 0
    let pky1 = c.iter().find(|x| x.1 == "PKY1").unwrap().2;
    assert!(l.fy.stiffness() > 0.0 && pky1 < 0.0, "PKY1 = {pky1}");
}
