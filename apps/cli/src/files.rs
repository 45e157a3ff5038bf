//! Checks of input paths named in a configuration or on the command line, with messages that
//! say what is wrong: missing, a directory, or unreadable.

use crate::error::InputError;
use std::path::Path;

/// `Ok` when `path` is a readable regular file; otherwise an [`InputError`] for `field`
/// saying whether the path does not exist, is a directory, or cannot be inspected
/// ([`mbd_core::validate::check::input_file`], shared with the library configurations).
pub fn check_input_file(field: &str, path: &Path) -> Result<(), InputError> {
    mbd_core::validate::check::input_file(field, path)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The three cases a user meets, told apart (issue #20: a directory was "does not exist").
    #[test]
    fn missing_directory_and_file_are_told_apart() {
        let dir = crate::testing::fresh_dir("flowmbd-cli", "files");
        let e = check_input_file("tire.import.mass", &dir).unwrap_err();
        assert!(e.to_string().contains("is a directory"), "{e}");
        assert!(e.to_string().starts_with("tire.import.mass"), "{e}");
        let e = check_input_file("x", &dir.join("none.mtx")).unwrap_err();
        assert!(e.to_string().contains("does not exist"), "{e}");
        let f = dir.join("K.mtx");
        std::fs::write(&f, "x").unwrap();
        assert!(check_input_file("x", &f).is_ok());
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
