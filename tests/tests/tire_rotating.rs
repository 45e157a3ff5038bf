//! Complex modes of the rotating tire in the ground frame (tire::rotating, issue 21):
//! zero-speed limit, the forward/backward split of the circumferential modes against thin-ring
//! theory, and the full (untruncated) flowing FE model against the reduced one.

use crate::common;

use common::coarse_reduced_tire;
use faer::Mat;
use flowing::derivative::{FlowLine, mode_shape_derivatives};
use std::f64::consts::PI;
use tire::*;

fn opts(spin: f64) -> RotatingOptions {
    RotatingOptions {
        spin,
        alpha: 0.0,
        beta: 0.0,
        max_hz: 400.0,
    }
}

#[test]
fn zero_speed_modes_are_the_rim_fixed_and_loaded_modes() {
    // Second formulation: at Ω = 0 the quadratic eigenproblem is K_z φ = ω² M_z φ, the
    // frequencies of `flowmbd-tire modes` (ReducedTire::frequencies_hz, free) and of
    // loaded_modes (patch held); with Rayleigh damping |λ| is the undamped frequency.
    let red = coarse_reduced_tire();
    let free = red.frequencies_hz().unwrap();
    let held = held_nodes(
        &preload(red, &GroundConfig::default(), 4448.2)
            .unwrap()
            .patch,
    );
    let loaded: Vec<f64> = loaded_modes(red, &held)
        .unwrap()
        .iter()
        .map(|m| m.hz)
        .collect();
    for (h, reference) in [(&[][..], &free), (&held[..], &loaded)] {
        for damped in [false, true] {
            let mut o = opts(0.0);
            if damped {
                (o.alpha, o.beta) = (10.0, 2e-5);
            }
            let modes = rotating_modes(red, h, &o).unwrap();
            assert!(modes.len() > 20);
            for (m, f) in modes.iter().zip(reference.iter()) {
                assert!(
                    (m.natural_hz - f).abs() < 1e-7 * f,
                    "held {}: {} vs {f} Hz",
                    h.len(),
                    m.natural_hz
                );
                assert_eq!(m.direction, WaveDirection::Standing);
                if !damped {
                    assert!(m.damping_ratio.abs() < 1e-8);
                }
            }
        }
    }
}

/// One forward/backward pair of order `n ≥ 2` below 200 Hz at one spin rate.
#[derive(Debug, Clone, Copy)]
struct Pair {
    n: usize,
    /// Whether the pair is out of plane (lateral part of the tread motion above one half).
    lateral: bool,
    forward_hz: f64,
    backward_hz: f64,
    /// Radial, tangential, lateral energy fractions of the forward mode's order n.
    parts: [f64; 3],
}

/// Pairs each forward mode with the backward mode of the same order and plane nearest in
/// frequency.
fn pairs(red: &ReducedTire, w: f64) -> Vec<Pair> {
    let modes = rotating_modes(red, &[], &opts(w)).unwrap();
    let lateral = |m: &RotatingMode| m.parts[2] > 0.5;
    let mut out = Vec::new();
    for f in modes
        .iter()
        .filter(|m| m.direction == WaveDirection::Forward && m.n >= 2 && m.hz < 200.0)
    {
        let b = modes
            .iter()
            .filter(|m| {
                m.direction == WaveDirection::Backward && m.n == f.n && lateral(m) == lateral(f)
            })
            .min_by(|a, b| (a.hz - f.hz).abs().total_cmp(&(b.hz - f.hz).abs()));
        if let Some(b) = b {
            out.push(Pair {
                n: f.n,
                lateral: lateral(f),
                forward_hz: f.hz,
                backward_hz: b.hz,
                parts: f.parts,
            });
        }
    }
    out
}

