//! [`forward_dynamics!`](crate::forward_dynamics): a wrapper model's unconstrained dynamics
//! taken from the model it wraps.

/// Inside an `impl SecondOrderSystem for Wrapper`, forwards the unconstrained dynamics to the
/// wrapped model in the field `$inner`: [`n_q`], [`dof_name`], [`mass_is_constant`], [`mass`],
/// [`forces`] and [`force_tangent`] (Lin (2.27)'s `M(q)` and `f(t, q, v)` with their tangent),
/// and the Newton hooks [`predict_increment`] and [`correction_limit`].
///
/// For the wrappers that change something else and keep the coordinates, mass and forces of
/// the model they wrap: the unilateral rows of
/// [`ActiveSetSystem`](crate::integrators::ActiveSetSystem), the belt-model interface of
/// `ancf::MountedBelt`. Every other method keeps the trait's default or is written by the
/// wrapper.
///
/// [`n_q`]: crate::SecondOrderSystem::n_q
/// [`dof_name`]: crate::SecondOrderSystem::dof_name
/// [`mass_is_constant`]: crate::SecondOrderSystem::mass_is_constant
/// [`mass`]: crate::SecondOrderSystem::mass
/// [`forces`]: crate::SecondOrderSystem::forces
/// [`force_tangent`]: crate::SecondOrderSystem::force_tangent
/// [`predict_increment`]: crate::SecondOrderSystem::predict_increment
/// [`correction_limit`]: crate::SecondOrderSystem::correction_limit
#[macro_export]
macro_rules! forward_dynamics {
    ($inner:ident) => {
        fn n_q(&self) -> usize {
            self.$inner.n_q()
        }
        fn dof_name(&self, dof: usize) -> String {
            self.$inner.dof_name(dof)
        }
        fn mass_is_constant(&self) -> bool {
            self.$inner.mass_is_constant()
        }
        fn mass(&self, t: f64, q: &[f64]) -> Result<$crate::SysMatrix, $crate::MbdError> {
            self.$inner.mass(t, q)
        }
        fn forces(
            &self, t: f64, q: &[f64], v: &[f64], f: &mut [f64], ws: &mut $crate::Workspace,
        ) -> Result<(), $crate::MbdError> {
            self.$inner.forces(t, q, v, f, ws)
        }
        fn force_tangent(
            &self, t: f64, q: &[f64], v: &[f64], ws: &mut $crate::Workspace,
        ) -> Result<Option<$crate::ForceTangent>, $crate::MbdError> {
            self.$inner.force_tangent(t, q, v, ws)
        }
        fn predict_increment(
            &self, t: f64, q: &[f64], v: &[f64], vdot: &[f64], h: f64, dq: &mut [f64],
        ) -> bool {
            self.$inner.predict_increment(t, q, v, vdot, h, dq)
        }
        fn correction_limit(
            &self, t: f64, q: &[f64], v: &[f64], dq: &[f64], dv: &[f64], ws: &mut $crate::Workspace,
        ) -> Result<f64, $crate::MbdError> {
            self.$inner.correction_limit(t, q, v, dq, dv, ws)
        }
    };
}
