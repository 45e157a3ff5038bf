//! The scalar root finders of the workspace, in one place: bisection of a bracket on a
//! monotone predicate ([`bisect`]), the Illinois variant of regula falsi with a bisection
//! safeguard ([`false_position`], [`illinois`]) and the unbracketed secant method for costly
//! residuals ([`secant`]: the ANCF tensioner arm's static angle, each residual a static solve). No crate writes its own bisection or
//! false-position loop on a scalar function: the tensioner's static angle, the sliding speed
//! of a friction law, Bechtel's steady tension, the Coulomb disc projection, Dormand–Prince's
//! event location and the tire's static deflection under a load use these. No crate of the
//! workspace's library notes offers them, and each is a few lines.

/// When [`bisect`] stops: after `max_iterations` halvings, or as soon as the bracket width
/// `hi − lo` is at most `max(abs_width, rel_width·|hi|)` (in the unit of the argument), or when
/// the mid-point can no longer be told from an end (the bracket is one ulp wide).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Stop {
    /// Maximum number of halvings.
    pub max_iterations: usize,
    /// Absolute width of the final bracket.
    pub abs_width: f64,
    /// Width of the final bracket relative to `|hi|`.
    pub rel_width: f64,
}

impl Stop {
    /// `n` halvings at most, no width test (the bracket is halved `n` times or to one ulp).
    pub fn iterations(n: usize) -> Self {
        Self {
            max_iterations: n,
            abs_width: 0.0,
            rel_width: 0.0,
        }
    }

    /// At most `n` halvings, stopping at the absolute bracket width `width`.
    pub fn absolute(n: usize, width: f64) -> Self {
        Self {
            abs_width: width,
            ..Self::iterations(n)
        }
    }

    /// At most `n` halvings, stopping at the bracket width `rel·|hi|`.
    pub fn relative(n: usize, rel: f64) -> Self {
        Self {
            rel_width: rel,
            ..Self::iterations(n)
        }
    }
}

/// Bisection of the bracket `[lo, hi]` (`lo < hi`) of the point where the monotone predicate
/// `above` switches from `false` (at `lo`) to `true` (at `hi`); the ends are not evaluated.
/// Each step evaluates `above` at the mid-point `½(lo + hi)` and replaces `hi` by it when
/// `true`, `lo` otherwise, until [`Stop`]. Returns the final bracket `(lo, hi)`: a root of a
/// continuous `g` that changes sign is found with `above = |x| g(x)·sign(g(lo)) ≤ 0`; a
/// threshold (first `x` at which something happens) is the returned `hi`.
pub fn bisect(
    mut lo: f64, mut hi: f64, mut above: impl FnMut(f64) -> bool, stop: Stop,
) -> (f64, f64) {
    for _ in 0..stop.max_iterations {
        let mid = 0.5 * (lo + hi);
        if mid <= lo || mid >= hi {
            break;
        }
        if above(mid) {
            hi = mid;
        } else {
            lo = mid;
        }
        if hi - lo <= stop.abs_width.max(stop.rel_width * hi.abs()) {
            break;
        }
    }
    (lo, hi)
}

/// When [`false_position`] stops: after `max_iterations` evaluations, when the bracket is at
/// most `width` wide (in the unit of the argument), or when `|g|` at the point just evaluated is
/// at most `residual` (`0`: only an exact zero, which then shrinks the bracket from the right).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FalsePositionStop {
    /// Maximum number of evaluations of `g`.
    pub max_iterations: usize,
    /// Width of the final bracket.
    pub width: f64,
    /// Residual `|g|` accepted at a point (`0`: none but an exact zero).
    pub residual: f64,
}

/// What [`false_position`] found: the last point it evaluated and the final bracket `[a, b]`
/// (`g(a)` and `g(b)` of opposite signs, or zero).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Bracketed {
    /// The last point evaluated (the end of the bracket where no evaluation was needed).
    pub last: f64,
    /// Left end of the final bracket.
    pub a: f64,
    /// Right end of the final bracket.
    pub b: f64,
}

