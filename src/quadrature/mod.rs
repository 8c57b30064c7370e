//! Quadrature rules that know nothing of BRDFs: Gauss–Kronrod tables and the deterministic
//! adaptive integrator, nested Clenshaw–Curtis rules (1D and the tensor driver), Chebyshev
//! interpolation and lines of texels interpolated from it, and the evaluation budget that
//! nested integrals share. The hemisphere's parameterization is in [`crate::hemisphere`], the
//! model-specific reductions in [`crate::kernels`].

pub mod adaptive;
pub mod budget;
pub mod cc1d;
pub mod chebyshev;
pub mod clenshaw_curtis;
pub mod gauss;
pub mod interp1d;
pub mod trapezoid;

pub use adaptive::{integrate, integrate1, Estimate, Tolerance};
