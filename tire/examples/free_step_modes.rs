//! Check of a modal (eigenbasis) free step for the full rolling tire (issue 37 item 2): the
//! figures that decide whether the contact-free part of the converged step can run as a
//! diagonal update in the eigenbasis of the step's linear map.
//!
//! Loads a saved reduced tire, starts the default rig (drum, 60 km/h, `symmetry = "off"`,
//! h = 0.05 ms, no impact sub-steps) and, in the modal coordinates the step runs in
//! (`M = I`, `K = Λ`), with the spin-dependent matrices at the start's spin rate θ̇:
//!
//! 1. forms the linear map `A` of one linearly implicit generalized-α step of the tire's `z`
//!    part without contact (zero predictor `z̈ₙ₊₁ = 0`, one Newton iteration with the
//!    consistent iteration matrix `S = β' I + γ' C_eff + K_eff`, state `[z; ż; z̈; a]`,
//!    4 n_z), its eigendecomposition `A = V D V⁻¹` (faer, one thread: CPU time) and
//!    `cond₂(V) = σ_max/σ_min`;
//!    The same on the scaled state `[z; h ż; h² z̈; h² a]` (a similarity transformation).
//! 2. the same for the first-order matrix `[0 I; −K_eff −C_eff]` (2 n_z);
//! 3. the singular values of `G₁` (is the lagged coupling `θ̈ₙ G₁ zₙ` of low rank?);
//! 4. runs the given number of rig steps and reports the largest size of the lagged
//!    coupling `θ̈ₙ G₁ zₙ` against the gyroscopic `2θ̇ G₁ żₙ` and the elastic `Λ zₙ` forces.
//!
//! Run: `cargo run --release -p tire --example free_step_modes -- <reduced tire file> [steps]`.

use faer::linalg::solvers::DenseSolveCore;
use faer::{Mat, Par};
use tire::rig::thread_cpu_s;
use tire::*;

fn norm(v: &[f64]) -> f64 {
    v.iter().map(|x| x * x).sum::<f64>().sqrt()
}

fn cond_and_time(a: &Mat<f64>, what: &str) {
    let c0 = thread_cpu_s().unwrap_or(f64::NAN);
    let eig = a.eigen().expect("eigendecomposition");
    let c1 = thread_cpu_s().unwrap_or(f64::NAN);
    let s = eig.U().singular_values().expect("svd of V");
    let c2 = thread_cpu_s().unwrap_or(f64::NAN);
    let (smax, smin) = (s[0], s[s.len() - 1]);
    let d = eig.S();
    let rho = (0..a.nrows()).map(|i| d[i].norm()).fold(0.0f64, f64::max);
    let mut mags: Vec<(f64, f64, f64)> = (0..a.nrows())
        .map(|i| (d[i].norm(), d[i].re, d[i].im))
        .collect();
    mags.sort_by(|x, y| y.0.total_cmp(&x.0));
    let re_max = (0..a.nrows()).map(|i| d[i].re).fold(f64::MIN, f64::max);
    let zeros = mags.iter().filter(|m| m.0 < 1e-12 * mags[0].0).count();
    println!(
        "{what}: largest |eigenvalues| {:?}; largest real part {re_max:.6e}; {zeros} below 1e-12 of the largest",
        &mags[..4]
    );
    println!(
        "{what}: n = {}, eigendecomposition {:.2} s CPU (one thread), cond2(V) = {:.3e} \
         (sigma {:.3e} .. {:.3e}; SVD {:.2} s), spectral radius {:.6}",
        a.nrows(),
        c1 - c0,
        smax / smin,
        smin,
        smax,
        c2 - c1,
        rho
    );
}

