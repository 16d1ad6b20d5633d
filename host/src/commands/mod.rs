//! The subcommands' bodies, one module each: they parse nothing and print results.

pub mod bench;
pub mod firmware_reference;
pub mod fly;
pub mod inspect;
pub mod map;
pub mod render;
pub mod report;
pub mod specular;
pub mod table;

pub use bench::{bench, BenchArgs};
pub use firmware_reference::{firmware_reference, FirmwareReferenceArgs};
pub use fly::{fly, FlyArgs};
pub use inspect::{inspect, InspectArgs};
pub use map::{map, MapCommandArgs};
pub use render::{render, RenderArgs};
pub use report::{report, ReportArgs};
pub use specular::{specular, SpecularArgs};
pub use table::{table, TableArgs};
