//! `flowmbd-string`: studies of the flowmbd toolkit (not implemented yet; see the README's crate map).

fn main() {
    eprintln!("flowmbd-string: no studies are available yet in this build");
    std::process::exit(2);
}
