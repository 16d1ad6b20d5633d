//! Experiments: each returns data and prints nothing.

pub mod bench;
