//! The validation grid of a fit (`super::target`'s dense set): how many points per axis,
//! and its axes for a table. Apart from the target so that a preset can check that a table
//! can be fitted (`fit`) without depending on how its values are computed.

use crate::lut::{Axis, Convention, Quantity};
use crate::table::spec::MIN_COSINE;
use crate::table::TableSpec;

/// Least points per axis of the validation set.
pub const MIN_POINTS: usize = 129;
/// Most points per axis (a 2D set of 513² is 263k points).
pub const MAX_POINTS: usize = 513;
/// Grid points for an axis of `size` texels in `convention`.
pub fn grid_points(size: usize, convention: Convention) -> usize {
    if size <= 1 {
        return 1;
    }
    let mut g = match convention {
        Convention::Centers => 2 * size + 1,
        Convention::Endpoints => 2 * size - 1,
    };
    while g < MIN_POINTS {
        g = 2 * g - 1;
    }
    g
}

/// The validation grid's axes for `spec`: endpoint grids over each axis' parameter range
/// (warp and clamp kept), a cosine end at 0 moved to [`MIN_COSINE`]. `Err` if a grid would
/// exceed [`MAX_POINTS`] or the table is not one a fit takes.
pub fn grid_axes(spec: &TableSpec) -> Result<Vec<Axis>, String> {
    if spec.kind.is_ltc() {
        return Err(format!(
            "a {} table is an LTC fit itself, not an integral a polynomial approximates",
            spec.kind.name()
        ));
    }
    let mut axes = Vec::with_capacity(spec.axes.len());
    for a in &spec.axes {
        let g = grid_points(a.size, a.convention);
        if g > MAX_POINTS {
            return Err(format!(
                "axis {} has {} texels: its validation grid would need {g} points (at most {MAX_POINTS}); \
                 fit a table of at most {} texels per axis",
                a.name,
                a.size,
                (MAX_POINTS - 1) / 2
            ));
        }
        let mut b = a.clone();
        b.size = g;
        // endpoints over the whole parameter range: the range ends, and (by grid_points'
        // count) every texel and every midpoint between two
        b.convention = if g == 1 {
            Convention::Centers
        } else {
            Convention::Endpoints
        };
        if a.quantity == Quantity::Cosine && g > 1 {
            for end in 0..2 {
                let x = b.warp.coordinate(b.range[end]);
                if x < MIN_COSINE {
                    b.range[end] = b.warp.parameter(MIN_COSINE);
                }
            }
        }
        axes.push(b);
    }
    Ok(axes)
}

/// How many points off the grid the check set holds.
pub const CHECK_POINTS: usize = 1024;

/// The validation points a table's fit uses (the grid's and the check set's: the search's
/// time and memory grow with them), or why the table cannot be fitted.
pub fn points(spec: &TableSpec) -> Result<usize, String> {
    let axes = grid_axes(spec)?;
    Ok(axes.iter().map(|x| x.size).product::<usize>() + CHECK_POINTS)
}

/// Search CPU seconds per validation point (measured: 66k points, 2 threads, 80 s wall).
pub const SECONDS_PER_POINT: f64 = 2.5e-3;
/// Peak bytes per validation point (the exchange's rows: up to 66 unknowns of 8 bytes, the
/// coarse copy, variables and values).
pub const BYTES_PER_POINT: u64 = 1200;
