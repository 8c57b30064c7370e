//! brdfbake: exact BRDF lookup tables for real-time renderers.

pub mod integrate;
pub mod lut;
pub mod model;
pub mod table;

pub use lut::Lut;
pub use table::{bake, TableSpec};
