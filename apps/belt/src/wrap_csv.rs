//! The columns of the wrap tables, one row per contact point of a wrap ([`belt::WrapPoint`]):
//! `wrap.csv` of `flowmbd-belt ancf` and `wrap_omega_*.csv` of `flowmbd-belt speed-loss`.

use belt::WrapPoint;

/// Column names of [`row`], in its order.
pub(crate) const COLUMNS: [&str; 8] = [
    "pulley_index",
    "angle_from_inlet_rad",
    "length_m",
    "tension_N",
    "pressure_N_per_m",
    "friction_N_per_m",
    "slip_velocity_m_per_s",
    "friction_utilisation_ratio",
];

/// The contact point `w` as a row of [`COLUMNS`]; `mu` is the coefficient of the friction law on
/// `w`'s pulley, of the utilisation `|f|/(μ p)` ([`WrapPoint::utilisation`],
/// [`belt::Drive::wrap_friction_law`]).
pub(crate) fn row(w: &WrapPoint, mu: f64) -> [f64; 8] {
    [
        w.pulley as f64,
        w.angle,
        w.length,
        w.tension,
        w.pressure,
        w.friction,
        w.slip,
        w.utilisation(mu),
    ]
}