#[test]
fn forward_backward_split_grows_linearly_and_matches_thin_ring_theory() {
    // Analytical reference: a thin ring (radial w, tangential v) rotating at Ω. In the
    // co-rotating frame the Coriolis term splits the pair n by ±(2n/(n²+1))Ω (Bryan 1890;
    // Huang & Soedel, J. Sound Vib. 115 (1987) 253, inextensional modes w = −∂v/∂θ), and a
    // wave cos(nφ ∓ ωt) of the rotating frame, φ = θ − Ωt, is seen from the ground at ω ± nΩ.
    // The ground-frame split of the pair is therefore
    //     Δω = 2nΩ − 2·(2n/(n²+1))Ω = 2nΩ (n² − 1)/(n² + 1).
    // Derived directly in the Eulerian form (7.14)–(7.16): for the travelling wave
    // φ = (W e_r + iV e_θ + U ŷ) e^{inθ} the Rayleigh quotient of the gyroscopic term 2Ω T_,θ
    // (Cartesian derivative, ∂e_r/∂θ = e_θ, ∂e_θ/∂θ = −e_r) is Ω(n − 2VW/(W² + V² + U²)), so
    //     Δω = 2Ω (n − 2VW/(W² + V² + U²)),
    // the formula above for W = nV, U = 0, and 2nΩ for a purely lateral wave. The tire's T_,θ
    // is the central difference (A.1) on rings of N nodes, which differentiates e^{ikθ} to
    // iκ(k)e^{ikθ}, κ(k) = sin(kΔ)/Δ, Δ = 2π/N; the Cartesian parts of the wave hold the
    // harmonics n ± 1 (x = (i/2)[(V − W)e^{i(n+1)θ} + (V + W)e^{i(n−1)θ}], likewise z), so
    //     Δω/Ω = [κ(n+1)(W − V)² + κ(n−1)(W + V)² + 2κ(n)U²] / (W² + V² + U²),
    // which is the continuum form for κ(k) = k. The tire's modes are not exactly inextensional
    // rings: the test checks this form with W, V, U measured at the tread
    // (Harmonic::parts) within 4 % (the sidewalls, whose share of the modal mass moves
    // differently from the tread, make the rest), and the inextensional continuum ring for the
    // in-plane pairs within 10 %.
    let red = coarse_reduced_tire();
    let tread = red.tread.as_ref().unwrap();
    let ring0 = tread.ring.iter().filter(|&&r| r == 0).count();
    let delta = 2.0 * PI / ring0 as f64;
    let (w1, w2) = (4.0, 8.0);
    let p1 = pairs(red, w1);
    let p2 = pairs(red, w2);
    let (mut in_plane, mut lateral) = (0, 0);
    for a in &p1 {
        let Some(b) = p2.iter().find(|b| {
            b.n == a.n && b.lateral == a.lateral && (b.forward_hz - a.forward_hz).abs() < 5.0
        }) else {
            continue;
        };
        // pure radial-tangential or lateral shapes (modes near a veering mix both)
        if a.parts[2].max(a.parts[0] + a.parts[1]) < 0.8 {
            continue;
        }
        let s1 = 2.0 * PI * (a.forward_hz - a.backward_hz) / w1;
        let s2 = 2.0 * PI * (b.forward_hz - b.backward_hz) / w2;
        let n = a.n as f64;
        let ring = 2.0 * n * (n * n - 1.0) / (n * n + 1.0);
        let [pw, pv, pu] = a.parts;
        let (w, v) = (pw.sqrt(), pv.sqrt());
        let kappa = |k: f64| (k * delta).sin() / delta;
        let measured = kappa(n + 1.0) * (w - v).powi(2)
            + kappa(n - 1.0) * (w + v).powi(2)
            + 2.0 * kappa(n) * pu;
        println!(
            "n={} lateral={} f≈{:.1} Hz: split/Ω = {s1:.4} ({s2:.4} at 2Ω), ring {ring:.4}, \
             ring with the measured W, V, U {measured:.4} (parts {:.3?})",
            a.n,
            a.lateral,
            0.5 * (a.forward_hz + a.backward_hz),
            a.parts
        );
        // linear at low speed: the split per Ω is the same at Ω and 2Ω within 1 %
        assert!((s2 / s1 - 1.0).abs() < 0.01, "n={}: {s1} vs {s2}", a.n);
        assert!(
            (s1 / measured - 1.0).abs() < 0.04,
            "n={}: split/Ω {s1} vs {measured}",
            a.n
        );
        if a.lateral {
            lateral += 1;
        } else {
            assert!(
                (s1 / ring - 1.0).abs() < 0.10,
                "n={}: split/Ω {s1} vs {ring}",
                a.n
            );
            in_plane += 1;
        }
    }
    assert!(in_plane >= 3 && lateral >= 1, "{p1:?}");
}

