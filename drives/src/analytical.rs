//! Bechtel's analytical speed loss, the reference line of the speed-loss study (Ribaric (6.3)),
//! and the Euler–Eytelwein capacity of the two-pulley drive.

use belt::Drive;

/// Angular speed loss of Bechtel et al., Ribaric (6.3):
/// `Δω = (1 − (2RT0 − M_p + 2Rk)/(2RT0 + M_p + 2Rk)) ω = 2 M_p ω / (2R(T0 + k) + M_p)` \[rad/s\],
/// with `k = EA` \[N\] (the dimensionally consistent reading, seed-000 note U13), pulley radius
/// `R` \[m\], pre-tension `T0` \[N\], load torque `M_p` \[N m\] and driver speed `ω` \[rad/s\].
pub fn analytical_speed_loss(radius: f64, tension: f64, ea: f64, torque: f64, omega: f64) -> f64 {
    let a = 2.0 * radius * tension + 2.0 * radius * ea;
    (1.0 - (a - torque) / (a + torque)) * omega
}

/// Bechtel's line (6.3) for the drive `d`: [`analytical_speed_loss`] with the driven pulley's
/// radius ([`Drive::driven`]), the installation tension and EA of `d`, at load torque `torque`
/// \[N m\] and driver speed `omega` \[rad/s\] (`NaN` without a driven pulley).
pub fn bechtel(d: &Drive, torque: f64, omega: f64) -> f64 {
    let Some(k) = d.driven() else {
        return f64::NAN;
    };
    analytical_speed_loss(
        d.pulleys()[k].radius,
        d.tension(),
        d.belt().ea,
        torque,
        omega,
    )
}

/// The friction coefficient of both wraps of the two-pulley drive `d` (driver first, no
/// tensioner): [`Drive::wrap_friction_law`]'s `μ` (`μ/sin(β/2)` for a multi-ribbed belt in
/// grooved pulleys); `None` for other drives or if the two wraps' coefficients differ (the
/// closed forms below take one `μ`).
fn two_pulley_mu(d: &Drive) -> Option<f64> {
    if d.pulleys().len() != 2 || d.driver() != Some(0) || d.arm().is_some() {
        return None;
    }
    let mu = d.wrap_friction_coefficients();
    (mu[0] == mu[1]).then_some(mu[0])
}

/// Largest load torque \[N·m\] friction lets the two-pulley drive `d` (driver first) transmit
/// at driver speed `omega` \[rad/s\] (Euler–Eytelwein capacity of a fixed-centre drive; `NaN`
/// for other layouts).
///
/// At the capacity the pulley with the smaller wrap `φ_min` slides over its whole wrap:
/// `T₁ − T_c = e^{μ φ_min} (T₂ − T_c)` (Euler–Eytelwein with the centrifugal tension
/// `T_c = ρA v²`, v = ω₁R₁). The centres are fixed, so a linearly elastic belt keeps its
/// stretched length: `∫ (T − T0) ds = 0` around the loop, with the tension constant on the
/// spans, exponential over the slip arcs (`∫ (T − T_c) ds = R (T₁ − T₂)/μ` over a slip arc of
/// `φ_min`) and constant over the rest of the larger wrap (`T₁` at the driver's inlet, `T₂` at
/// the driven pulley's). Hence `T₂ − T_c = (T0 − T_c) L / (L_s (E + 1) + Σ_k R_k ((E − 1)/μ +
/// (φ_k − φ_min) a_k))` with `E = e^{μ φ_min}`, `L` the path length, `L_s` a span length and
/// `a_k = E` (driver) or 1 (driven); the capacity is `R₂ (T₁ − T₂)`. Table 6-1 (T0 = 310 N,
/// μ = 1.2, wrap π): 33.9 N·m, T₂ ≈ 16 N, T₁ ≈ 695 N (T₁ + T₂ = 711 N > 2 T0: the exponential
/// tension profile over the wraps averages below the span tensions).
pub fn euler_eytelwein_capacity(d: &Drive, omega: f64) -> f64 {
    let path = d.path();
    let Some(mu) = two_pulley_mu(d) else {
        return f64::NAN;
    };
    let radii = [path.pulleys()[0].radius, path.pulleys()[1].radius];
    let wraps = [0, 1].map(|k| path.wrap_angle(k).unwrap_or(f64::NAN));
    let phi_min = wraps[0].min(wraps[1]);
    let e = (mu * phi_min).exp();
    let v = omega * radii[0];
    let tc = d.belt().mass_per_length * v * v;
    let span = path.spans().first().map_or(f64::NAN, |s| s.length);
    let mut den = span * (e + 1.0);
    for k in 0..2 {
        let a = if k == 0 { e } else { 1.0 };
        den += radii[k] * ((e - 1.0) / mu + (wraps[k] - phi_min) * a);
    }
    let x = (d.tension() - tc) * path.length() / den;
    radii[1] * (e - 1.0) * x
}

