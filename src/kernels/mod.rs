//! Kernels: one file per reduced integral. Each turns a model's integral into integrands the
//! rules of [`crate::quadrature`] consume, by a closed-form reduction it cites, and reports
//! `Err(evaluations spent)` where it does not reach its tolerance, so that the table kind that
//! tried it falls back (the order is in each kind's file under [`crate::table`]).

pub mod classic_lobes;
pub mod dielectric_average;
pub mod ggx_polar;
pub mod ltc_check;
pub mod ltc_fit;
pub mod ltc_lights;
pub mod ltc_lm;
pub mod ltc_polygon;
pub mod ltc_probe;
pub mod ltc_reference;
pub mod ltc_rule;
pub mod micro_normals;
pub mod roughness_fibre;
pub mod sheen_azimuth;
pub mod sheen_polar;
pub mod vgroove;
