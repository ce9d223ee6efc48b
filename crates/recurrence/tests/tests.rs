//! Integration tests of the `recurrence` crate, one module per topic.

mod closed_form;
mod props;
mod util;