#[test]
fn full_flowing_fe_model_and_untruncated_reduction_agree() {
    // Second formulation: the flowing-material equations written on the FE nodes themselves
    // (T = I on the non-rim DOFs: G₁ = M D₁, G₂ = M D₂, K₁ = K D₁ with the ring derivative
    // operators D of App. A) against the reduced tire with every free-node mode kept, whose
    // basis then spans all non-rim deflections (a congruence of the same pencil). Small mesh
    // (16 × 4 elements), spinning at 30 rad/s with Rayleigh damping (α, β) = (5 /s, 1e-5 s).
    let fe = generated_tire(&coarse_tire_config(16, 4, 45.0)).unwrap();
    let rcfg = ReductionConfig {
        contact_nodes: 5,
        free_modes: 100_000,
        ..Default::default()
    };
    let red = reduce(&fe, &rcfg).unwrap().0;
    let rim = fe.rim_mask();
    let dofs: Vec<usize> = (0..fe.n_dofs()).filter(|&d| !rim[d / 3]).collect();
    let nf = dofs.len();
    assert_eq!(red.n_z(), nf, "the reduction keeps every deflection");
    let sel = Mat::from_fn(fe.n_dofs(), nf, |i, j| f64::from(dofs[j] == i));
    let mut lines = Vec::new();
    for ring in fe.rings(rcfg.ring_tolerance).unwrap() {
        lines.extend(FlowLine::per_component(&ring.grid().unwrap(), &ring.nodes, 3).unwrap());
    }
    let der = mode_shape_derivatives(&lines, red.derivative, sel.as_ref()).unwrap();
    let kd = fe.stiffness.to_dense();
    let m = Mat::from_fn(nf, nf, |i, j| if i == j { fe.mass[dofs[i]] } else { 0.0 });
    let k = Mat::from_fn(nf, nf, |i, j| kd[(dofs[i], dofs[j])]);
    let g1 = Mat::from_fn(nf, nf, |i, j| fe.mass[dofs[i]] * der.d1[(dofs[i], j)]);
    let g2 = Mat::from_fn(nf, nf, |i, j| fe.mass[dofs[i]] * der.d2[(dofs[i], j)]);
    let kd1 = &kd * &der.d1;
    let k1 = Mat::from_fn(nf, nf, |i, j| kd1[(dofs[i], j)]);
    let tr = red.tread.as_ref().unwrap();
    let tread = TreadBasis {
        rows: Mat::from_fn(tr.rows.nrows(), nf, |r, j| {
            f64::from(dofs[j] == 3 * tr.nodes[r / 3] + r % 3)
        }),
        ..tr.clone()
    };
    let o = RotatingOptions {
        spin: 30.0,
        alpha: 5.0,
        beta: 1e-5,
        max_hz: 1e4,
    };
    let mats = FlowingMatrices {
        m: m.as_ref(),
        k: k.as_ref(),
        g1: g1.as_ref(),
        g2: g2.as_ref(),
        k1: k1.as_ref(),
    };
    let full = spinning_modes(mats, &tread, Mat::<f64>::zeros(0, nf).as_ref(), &o).unwrap();
    let reduced = rotating_modes(&red, &[], &o).unwrap();
    assert_eq!(full.len(), reduced.len());
    let mut travelling = 0;
    for (a, b) in full.iter().zip(&reduced).take(40) {
        assert!((a.hz - b.hz).abs() < 1e-7 * a.hz, "{} vs {} Hz", a.hz, b.hz);
        assert!((a.growth_rate - b.growth_rate).abs() < 1e-6 * a.natural_hz);
        assert_eq!((a.n, a.direction), (b.n, b.direction), "at {} Hz", a.hz);
        travelling += usize::from(a.direction != WaveDirection::Standing);
    }
    assert!(travelling > 10);
}

