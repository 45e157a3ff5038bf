//! [`ancf_equations!`]: the equations of motion the planar and the plate ANCF drive share
//! (issue 33 item 2), written once for both.

/// Inside `impl SecondOrderSystem for` an ANCF drive ([`crate::belt_drive::BeltDrive`],
/// [`crate::plate::belt_drive::PlateBeltDrive`]), the methods both drives' equations of motion
/// share: the constant sparse mass `M` (Kerkkänen (2.26) and the free pulleys' inertias
/// (3.26)), the forces `Q_e + Q_c` (2.27), (3.27) with the free pulleys' right-hand sides
/// `s τ − T_a(t) − c ω` (3.26) at the pulleys' travel-sense speeds
/// ([`PulleyCoordinates::speeds_and_loads`](crate::mounted::PulleyCoordinates::speeds_and_loads)),
/// and their tangent.
///
/// The drive provides the fields `pattern` (the system matrices' [`crate::sparse::Pattern`]),
/// `mass_values` (`M` in that pattern), `pulley_dofs` ([`crate::mounted::PulleyCoordinates`])
/// and `spec.pulleys`, and the inherent methods `forces_with(t, q, v, omegas, loads, f, ws)`
/// and `force_tangent_with(t, q, v, omegas, ws)` (the forces and their tangent at given
/// pulley speeds and loads); the impl writes [`n_q`](mbd_core::SecondOrderSystem::n_q) and
/// [`dof_name`](mbd_core::SecondOrderSystem::dof_name) itself.
macro_rules! ancf_equations {
    () => {
        fn mass_is_constant(&self) -> bool {
            true
        }
        fn mass(&self, _t: f64, _q: &[f64]) -> Result<mbd_core::SysMatrix, mbd_core::MbdError> {
            let values = self.mass_values.clone();
            Ok(mbd_core::SysMatrix::Sparse(self.pattern.to_matrix(values)))
        }
        fn forces(
            &self, t: f64, q: &[f64], v: &[f64], f: &mut [f64], ws: &mut mbd_core::Workspace,
        ) -> Result<(), mbd_core::MbdError> {
            let pulleys = &self.spec.pulleys;
            let (omegas, loads) = self.pulley_dofs.speeds_and_loads(pulleys, t, v)?;
            let np = pulleys.len();
            self.forces_with(t, q, v, &omegas[..np], &loads[..np], f, ws);
            Ok(())
        }
        fn force_tangent(
            &self, t: f64, q: &[f64], v: &[f64], ws: &mut mbd_core::Workspace,
        ) -> Result<Option<mbd_core::system::ForceTangent>, mbd_core::MbdError> {
            let omegas = self.pulley_dofs.speeds(&self.spec.pulleys, t, v);
            Ok(Some(self.force_tangent_with(t, q, v, &omegas, ws)))
        }
    };
}

pub(crate) use ancf_equations;
