//! The `subcount` command-line program.
fn main() {}
