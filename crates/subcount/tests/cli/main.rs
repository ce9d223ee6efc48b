//! End-to-end tests of the `subcount` binary.

mod matrix;
mod schemes;
mod util;
