//! Real subdivision for every built-in scheme.
