//! Bechtel's analytical speed loss, the reference line of the speed-loss study (Ribaric (6.3)),
//! and the Euler–Eytelwein capacity of the two-pulley drive.

use belt::Drive;
use contact::friction::FrictionLaw;

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
    if path.pulleys().len() != 2 || d.driver() != Some(0) || d.arm().is_some() {
        return f64::NAN;
    }
    let mu = d.contact().friction.coefficient();
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

#[cfg(test)]
mod tests {
    use super::*;

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
