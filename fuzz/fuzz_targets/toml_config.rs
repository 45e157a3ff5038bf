//! TOML configuration reader of the apps (`flowmbd_cli::config::parse_config`) on the real
//! configurations (belt drive, tire rig, generated tire, the library study configurations of
//! the ANCF drive, speed loss and string modes (the rig also with a prescribed wheel-centre
//! motion, seed `rig_centre_motion.toml`); Kerkkänen's dynamic beam cases and Lin's beam
//! and slab of `flowmbd-beam` / `flowmbd-reduce`, issue 35): a configuration or a one-line error naming a
//! line inside the file; parsed configurations are validated without panicking. The same
//! bodies run as property tests in `apps/cli/tests/config_fuzz.rs`.
#![no_main]
use drives::ancf_study::AncfStudyConfig;
use drives::speed_loss_study::SpeedLossStudyConfig;
use fe_model::generate::TireConfig;
use drives::fead::FeadConfig;
use flowmbd_cases::ancf_dynamics::{PendulumCase, SpinningCase};
use flowmbd_cases::lin::beam::LinBeamConfig;
use flowmbd_cases::lin::slab_sim::SlabSimConfig;
use flowing::string_study::ModesConfig;
use tire::RigConfig;
use flowmbd_cli::{PartialRules, Validate};
use flowmbd_cli::config::parse_config;
use libfuzzer_sys::fuzz_target;
use std::path::Path;

fn check<C>(text: &str)
where
    C: serde::de::DeserializeOwned + serde::Serialize + Default + Validate + PartialRules,
{
    match parse_config::<C>(text, Path::new("fuzz.toml")) {
        Ok(c) => {
            let _ = c.validate();
        }
        Err(e) => assert!(!e.to_string().contains('\n'), "one-line errors"),
    }
}

fuzz_target!(|data: &[u8]| {
    if let Ok(text) = std::str::from_utf8(data) {
        check::<RigConfig>(text);
        check::<FeadConfig>(text);
        check::<TireConfig>(text);
        check::<AncfStudyConfig>(text);
        check::<SpeedLossStudyConfig>(text);
        check::<ModesConfig>(text);
        check::<PendulumCase>(text);
        check::<SpinningCase>(text);
        check::<LinBeamConfig>(text);
        check::<SlabSimConfig>(text);
    }
});
