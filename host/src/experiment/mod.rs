//! Experiments: each returns data and prints nothing.

pub mod bench;
pub mod fly;
pub mod reference;
pub mod table;
