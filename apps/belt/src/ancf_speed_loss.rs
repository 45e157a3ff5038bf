//! `flowmbd-belt speed-loss --model ancf`: one driver speed of the speed-loss study computed
//! with the ANCF belt ([`crate::ancf_drive_model::AncfDrive`]) through the same procedure
//! ([`speed_loss_sweep`]) as the flowing model.

use crate::ancf_drive_model::{AncfDrive, AncfSettings};
use crate::speed_loss::{Case, Point};
use flowing::belt::study::{Sample, SpeedLossPoint};
use flowing::belt::{BeltDriveConfig, SpeedLossSettings, analytical_speed_loss, speed_loss_sweep};
use flowmbd_cli::{InputError, StudyContext, StudyError};
use std::sync::atomic::{AtomicUsize, Ordering};

/// Run the procedure at `settings.omega_driver` with the ANCF belt; the step is
/// `ancf.step`. Returns the case and the number of coordinates of the model.
pub fn run_case(
    drive: &BeltDriveConfig,
    ancf: &AncfSettings,
    settings: &SpeedLossSettings,
    every: usize,
    ctx: &StudyContext,
    done: &AtomicUsize,
    report: &(dyn Fn(usize) + Sync),
) -> Result<(Case, usize), StudyError> {
    let start = std::time::Instant::now();
    let mut model = AncfDrive::new(drive, ancf).map_err(|e| match e {
        ancf::AncfError::InvalidInput { item, reason } => {
            StudyError::Input(InputError::new(item, reason))
        }
        other => StudyError::numerical(other),
    })?;
    let n = mbd_core::SecondOrderSystem::n_q(model.drive());
    // the derived parameters of the Table 6-1 → ANCF mapping, for the record
    ctx.out.write_json(
        &format!("ancf_mapping_omega_{:.1}.json", settings.omega_driver),
        model.mapping(),
    )?;
    let settings = SpeedLossSettings {
        step: ancf.step,
        ..settings.clone()
    };
    let name = format!("history_ancf_omega_{:.1}.csv", settings.omega_driver);
    let mut csv = ctx
        .out
        .csv(&name, &["t", "omega_driver", "omega_driven", "load_torque"])?;
    let mut io_err = None;
    let mut k = 0usize;
    let mut found = 0usize;
    let result = speed_loss_sweep(&mut model, &settings, |_, s: Sample| {
        k += 1;
        if k.is_multiple_of(every)
            && let Err(e) = csv.row(&[s.t, s.omega_driver, s.omega_driven, s.load])
        {
            io_err.get_or_insert(e);
        }
        if s.points > found {
            found = s.points;
            report(done.fetch_add(1, Ordering::Relaxed) + 1);
        }
    });
    csv.flush()?;
    if let Some(e) = io_err {
        return Err(e.into());
    }
    let (points, stats) = result.map_err(|f| StudyError::Numerical {
        message: format!("ANCF, ω₁ = {} rad/s: {}", settings.omega_driver, f.error),
        partial: Some(serde_json::json!({
            "omega_driver": settings.omega_driver,
            "points": f.points,
        })),
    })?;
    let extra = points.len().saturating_sub(found);
    report(done.fetch_add(extra, Ordering::Relaxed) + extra);
    let g = &drive.geometry;
    let case = Case {
        omega_driver: settings.omega_driver,
        analytical: points
            .iter()
            .map(|p| {
                analytical_speed_loss(
                    g.radius_driven,
                    drive.belt.tension,
                    drive.belt.ea,
                    p.torque,
                    settings.omega_driver,
                )
            })
            .collect(),
        points: points
            .iter()
            .map(|p: &SpeedLossPoint| Point {
                torque: p.torque,
                delta_omega: p.delta_omega,
            })
            .collect(),
        stats,
        wall_time_s: start.elapsed().as_secs_f64(),
    };
    Ok((case, n))
}
