//! The paper cases of flowmbd: the example models and studies of the dissertations, built from
//! the library crates and shared by the apps, the validation tests, benchmarks and examples.
//! Library crates hold no paper case; they live here (or in the app that alone runs them).
//!
//! * [`lin`]: Lin (2005) Appendix A beam (ch. 6.2, 7.1, 8.5 studies) and Appendix B slab with
//!   its simulations 1–3;
//! * [`ancf_beams`]: Kerkkänen (2006) §2.4 static beam set-ups (Tables 2.1–2.4) and the ground
//!   contact case;
//! * [`ancf_dynamics`]: Kerkkänen §2.4 dynamic cases (falling pendulum, spinning beam);
//! * [`beam_study`]: the five studies of `flowmbd-beam` on those cases (summaries, checks and
//!   CSV series shared by the app and the Python package);
//! * [`chain`]: a hanging spherical-joint chain (multibody benchmarks and examples);
//! * [`slider_crank`]: the rigid slider-crank, and [`slider_crank_study`] the
//!   `flowmbd-belt demo` study on it.

pub mod ancf_beams;
pub mod ancf_dynamics;
pub mod beam_study;
pub mod chain;
pub mod lin;
pub mod slider_crank;
pub mod slider_crank_study;