/// The span tensions of a fixed-centre string drive on a penalty contact (issue 34 item 8):
/// what [`euler_eytelwein_capacity`] computes, with the contact law's penetration in the length
/// balance.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PenetratingString {
    /// Tight-span tension `T₁` \[N\].
    pub tight: f64,
    /// Slack-span tension `T₂` \[N\].
    pub slack: f64,
    /// Slip arc `ln((T₁ − T_c)/(T₂ − T_c))/μ` \[rad\] on each pulley.
    pub slip_arc: f64,
}

/// Penetration \[m\] of the penalty law (6.1) `k₂ d² + k₁ d = p` under the pressure `p`
/// \[N/m\] (0 for `p ≤ 0`; [`belt::BeltContact::mounting_penetration`] at unit radius).
fn penalty_penetration(d: &Drive, p: f64) -> f64 {
    if p <= 0.0 {
        0.0
    } else {
        d.contact().mounting_penetration(p, 1.0)
    }
}

/// Steady span tensions of the two-pulley drive `d` as a string on fixed centres at driver speed
/// `omega` \[rad/s\] and load `torque` \[N·m\] (Coulomb friction: adhesion over the inlet part of
/// each wrap, Euler–Eytelwein `T − T_c ∝ e^{±μθ}` over a slip arc at the exit), with the belt
/// sinking into the penalty contact (6.1).
///
/// The mounted belt's centreline runs on the path of the pulley radii `R` with the contact at
/// `R + p₀` (`p₀` the penetration under `T0/R`, the mapping of the flowing, nodal and ANCF
/// models); running, it sits at `R + p₀ − d(p)`, `d` the penetration under the string's pressure
/// `p = (T − T_c)/R` (`T_c = ρA v²`). The belt is linearly elastic with its stretched length
/// equal to the centreline's path:
///
/// `∫ (T − T0) ds = EA Σ_k ∫_{wrap k} (p₀ − d(p)) dθ`,
///
/// where the spans carry `T₁`, `T₂`, the wraps `T` at the inlet over the adhesion arcs and the
/// exponential profile over the slip arcs (integrated with the composite Simpson rule, 400
/// intervals). Because the penalty stiffens with the pressure (`k₂ > 0`), `d` is concave in `T`:
/// the tight side sinks in less than the slack side rises, the path lengthens with the load and
/// `T₁ + T₂` rises above the rigid string's. With `k₁, k₂ → ∞` this is
/// [`euler_eytelwein_capacity`]'s length balance. `None` when the torque exceeds the capacity
/// (the slip arc would exceed the smaller wrap) and for drives other than two pulleys, driver
/// first, without a tensioner.
pub fn penetrating_string(d: &Drive, omega: f64, torque: f64) -> Option<PenetratingString> {
    let path = d.path();
    let mu = two_pulley_mu(d)?;
    let radii = [path.pulleys()[0].radius, path.pulleys()[1].radius];
    let wraps = [0, 1].map(|k| path.wrap_angle(k).unwrap_or(f64::NAN));
    let v = omega * radii[0];
    let tc = d.belt().mass_per_length * v * v;
    let spans: f64 = path.spans().iter().map(|s| s.length).sum::<f64>() * 0.5;
    let (t0, ea) = (d.tension(), d.belt().ea);
    let p0 = [0, 1].map(|k| penalty_penetration(d, t0 / radii[k]));
    let diff = torque / radii[1];
    // length defect of the balance at slack tension t2 (increasing in t2)
    let defect = |t2: f64| -> (f64, f64) {
        let t1 = t2 + diff;
        let phi = ((t1 - tc) / (t2 - tc)).ln() / mu;
        let mut lhs = spans * (t1 + t2 - 2.0 * t0);
        let mut rhs = 0.0;
        // driver: inlet T1, slip arc at the exit down to T2; driven: inlet T2, up to T1
        for (k, (t_in, sign)) in [(t1, -1.0), (t2, 1.0)].into_iter().enumerate() {
            let r = radii[k];
            let adhesion = (wraps[k] - phi).max(0.0);
            lhs += r * adhesion * (t_in - t0);
            rhs += ea * adhesion * (p0[k] - penalty_penetration(d, (t_in - tc) / r));
            let n = 400;
            let hstep = phi / n as f64;
            for i in 0..=n {
                let w = simpson_weight(i, n) * hstep / 3.0;
                let t = tc + (t_in - tc) * (sign * mu * i as f64 * hstep).exp();
                lhs += w * r * (t - t0);
                rhs += w * ea * (p0[k] - penalty_penetration(d, (t - tc) / r));
            }
        }
        (lhs - rhs, phi)
    };
    let (lo, mut hi) = (tc + 1e-9 * t0.max(1.0), t0 + 1.0);
    while defect(hi).0 < 0.0 {
        hi *= 2.0;
        if hi > 1e3 * t0 {
            return None;
        }
    }
    let (lo, hi) = mbd_core::roots::bisect(
        lo,
        hi,
        |t| defect(t).0 >= 0.0,
        mbd_core::roots::Stop::iterations(200),
    );
    let t2 = 0.5 * (lo + hi);
    let phi = defect(t2).1;
    if phi > wraps[0].min(wraps[1]) {
        return None;
    }
    Some(PenetratingString {
        tight: t2 + diff,
        slack: t2,
        slip_arc: phi,
    })
}

