//! Circumferential order and travelling direction of a tire mode from its displacement over
//! whole tread rings ([`TreadBasis`]).
//!
//! At each tread node (angle θ, `θ = atan2(x, z)`, [`super::mesh`]) the complex displacement
//! `d` of the mode is split into its radial, tangential and lateral parts,
//! `w = d·e_r`, `v = d·e_θ`, `u = d·ŷ` with `e_r = (sin θ, 0, cos θ)`, `e_θ = (cos θ, 0, −sin θ)`
//! (polar parts, so that a shape `cos nθ` of the ring is the single harmonic `n`, whereas its
//! Cartesian parts mix `n ± 1`). Each part of each ring is expanded in circumferential
//! harmonics by the discrete Fourier sum over the ring's nodes (weighted by their angular
//! spacing, exact for the uniform rings of the generated tire)
//!
//! ```text
//!   c_k = Σ_j d_j e^{−i k θ_j} Δθ_j / 2π,    E_k = Σ_rings Σ_parts |c_k|²,   |k| < N/2,
//! ```
//!
//! and the mode's order is the `n ≥ 0` with the largest `E_n + E_{−n}`.
//!
//! **Direction.** The motion of an eigenpair `(λ, φ)` with `ω = Im λ > 0` is `Re(φ e^{λt})`; its
//! harmonic `c_k e^{i(kθ + ωt)}` has constant phase along `θ = −ωt/k + const`, i.e. it travels
//! towards increasing θ for `k < 0`. The material flows towards increasing θ for a positive
//! spin `θ̇` ([`super::mesh`]), so with `s = sign θ̇` the forward wave (travelling with the
//! rotation, in the ground frame) is `k = −s n` and the backward wave `k = s n`. The signed
//! share `t = (E_fwd − E_bwd)/(E_fwd + E_bwd)` is +1 for a pure forward wave, −1 for a pure
//! backward wave and 0 for a standing wave.

use crate::reduced::TreadBasis;
use faer::c64;
use serde::Serialize;
use std::f64::consts::PI;

/// Direction of a travelling wave in the ground-fixed frame, relative to the tire's rotation.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum WaveDirection {
    /// Travels with the rotation (|t| ≥ [`TRAVELLING_SHARE`], t > 0).
    Forward,
    /// Travels against the rotation.
    Backward,
    /// Neither dominates (`n = 0`, no spin, or a standing wave, e.g. with the patch held).
    Standing,
}

/// Signed travelling share `|t|` from which a mode counts as a travelling wave (the energy of
/// one direction at least 3 times that of the other).
pub const TRAVELLING_SHARE: f64 = 0.5;

/// Circumferential content of one mode.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Harmonic {
    /// Dominant circumferential order `n`.
    pub order: usize,
    /// Share of the energy `Σ_k E_k` in the harmonics `±n` (1: a pure order-`n` shape).
    pub order_share: f64,
    /// Signed travelling share `t` (module docs), 0 for `n = 0` or no spin.
    pub travelling: f64,
    /// Direction from `t`.
    pub direction: WaveDirection,
    /// Energies of the radial, tangential and lateral parts in the harmonics `±n`, as
    /// fractions of `E_n + E_{−n}` (in-plane modes: lateral ≈ 0; an inextensional ring:
    /// tangential/radial = 1/n², thin-ring theory).
    pub parts: [f64; 3],
}

impl TreadBasis {
    /// Highest order resolved on every ring, `(N_min − 1)/2` (below the Nyquist order).
    pub fn max_order(&self) -> usize {
        let rings = self.ring.iter().max().map_or(0, |r| r + 1);
        (0..rings)
            .map(|r| self.ring.iter().filter(|&&q| q == r).count())
            .min()
            .map_or(0, |n| n.saturating_sub(1) / 2)
    }

    /// Energies `E_k` for `k = −K..=K` (index `k + K`, `K` = [`TreadBasis::max_order`]) of the
    /// complex nodal displacements `d` (3 per tread node, Cartesian).
    pub fn spectrum(&self, d: &[c64]) -> Vec<f64> {
        self.part_spectrum(d)
            .iter()
            .map(|p| p.iter().sum())
            .collect()
    }

