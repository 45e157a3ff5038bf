//! The fead summary's `meaning` names the drive that ran (issue 39 item 3: a user's 2- or
//! 3-pulley drive is not described as the default six-pulley one). Reference: the layout's own
//! names and roles.

use drives::belt::Layout;
use drives::fead::{FeadConfig, fead_meaning};

#[test]
fn meaning_names_the_pulleys_of_the_drive() {
    let six = FeadConfig::default().drive.resolve().unwrap();
    let m = fead_meaning(&six);
    assert!(
        m.starts_with("A front-end accessory drive of 6 pulleys in travel order: "),
        "{m}"
    );
    let names = six.names();
    assert!(m.contains(&format!("{} (the crank)", names[0])), "{m}");
    let k = six.arm().unwrap().tensioner.pulley;
    assert!(
        m.contains(&format!("{} (the tensioner's idler on its arm)", names[k])),
        "{m}"
    );
    for n in &names {
        assert!(m.contains(n.as_str()), "{n} not in {m}");
    }
    // Ribaric's Table 6-1 drive: two pulleys, the second loaded, no tensioner
    let two = Layout::table_6_1().resolve().unwrap();
    let m = fead_meaning(&two);
    let names = two.names();
    let head = format!(
        "A front-end accessory drive of 2 pulleys in travel order: {} (the crank), {} (loaded), ",
        names[0], names[1]
    );
    assert!(m.starts_with(&head), "{m}");
    assert!(!m.contains("tensioner's idler"), "{m}");
}
