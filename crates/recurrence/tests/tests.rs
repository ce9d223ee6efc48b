//! Integration tests of the `recurrence` crate, one module per topic.

mod closed_form;
mod generated_rust;
mod paper;
mod props;
mod queries;
mod render;
mod util;
