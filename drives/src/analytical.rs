//! Bechtel's analytical speed loss, the reference line of the speed-loss study (Ribaric (6.3)).

use flowing::belt::BeltDriveConfig;

/// Angular speed loss of Bechtel et al., Ribaric (6.3):
/// `Δω = (1 − (2RT0 − M_p + 2Rk)/(2RT0 + M_p + 2Rk)) ω = 2 M_p ω / (2R(T0 + k) + M_p)` \[rad/s\],
/// with `k = EA` \[N\] (the dimensionally consistent reading, seed-000 note U13), pulley radius
/// `R` \[m\], pre-tension `T0` \[N\], load torque `M_p` \[N m\] and driver speed `ω` \[rad/s\].
pub fn analytical_speed_loss(radius: f64, tension: f64, ea: f64, torque: f64, omega: f64) -> f64 {
    let a = 2.0 * radius * tension + 2.0 * radius * ea;
    (1.0 - (a - torque) / (a + torque)) * omega
}

/// Bechtel's line (6.3) for the drive `d` (Ribaric Table 6-1 fields): [`analytical_speed_loss`]
/// with the driven pulley's radius, the pre-tension and EA of `d`, at load torque `torque`
/// \[N m\] and driver speed `omega` \[rad/s\].
pub fn bechtel(d: &BeltDriveConfig, torque: f64, omega: f64) -> f64 {
    analytical_speed_loss(
        d.geometry.radius_driven,
        d.belt.tension,
        d.belt.ea,
        torque,
        omega,
    )
}

#[cfg(test)]
mod tests {
    use super::*;

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
        let d = BeltDriveConfig::default();
        assert_eq!(
            bechtel(&d, 10.0, 62.8),
            analytical_speed_loss(0.05, 310.0, 152_000.0, 10.0, 62.8)
        );
    }
}