/// Capacity \[N·m\] of [`penetrating_string`]: the torque at which the slip arc covers the smaller
/// wrap (bisection to 1e-6 N·m). Table 6-1 at 62.8 rad/s: 36.2 N·m against the rigid string's
/// 33.8 N·m ([`euler_eytelwein_capacity`]): at the capacity the slack wraps rise by ≈ 60 µm
/// out of the penalty (d = 10 µm under T₂ ≈ 16 N against p₀ = 72 µm) while the tight ones sink
/// by ≈ 60 µm, and the quadratic law makes the rise win.
pub fn penetrating_string_capacity(d: &Drive, omega: f64) -> f64 {
    let hi = 2.0 * euler_eytelwein_capacity(d, omega);
    if penetrating_string(d, omega, hi).is_some() {
        return f64::NAN;
    }
    let (lo, hi) = mbd_core::roots::bisect(
        0.0,
        hi,
        |t| penetrating_string(d, omega, t).is_none(),
        mbd_core::roots::Stop::absolute(200, 1e-6),
    );
    0.5 * (lo + hi)
}

/// Weight of node `i` of the composite Simpson rule on `n` (even) intervals, before the factor
/// `h/3`: 1 at the ends, 4 at odd and 2 at even interior nodes.
pub(crate) fn simpson_weight(i: usize, n: usize) -> f64 {
    if i == 0 || i == n {
        1.0
    } else if i % 2 == 1 {
        4.0
    } else {
        2.0
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    // Closed form with a linear penalty (k₂ = 0): d = (T − T_c)/(R k₁) is linear in T, so the
    // balance stays linear: L_s(T₁ + T₂ − 2T0) + (1 + c) R ∫(T − T0) dθ − c R T_c Σφ = 0 over
    // the wraps, c = EA/(R² k₁); at the capacity (slip over the whole wrap π on both equal
    // pulleys) ∫_wrap (T − T0) dθ = (T₁ − T₂)/μ + π(T_c − T0) and T₁ − T_c = E (T₂ − T_c),
    // E = e^{μπ}: T₂ − T_c = [2 L_s (T0 − T_c) + 2π(1 + c) R (T0 − T_c) + 2πcR T_c]
    // / [L_s (E + 1) + 2(1 + c) R (E − 1)/μ]; rigid limit c → 0: euler_eytelwein_capacity.
    #[test]
    fn penetrating_string_capacity_with_a_linear_penalty() {
        let mut layout = crate::table_6_1::layout();
        layout.contact.penalty_quadratic = 0.0;
        layout.contact.penalty_linear = 2.0e7;
        let d = layout.resolve().unwrap();
        let omega = 62.8;
        let (ls, r, mu, t0, ea) = (0.45, 0.05, 1.2, 310.0, 152_000.0);
        let tc = 0.096 * (omega * r) * (omega * r);
        let pi = std::f64::consts::PI;
        let e = (mu * pi).exp();
        let c = ea / (r * r * 2.0e7);
        let t2 = tc
            + (2.0 * ls * (t0 - tc) + 2.0 * pi * (1.0 + c) * r * (t0 - tc) + 2.0 * pi * c * r * tc)
                / (ls * (e + 1.0) + 2.0 * (1.0 + c) * r * (e - 1.0) / mu);
        let m = r * (e - 1.0) * (t2 - tc);
        let cap = penetrating_string_capacity(&d, omega);
        assert!((cap / m - 1.0).abs() < 1e-5, "{cap} vs closed form {m}");
        // the rigid limit
        layout.contact.penalty_linear = 1e15;
        let d = layout.resolve().unwrap();
        let rigid = penetrating_string_capacity(&d, omega);
        assert!((rigid / euler_eytelwein_capacity(&d, omega) - 1.0).abs() < 1e-5);
        // Table 6-1's stiffening penalty (6.1) lifts the capacity by 7 %
        let t61 = penetrating_string_capacity(&crate::table_6_1::drive(), omega);
        assert!((t61 - 36.2).abs() < 0.1, "{t61}");
    }

    // Hand solve of the fixed-centre capstan limit for Table 6-1 at rest (T_c = 0): equal
    // pulleys, wrap π, E = e^{1.2π}: T₂ = T0 (2 L_s + 2πR) / (L_s (E + 1) + 2R (E − 1)/μ),
    // M = R (E − 1) T₂ = 33.94 N·m (the limit quoted in issue 17)
    #[test]
    fn capacity_of_table_6_1() {
        let d = crate::table_6_1::drive();
        let e = (1.2 * std::f64::consts::PI).exp();
        let (ls, r) = (0.45, 0.05);
        let t2 = 310.0 * (2.0 * ls + 2.0 * std::f64::consts::PI * r)
            / (ls * (e + 1.0) + 2.0 * r * (e - 1.0) / 1.2);
        let m = r * (e - 1.0) * t2;
        assert!((m - 33.94).abs() < 0.01, "{m}");
        assert!((euler_eytelwein_capacity(&d, 0.0) / m - 1.0).abs() < 1e-12);
        // the centrifugal tension ρA v² (0.95 N at 62.8 rad/s) lowers it by 0.3 %
        let fast = euler_eytelwein_capacity(&d, 62.8);
        assert!((fast / m - (310.0 - 0.096 * (62.8f64 * 0.05).powi(2)) / 310.0).abs() < 1e-12);
    }

    // seed-000 note §2.3 table: Δω = 2 M_p ω / (15231 + M_p) for Table 6-1
    #[test]
    fn bechtel_line_matches_the_note_table() {
        let d = analytical_speed_loss(0.05, 310.0, 152_000.0, 10.0, 62.8);
        assert!((d - 0.08241).abs() < 5e-6, "{d}");
        let d = analytical_speed_loss(0.05, 310.0, 152_000.0, 20.0, 22.6);
        assert!((d - 0.05927).abs() < 5e-6, "{d}");
    }

    // the drive form reads R₂, T0 and EA of Table 6-1 (formula above)
    #[test]
    fn bechtel_reads_the_table_6_1_drive() {
        let d = crate::table_6_1::drive();
        assert_eq!(
            bechtel(&d, 10.0, 62.8),
            analytical_speed_loss(0.05, 310.0, 152_000.0, 10.0, 62.8)
        );
    }
}