/// Root of `g` in `[a, b]` with `g(a) = ga`, `g(b) = gb` of opposite signs: the Illinois
/// variant of regula falsi (the retained end's value halved when the same end is kept twice;
/// Dowell & Jarratt 1971), a bisection step whenever the secant point
/// `b − g_b (b − a)/(g_b − g_a)` leaves the bracket, until [`FalsePositionStop`]. An exact zero
/// at `m` (with `residual = 0`) shrinks the bracket from the right, so the earliest zero of a
/// bracket holding several is approached (event location). An error of `g` is returned as is.
pub fn false_position<E>(
    mut g: impl FnMut(f64) -> Result<f64, E>, mut a: f64, mut b: f64, mut ga: f64, mut gb: f64,
    stop: FalsePositionStop,
) -> Result<Bracketed, E> {
    let mut side = 0i8;
    let mut last = b;
    for _ in 0..stop.max_iterations {
        if (b - a).abs() <= stop.width {
            break;
        }
        let mut m = if ga != gb {
            b - gb * (b - a) / (gb - ga)
        } else {
            0.5 * (a + b)
        };
        if !(m > a && m < b) {
            m = 0.5 * (a + b);
        }
        let gm = g(m)?;
        last = m;
        if stop.residual > 0.0 && gm.abs() <= stop.residual {
            break;
        }
        if gm == 0.0 {
            // the earliest zero might be left of m: shrink the bracket from the right
            b = m;
            gb = gm;
            if ga == 0.0 {
                break;
            }
            continue;
        }
        if (gm > 0.0) == (ga > 0.0) {
            a = m;
            ga = gm;
            if side == -1 {
                gb *= 0.5;
            }
            side = -1;
        } else {
            b = m;
            gb = gm;
            if side == 1 {
                ga *= 0.5;
            }
            side = 1;
        }
    }
    Ok(Bracketed { last, a, b })
}

/// [`false_position`] of an infallible `g` to the bracket width `tol` (at most 200 steps, no
/// residual test): the right end `b` of the final bracket (Dormand–Prince's event location).
pub fn illinois(g: impl Fn(f64) -> f64, a: f64, b: f64, ga: f64, gb: f64, tol: f64) -> f64 {
    let stop = FalsePositionStop {
        max_iterations: 200,
        width: tol,
        residual: 0.0,
    };
    match false_position(
        |x| Ok::<f64, std::convert::Infallible>(g(x)),
        a,
        b,
        ga,
        gb,
        stop,
    ) {
        Ok(r) => r.b,
        Err(e) => match e {},
    }
}

/// When [`secant`] stops: after `max_iterations` new evaluations, or as soon as a step
/// `|x_{k+1} − x_k|` is at most `step` (in the unit of the argument).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SecantStop {
    /// Maximum number of evaluations of `g` (besides the given `g(x0)`).
    pub max_iterations: usize,
    /// Step length at which the iteration has converged.
    pub step: f64,
}

/// What [`secant`] found: the last point evaluated and whether a step below
/// [`SecantStop::step`] was reached (`false`: out of iterations, or a zero or non-finite
/// secant slope).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Secant {
    /// The last point at which `g` was evaluated.
    pub x: f64,
    /// `g` at [`Secant::x`].
    pub g: f64,
    /// Whether the last step was at most [`SecantStop::step`].
    pub converged: bool,
}