    /// [`TreadBasis::spectrum`] split into the radial, tangential and lateral parts.
    pub fn part_spectrum(&self, d: &[c64]) -> Vec<[f64; 3]> {
        let kmax = self.max_order() as i64;
        let mut e = vec![[0.0; 3]; (2 * kmax + 1) as usize];
        let rings = self.ring.iter().max().map_or(0, |r| r + 1);
        for r in 0..rings {
            let idx: Vec<usize> = (0..self.nodes.len())
                .filter(|&j| self.ring[j] == r)
                .collect();
            let m = idx.len();
            // angular weights Δθ_j / 2π: half the spacing to each neighbour on the closed ring
            let w: Vec<f64> = (0..m)
                .map(|a| {
                    let prev = self.theta[idx[(a + m - 1) % m]];
                    let next = self.theta[idx[(a + 1) % m]];
                    let gap = |x: f64, y: f64| (y - x).rem_euclid(2.0 * PI);
                    if m == 1 {
                        1.0
                    } else {
                        0.5 * (gap(prev, self.theta[idx[a]]) + gap(self.theta[idx[a]], next))
                            / (2.0 * PI)
                    }
                })
                .collect();
            // polar parts of each node
            let parts: Vec<[c64; 3]> = idx
                .iter()
                .map(|&j| {
                    let (s, c) = self.theta[j].sin_cos();
                    let (dx, dy, dz) = (d[3 * j], d[3 * j + 1], d[3 * j + 2]);
                    [dx * s + dz * c, dx * c - dz * s, dy]
                })
                .collect();
            for k in -kmax..=kmax {
                let mut ck = [c64::new(0.0, 0.0); 3];
                for (a, &j) in idx.iter().enumerate() {
                    let ph = -(k as f64) * self.theta[j];
                    let z = c64::new(ph.cos(), ph.sin()) * w[a];
                    for p in 0..3 {
                        ck[p] += parts[a][p] * z;
                    }
                }
                for p in 0..3 {
                    e[(k + kmax) as usize][p] += ck[p].norm_sqr();
                }
            }
        }
        e
    }

    /// The dominant order and direction of the displacements `d` of a mode with `Im λ > 0`
    /// under the spin `spin` \[rad/s\] (module docs).
    pub fn harmonic(&self, d: &[c64], spin: f64) -> Harmonic {
        let ep = self.part_spectrum(d);
        let e: Vec<f64> = ep.iter().map(|p| p.iter().sum()).collect();
        let kmax = self.max_order();
        let at = |k: i64| e[(k + kmax as i64) as usize];
        let total: f64 = e.iter().sum();
        let order = (0..=kmax)
            .max_by(|&a, &b| {
                let ea = at(a as i64) + if a > 0 { at(-(a as i64)) } else { 0.0 };
                let eb = at(b as i64) + if b > 0 { at(-(b as i64)) } else { 0.0 };
                ea.total_cmp(&eb)
            })
            .unwrap_or(0);
        let n = order as i64;
        let pair = at(n) + if n > 0 { at(-n) } else { 0.0 };
        let travelling = if n == 0 || spin == 0.0 || pair <= 0.0 {
            0.0
        } else {
            let s = spin.signum() as i64;
            (at(-s * n) - at(s * n)) / pair
        };
        let direction = if travelling >= TRAVELLING_SHARE {
            WaveDirection::Forward
        } else if travelling <= -TRAVELLING_SHARE {
            WaveDirection::Backward
        } else {
            WaveDirection::Standing
        };
        let mut parts = [0.0; 3];
        for (p, part) in parts.iter_mut().enumerate() {
            let at_p = |k: i64| ep[(k + kmax as i64) as usize][p];
            let v = at_p(n) + if n > 0 { at_p(-n) } else { 0.0 };
            *part = if pair > 0.0 { v / pair } else { 0.0 };
        }
        Harmonic {
            order,
            order_share: if total > 0.0 { pair / total } else { 0.0 },
            travelling,
            direction,
            parts,
        }
    }
}
