//! What a fit approximates: a table's exact function — the integrals the table's texels
//! hold, at any point of its axes' ranges — on a dense *validation set*, and at any other
//! point on demand.
//!
//! The validation set is a grid per axis that holds every texel of the table, every point
//! midway between two texels and both range ends: for N texels at centers, the 2N + 1
//! points lo + (hi − lo)·k/(2N) of the axis' parameter (ends, texel borders, centers); for
//! N texels at endpoints, the 2N − 1 points k/(2(N − 1)). Grids under [`MIN_POINTS`] are
//! halved again until they reach it. Its values are baked by the library's own integrators
//! (`table::bake` of the same kind and model on the grid's axes, at [`TOLERANCE`]): exact
//! integrals at those coordinates, not interpolated texels. A cosine end at 0, where the
//! kinds that divide by n·v have no value, is evaluated at [`MIN_COSINE`] (the limit, to
//! 1e-12).

pub use super::grid::{grid_axes, grid_points, CHECK_POINTS, MAX_POINTS, MIN_POINTS};
use crate::lut::Quantity;
use crate::table::spec::MIN_COSINE;
use crate::table::{BakeOptions, TableSpec};

/// The quadrature tolerance of the exact values: far below any error a fit states (the
/// values are kept as f32, relative error 6e-8, which bounds what a fit can resolve).
pub const TOLERANCE: f64 = 1e-8;

/// One parameter of the fitted function: a table axis, in its own quantity.
#[derive(Clone, Debug, PartialEq)]
pub struct Input {
    pub name: String,
    pub quantity: Quantity,
    /// The coordinates the table spans, [lo, hi]: the fit's domain along this axis.
    pub domain: [f64; 2],
}

/// The exact function on the validation set.
#[derive(Clone, Debug)]
pub struct Target {
    /// The table (its kind's channels are fitted, unscaled).
    pub spec: TableSpec,
    pub channels: Vec<String>,
    pub inputs: Vec<Input>,
    /// Per axis, the grid's coordinates (as a caller passes them: before any clamp).
    pub coords: Vec<Vec<f64>>,
    /// Per channel, the exact value at every point (axis 0 fastest).
    pub values: Vec<Vec<f64>>,
    /// Points off the grid ([`check_points`]), coordinates as a caller passes them, and the
    /// exact channels at each: a fit's stated error is the larger of its errors on the grid
    /// and here, so a fit that is good at the grid's points and wrong between them (a
    /// piecewise fit near grazing views, seen off by twice its grid error) says so.
    pub check: Vec<Vec<f64>>,
    pub check_values: Vec<Vec<f64>>,
    /// Quadrature evaluations spent.
    pub evaluations: u64,
}

impl Target {
    pub fn points(&self) -> usize {
        self.coords.iter().map(|c| c.len()).product()
    }

    /// The coordinates of point `i`.
    pub fn point(&self, i: usize) -> Vec<f64> {
        let mut rest = i;
        self.coords
            .iter()
            .map(|c| {
                let k = rest % c.len();
                rest /= c.len();
                c[k]
            })
            .collect()
    }

    /// Grid points per axis.
    pub fn shape(&self) -> Vec<usize> {
        self.coords.iter().map(|c| c.len()).collect()
    }
}

