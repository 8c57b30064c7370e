//! What the texel code of every table kind shares: a texel's result (values, error
//! estimates, evaluations), the fibres of texels along the Fresnel and roughness axes, the collection of
//! texels that missed their tolerance, and the BRDF of each roughness texel. A leaf of
//! [`crate::table`]: the kinds and the texel loop of `mod.rs` use it.

use super::spec::TableSpec;
use crate::model::Brdf;
use rayon::prelude::*;

/// How many of the texels that missed the tolerance an error names.
pub const MISSES_SHOWN: usize = 5;

/// The result of one texel: a value and an error estimate per channel, and the
/// evaluations it cost.
#[derive(Clone, Debug)]
pub(crate) struct TexelResult {
    pub value: Vec<f64>,
    pub error: Vec<f64>,
    pub evals: u64,
}

impl TexelResult {
    pub fn exact(value: Vec<f64>) -> Self {
        let n = value.len();
        TexelResult {
            value,
            error: vec![0.0; n],
            evals: 0,
        }
    }
}

/// A table kind's fibre path: the texel results of the line of texels along axis 2 (every
/// slice) at axis-0 index `i` and axis-1 index `j`, in slice order. For kinds whose texels
/// along axis 2 (the Fresnel axis) share every quadrature node but a per-slice factor, so
/// that one task integrates them together (`energy::fibre_fn`).
pub(crate) type FibreFn = Box<dyn Fn(usize, usize) -> Vec<TexelResult> + Sync>;

/// A table kind's roughness-fibre path: the texel results of the line of texels along axis 1
/// (every roughness) at axis-0 index `i` and slice `z`, in roughness order, for the slices
/// `slices` marks. For kinds whose integrals at one view and slice have the same panel
/// breaks at every roughness (the η < 1 dielectric slices: `dielectric_schlick`); the kind's
/// [`FibreFn`] leaves those slices' texels to it.
pub(crate) struct RoughnessFibres {
    pub slices: Vec<bool>,
    pub run: Box<dyn Fn(usize, usize) -> Vec<TexelResult> + Sync>,
}

/// Collects the texel channels whose estimate exceeds `limit`: their count and the
/// [`MISSES_SHOWN`] largest (ties: lowest texel index first, so the list is deterministic).
#[derive(Debug, Default)]
pub(crate) struct Misses {
    pub count: usize,
    /// (estimate, texel index, channel)
    pub worst: Vec<(f64, usize, usize)>,
}

impl Misses {
    /// Records channel `c` of texel `i` if `e` exceeds `limit` (or is NaN).
    #[inline]
    pub fn check(&mut self, limit: f64, i: usize, c: usize, e: f64) {
        if e <= limit {
            return;
        }
        self.count += 1;
        let e = if e.is_nan() { f64::INFINITY } else { e };
        self.worst.push((e, i, c));
        if self.worst.len() > 4 * MISSES_SHOWN {
            self.trim();
        }
    }

    pub fn trim(&mut self) {
        self.worst
            .sort_by(|a, b| b.0.total_cmp(&a.0).then(a.1.cmp(&b.1)).then(a.2.cmp(&b.2)));
        self.worst.truncate(MISSES_SHOWN);
    }

    /// Adds another collection's misses.
    pub fn merge(&mut self, o: Misses) {
        self.count += o.count;
        self.worst.extend(o.worst);
        self.trim();
    }
}

/// One BRDF per roughness texel, with any lazily built numeric G1 forced now (in parallel,
/// deterministically: each is a pure function of its α).
pub(crate) fn brdfs_per_roughness(spec: &TableSpec) -> Vec<Brdf> {
    let r = spec.axes.last().expect("roughness axis");
    (0..r.size)
        .into_par_iter()
        .map(|i| {
            let b = spec
                .model
                .brdf(r.alpha(i).expect("roughness axis"))
                .expect("validated");
            if let Some(s) = &b.specular {
                s.prepare();
            }
            b
        })
        .collect()
}
