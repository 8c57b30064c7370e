//! brdfbake: exact BRDF lookup tables for real-time renderers.

pub mod integrate;
pub mod model;