/// Root of `g` by the secant method `x_{k+1} = x_k − g_k (x_k − x_{k−1})/(g_k − g_{k−1})` from
/// `x0` (with `g(x0) = g0` known) and the first trial `x1`, without a bracket: for a smooth `g`
/// whose evaluation is costly (superlinear convergence, one evaluation per step). Stops as
/// [`SecantStop`] says; an error of `g` is returned as is.
pub fn secant<E>(
    mut g: impl FnMut(f64) -> Result<f64, E>, mut x0: f64, mut g0: f64, mut x1: f64,
    stop: SecantStop,
) -> Result<Secant, E> {
    let mut last = Secant {
        x: x0,
        g: g0,
        converged: false,
    };
    for _ in 0..stop.max_iterations {
        let g1 = g(x1)?;
        last = Secant {
            x: x1,
            g: g1,
            converged: (x1 - x0).abs() <= stop.step,
        };
        if last.converged {
            break;
        }
        let slope = (g1 - g0) / (x1 - x0);
        if !(slope.is_finite() && slope != 0.0) {
            break;
        }
        (x0, g0) = (x1, g1);
        x1 -= g1 / slope;
    }
    Ok(last)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bisect_finds_sqrt2_to_the_width_asked() {
        // closed form √2 (root of x² − 2 on [0, 2])
        let (lo, hi) = bisect(0.0, 2.0, |x| x * x - 2.0 >= 0.0, Stop::absolute(200, 1e-12));
        assert!(hi - lo <= 1e-12);
        assert!(lo <= 2f64.sqrt() && 2f64.sqrt() <= hi);
        // relative width: 1e-14·|hi|
        let (lo, hi) = bisect(0.0, 2.0, |x| x * x >= 2.0, Stop::relative(200, 1e-14));
        assert!(hi - lo <= 1e-14 * hi && (0.5 * (lo + hi) - 2f64.sqrt()).abs() < 2e-14);
        // a fixed number of halvings: width 2/2^10
        let (lo, hi) = bisect(0.0, 2.0, |x| x * x >= 2.0, Stop::iterations(10));
        assert_eq!(hi - lo, 2.0 / 1024.0);
        // to one ulp: the ends are neighbouring doubles around √2
        let (lo, hi) = bisect(1.0, 2.0, |x| x * x >= 2.0, Stop::iterations(500));
        assert_eq!(hi, f64::from_bits(lo.to_bits() + 1));
        assert!(lo * lo < 2.0 && hi * hi >= 2.0);
    }

    #[test]
    fn bisect_finds_a_threshold_of_a_step_predicate() {
        // predicate switching at 0.3 exactly (threshold; independent value 0.3)
        let (lo, hi) = bisect(0.0, 1.0, |x| x >= 0.3, Stop::iterations(60));
        assert!(lo < 0.3 && hi >= 0.3 && hi - lo < 1e-15);
    }

    #[test]
    fn illinois_finds_cos_root_and_the_earliest_of_two() {
        // cos x = 0 at π/2 (closed form)
        let g = |x: f64| x.cos();
        let r = illinois(g, 1.0, 2.0, g(1.0), g(2.0), 1e-13);
        assert!((r - std::f64::consts::FRAC_PI_2).abs() < 1e-12);
        // a bracket holding a double root 0.25 and a sign change at 0.5 (g = (x−¼)²(x−½)):
        // the sign change is bracketed, found to the tolerance
        let g = |x: f64| (x - 0.25).powi(2) * (x - 0.5);
        let r = illinois(g, 0.4, 1.0, g(0.4), g(1.0), 1e-12);
        assert!((r - 0.5).abs() < 1e-11, "{r}");
    }

    #[test]
    fn false_position_stops_on_the_residual_and_passes_errors_on() {
        // x³ = 2 on [1, 2] (closed form 2^(1/3)), stopped at |g| ≤ 1e-12
        let stop = FalsePositionStop {
            max_iterations: 100,
            width: 1e-14,
            residual: 1e-12,
        };
        let g = |x: f64| Ok::<f64, ()>(x.powi(3) - 2.0);
        let r = false_position(g, 1.0, 2.0, -1.0, 6.0, stop).unwrap();
        assert!((r.last.powi(3) - 2.0).abs() <= 1e-12);
        assert!((r.last - 2f64.cbrt()).abs() < 1e-12);
        // an error of g ends the search
        let fails = |x: f64| if x > 1.2 { Err("beyond") } else { Ok(x - 1.5) };
        assert_eq!(
            false_position(fails, 1.0, 2.0, -0.5, 0.5, stop),
            Err("beyond")
        );
    }

    #[test]
    fn secant_finds_the_cube_root_superlinearly() {
        // closed form: the real root 2 of x³ − 8
        let mut calls = 0;
        let r = secant(
            |x| {
                calls += 1;
                Ok::<f64, ()>(x * x * x - 8.0)
            },
            1.0,
            -7.0,
            1.5,
            SecantStop {
                max_iterations: 50,
                step: 1e-13,
            },
        )
        .unwrap();
        assert!(r.converged && (r.x - 2.0).abs() < 1e-12, "{r:?}");
        assert!(calls < 15, "{calls} evaluations");
        // a flat residual stops without converging; an error is passed through
        let stop = SecantStop {
            max_iterations: 9,
            step: 1e-12,
        };
        let flat = secant(|_| Ok::<f64, ()>(1.0), 0.0, 1.0, 1.0, stop);
        assert!(!flat.unwrap().converged);
        let err = secant(|_| Err::<f64, &str>("boom"), 0.0, 1.0, 1.0, stop);
        assert_eq!(err, Err("boom"));
    }
}
