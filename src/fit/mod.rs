//! Fits: tables without textures. For a table of one to three axes, the cheapest
//! polynomial (global, in warped variables, or piecewise) that meets a requested max
//! error against the table's *exact* function — the integrals, not the texels — with its
//! error measured on a dense validation set and searched for between its points, emitted
//! as a shader function by `crate::encode::function`.
//!
//! What to fit is decided here ([`target`]: the exact function; [`vars`]: the variables,
//! including the corner pair of grazing smooth microfacet integrals; [`search`]: forms and
//! their Pareto front); how to fit is `crate::approx`'s, which knows nothing of BRDFs.

pub mod form;
pub mod reference;
pub mod search;
pub mod target;
pub mod vars;
