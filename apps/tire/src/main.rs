//! `flowmbd-tire`: studies of the flowmbd toolkit (not implemented yet; see the README's crate map).

fn main() {
    eprintln!("flowmbd-tire: no studies are available yet in this build");
    std::process::exit(2);
}
