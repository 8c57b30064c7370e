//! Quadrature: fixed rules, deterministic adaptive integration, interpolation of smooth
//! functions, and the half-vector parameterization of the hemisphere used by every
//! reflectance integral. This folder knows integrands, not tables.

pub mod adaptive;
pub mod budget;
pub mod cc1d;
pub mod chebyshev;
pub mod classic_lobes;
pub mod gauss;
pub mod ggx_polar;
pub mod hemisphere;
pub mod interp1d;
pub mod monte_carlo;
pub mod sheen_azimuth;
pub mod tensor;
pub mod vgroove;

pub use adaptive::{integrate, integrate1, Estimate, Tolerance};
