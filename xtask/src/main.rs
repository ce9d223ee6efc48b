//! Project chores for subcount.
fn main() {}
