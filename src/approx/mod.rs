//! Approximation rules that know nothing of BRDFs (as `quadrature/` for integrals): the
//! discrete minimax solver, multivariate polynomial bases and their evaluation plans, and
//! the search for the worst point of an error curve. `crate::fit` decides what to fit.

pub mod minimax;
pub mod poly;
pub mod polyfit;
pub mod program;
