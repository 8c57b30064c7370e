//! brdfbake: exact BRDF lookup tables for real-time renderers.
//!
//! The flow runs one way: a preset ([`preset`]) is validated into [`TableSpec`]s, each is
//! baked ([`table`]) by the rules of [`quadrature`] over the [`hemisphere`], fed by the
//! model-specific [`kernels`], of the physics ([`model`]) into a [`Lut`],
//! encoded by pure encoders ([`encode`]) with its metadata ([`meta`]), and written
//! atomically by [`write`](mod@write), the only module that touches the disk.
//!
//! ```
//! use brdfbake::lut::{Axis, Convention, Quantity};
//! use brdfbake::model::{Fresnel, Masking, NdfKind, RoughnessQuantity};
//! use brdfbake::table::{bake, ModelSpec, Storage, TableKind, TableSpec};
//!
//! let spec = TableSpec {
//!     name: "e".into(),
//!     kind: TableKind::Albedo,
//!     model: ModelSpec { ndf: Some(NdfKind::Ggx), masking: Masking::SmithHeightCorrelated,
//!                        fresnel: Fresnel::None, diffuse_weight: 0.0, diffuse_model: Default::default(), classic: None },
//!     axes: vec![
//!         Axis { name: "cos_theta_v".into(), quantity: Quantity::Cosine, size: 4,
//!                range: [0.0, 1.0], convention: Convention::Centers, warp: Default::default(), clamp: None },
//!         Axis { name: "roughness".into(), quantity: Quantity::Roughness(RoughnessQuantity::Perceptual),
//!                size: 4, range: [0.0, 1.0], convention: Convention::Centers,
//!                warp: Default::default(), clamp: None },
//!     ],
//!     dfg_layout: None, cloth: false, cloth_alpha_min: None, ltc_channels: None, storage: Storage::F32, tolerance: 1e-7,
//! };
//! let lut = bake(&spec).unwrap();
//! let e = lut.lookup(&[0.5, 0.5])[0];
//! assert!(e > 0.0 && e <= 1.0);
//! ```

pub mod approx;
pub mod cli;
pub mod deadline;
pub mod digest;
pub mod encode;
pub mod engine;
pub mod engines;
pub mod fit;
pub mod hemisphere;
pub mod input;
pub mod kernels;
pub mod laws;
pub mod lut;
pub mod merl;
pub mod meta;
pub mod model;
pub mod names;
pub mod numerics;
pub mod numfmt;
pub mod pipeline;
pub mod preset;
pub mod presets;
pub mod quadrature;
pub mod readback;
pub mod report;
pub mod resources;
pub mod signals;
pub mod table;
pub mod write;

pub use lut::Lut;
pub use table::{bake, TableSpec};
