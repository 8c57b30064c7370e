//! The physics: pure functions of f64, one small type per term, each with its formula and
//! its source. Nothing here knows about tables or files.

pub mod brdf;
pub mod classic;
pub mod diffuse;
pub mod fresnel;
pub mod masking;
pub mod ndf;
pub mod roughness;

pub use brdf::{Brdf, Specular};
pub use diffuse::{DiffuseLobe, DiffuseModel};
pub use fresnel::Fresnel;
pub use masking::Masking;
pub use ndf::{Ndf, NdfKind};
pub use roughness::RoughnessQuantity;
pub mod energy;
pub mod fresnel_axis;
pub use fresnel_axis::FresnelQuantity;
pub mod btdf;
pub mod ltc;
pub mod schlick_dielectric;