fn main() {
    faer::set_global_parallelism(Par::Seq);
    let mut args = std::env::args().skip(1);
    let file = args.next().expect("reduced tire file");
    let steps: usize = args.next().map_or(0, |s| s.parse().expect("steps"));
    let red = ReducedTire::load(std::path::Path::new(&file)).expect("reduced tire file");
    let mut cfg = RigConfig::default();
    cfg.rolling.time_step = 5e-5;
    cfg.impact.substeps = 1;
    cfg.rolling.threads = 1;
    cfg.rolling.symmetry = Symmetry::Off;
    let mut start = start_rolling(&red, &cfg).expect("start");
    let sim = &mut start.sim;
    let m = sim.reduced().clone();
    let nz = m.n_z();
    let (alpha, beta) = (sim.alpha, sim.beta);
    let w = sim.state.theta_d;
    let h = cfg.rolling.time_step;
    let (am, af, nb, ng) = cfg.rolling.alpha_config().alpha_coefficients();
    let bp = (1.0 - am) / (h * h * nb * (1.0 - af));
    let gp = ng / (h * nb);
    println!(
        "n_z {nz}, spin {w:.4} rad/s, alpha {alpha:.4e} 1/s, beta {beta:.4e} s, h {h:e} s, \
         (am, af, beta, gamma) = ({am}, {af}, {nb}, {ng})"
    );
    let lam: Vec<f64> = (0..nz).map(|i| m.k[(i, i)]).collect();
    let c_eff = Mat::<f64>::from_fn(nz, nz, |i, j| {
        let d = if i == j { alpha + beta * lam[i] } else { 0.0 };
        d + 2.0 * w * m.g1[(i, j)]
    });
    let k_eff = Mat::<f64>::from_fn(nz, nz, |i, j| {
        let d = if i == j { lam[i] } else { 0.0 };
        d + w * w * m.g2[(i, j)] + beta * w * m.k1[(i, j)]
    });
    let s = Mat::<f64>::from_fn(nz, nz, |i, j| {
        let d = if i == j { bp } else { 0.0 };
        d + gp * c_eff[(i, j)] + k_eff[(i, j)]
    });
    let s_inv = s.partial_piv_lu().inverse();
    // the step map, column by column: x = [z; ż; z̈; a]
    let n4 = 4 * nz;
    let mut a = Mat::<f64>::zeros(n4, n4);
    for col in 0..n4 {
        let mut x = vec![0.0; n4];
        x[col] = 1.0;
        let (q, rest) = x.split_at(nz);
        let (v, rest) = rest.split_at(nz);
        let (vd, acc) = rest.split_at(nz);
        let a1: Vec<f64> = (0..nz)
            .map(|i| (af * vd[i] - am * acc[i]) / (1.0 - am))
            .collect();
        let q1: Vec<f64> = (0..nz)
            .map(|i| q[i] + h * v[i] + h * h * ((0.5 - nb) * acc[i] + nb * a1[i]))
            .collect();
        let v1: Vec<f64> = (0..nz)
            .map(|i| v[i] + h * ((1.0 - ng) * acc[i] + ng * a1[i]))
            .collect();
        let qm = faer::MatRef::from_column_major_slice(&q1, nz, 1);
        let vm = faer::MatRef::from_column_major_slice(&v1, nz, 1);
        let r = &c_eff * vm + &k_eff * qm;
        let dx = -(&s_inv * &r);
        let mut out = a.col_mut(col);
        for i in 0..nz {
            let vdn = bp * dx[(i, 0)];
            out[i] = q1[i] + dx[(i, 0)];
            out[nz + i] = v1[i] + gp * dx[(i, 0)];
            out[2 * nz + i] = vdn;
            out[3 * nz + i] = (af * vd[i] - am * acc[i] + (1.0 - af) * vdn) / (1.0 - am);
        }
    }
    cond_and_time(&a, "step map A (4 n_z)");
    // the same map on the scaled state [z; h ż; h² z̈; h² a] (a similarity: the same
    // eigenvalues in exact arithmetic, entries of comparable size)
    let scale = |i: usize| match i / nz {
        0 => 1.0,
        1 => h,
        _ => h * h,
    };
    let a_scaled = Mat::<f64>::from_fn(n4, n4, |i, j| scale(i) * a[(i, j)] / scale(j));
    cond_and_time(&a_scaled, "scaled step map (4 n_z)");
    let n2 = 2 * nz;
    let first = Mat::<f64>::from_fn(n2, n2, |i, j| match (i < nz, j < nz) {
        (true, true) => 0.0,
        (true, false) => f64::from(u8::from(i == j - nz)),
        (false, true) => -k_eff[(i - nz, j)],
        (false, false) => -c_eff[(i - nz, j - nz)],
    });
    cond_and_time(&first, "first-order matrix [0 I; -K_eff -C_eff] (2 n_z)");
    let sg = m.g1.singular_values().expect("svd of G1");
    let rank = |tol: f64| sg.iter().filter(|&&x| x > tol * sg[0]).count();
    println!(
        "G1 singular values: max {:.3e}, min {:.3e}; rank at 1e-15: {}, 1e-12: {}, 1e-8: {}, \
         1e-4: {} of {nz}",
        sg[0],
        sg[sg.len() - 1],
        rank(1e-15),
        rank(1e-12),
        rank(1e-8),
        rank(1e-4)
    );
    if steps == 0 {
        return;
    }
    // the lagged coupling θ̈ₙ G₁ zₙ against 2θ̇ G₁ żₙ and Λ zₙ over a run
    let (mut lag_max, mut gyro_at, mut elastic_at, mut t_at, mut rel_max) =
        (0.0f64, 0.0, 0.0, 0.0, 0.0f64);
    let mut g = vec![0.0; nz];
    for _ in 0..steps {
        rig_step(sim, &cfg).expect("step");
        let st = &sim.state;
        mbd_core::linalg::matvec(m.g1.as_ref(), &st.z, &mut g);
        let lag = st.theta_dd.abs() * norm(&g);
        mbd_core::linalg::matvec(m.g1.as_ref(), &st.zd, &mut g);
        let gyro = 2.0 * st.theta_d.abs() * norm(&g);
        let el: Vec<f64> = st.z.iter().zip(&lam).map(|(z, l)| z * l).collect();
        let elastic = norm(&el);
        rel_max = rel_max.max(lag / elastic);
        if lag > lag_max {
            (lag_max, gyro_at, elastic_at, t_at) = (lag, gyro, elastic, st.t);
        }
    }
    println!(
        "{steps} steps: largest |theta_dd G1 z| {lag_max:.4e} (t = {t_at:.5} s; there \
         |2 theta_d G1 zd| {gyro_at:.4e}, |Lambda z| {elastic_at:.4e}); largest ratio to |Lambda z| \
         {rel_max:.3e}"
    );
}
