//! Shared pieces of the tire studies: the tire source (generated truck tire, reduced and saved,
//! or a saved reduced tire reused) and error mapping.

use flowmbd_cli::{StudyContext, StudyError, set_given};
use tire::{
    CacheUse, GroundKind, ReducedTire, Reducing, RigConfig, TireError, rig_input_error,
    tire_input_error,
};

pub use tire::TireSource;

/// Map a library error: invalid input → exit 2 naming the item
/// ([`tire::tire_input_error`]), otherwise numerical (exit 1).
pub fn tire_err(e: TireError) -> StudyError {
    match tire_input_error(e) {
        Ok(field) => StudyError::Input(field),
        Err(other) => StudyError::numerical(other),
    }
}

/// Map an error of the rig (cleat test): like [`tire_err`], with the rig's invalid items named
/// by their configuration path (`rig.damping.mode1`, not `damping.mode1`).
pub fn rig_err(e: TireError) -> StudyError {
    match rig_input_error(e) {
        Ok(field) => StudyError::Input(field),
        Err(other) => StudyError::numerical(other),
    }
}

/// The app's side of [`TireSource`]: the reduced tire with the app's error mapping and
/// progress line.
pub trait TireSourceExt {
    /// The FE model (imported or generated), errors mapped by [`tire_err`].
    fn fe_model_or_err(&self) -> Result<tire::TireFe, StudyError>;
    /// The reduced tire: loaded from its file or cache, or reduced and saved
    /// ([`TireSource::reduced_tire`]); unless `quiet`, a line on stderr says when the tire is
    /// reduced and why.
    fn reduced(&self, quiet: bool) -> Result<ReducedTire, StudyError>;
}

impl TireSourceExt for TireSource {
    fn fe_model_or_err(&self) -> Result<tire::TireFe, StudyError> {
        self.fe_model().map_err(tire_err)
    }

    fn reduced(&self, quiet: bool) -> Result<ReducedTire, StudyError> {
        let mut notice = |r: &Reducing<'_>| {
            if quiet {
                return;
            }
            let what = if r.imported { "imported" } else { "generated" };
            match (r.file, r.replacing) {
                (None, _) => {
                    eprintln!("reducing the {what} tire (not saved: tire.reduced_file is empty)")
                }
                (Some(f), None) => {
                    eprintln!("reducing the {what} tire (saved to `{}`)", f.display())
                }
                (Some(f), Some(why)) => eprintln!(
                    "reducing the {what} tire again: the cached `{}` {why}; it is replaced",
                    f.display()
                ),
            }
        };
        let got = self.reduced_tire(&mut notice).map_err(tire_err)?;
        if let (CacheUse::NotSaved(why), false) = (&got.cache, quiet) {
            eprintln!("warning: the reduced tire was not cached ({why})");
        }
        Ok(got.tire)
    }
}

/// The reduced tire of `source` ([`TireSourceExt::reduced`]) and what `run` makes of it behind a
/// progress bar over `steps` units of work labelled `label`: `run` gets the reduced tire and
/// the progress callback of the library's run, which takes the fraction done.
pub fn run_reduced<T>(
    ctx: &StudyContext, source: &TireSource, steps: usize, label: &str,
    run: impl FnOnce(&ReducedTire, &mut dyn FnMut(f64)) -> Result<T, StudyError>,
) -> Result<(ReducedTire, T), StudyError> {
    let red = source.reduced(ctx.quiet)?;
    let n = steps as f64;
    let bar = ctx.progress(n, label);
    let out = run(&red, &mut |f| bar.set(f * n))?;
    bar.finish();
    Ok((red, out))
}

/// The ground named on the command line (`drum` or `road`, the values clap accepts).
pub fn ground_named(name: &str) -> GroundKind {
    if name == "road" {
        GroundKind::Road
    } else {
        GroundKind::Drum
    }
}

/// Command-line overrides of the rig shared by `cleat` and `sweep` (the sensitivity studies of
/// Ribaric §8.4–8.5 without editing a configuration file).
#[derive(Debug, Clone, Default, clap::Args)]
pub struct RigFlags {
    /// Ground: `drum` (R = 1.25 m) or `road` (overrides `rig.ground.kind`).
    #[arg(long, value_parser = ["drum", "road"])]
    pub ground: Option<String>,
    /// Coulomb friction coefficient (overrides `rig.rolling.friction`; §8.4.3: 0.85 or 0).
    #[arg(long)]
    pub friction: Option<f64>,
    /// Damping ratio at both target modes (overrides `rig.damping.zeta1/zeta2`; §8.4.1: 0.01
    /// or 0.03).
    #[arg(long)]
    pub zeta: Option<f64>,
    /// Roll without the cleat (steady rolling).
    #[arg(long)]
    pub no_cleat: bool,
    /// Time step [s] (overrides `rig.rolling.time_step`).
    #[arg(long)]
    pub time_step: Option<f64>,
    /// Sub-steps per time step while the cleat passes the patch (overrides
    /// `rig.impact.substeps`; 1 = uniform steps, e.g. with `--time-step 5e-5` for converged
    /// cleat amplitudes).
    #[arg(long)]
    pub substeps: Option<usize>,
    /// Contact nodes of the reduction (overrides `tire.reduction.contact_nodes`; §8.4.2: 95 or
    /// 252). The cached reduced tire follows the count; the generated tire's candidate patch
    /// is widened when needed.
    #[arg(long)]
    pub contact_nodes: Option<usize>,
}

impl RigFlags {
    /// Apply the overrides.
    pub fn apply(&self, tire: &mut TireSource, rig: &mut RigConfig) {
        if let Some(g) = &self.ground {
            rig.ground.kind = ground_named(g);
        }
        set_given(&mut rig.rolling.friction, self.friction);
        if let Some(z) = self.zeta {
            rig.damping.zeta1 = z;
            rig.damping.zeta2 = z;
        }
        if self.no_cleat {
            rig.ground.cleat = false;
        }
        set_given(&mut rig.rolling.time_step, self.time_step);
        set_given(&mut rig.impact.substeps, self.substeps);
        if let Some(n) = self.contact_nodes {
            // (the cached file's name follows the reduction, see `TireSource::reduced_path`)
            tire.reduction.contact_nodes = n;
            // the generator's candidate set grows about linearly with the patch angle (99 nodes
            // at the default ±8°): widen it so that n nodes exist (252 nodes: ±25.5°)
            let need = 8.0 * 1.2 * n as f64 / 95.0;
            if tire.generator.patch_half_angle_deg < need {
                tire.generator.patch_half_angle_deg = need;
            }
        }
    }
}
