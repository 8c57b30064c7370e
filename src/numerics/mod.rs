//! Small shared numerics that know nothing of quadrature or BRDFs: a leaf both the rules and
//! the kernels may use.

pub mod poly;
pub mod vec3;

pub use poly::{cos_0_pi, exp_poly, sin_cos_taylor};
