//! A transition-aware limit on Newton corrections through a regularised friction law.
//!
//! A smooth law `f_t = −μ φ(v_t/w) |f_n|` (e.g. `φ = tanh`, Ribaric (6.2) with `w = 1/κ`) is
//! steep only inside a band of width `w` around zero slip and flat outside it. A Newton
//! correction computed with the slope at a sliding point (nearly zero) can move its slip
//! velocity through the whole band onto the opposite saturated branch, and one computed inside
//! the band can throw the point far out onto a flat branch, where the next tangent no longer
//! sees the friction: the iteration then jumps between the branches. Castro et al. (2019),
//! "Transition-aware line search" of Drake's TAMSI solver, limit the step length `α` of the
//! whole correction so that no contact crosses the band in one iteration. This module is the
//! planar (scalar slip) rule; a model takes the smallest `α` over its contact points
//! (`mbd_core::SecondOrderSystem::correction_limit`).

/// Where a limited correction puts a point that would cross the band from sliding: at
/// `±LAND_INSIDE·w` on its own side \[-\] (inside the steep part, where the next tangent
/// resolves the law).
pub const LAND_INSIDE: f64 = 0.5;

/// How far past the band a limited correction lets a point inside the band leave:
/// `|v_t| ≤ LEAVE_TO·w` \[-\] (`tanh(2)` = 0.96 of the sliding force, the slope still 7 % of
/// its value at zero; from there on the point counts as sliding and moves freely along its
/// branch).
pub const LEAVE_TO: f64 = 2.0;

/// Largest step length `α ∈ (0, 1]` of a Newton correction that changes a contact's slip
/// velocity from `slip` to `slip + α·change` \[m/s\] through a regularised law of transition
/// width `width` \[m/s\] (`1/κ` of the tanh law):
///
/// * a sliding point (`|v| > w`) whose full correction ends beyond the band on the other side
///   is stopped at `sign(v)·LAND_INSIDE·w`;
/// * a point inside the band (`|v| ≤ w`) whose full correction ends beyond `LEAVE_TO·w` is
///   stopped at `±LEAVE_TO·w` on the side it moves to;
/// * every other correction is taken in full (`1`), as is any with a non-positive or
///   non-finite width.
pub fn transition_limit(slip: f64, change: f64, width: f64) -> f64 {
    if !(width > 0.0 && width.is_finite() && change != 0.0 && change.is_finite()) {
        return 1.0;
    }
    let end = slip + change;
    let alpha = if slip.abs() > width {
        if slip * end < 0.0 && end.abs() > width {
            (slip.abs() - LAND_INSIDE * width) / change.abs()
        } else {
            1.0
        }
    } else if end.abs() > LEAVE_TO * width {
        (end.signum() * LEAVE_TO * width - slip) / change
    } else {
        1.0
    };
    alpha.clamp(f64::MIN_POSITIVE, 1.0)
}

#[cfg(test)]
mod tests {
    use super::*;

    // Reference: the rule's closed form, checked on the slip velocity the limited step reaches.
    #[test]
    fn a_sliding_point_lands_inside_the_band_on_its_own_side() {
        let w = 1e-3;
        let a = transition_limit(5e-3, -1e-2, w);
        assert!((5e-3 - a * 1e-2 - LAND_INSIDE * w).abs() < 1e-15, "{a}");
        let a = transition_limit(-5e-3, 1e-2, w);
        assert!((-5e-3 + a * 1e-2 + LAND_INSIDE * w).abs() < 1e-15, "{a}");
    }

    #[test]
    fn a_point_inside_the_band_leaves_it_by_at_most_leave_to_widths() {
        let w = 1e-3;
        for (v, d) in [(2e-4, 1.0), (2e-4, -1.0), (-9e-4, 0.5), (0.0, -3e-3)] {
            let a = transition_limit(v, d, w);
            let end = v + a * d;
            assert!(
                (end.abs() - LEAVE_TO * w).abs() < 1e-15,
                "{v} + {a}·{d} = {end}"
            );
            assert_eq!(end.signum(), d.signum());
        }
    }

    #[test]
    fn corrections_that_cross_no_band_are_taken_in_full() {
        let w = 1e-3;
        // sliding on, sliding into the band, inside the band, a small exit, no band
        for (v, d, width) in [
            (5e-3, 1.0, w),
            (5e-3, -4.5e-3, w),
            (5e-3, -5.9e-3, w),
            (3e-4, -1e-3, w),
            (3e-4, 1.5e-3, w),
            (5e-3, -1.0, 0.0),
            (5e-3, -1.0, f64::INFINITY),
            (5e-3, 0.0, w),
        ] {
            assert_eq!(transition_limit(v, d, width), 1.0, "{v} {d} {width}");
        }
    }

    #[test]
    fn the_limit_is_a_positive_fraction() {
        // exactly at the band's edge going across: lands at the inner point
        let a = transition_limit(1e-3 + 1e-18, -1e9, 1e-3);
        assert!(a > 0.0 && a < 1e-9, "{a}");
    }
}