/// Bakes the exact function on the validation set. `deadline`: `--max-time`.
pub fn build(
    spec: &TableSpec,
    deadline: Option<&crate::deadline::Deadline>,
) -> Result<Target, String> {
    let axes = grid_axes(spec)?;
    let mut grid = spec.clone();
    grid.name = format!("{}-validation", spec.name);
    grid.axes = axes.clone();
    grid.tolerance = spec.tolerance.min(TOLERANCE);
    // a cosine end moved off 0 is still refused by a kind that allows 0 nowhere else: keep
    // the spec's own message then
    grid.validate()?;
    let lut = crate::table::bake_with(
        &grid,
        &BakeOptions {
            deadline,
            ..Default::default()
        },
    )
    .map_err(|e| e.to_string())?;
    let nc = lut.channels.len();
    let n = lut.texel_count();
    let values: Vec<Vec<f64>> = (0..nc)
        .map(|c| (0..n).map(|i| lut.data[i * nc + c] as f64).collect())
        .collect();
    let coords: Vec<Vec<f64>> = axes
        .iter()
        .map(|a| (0..a.size).map(|i| a.nominal_coord(i)).collect())
        .collect();
    let inputs = inputs(spec);
    let check = check_points(&inputs, &coords);
    let check_values = {
        use rayon::prelude::*;
        check
            .par_iter()
            .map(|x| {
                if deadline.is_some_and(|d| d.passed()) {
                    return Err("stopped".to_string());
                }
                exact_at(spec, x, grid.tolerance)
            })
            .collect::<Result<Vec<_>, String>>()?
    };
    Ok(Target {
        spec: spec.clone(),
        channels: lut.channels.iter().map(|c| c.name.clone()).collect(),
        inputs,
        coords,
        values,
        check,
        check_values,
        evaluations: lut.evaluations,
    })
}

/// The fitted function's inputs: the table's axes, their quantities and coordinate spans.
pub fn inputs(spec: &TableSpec) -> Vec<Input> {
    spec.axes
        .iter()
        .map(|a| Input {
            name: a.name.clone(),
            quantity: a.quantity,
            domain: a.coordinate_span(),
        })
        .collect()
}

/// The check set: [`CHECK_POINTS`] points drawn from a fixed splitmix64 stream, uniform over
/// the domain, except that a quarter of them put a cosine axis in the grid's first four
/// cells (grazing views, where the split sum and the albedos change fastest and a fit's
/// variables, √μ and μ/(μ + α), bend most). None is a grid point but by chance.
pub fn check_points(inputs: &[Input], coords: &[Vec<f64>]) -> Vec<Vec<f64>> {
    let mut state = 0x5EED_F17Eu64;
    let mut next = || {
        state = state.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = state;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        ((z ^ (z >> 31)) >> 11) as f64 / (1u64 << 53) as f64
    };
    (0..CHECK_POINTS)
        .map(|k| {
            inputs
                .iter()
                .zip(coords)
                .map(|(i, c)| {
                    let [lo, hi] = i.domain;
                    let u = next();
                    if k % 4 == 0 && i.quantity == Quantity::Cosine && c.len() > 4 {
                        let end = c[4].min(hi);
                        lo + (end - lo) * u
                    } else {
                        lo + (hi - lo) * u
                    }
                })
                .collect()
        })
        .collect()
}

/// The exact channels at the coordinates `x` (one per axis), at quadrature tolerance `tol`
/// (`readback::exact_at`: the library's integrators at one point).
pub fn exact_at(spec: &TableSpec, x: &[f64], tol: f64) -> Result<Vec<f64>, String> {
    let x: Vec<f64> = spec
        .axes
        .iter()
        .zip(x)
        .map(|(a, &v)| {
            if a.quantity == Quantity::Cosine {
                v.max(MIN_COSINE)
            } else {
                v
            }
        })
        .collect();
    crate::readback::exact_at(spec, &x, tol).map(|(v, _)| v)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::lut::Convention;

    #[test]
    fn grids_hold_texels_midpoints_and_ends() {
        assert_eq!(grid_points(128, Convention::Centers), 257);
        assert_eq!(grid_points(32, Convention::Centers), 129);
        assert_eq!(grid_points(16, Convention::Centers), 129);
        assert_eq!(grid_points(16, Convention::Endpoints), 241);
        assert_eq!(grid_points(1, Convention::Centers), 1);
        // 16 centres: 33 points, halved twice: 129 — every texel centre is a grid point
        let g = grid_points(16, Convention::Centers);
        for i in 0..16 {
            let centre = (i as f64 + 0.5) / 16.0;
            let k = centre * (g - 1) as f64;
            assert_eq!(k, k.round(), "texel {i}");
        }
    }
}
