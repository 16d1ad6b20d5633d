//! Experiments: each returns data and prints nothing.

pub mod bench;
pub mod causes;
pub mod claims;
pub mod differences;
pub mod fly;
pub mod glint;
pub mod heights;
pub mod inspect;
pub mod paper;
pub mod specular;
pub mod synthetic;
pub mod table;
