//! Modes of the loaded tire (tire::loaded): the reduced tire with the preloaded patch
//! held, wheel fixed, and the effective spindle masses that single out its vertical in-plane
//! mode (issue 9: "the dominant vertical spindle frequency of the cleat response is a vertical
//! in-plane mode of the loaded tire").

use crate::common;

use common::{coarse_reduced_tire, rig};
use faer::prelude::*;
use faer::{Mat, Side};
use tire::*;

/// Contact nodes carrying the static preload on the drum.
fn held(red: &ReducedTire) -> Vec<usize> {
    held_nodes(
        &preload(red, &GroundConfig::default(), 4448.2)
            .unwrap()
            .patch,
    )
}

#[test]
fn nothing_held_gives_the_rim_fixed_frequencies() {
    // Second formulation: with no contact node held the loaded pencil is the reduced tire's
    // own (ReducedTire::frequencies_hz), and no ground motion reaches the spindle.
    let red = coarse_reduced_tire();
    let free = red.frequencies_hz().unwrap();
    let modes = loaded_modes(red, &[]).unwrap();
    assert_eq!(modes.len(), free.len());
    for (m, f) in modes.iter().zip(&free) {
        assert!((m.hz - f).abs() < 1e-8 * f, "{} vs {f} Hz", m.hz);
        assert_eq!(m.vertical_mass, 0.0);
    }
}

#[test]
fn holding_the_patch_stiffens_every_mode_within_the_interlacing_bounds() {
    // Invariant (Rayleigh's theorem on constraints): r independent constraints raise each
    // eigenvalue, ω_k ≤ ω̂_k ≤ ω_{k+r}.
    let red = coarse_reduced_tire();
    let held = held(red);
    assert!(!held.is_empty());
    let r = 3 * held.len();
    let free = red.frequencies_hz().unwrap();
    let modes = loaded_modes(red, &held).unwrap();
    assert_eq!(modes.len(), free.len() - r);
    for (k, m) in modes.iter().enumerate() {
        assert!(
            m.hz >= free[k] * (1.0 - 1e-9),
            "mode {k}: {} < {}",
            m.hz,
            free[k]
        );
        assert!(
            m.hz <= free[k + r] * (1.0 + 1e-9),
            "mode {k}: {} > {}",
            m.hz,
            free[k + r]
        );
    }
}

#[test]
fn effective_spindle_masses_sum_to_the_constrained_static_response() {
    // Second formulation without the eigenproblem: the modal sum Σ m_k equals
    // (K_r G M_z z_s)·e with G the constrained flexibility, computed by a direct constrained
    // solve w = K⁻¹b − K⁻¹Aᵀ(AK⁻¹Aᵀ)⁻¹AK⁻¹b, b = M_z z_s (module docs of tire::loaded).
    let red = coarse_reduced_tire();
    let held = held(red);
    let nz = red.n_z();
    let a = Mat::from_fn(3 * held.len(), nz, |r, j| {
        red.tc[(3 * held[r / 3] + r % 3, j)]
    });
    let k = red.k.llt(Side::Lower).unwrap();
    let x = k.solve(a.transpose().to_owned());
    let y = (&a * &x).llt(Side::Lower).unwrap();
    let modes = loaded_modes(red, &held).unwrap();
    for (comp, sum) in [
        (2, modes.iter().map(|m| m.vertical_mass).sum::<f64>()),
        (0, modes.iter().map(|m| m.longitudinal_mass).sum::<f64>()),
    ] {
        let d = Mat::from_fn(
            3 * held.len(),
            1,
            |r, _| if r % 3 == comp { 1.0 } else { 0.0 },
        );
        let zs = &x * y.solve(d);
        let b = &red.m * &zs;
        let kb = k.solve(&b);
        let w = &kb - &x * y.solve(&a * &kb);
        let direct = (&red.kr * &w)[(comp, 0)];
        println!("component {comp}: modal sum {sum} kg, direct {direct} kg");
        assert!(direct.abs() > 1e-3, "no spindle response: {direct}");
        assert!(
            (sum - direct).abs() < 1e-7 * direct.abs(),
            "modal sum {sum} vs direct {direct}"
        );
    }
}

#[test]
fn the_dominant_vertical_mode_is_in_plane_and_vertical() {
    // Symmetry invariant of the tire (symmetric about its mid-plane, patch held symmetrically):
    // the mode with the largest effective vertical mass loads the spindle only vertically.
    let red = coarse_reduced_tire();
    let modes = loaded_modes(red, &held(red)).unwrap();
    let v = dominant_vertical_mode(&modes).unwrap();
    let x = dominant_longitudinal_mode(&modes).unwrap();
    println!(
        "vertical mode {} Hz (share {}), longitudinal {} Hz",
        v.hz,
        v.vertical_share(),
        x.hz
    );
    assert!(v.vertical_share() > 0.999, "{:?}", v.spindle);
    assert!(x.spindle[0].powi(2) > 0.999 * (x.spindle.iter().map(|f| f * f).sum::<f64>()));
    assert!(v.vertical_mass.abs() > 10.0 * x.vertical_mass.abs());
}

#[test]
fn cleat_response_peaks_at_the_loaded_vertical_mode() {
    // Issue 9 validation on the coarse tire: the dominant vertical line of the cleat response
    // (60 km/h, drum, μ = 0.85) lies within two spectral bins of the loaded tire's vertical
    // in-plane mode, which the rig result carries.
    let red = coarse_reduced_tire();
    let mut rc = rig(GroundKind::Drum, true, 0.85);
    rc.settle_time = 0.2;
    rc.record_time = 0.3;
    let r = run_cleat(red, &rc, &mut |_| {}).unwrap();
    let (_, sy) = r.spectra();
    let (f_peak, amp) = sy.peak(10.0, 500.0).unwrap();
    let df = 1.0 / rc.record_time;
    let mode = r.loaded_vertical_mode.as_ref().unwrap();
    println!(
        "Fy peak {f_peak} Hz ({amp} N), loaded vertical mode {} Hz",
        mode.hz
    );
    assert!(
        (f_peak - mode.hz).abs() <= 2.0 * df,
        "peak {f_peak} Hz vs mode {} Hz",
        mode.hz
    );
}
