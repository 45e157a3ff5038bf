//! Physical parameters of a string under tension (Ribaric 4.1.1, Example 4.2.3).

use crate::error::{FlowError, invalid};

/// A uniform string: length between the boundaries, density, cross-section and tension.
///
/// `Default` is Ribaric's example of Sec. 4.2.3: L = 1 m, ρ₀ = 7850 kg/m³,
/// A₀ = 7.854e-5 m² (10 mm steel wire), T₀ = 1000 N.
#[derive(
    Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize, schemars::JsonSchema,
)]
#[serde(deny_unknown_fields)]
pub struct StringConfig {
    /// Length between the boundaries `L` \[m\].
    pub length: f64,
    /// Density `ρ₀` \[kg/m³\].
    pub density: f64,
    /// Cross-section `A₀` \[m²\].
    pub area: f64,
    /// Tension `T₀` \[N\].
    pub tension: f64,
}

impl Default for StringConfig {
    fn default() -> Self {
        Self {
            length: 1.0,
            density: 7850.0,
            area: 7.854e-5,
            tension: 1000.0,
        }
    }
}

impl StringConfig {
    /// Checks that all parameters are finite and positive.
    pub fn validate(&self) -> Result<(), FlowError> {
        for (name, v) in [
            ("length", self.length),
            ("density", self.density),
            ("area", self.area),
            ("tension", self.tension),
        ] {
            if !(v.is_finite() && v > 0.0) {
                return Err(invalid(
                    format!("string parameter `{name}`"),
                    format!("{v} is not a positive number"),
                ));
            }
        }
        Ok(())
    }

    /// Mass per unit length `μ = ρ₀A₀` \[kg/m\].
    pub fn mu(&self) -> f64 {
        self.density * self.area
    }

    /// Wave speed `c = √(T₀/(ρ₀A₀))` \[m/s\] (Ribaric (4.21)); also the critical axial speed.
    pub fn wave_speed(&self) -> f64 {
        (self.tension / self.mu()).sqrt()
    }

    /// Exact natural frequency of mode `n` of the axially moving fixed–fixed string at any
    /// speed, `f_n = n |c² − v²| / (2 c L)` \[Hz\] (0 at `|v| = c`).
    ///
    /// The eigenvalues of (4.23) with `u(0) = u(L) = 0` are `λ_n = iπn(c² − v²)/(cL)`
    /// (Wickert & Mote 1990 for `|v| < c`; notes §1.4.4 / erratum E25; the eigenvalues of
    /// Ribaric's (4.29) converge to them): with `u = e^{λt}(e^{ik₁x} − e^{ik₂x})` and the two
    /// wave numbers `k₁ = −iλ/(c − v)`, `k₂ = iλ/(c + v)` the end conditions give
    /// `(k₁ − k₂)L = 2πn`. The same algebra holds for `|v| > c`, where `λ_n` changes sign and
    /// stays imaginary: the characteristic time `τ = t + v x/(c² − v²)` turns (4.23) into the
    /// fixed string `u_ττ = c'² u_xx` with `c' = |c² − v²|/c`, whose frequencies are
    /// `n c'/(2L)` (see [`crate::string_study`]).
    pub fn exact_moving_frequency_hz(&self, n: usize, speed: f64) -> f64 {
        n as f64 * self.characteristic_wave_speed(speed) / (2.0 * self.length)
    }

    /// Wave speed of the string travelling at `speed` seen in its characteristic time
    /// `τ = t + v x/(c² − v²)`: `c' = |c² − v²|/c` \[m/s\] (0 at the critical speed).
    pub fn characteristic_wave_speed(&self, speed: f64) -> f64 {
        let c = self.wave_speed();
        (c * c - speed * speed).abs() / c
    }
}
