//! The flowing-material belt drive (Ribaric ch. 5–6): a belt loop whose FE mesh stays in place
//! while the material flows through it, reduced to contact-node static modes plus truncated
//! free-node modes, on rigid pulleys with penalty contact and friction; and the rotating-mesh
//! nodal belt it replaces (Ribaric (5.7)). Both are built from a resolved [`belt::Drive`] and
//! implement [`belt::BeltModel`].
//!
//! - [`FlowingSettings`], [`BeltMesh`]: the models' settings (element lengths, reduction);
//! - [`BeltFe`], [`FlowingBasis`]: the loop, its matrices and the reduction basis (5.9)–(5.13);
//! - [`FlowingBelt`]: the flowing-material equations (5.14) as a [`mbd_core::SecondOrderSystem`];
//! - [`nodal::NodalBelt`]: the rotating-mesh nodal equations (5.7).
//!
//! The speed-loss procedure, Bechtel's line (6.3) and the studies live in the `drives` crate.

pub mod config;
pub mod contact;
mod coordinates;
pub mod flowing_system;
pub mod model;
pub mod nodal;
mod snapshot;
mod statics;
pub mod wave;

pub use config::{
    AxialForce, BeltEquations, BeltMesh, BeltReduction, BendingForce, ContactVelocity,
    FlowingSettings, ViscousForce,
};
pub use coordinates::DriveCoordinates;
pub use flowing_system::{FlowingBelt, NodeReport};
pub use model::{BeltFe, FlowingBasis};
pub use nodal::NodalBelt;
pub use snapshot::LINEAR_FORCE_MEASURE;

/// Ribaric Table 6-1's drive for the tests: driver at 0 (speed `speed` \[rad/s\]), driven
/// free with 0.013 kg m² against `load` \[N m\], T0 = 310 N, Ribaric's contact (κ = 40 s/m).
#[cfg(test)]
pub(crate) fn table_6_1(speed: f64, load: f64) -> belt::Drive {
    use belt::{Layout, Signal};
    let mut l = Layout::table_6_1();
    l.pulleys[0].motion = belt::Motion::speed(Signal::constant(speed));
    l.pulleys[1].motion = belt::Motion::load(0.013, Signal::constant(load));
    l.resolve().unwrap()
}

/// Ribaric Table 6-1's drive for the tests with the sharp friction law at the default slip
/// scale (`tanh_slip`, μ = 1.2, `v_s` = [`::contact::friction::spec::DEFAULT_SLIP_VELOCITY`]):
/// driver at `speed` \[rad/s\], driven free with 0.013 kg m² and no load.
#[cfg(test)]
pub(crate) fn table_6_1_sharp(speed: f64) -> belt::Drive {
    use belt::{Layout, Signal};
    let mut l = Layout::table_6_1();
    l.pulleys[0].motion = belt::Motion::speed(Signal::constant(speed));
    l.pulleys[1].motion = belt::Motion::load(0.013, Signal::constant(0.0));
    l.contact.friction = ::contact::friction::FrictionSpec::tanh_slip(1.2);
    l.resolve().unwrap()
}

/// The transition-aware correction limit of a belt model (`sys`) at the mounted state `q`
/// moving at 3 m/s, for a correction of the driven pulley's speed alone (velocity index
/// `dof`, contact radius `radius` \[m\]): `slips(v)` lists `(pulley, penetration, slip)` of the
/// model's contact points from its force evaluation.
///
/// Reference (closed form): the slip `t·V − ωR` changes by exactly `−R Δω` on the driven
/// pulley's points and not elsewhere, so the limit is the planar rule
/// ([`::contact::friction::transition_limit`]) on these changes, and the limited correction
/// lands the limiting point at `±w/2` on its own side and no point across the band.
#[cfg(test)]
pub(crate) fn check_pulley_speed_limit<S: mbd_core::SecondOrderSystem>(
    sys: &S, q: &[f64], dof: usize, radius: f64, slips: impl Fn(&[f64]) -> Vec<(usize, f64, f64)>,
) {
    use ::contact::friction::transition_limit;
    let w = ::contact::friction::spec::DEFAULT_SLIP_VELOCITY;
    let speed = 3.0;
    let mut v = vec![0.0; q.len()];
    v[0] = speed;
    // the driven pulley 10 mm/s slower than the belt: its points slide forward
    v[dof] = (speed - 0.01) / radius;
    let mut dv = vec![0.0; q.len()];
    // a correction that would make it 10 mm/s faster than the belt
    dv[dof] = 0.02 / radius;
    let dq = vec![0.0; q.len()];
    let mut ws = mbd_core::Workspace::new();
    let alpha = sys.correction_limit(0.0, q, &v, &dq, &dv, &mut ws).unwrap();
    let before = slips(&v);
    let driven: Vec<f64> = before
        .iter()
        .filter(|(p, pen, _)| *p == 1 && *pen > 0.0)
        .map(|c| c.2)
        .collect();
    assert!(
        driven.len() > 5,
        "{} driven points in contact",
        driven.len()
    );
    let expected = driven
        .iter()
        .map(|&s| transition_limit(s, -0.02, w))
        .fold(1.0, f64::min);
    assert!(alpha < 0.6 && alpha > 0.4, "{alpha}");
    assert!(
        (alpha - expected).abs() <= 1e-9 * expected,
        "{alpha} vs {expected}"
    );
    let limited: Vec<f64> = v.iter().zip(&dv).map(|(a, b)| a + alpha * b).collect();
    let after = slips(&limited);
    assert_eq!(after.len(), before.len());
    let mut closest = f64::INFINITY;
    for (a, b) in before.iter().zip(&after) {
        assert_eq!(a.0, b.0);
        if a.1 > 0.0 && a.2.abs() > w {
            // no point crosses the band
            assert!(
                a.2 * b.2 > 0.0 || b.2.abs() <= w * (1.0 + 1e-6),
                "{a:?} -> {b:?}"
            );
        }
        if a.1 > 0.0 && a.0 == 1 {
            closest = closest.min((b.2 - 0.5 * w).abs());
        }
    }
    // the limiting point lands at +w/2 (the slip is linear in ω: exactly)
    assert!(closest <= 1e-6 * w, "{closest:e}");
}
