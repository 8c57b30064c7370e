//! Fits: tables without textures. For a table of one to three axes, the cheapest
//! polynomial (global, in warped variables, or piecewise) that meets a requested max
//! error against the table's *exact* function — the integrals, not the texels — with its
//! error measured on a dense validation set and searched for between its points, emitted
//! as a shader function by `crate::encode::function`.
//!
//! What to fit is decided here ([`target`]: the exact function; [`vars`]: the variables,
//! including the corner pair of grazing smooth microfacet integrals; [`search`]: forms and
//! their Pareto front); how to fit is `crate::approx`'s, which knows nothing of BRDFs.

pub mod emit;
pub mod figures;
pub mod form;
pub mod grid;
pub mod reference;
pub mod request;
pub mod resolution;
pub mod search;
pub mod target;
pub mod vars;

use crate::approx::program::Program;
use crate::table::TableSpec;

/// What [`verify`] found: the largest |program − exact| per channel over the points, and
/// where.
#[derive(Clone, Debug)]
pub struct Verified {
    pub error: Vec<f64>,
    pub argmax: Vec<Vec<f64>>,
    pub points: usize,
}

/// Re-evaluates a fitted function (its program, in f32 arithmetic as the code runs) at
/// `n` pseudo-random points of the table's domain — none of them validation points, a
/// fixed sequence (a splitmix64 stream from `seed`) so runs agree — against the exact
/// integral at quadrature tolerance `tol`.
pub fn verify(
    spec: &TableSpec,
    inputs: &[target::Input],
    program: &Program,
    n: usize,
    seed: u64,
    tol: f64,
) -> Result<Verified, String> {
    let mut state = seed;
    let mut next = || {
        state = state.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = state;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        ((z ^ (z >> 31)) >> 11) as f64 / (1u64 << 53) as f64
    };
    let nc = program.outputs.len();
    let mut error = vec![0.0f64; nc];
    let mut argmax = vec![Vec::new(); nc];
    for _ in 0..n {
        let x: Vec<f64> = inputs
            .iter()
            .map(|i| i.domain[0] + (i.domain[1] - i.domain[0]) * next())
            .collect();
        let exact = target::exact_at(spec, &x, tol)?;
        let y = program.eval_f32(&x);
        for c in 0..nc {
            let e = (y[c] - exact[c]).abs();
            if e >= error[c] {
                error[c] = e;
                argmax[c] = x.clone();
            }
        }
    }
    Ok(Verified {
        error,
        argmax,
        points: n,
    })
}
