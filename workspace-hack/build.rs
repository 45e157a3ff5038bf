//! Empty: the `[build-dependencies]` entry unifies the features of the proc-macro dependencies
//! (host builds), which cargo resolves apart from the target's (see `Cargo.toml`).
fn main() {}
