//! The belt layout's merge rules reach every configuration that holds a layout (issue 33):
//! a partial configuration that gives `belt_length` drops the default `tension`, new
//! `pulleys` drop the default `tensioner`. Reference: the defaults edited by hand.

use drives::fead::FeadConfig;
use drives::fead_design::DesignConfig;
use drives::speed_loss_study::SpeedLossStudyConfig;
use mbd_core::config::{PartialRules, from_partial};

fn read<C>(text: &str) -> C
where
    C: serde::Serialize + serde::de::DeserializeOwned + Default + PartialRules,
{
    from_partial(toml::from_str(text).unwrap()).unwrap()
}

#[test]
fn a_belt_length_drops_the_default_tension() {
    let c: FeadConfig = read("[drive]\nbelt_length = 1.3\n");
    let mut expected = FeadConfig::default();
    assert!(expected.drive.tension.is_some());
    expected.drive.tension = None;
    expected.drive.belt_length = Some(1.3);
    assert_eq!(c.drive, expected.drive);

    let c: SpeedLossStudyConfig = read("[drive]\nbelt_length = 1.3\n");
    assert_eq!((c.drive.tension, c.drive.belt_length), (None, Some(1.3)));
    let c: DesignConfig = read("[drive]\nbelt_length = 1.3\n");
    assert_eq!((c.drive.tension, c.drive.belt_length), (None, Some(1.3)));
}

#[test]
fn new_pulleys_drop_the_default_tensioner() {
    let d = FeadConfig::default();
    assert!(d.drive.tensioner.is_some());
    let two = &d.drive.pulleys[..2];
    let text = format!(
        "[drive]\npulleys = {}\n",
        toml::Value::try_from(two).unwrap()
    );
    let c: FeadConfig = read(&text);
    assert_eq!(c.drive.pulleys, two);
    assert_eq!(c.drive.tensioner, None);
    // a table of its own that gives no pulleys keeps the default tensioner
    let c: FeadConfig = read("[drive]\ntension = 500.0\n");
    assert_eq!(c.drive.tensioner, d.drive.tensioner);
}