#[test]
fn line_participations_sum_to_the_direct_frequency_response() {
    // Second formulation: the modal expansion of tire::lines against a direct complex solve of
    // (−ω²M_y + iωC_y + K_y) Y = −Nᵀ(−ω²M + iωC_Ω + K_Ω) z_s, F = −K_r N Y, written here from
    // the reduced matrices (undamped, so every eigenvalue is an oscillating mode and the listed
    // contributions hold the whole sum). Rolling at 30 rad/s, vertical and longitudinal lines
    // at 70 Hz, patch held.
    use faer::c64;
    use faer::linalg::solvers::Solve;
    let red = coarse_reduced_tire();
    let held = held_nodes(
        &preload_rolling(red, &GroundConfig::default(), 4448.2, 30.0, 0.0)
            .unwrap()
            .patch,
    );
    let o = RotatingOptions {
        spin: 30.0,
        alpha: 0.0,
        beta: 0.0,
        max_hz: 1e5,
    };
    let nz = red.n_z();
    let a = Mat::from_fn(3 * held.len(), nz, |r, j| {
        red.tc[(3 * held[r / 3] + r % 3, j)]
    });
    let n = reduction::linalg::null_space(a.as_ref(), 1e-12).unwrap();
    let w = 2.0 * PI * 70.0;
    let c = Mat::from_fn(nz, nz, |i, j| 2.0 * o.spin * red.g1[(i, j)]);
    let k = Mat::from_fn(nz, nz, |i, j| {
        red.k[(i, j)] + o.spin.powi(2) * red.g2[(i, j)]
    });
    let dz = Mat::from_fn(nz, nz, |i, j| {
        c64::new(-w * w * red.m[(i, j)] + k[(i, j)], w * c[(i, j)])
    });
    let nc = Mat::from_fn(nz, n.ncols(), |i, j| c64::new(n[(i, j)], 0.0));
    let dy = nc.transpose() * &dz * &nc;
    // z_s: the held nodes moved rigidly by a unit vertical (col 0) or longitudinal (col 1)
    // displacement with the least strain energy, K z_s = Aᵀμ, A z_s = d
    let kinv_at = red
        .k
        .llt(faer::Side::Lower)
        .unwrap()
        .solve(a.transpose().to_owned());
    let flex = &a * &kinv_at;
    for (col, comp, row) in [
        (0, SpindleComponent::Vertical, 2),
        (1, SpindleComponent::Longitudinal, 0),
    ] {
        let d = Mat::from_fn(3 * held.len(), 1, |r, _| {
            f64::from(r % 3 == if col == 0 { 2 } else { 0 })
        });
        let mu = flex.llt(faer::Side::Lower).unwrap().solve(d);
        let zs = &kinv_at * &mu;
        let zsc = Mat::from_fn(nz, 1, |i, _| c64::new(zs[(i, 0)], 0.0));
        let f = -(nc.transpose() * &dz * &zsc);
        let y = dy.partial_piv_lu().solve(&f);
        let zy = &nc * &y;
        let mut direct = c64::new(0.0, 0.0);
        for j in 0..nz {
            direct -= zy[(j, 0)] * red.kr[(row, j)];
        }
        let modes = line_modes(red, &held, &o, comp, 70.0).unwrap();
        let sum = modes.iter().fold(c64::new(0.0, 0.0), |s, m| {
            s + c64::new(m.contribution[0], m.contribution[1])
        });
        assert!(
            (sum - direct).norm() < 1e-6 * direct.norm(),
            "{comp:?}: modal sum {sum:?} vs direct {direct:?}"
        );
        let shares: f64 = modes.iter().map(|m| m.share).sum();
        assert!((shares - 1.0).abs() < 1e-9);
    }
}
