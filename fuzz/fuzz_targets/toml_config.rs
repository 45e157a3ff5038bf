//! TOML configuration reader of the apps (`flowmbd_cli::config::parse_config`) on two real
//! configurations (belt drive, tire rig): a configuration or a one-line error naming a line
//! inside the file; parsed configurations are validated.
#![no_main]
use flowing::belt::BeltDriveConfig;
use flowing::tire::RigConfig;
use flowmbd_cli::Validate;
use flowmbd_cli::config::parse_config;
use libfuzzer_sys::fuzz_target;
use std::path::Path;

fn check<C: serde::de::DeserializeOwned + Validate>(text: &str) {
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
        check::<BeltDriveConfig>(text);
    }
});
