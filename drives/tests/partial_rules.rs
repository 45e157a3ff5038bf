//! The belt layout's merge rules reach every configuration that holds a layout (issue 33):
//! a partial configuration that gives `belt_length` drops the default `tension`, new
//! `pulleys` drop the default `tensioner` and the default drive's friction (issue 34 item 3).
//! Reference: the defaults edited by hand.

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

// New pulleys are the user's drive: its friction is the layouts' default
// (`BeltContact::default`, the `tanh_slip` law), not the default drive's κ = 40 s/m, unless the
// user states one; the rest of the default contact (the penalty law) stays.
#[test]
fn new_pulleys_drop_the_default_friction() {
    use belt::BeltContact;
    use contact::friction::FrictionSpec;
    let d = FeadConfig::default();
    let kappa40 = FrictionSpec::Tanh {
        mu: 1.2,
        kappa: 40.0,
    };
    assert_eq!(d.drive.contact.friction, kappa40);
    assert_ne!(BeltContact::default().friction, kappa40);
    let two = toml::Value::try_from(&d.drive.pulleys[..2]).unwrap();
    let c: FeadConfig = read(&format!("[drive]\npulleys = {two}\n"));
    assert_eq!(c.drive.contact, BeltContact::default());
    // a contact table of the user's without friction: its keys, the layouts' default friction
    let c: FeadConfig = read(&format!(
        "[drive]\npulleys = {two}\n[drive.contact]\npenalty_linear = 1e8\n"
    ));
    assert_eq!(c.drive.contact.penalty_linear, 1e8);
    assert_eq!(c.drive.contact.friction, BeltContact::default().friction);
    // the user's friction is kept
    let c: FeadConfig = read(&format!(
        "[drive]\npulleys = {two}\n[drive.contact.friction]\nlaw = \"tanh\"\nmu = 0.9\nkappa = 40.0\n"
    ));
    assert_eq!(
        c.drive.contact.friction,
        FrictionSpec::Tanh {
            mu: 0.9,
            kappa: 40.0
        }
    );
    // the default drive edited without new pulleys keeps its κ = 40 s/m (Table 6-1 likewise)
    let c: FeadConfig = read("[drive]\ntension = 500.0\n");
    assert_eq!(c.drive.contact.friction, kappa40);
    let c: SpeedLossStudyConfig = read("[drive]\ntension = 200.0\n");
    assert_eq!(c.drive.contact.friction, kappa40);
    let c: DesignConfig = read(&format!("[drive]\npulleys = {two}\n"));
    assert_eq!(c.drive.contact, BeltContact::default());
}
