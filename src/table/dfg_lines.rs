//! How a GGX dfg table is baked: by lines of texels interpolated from fewer quadratures.
//!
//! Each channel of a texel is an integral that costs ~1,000–20,000 integrand evaluations, but
//! along a line of the table it is a smooth function of the line's coordinate, so
//! [`interp1d`] computes it at Chebyshev nodes and interpolates, with the interpolation's
//! error in each texel's estimate. A table is covered by three kinds of lines:
//! - **rows** (one roughness, every view μ, in x = √μ): each node one quadrature;
//! - **grids**: lines across the table in x whose samples are whole *columns* — a column
//!   (one μ, the rows of a band of roughnesses) itself interpolated along the roughness axis
//!   (`RoughnessLine`). A grid's cost hardly grows with the table's size (a 512² table
//!   needs about the columns and column nodes of a 128² one), while rows cost per row;
//! - **strips**: columns alone, at the texel columns nearest grazing.
//!
//! Which line serves which texels was measured (filament-dfg, evaluations at 128² / 512²,
//! 2026-11-30; `plan` has the rules; the alternatives were measured before interp1d's
//! truncation estimate was doubled, which adds ~10% to any of them):
//! - *Split-sum pair.* Lobes from α = 1/64 up on a grid in (√μ, √α) (since in (√μ, ln α):
//!   `RoughnessVar::Ln`; since round 9 from α = 1/32 up, since round 11 from 1/40, see
//!   `PAIR_BANDS`): 3.8 M / 5.4 M (by rows ~6 M / ~60 M). At 512² the band [1/256, 1/64)
//!   on a grid of its own (5.6 M; by rows 7.1 M): a band goes on a grid where it holds at
//!   least `GRID_MIN_ROWS` rows, else by rows; α < 1/256 always by rows (their rows are
//!   cheap and their columns are not): 2.3 M / 3.4 M. One grid over every roughness cost
//!   19.8 M / 53.3 M: near grazing the split sum of a narrow lobe changes on the scale of α
//!   itself.
//! - *Cloth, wide lobes* (1/16 ≤ α ≤ 1): a grid in (√μ, √α), whose kernel shares its node
//!   data along a column ([`View`]): 3.6 M / 4.2 M (columns alone: 4.3 M / 17.4 M).
//! - *Cloth, narrow lobes* (α < 1/16): by rows in √μ above μ = 0.04 and texel by texel below:
//!   2.3 M at 128². From 64 narrow rows on, below μ = 0.01 a strip of columns in ln α, and
//!   above it a grid for α ≥ 1/1024 and rows below: at 512² 2.5 M + 3.8 M + 0.8 M (with the
//!   strip up to μ = 0.04: 5.8 M + 2.2 M + 0.3 M; that strip's texels one by one 20.4 M,
//!   the grid's rows by rows 4.1 M). Their albedo behaves like `exp(−c/α)` away from
//!   grazing: one grid in ln α over every narrow row cost 20.6 M at 512².
//!
//! The cloth measurements above were made with earlier cloth kernels; with the θh kernel
//! ([`sheen_azimuth`](crate::kernels::sheen_azimuth)) the cloth channel costs 0.87 M / 1.31 M
//! evaluations in all (~10 / ~13 ms of one core at 128² / 512²), and its plan was kept.
//!
//! **Error.** A grid's texel estimate is its x-interpolation's (truncation, plus the
//! Lebesgue constant times the largest column estimate at its nodes); a column's is its
//! y-interpolation's over its own nodes. Samples that serve as nodes are computed at 1/8 of
//! the tolerance of the line they serve (`NODE_TOL_FRACTION`), so that the Lebesgue
//! constant (at most 3.66 at degree 64) times their estimates stays below half the
//! tolerance; where it still does not, [`interp1d`] recomputes them tighter.
//!
//! **Determinism.** Every sample is a pure function of its coordinates, and each line is
//! processed in a fixed order; lines, and the columns of one grid degree, run in parallel
//! without changing a bit.

use super::dfg::{as_sample, cloth_sample, cloth_texel, Ctx, Dense};
use super::methods::GRID_MIN_COLUMNS;
use super::TableSpec;
use crate::kernels::sheen_azimuth::View;
use crate::lut::Axis;
use crate::quadrature::interp1d::{self, LineValues, Sample};
use rayon::prelude::*;

/// Where the lines in x = √μ are cut first: μ = 1/64 (θv ≈ 89.1°). Closer to grazing the split
/// sum of a narrow lobe changes on the scale of μ itself (the masking layer at the horizon),
/// which costs many nodes, and those nodes are the most expensive quadratures of the row:
/// the few texels there (two of a 128-texel row, eight of 512) are computed directly (as
/// columns, on a grid). Measured on karis-envbrdf's rows: 10.3 → 6.5 M evaluations at 128²,
/// 79 → 42 M at 512² (cuts at μ = 0.0025 … 0.0625 tried; 0.01 was best at both sizes). With
/// the polar kernel's outer estimate of 2026-11-30 (whole filament-dfg table, 128² / 512²,
/// x = 0.1: 2.22 M / 5.89 M): x = 0.11 2.17 / 5.92, 0.12 2.22 / 4.95, 0.125 2.13 / 5.18,
/// 0.13 2.11 / 5.22, 0.135 2.10 / 5.00, 0.14 2.16 / 7.52, 0.15 2.13 / 7.57, 0.2 2.23 / 10.2
/// (where the intervals' nodes fall makes it bumpy; 0.125 is inside the good stretch).
const GRAZING_BREAK: f64 = 0.125;

/// A second cut of the split sum's rows (not of its grids), in x = √μ: μ ≈ 0.073. A
/// narrow lobe's row changes faster below it (the masking layer at the horizon, of width
/// ~α/μ in θl), and one interpolant over [0.1, 1] then often needs degree 64 where two need
/// 16 and 32. Measured on the evaluations of filament-dfg and karis-envbrdf at 128² / 512²
/// (2026-11-30): without it 3.95 M / 8.20 M and 3.08 M / 6.90 M; at 0.27, 3.31 M / 7.88 M
/// and 2.78 M / 7.15 M (cuts at 0.15, 0.2, 0.22, 0.25–0.29, 0.3, 0.35, 0.4 tried, and
/// three cuts: 0.26–0.28 was best; the same cut on the grids' lines cost more at every
/// value tried, 0.2, 0.3, 0.5).
const ROW_BREAK: f64 = 0.27;

/// Below which, in x = √μ, the cloth channel of narrow lobes goes by columns (the strip):
/// μ = 0.04. There their albedo changes on the scale of μ, and their quadratures are the
/// costliest of a row. Measured on filament-dfg's narrow rows at 128²
/// (cut as a break, nodes at tol/8): x = 0.1, 0.2 and 0.25 gave 937, 467 and 460
/// evaluations per texel (778 texel by texel); as a break at 512², interpolating down to the
/// first texel spent 46 M of 138 M evaluations on nodes near grazing.
const CLOTH_GRAZING_BREAK: f64 = 0.2;

/// Where the strip ends, in x = √μ, when there is one: μ = 0.01. With the narrow lobes
/// above it on a grid, a lower break pays (512², narrow cloth evaluations: 7.2 M at x = 0.1,
/// 7.7 M at 0.15, 8.4 M at 0.2; the process's CPU time 0.57 against 0.63 s, best of 5).
const STRIP_BREAK: f64 = 0.1;

/// Interpolation nodes (and sample-test points) are computed at this fraction of the
/// tolerance of the line they serve, not interp1d's 1/4: a quadrature's or a column's
/// estimate comes close to what it was asked for, and at 1/4 the Lebesgue constant (2.4 at
/// degree 8, 3.66 at 64) times it exceeds the half of the tolerance beyond which interp1d
/// recomputes the nodes (measured: most narrow cloth rows then went texel by texel, before
/// that recomputation existed). The columns of the split sum and of the wide cloth lobes use
/// 1/4 for their own nodes: their kernels' estimates sit well below what they are asked for
/// (at 128², wide cloth 3.4 M against 4.1 M evaluations, the pair's grid 3.7 M against 3.8 M;
/// the narrow lobes' columns cost more at 1/4).
const NODE_TOL_FRACTION: f64 = 1.0 / 8.0;
const COLUMN_NODE_TOL_FRACTION: f64 = 1.0 / 4.0;

/// Bands of α (lower edges) whose split-sum pair may go on a grid of its own; below the
/// lowest, rows. Measured as in the module doc, and on the pair at 512² (evaluations):
/// bands from [1/256, 1/64, 1/16] 16.2 M, [1/256, 1/64] 14.4 M, [1/256] 17.3 M, [1/64]
/// 15.9 M, [1/16] 21.3 M; at 128², [1/64] (the lower band holds 8 rows) 6.2 M, [1/16]
/// 6.8 M, [1/256] 11.7 M. Since the polar kernel's outer estimate of 2026-11-30 (whole
/// filament-dfg table, 128² / 512²): [1/256, 1/64] 2.38 M / 6.22 M, [1/256, 1/32]
/// 2.22 M / 5.89 M (1/28: 2.18 / 6.03, 1/36: 2.19 / 6.01, 1/24: 2.26 / 6.48, 1/16:
/// 4.03 / 6.90; [1/128, 1/32] and [1/512, 1/32] 6.54 M and 6.90 M at 512²; three bands
/// [1/256, 1/64, x] for x = 1/4, 1/8, 1/16: 2.36–2.76 M / 6.75–7.02 M); karis-envbrdf
/// 1.97 → 1.92 M at 128². Since the polar kernel's wider warp (`WARP_LAMBDA`, 2026-11-30),
/// with [`PAIR_ROW_FIRST_DEGREE`] 20, instructions (cachegrind, one thread; filament-dfg
/// 128² / 512², karis-envbrdf): upper band from 1/32 236 / 664 / 169 M, 1/36 231 / 665 /
/// 164, 1/40 228 / 667 / 162, 1/44 239 / 682 / 159, 1/48 247 / 694 / 165.
const PAIR_BANDS: [f64; 2] = [1.0 / 256.0, 1.0 / 40.0];

/// The degree at which the interpolation of a column of `PAIR_BANDS`' band k starts
/// ([`interp1d::line_batched`]). The upper band (measured from α = 1/32 up, since round 11 from
/// 1/40) needs degree ~20–24 in ln α at most view cosines (its Chebyshev coefficients fall
/// below the column tolerance, ~1e-8, near degree 20 for μ = 0.3 … 1): from 8 that costs
/// 9 + 8 + 16 = 33 nodes, from 24 it costs 25. Measured (cachegrind, one thread, 2026-11-30):
/// filament-dfg 128² 305 → 288 M instructions, 512² 807 → 795 M, karis-envbrdf 227 → 212 M;
/// from 12 (and 6) 292 M at 128²; the lower band from 24, 12 or 6 cost more at 512² (826, 815,
/// 812 M).
const PAIR_FIRST_DEGREE: [usize; 2] = [interp1d::MIN_DEG, 24];

/// Split-sum rows of at least this α start their interpolation at degree
/// [`PAIR_ROW_FIRST_DEGREE`]: on [`ROW_BREAK`], 1] they need degree ~20–32 in √μ (from 8:
/// 9 + 8 + 16 nodes), narrower lobes ≤ 16. Measured (cachegrind, one thread, 2026-11-30):
/// filament-dfg 128² 288 → 277 M instructions, karis-envbrdf 212 → 203 M; from α = 1/128
/// 279 M and 205 M, from 1/256 281 M and 208 M, every row from 12 286 M and 209 M. (Only
/// tables below ~200 rows have such rows: larger ones put [1/256, 1/40) on a grid.) Since
/// the polar kernel's wider warp (2026-11-30), with the upper band from 1/40: from degree
/// 24 231 M and 163 M, 22 230 M and 163 M, 20 228 M and 162 M, 18 231 M and 162 M.
const PAIR_ROW_WIDE_FROM: f64 = 0.01;
const PAIR_ROW_FIRST_DEGREE: usize = 20;

/// A band goes on a grid when it holds at least this many rows: a grid costs about what
/// 24 rows do (at 512² the 32 rows of [1/256, 1/64) cost 7.1 M by rows, 5.6 M on a grid;
/// at 128², when it was a band of its own, the 16 rows of [1/64, 1/16) 1.2 M by rows,
/// 2.2 M on a grid).
const GRID_MIN_ROWS: usize = 24;

/// The strip only pays for at least this many narrow rows (at 128² its 32 rows cost 1.4 M
/// evaluations by columns against 1.2 M texel by texel; at 512², 128 rows: 5.6 M against
/// 20.4 M). Below it the rows' texels below the break are computed one by one.
const STRIP_MIN_ROWS: usize = 64;

/// The cloth channel's narrow lobes (α below this) and wide ones (α up to 1) are
/// interpolated differently: narrow ones along rows in √μ, or on the narrow strip and grid
/// below; wide ones along columns (or on a grid) in √α.
const CLOTH_NARROW_BELOW_ALPHA: f64 = 1.0 / 16.0;

/// The narrow cloth lobes from this α up go on a grid above the strip when they hold at
/// least [`STRIP_MIN_ROWS`] rows: at 512² their 112 rows cost 2.2 M evaluations above
/// μ = 0.04 against 4.1 M by rows; from 2e-4 (121 rows) the grid cost 7.0 M (the narrowest
/// lobes' albedo is ~0 but for a layer near grazing that columns resolve badly); their
/// 24 rows at 128² cost 14.7 M on a grid against 1.9 M by rows.
const NARROW_GRID_MIN_ALPHA: f64 = 1.0 / 1024.0;

/// The variable in which a line along the roughness axis is interpolated.
#[derive(Clone, Copy, Debug, PartialEq)]
enum RoughnessVar {
    /// y = √α: the wide cloth lobes (`sin^{1/α}`, analytic in 1/α away from α = 0).
    Sqrt,
    /// y = ln α: the narrow cloth lobes near grazing, whose albedo changes on the scale of α
    /// itself as α → 0, and the split sum's grids: near grazing, where most of a grid's
    /// quadratures go, the split sum changes on the scale of α too. Measured on the
    /// evaluations of filament-dfg and karis-envbrdf at 128² / 512² (2026-11-30): in √α
    /// 3.31 M / 7.88 M and 2.78 M / 7.15 M, in ln α 2.98 M / 7.56 M and 2.72 M / 6.92 M
    /// (in α: 5.38 M / 12.45 M and 4.06 M / 9.53 M; in α^p, p = 0.05 … 0.35, between √α and
    /// ln α).
    Ln,
}

impl RoughnessVar {
    fn y(self, alpha: f64) -> f64 {
        match self {
            RoughnessVar::Sqrt => alpha.sqrt(),
            RoughnessVar::Ln => alpha.ln(),
        }
    }
    fn alpha(self, y: f64) -> f64 {
        match self {
            RoughnessVar::Sqrt => y * y,
            RoughnessVar::Ln => y.exp(),
        }
    }
}

/// Some rows of the roughness axis as a line for [`interp1d`]: in order of increasing α, at
/// y = `var.y(α)`, and where each sits in the axis.
#[derive(Debug)]
struct RoughnessLine {
    var: RoughnessVar,
    /// `ys[k]` of the k-th smallest α, strictly increasing.
    ys: Vec<f64>,
    /// The k-th smallest α, exactly as the axis gives it (for texels computed directly).
    alphas: Vec<f64>,
    /// The axis index of the k-th smallest α.
    row: Vec<usize>,
    /// The degree its interpolation starts at ([`interp1d::line_batched`]).
    first_degree: usize,
}

impl RoughnessLine {
    /// The rows `rows` (in axis order); `None` if there are none, or their α is not positive
    /// and strictly monotonic along the axis (every roughness quantity is, but a line must
    /// not depend on it).
    fn new(axis: &Axis, var: RoughnessVar, mut row: Vec<usize>) -> Option<RoughnessLine> {
        let alpha = |j: usize| axis.alpha(j).unwrap_or(f64::NAN);
        if row.len() >= 2 && alpha(row[0]) > alpha(row[1]) {
            row.reverse();
        }
        let alphas: Vec<f64> = row.iter().map(|&j| alpha(j)).collect();
        let ys: Vec<f64> = alphas.iter().map(|&a| var.y(a)).collect();
        let ok = alphas.first().is_some_and(|&a| a > 0.0)
            && ys.iter().all(|y| y.is_finite())
            && ys.windows(2).all(|w| w[1] > w[0]);
        ok.then_some(RoughnessLine {
            var,
            ys,
            alphas,
            row,
            first_degree: interp1d::MIN_DEG,
        })
    }
}

/// Which lines serve which rows, per channel. Every row is on exactly one line per channel:
/// a grid, or its own row; the strip's columns serve the rows of `strip` below
/// [`STRIP_BREAK`] instead of those rows' lines.
#[derive(Debug)]
struct Plan {
    pair_grids: Vec<RoughnessLine>,
    pair_rows: Vec<usize>,
    cloth_grid: Option<RoughnessLine>,
    /// The same rows by columns alone, at every texel column (where a grid would not pay).
    cloth_columns: Option<RoughnessLine>,
    /// Narrow lobes of [`NARROW_GRID_MIN_ALPHA`], 1/16) on a grid above [`STRIP_BREAK`] (the
    /// strip serves them below).
    narrow_grid: Option<RoughnessLine>,
    cloth_rows: Vec<usize>,
    strip: Option<RoughnessLine>,
    /// Per row, the row whose values it takes: itself, or the first row of the same α where
    /// a clamp makes rows repeat one (a clamped roughness axis holds its end value in every
    /// row beyond the clamp; those rows are computed once, and no line sees the repeats).
    source_row: Vec<usize>,
}

/// The rules of the module doc for a table of `nx` texel columns and the rows of `ay`;
/// `cloth`: whether the table has the cloth channel, and its floor on α
/// (`cloth_alpha_min`, 0 when unset). Rows below the floor hold the cloth value at the
/// floor, a kink no line in α may cross: they go by rows (at the floor's α).
fn plan(nx: usize, ay: &Axis, cloth: Option<f64>) -> Plan {
    let alpha = |j: usize| ay.alpha(j).expect("roughness axis");
    let mut source_row: Vec<usize> = (0..ay.size).collect();
    for j in 1..ay.size {
        if alpha(j).to_bits() == alpha(j - 1).to_bits() {
            source_row[j] = source_row[j - 1];
        }
    }
    let own = |j: usize| source_row[j] == j;
    let rows_where = |p: &dyn Fn(f64) -> bool| -> Vec<usize> {
        (0..ay.size).filter(|&j| own(j) && p(alpha(j))).collect()
    };
    let mut pair_grids = Vec::new();
    let mut on_grid = vec![false; ay.size];
    for (k, &lo) in PAIR_BANDS.iter().enumerate() {
        let hi = PAIR_BANDS.get(k + 1).copied().unwrap_or(f64::INFINITY);
        let rows = rows_where(&|a| a >= lo && a < hi);
        if rows.len() < GRID_MIN_ROWS || nx < GRID_MIN_COLUMNS {
            continue;
        }
        if let Some(mut l) = RoughnessLine::new(ay, RoughnessVar::Ln, rows) {
            l.first_degree = PAIR_FIRST_DEGREE[k];
            for &j in &l.row {
                on_grid[j] = true;
            }
            pair_grids.push(l);
        }
    }
    let pair_rows = (0..ay.size).filter(|&j| own(j) && !on_grid[j]).collect();
    let Some(floor) = cloth else {
        return Plan {
            pair_grids,
            pair_rows,
            cloth_grid: None,
            cloth_columns: None,
            narrow_grid: None,
            cloth_rows: Vec::new(),
            strip: None,
            source_row,
        };
    };
    let rows_where = |p: &dyn Fn(f64) -> bool| rows_where(&|a| a >= floor && p(a));
    let wide = |a: f64| (CLOTH_NARROW_BELOW_ALPHA..=1.0).contains(&a);
    let wide = RoughnessLine::new(ay, RoughnessVar::Sqrt, rows_where(&wide));
    let (cloth_grid, cloth_columns) = if nx >= GRID_MIN_COLUMNS {
        (wide, None)
    } else {
        (None, wide)
    };
    let narrow = rows_where(&|a| a < CLOTH_NARROW_BELOW_ALPHA);
    let strip = if narrow.len() >= STRIP_MIN_ROWS {
        RoughnessLine::new(ay, RoughnessVar::Ln, narrow)
    } else {
        None
    };
    let band = rows_where(&|a| (NARROW_GRID_MIN_ALPHA..CLOTH_NARROW_BELOW_ALPHA).contains(&a));
    let narrow_grid = if strip.is_some() && band.len() >= STRIP_MIN_ROWS && nx >= GRID_MIN_COLUMNS {
        RoughnessLine::new(ay, RoughnessVar::Sqrt, band)
    } else {
        None
    };
    let on = |l: &Option<RoughnessLine>, j: usize| l.as_ref().is_some_and(|l| l.row.contains(&j));
    let cloth_rows = (0..ay.size)
        .filter(|&j| {
            own(j) && !on(&cloth_grid, j) && !on(&cloth_columns, j) && !on(&narrow_grid, j)
        })
        .collect();
    Plan {
        pair_grids,
        pair_rows,
        cloth_grid,
        cloth_columns,
        narrow_grid,
        cloth_rows,
        strip,
        source_row,
    }
}

fn line_sample(line: LineValues) -> Sample {
    Sample {
        value: line.value,
        error: line.error,
        evals: line.evals,
    }
}

/// `f()`, or, once `stop()` says so, a zero sample of `nc` channels (the caller then
/// discards the table).
fn unless_stopped(stop: Stop, nc: usize, f: impl FnOnce() -> Sample) -> Sample {
    if stop() {
        return Sample {
            value: vec![0.0; nc],
            error: vec![0.0; nc],
            evals: 0,
        };
    }
    f()
}

type Stop<'a> = &'a (dyn Fn() -> bool + Sync);

impl Ctx {
    /// The split-sum pair of the rows of `rl` at view μ (one table column), interpolated along
    /// the column from [`Ctx::pair_at`] values; channel `2k + c` is channel c of `rl`'s k-th
    /// row. Its texels computed directly are [`Ctx::pair`]'s.
    fn pair_column(&self, rl: &RoughnessLine, mu: f64, tol: f64, stop: Stop) -> LineValues {
        let view = View::new(mu);
        interp1d::line_with_node_tol(
            rl.first_degree,
            &rl.ys,
            &[],
            2,
            tol,
            tol * COLUMN_NODE_TOL_FRACTION,
            |y, t| {
                unless_stopped(stop, 2, || {
                    as_sample(self.pair_at(rl.var.alpha(y), &view, t))
                })
            },
            |k, t| unless_stopped(stop, 2, || as_sample(self.pair(rl.row[k], &view, t))),
        )
    }

    /// The cloth channel of the rows of `rl` at view μ, interpolated along the column from
    /// [`cloth_texel`] values, whose wide-lobe kernel shares its node data along the column
    /// ([`View`]); channel k is `rl`'s k-th row.
    fn cloth_column(
        &self,
        rl: &RoughnessLine,
        mu: f64,
        tol: f64,
        node_fraction: f64,
        stop: Stop,
    ) -> LineValues {
        let view = View::new(mu);
        let at = |alpha: f64, t: f64| {
            unless_stopped(stop, 1, || {
                cloth_sample(cloth_texel(self.sheen, &view, alpha, t))
            })
        };
        interp1d::line_with_node_tol(
            interp1d::MIN_DEG,
            &rl.ys,
            &[],
            1,
            tol,
            tol * node_fraction,
            |y, t| at(rl.var.alpha(y), t),
            |k, t| at(rl.alphas[k], t),
        )
    }
}

/// A grid: the line across the table in x = √μ from texel column `i0` on (`xs` holds every
/// column's x; cut at `breaks`) whose samples are the columns `column(μ, tol)`, each with
/// `channels` channels (its rows' channels, row-major), the columns of one batch (one
/// degree's new nodes, one interval's sample-test points or direct texel columns) computed
/// in parallel. Channel c of its texel i is channel c of the column at table column `i0 + i`.
fn grid(
    ax: &Axis,
    xs: &[f64],
    i0: usize,
    breaks: &[f64],
    channels: usize,
    tol: f64,
    column: &(dyn Fn(f64, f64) -> LineValues + Sync),
) -> LineValues {
    interp1d::line_batched(
        interp1d::MIN_DEG,
        &xs[i0..],
        breaks,
        channels,
        tol,
        tol * NODE_TOL_FRACTION,
        |ps, t| {
            ps.par_iter()
                .with_min_len(1)
                .map(|&x| line_sample(column(x * x, t)))
                .collect()
        },
        |is, t| {
            is.par_iter()
                .with_min_len(1)
                .map(|&i| line_sample(column(ax.coord(i0 + i), t)))
                .collect()
        },
    )
}

/// The split-sum pair of row j along x = √μ, cut at [`GRAZING_BREAK`] and [`ROW_BREAK`],
/// each batch of samples (one degree's new nodes, one interval's test points or direct
/// texels) computed in parallel: with a row as the smallest task, the rows' job ran
/// ~10 ms alone at the end of a 512² bake on 2 threads (its last, costliest row).
fn pair_row(ctx: &Ctx, xs: &[f64], j: usize, stop: Stop) -> LineValues {
    let ax = &ctx.axes[0];
    let at =
        |mu: f64, t: f64| unless_stopped(stop, 2, || as_sample(ctx.pair(j, &View::new(mu), t)));
    let first = match ctx.axes[1].alpha(j) {
        Some(a) if a >= PAIR_ROW_WIDE_FROM => PAIR_ROW_FIRST_DEGREE,
        _ => interp1d::MIN_DEG,
    };
    interp1d::line_batched(
        first,
        xs,
        &[GRAZING_BREAK, ROW_BREAK],
        2,
        ctx.tol,
        ctx.tol * interp1d::NODE_TOL_FRACTION,
        |ps, t| {
            ps.par_iter()
                .with_min_len(1)
                .map(|&x| at(x * x, t))
                .collect()
        },
        |is, t| {
            is.par_iter()
                .with_min_len(1)
                .map(|&i| at(ax.coord(i), t))
                .collect()
        },
    )
}

/// The cloth channel of row j along x = √μ above [`CLOTH_GRAZING_BREAK`] ([`cloth_texel`]
/// values, nodes at [`NODE_TOL_FRACTION`]), the texels below it computed one by one; or, for
/// a row the strip serves (`strip_end` = Some(k0)), above `xs[k0]` only, leaving the texels
/// below 0 (the strip computes them).
fn cloth_row(ctx: &Ctx, xs: &[f64], j: usize, strip_end: Option<usize>, stop: Stop) -> LineValues {
    let alpha = ctx.cloth_alpha(ctx.axes[1].alpha(j).expect("roughness axis"));
    let at = |mu: f64, t: f64| {
        unless_stopped(stop, 1, || {
            cloth_sample(cloth_texel(ctx.sheen, &View::new(mu), alpha, t))
        })
    };
    let direct_below = strip_end.is_none();
    let k0 = strip_end.unwrap_or_else(|| xs.partition_point(|&x| x < CLOTH_GRAZING_BREAK));
    let breaks = cloth_breaks(ctx, &[]);
    let mut out = interp1d::line_with_node_tol(
        interp1d::MIN_DEG,
        &xs[k0..],
        &breaks,
        1,
        ctx.tol,
        ctx.tol * NODE_TOL_FRACTION,
        |x, t| at(x * x, t),
        |i, t| at(ctx.axes[0].coord(k0 + i), t),
    );
    let (mut value, mut error) = (vec![0.0; k0], vec![0.0; k0]);
    if direct_below {
        for i in 0..k0 {
            let s = at(ctx.axes[0].coord(i), ctx.tol);
            value[i] = s.value[0];
            error[i] = s.error[0];
            out.evals += s.evals;
            out.direct += 1;
        }
    }
    value.extend_from_slice(&out.value);
    error.extend_from_slice(&out.error);
    out.value = value;
    out.error = error;
    out
}

/// Where Conty–Kulla's fitted Λ(μ) changes branch, in x = √μ: at μ = 1/2 the two branches
/// meet with equal values and slopes but not curvatures (`Λ = exp(L(μ))` below,
/// `exp(2L(1/2) − L(1 − μ))` above), so its albedo is only C¹ in μv there, and one
/// interpolant across it converges slowly (measured: 1024² albedo table, 553 columns on the
/// wide lobes' grid without this break).
const CONTY_KULLA_BREAK: f64 = std::f64::consts::FRAC_1_SQRT_2;

/// The cloth lines' breaks in x = √μ: `base`, and [`CONTY_KULLA_BREAK`] where the cloth
/// channel's masking is Conty–Kulla's.
fn cloth_breaks(ctx: &Ctx, base: &[f64]) -> Vec<f64> {
    let mut b = base.to_vec();
    if matches!(
        ctx.sheen,
        crate::model::Masking::ContyKulla | crate::model::Masking::ContyKullaSoftened
    ) {
        b.push(CONTY_KULLA_BREAK);
        b.sort_by(f64::total_cmp);
    }
    b
}

/// One job of [`bake`] and what it returns.
type Job<'a> = Box<dyn FnOnce() -> Done + Send + 'a>;
enum Done {
    Grid(LineValues),
    Rows(Vec<Option<LineValues>>),
    Columns(Vec<LineValues>, Vec<LineValues>),
}

/// The jobs' results in their order, each job started as soon as a thread is free, the
/// first at once: nested `rayon::join`s, the first job on this thread and the rest stealable
/// as one task (a thread that steals it runs the next job and leaves the rest stealable).
fn in_order(mut jobs: Vec<Job<'_>>) -> Vec<Done> {
    if jobs.is_empty() {
        return Vec::new();
    }
    let first = jobs.remove(0);
    let (a, mut rest) = rayon::join(first, move || in_order(jobs));
    rest.insert(0, a);
    rest
}

/// Texel i of a row in a line's values: at `base + (i − i0)·stride` (a grid holds a row's
/// texels a column apart, a row line holds them in order).
struct Strided<'a> {
    line: &'a LineValues,
    i0: usize,
    base: usize,
    stride: usize,
}

impl<'a> Strided<'a> {
    fn new(line: &'a LineValues, i0: usize, base: usize, stride: usize) -> Self {
        Strided {
            line,
            i0,
            base,
            stride,
        }
    }
    fn at(&self, i: usize) -> usize {
        self.base + (i - self.i0) * self.stride
    }
}

/// Where a row's cloth channel is: in a line, or, texel i, at index k of column line i.
enum Source<'a> {
    Strided(Strided<'a>),
    Columns(&'a [LineValues], usize),
}

/// For each row of an axis of `ny` rows, (grid, position) if it is on one of `lines`.
fn positions<'a>(
    lines: impl Iterator<Item = &'a RoughnessLine>,
    ny: usize,
) -> Vec<Option<(usize, usize)>> {
    let mut at = vec![None; ny];
    for (g, l) in lines.enumerate() {
        for (k, &j) in l.row.iter().enumerate() {
            at[j] = Some((g, k));
        }
    }
    at
}

/// The whole table by lines (see the module doc); `None` where [`interpolated`] says no.
/// Results in texel order (μ fastest), as stored (f32), without per-texel allocations.
/// `stop()` true makes every remaining sample a cheap zero (the caller then discards the
/// table).
pub(crate) fn bake(spec: &TableSpec, stop: Stop, limit: f64) -> Option<Dense> {
    bake_with(spec, stop, false, limit).map(|(d, _)| d)
}

/// Each texel's f64 values and their estimates, `(value, error)` in texel order.
type Detail = (Vec<f64>, Vec<f64>);

/// [`bake`], and with `detail` each texel's f64 values and estimates too (`(value, error)`
/// in texel order, 3 channels; the tests).
/// `limit`: the largest accepted error estimate (texels above it are collected as misses).
fn bake_with(
    spec: &TableSpec,
    stop: Stop,
    detail: bool,
    limit: f64,
) -> Option<(Dense, Option<Detail>)> {
    if !(super::methods::split_sum_by_lines(spec) || super::methods::albedo_by_lines(spec)) {
        return None;
    }
    let ctx = Ctx::new(spec);
    let (ax, ay) = (&ctx.axes[0], &ctx.axes[1]);
    let (nx, ny) = (ax.size, ay.size);
    let tol = ctx.tol;
    let mut p = plan(
        nx,
        ay,
        ctx.cloth.then_some(ctx.cloth_alpha_min.unwrap_or(0.0)),
    );
    if !ctx.pair {
        // (a Charlie albedo table: the cloth channel alone)
        p.pair_grids.clear();
        p.pair_rows.clear();
    }
    let xs: Vec<f64> = (0..nx).map(|i| ax.coord(i).sqrt()).collect();
    let k0 = if p.strip.is_some() {
        xs.partition_point(|&x| x < STRIP_BREAK)
    } else {
        0
    };
    let in_rows = |rows: &[usize], f: &(dyn Fn(usize) -> LineValues + Sync)| {
        let mut out: Vec<Option<LineValues>> = (0..ny).map(|_| None).collect();
        let lines: Vec<LineValues> = rows.par_iter().with_min_len(1).map(|&j| f(j)).collect();
        for (&j, l) in rows.iter().zip(lines) {
            out[j] = Some(l);
        }
        out
    };
    let pair_rows = || in_rows(&p.pair_rows, &|j| pair_row(&ctx, &xs, j, stop));
    let cloth_rows = || {
        let strip_rows = p.strip.as_ref().map_or(&[][..], |s| &s.row[..]);
        in_rows(&p.cloth_rows, &|j| {
            cloth_row(&ctx, &xs, j, strip_rows.contains(&j).then_some(k0), stop)
        })
    };
    let columns = |rl: &Option<RoughnessLine>, n: usize, fraction: f64| -> Vec<LineValues> {
        let Some(rl) = rl else {
            return Vec::new();
        };
        (0..n)
            .into_par_iter()
            .with_min_len(1)
            .map(|i| ctx.cloth_column(rl, ax.coord(i), tol, fraction, stop))
            .collect()
    };
    // the strip's columns, and the wide lobes' columns where they have no grid
    let column_sets = || {
        rayon::join(
            || columns(&p.strip, k0, NODE_TOL_FRACTION),
            || columns(&p.cloth_columns, nx, COLUMN_NODE_TOL_FRACTION),
        )
    };
    // Every job (grid, set of rows, set of columns) in order of decreasing cost, each started
    // as soon as a thread is free ([`in_order`]). A grid is a chain of batches, so one started
    // late ends late: at 512², with the grids started first and the rows and columns filling
    // the gaps, the split sum's second band started when its widest band ended and ran ~50 ms
    // on its own at the end. Costs of one core at 512² (2026-11-30): the pair's widest band
    // 62 ms, its second band 37, its rows 50, the cloth grids 12–17, the cloth rows 5.
    let cloth_grid_breaks = cloth_breaks(&ctx, &[GRAZING_BREAK]);
    let narrow_grid_breaks = cloth_breaks(&ctx, &[]);
    let (cloth_grid_breaks, narrow_grid_breaks) = (&cloth_grid_breaks, &narrow_grid_breaks);
    let mut jobs: Vec<Job> = Vec::new();
    // (the jobs own their references)
    let (xs, ctx) = (&xs[..], &ctx);
    for rl in p.pair_grids.iter().rev() {
        jobs.push(Box::new(move || {
            Done::Grid(grid(
                ax,
                xs,
                0,
                &[GRAZING_BREAK],
                2 * rl.ys.len(),
                tol,
                &|mu, t| ctx.pair_column(rl, mu, t, stop),
            ))
        }));
    }
    jobs.push(Box::new(|| Done::Rows(pair_rows())));
    if let Some(rl) = &p.cloth_grid {
        jobs.push(Box::new(move || {
            Done::Grid(grid(
                ax,
                xs,
                0,
                cloth_grid_breaks,
                rl.ys.len(),
                tol,
                &|mu, t| ctx.cloth_column(rl, mu, t, COLUMN_NODE_TOL_FRACTION, stop),
            ))
        }));
    }
    if let Some(rl) = &p.narrow_grid {
        jobs.push(Box::new(move || {
            Done::Grid(grid(
                ax,
                xs,
                k0,
                narrow_grid_breaks,
                rl.ys.len(),
                tol,
                &|mu, t| ctx.cloth_column(rl, mu, t, NODE_TOL_FRACTION, stop),
            ))
        }));
    }
    jobs.push(Box::new(|| Done::Rows(cloth_rows())));
    jobs.push(Box::new(|| {
        let (a, b) = column_sets();
        Done::Columns(a, b)
    }));
    let mut done = in_order(jobs).into_iter();
    let grid_of = |d: Option<Done>| match d {
        Some(Done::Grid(l)) => l,
        _ => unreachable!("jobs come back in order"),
    };
    let mut pair_grids: Vec<LineValues> = (0..p.pair_grids.len())
        .map(|_| grid_of(done.next()))
        .collect();
    pair_grids.reverse();
    let Some(Done::Rows(pair_rows)) = done.next() else {
        unreachable!("jobs come back in order")
    };
    let cloth_grid = p.cloth_grid.as_ref().map(|_| grid_of(done.next()));
    let narrow_grid = p.narrow_grid.as_ref().map(|_| grid_of(done.next()));
    let (Some(Done::Rows(cloth_rows)), Some(Done::Columns(strip, cloth_columns))) =
        (done.next(), done.next())
    else {
        unreachable!("jobs come back in order")
    };
    // channels: the pair's two (dfg tables), then the cloth channel
    let pair_nch = if ctx.pair { 2 } else { 0 };
    let nch = pair_nch + usize::from(ctx.cloth);
    let mut evals = pair_grids.iter().map(|l| l.evals).sum::<u64>();
    for l in pair_rows.iter().chain(&cloth_rows).flatten() {
        evals += l.evals;
    }
    evals += cloth_grid.as_ref().map_or(0, |l| l.evals);
    evals += narrow_grid.as_ref().map_or(0, |l| l.evals);
    evals += strip
        .iter()
        .chain(&cloth_columns)
        .map(|l| l.evals)
        .sum::<u64>();
    let pair_grids: Vec<(RoughnessLine, LineValues)> =
        p.pair_grids.into_iter().zip(pair_grids).collect();
    let pair_at = positions(pair_grids.iter().map(|g| &g.0), ny);
    let cloth_grids: Vec<(RoughnessLine, LineValues)> =
        p.cloth_grid.into_iter().zip(cloth_grid).collect();
    let cloth_at = positions(cloth_grids.iter().map(|g| &g.0), ny);
    let strip_at = positions(p.strip.iter(), ny);
    let columns_at = positions(p.cloth_columns.iter(), ny);
    let narrow_at = positions(p.narrow_grid.iter(), ny);
    let nn = p.narrow_grid.as_ref().map_or(0, |l| l.ys.len());
    // Each row's channels from the lines that hold them, resolved once per row (at 512²,
    // looking the line up texel by texel cost ~13 ms after the lines were done); rows in
    // parallel.
    let pair_src = |j: usize| match pair_at[j] {
        Some((g, k)) => Strided::new(&pair_grids[g].1, 0, k * 2, pair_grids[g].0.ys.len() * 2),
        None => Strided::new(
            pair_rows[j]
                .as_ref()
                .expect("every row is on a grid or its own line"),
            0,
            0,
            2,
        ),
    };
    // the cloth channel of row j from column i_from on; below `i_from`, the strip's columns
    let cloth_src = |j: usize| -> (usize, Source) {
        let i_from = if strip_at[j].is_some() { k0 } else { 0 };
        let src = match (columns_at[j], narrow_at[j], &narrow_grid) {
            (Some((_, k)), _, _) => Source::Columns(&cloth_columns, k),
            (_, Some((_, k)), Some(g)) => Source::Strided(Strided::new(g, k0, k, nn)),
            _ => Source::Strided(match cloth_at[j] {
                Some((g, k)) => Strided::new(&cloth_grids[g].1, 0, k, cloth_grids[g].0.ys.len()),
                None => Strided::new(
                    cloth_rows[j]
                        .as_ref()
                        .expect("every row is on a grid or its own line"),
                    0,
                    0,
                    1,
                ),
            }),
        };
        (i_from, src)
    };
    // (per row: the largest error of each channel, the first non-finite value)
    let mut data = vec![0.0f32; nx * ny * nch];
    type Row = (
        [f64; 3],
        Option<(usize, usize, f64)>,
        Vec<f64>,
        Vec<f64>,
        super::Misses,
    );
    let rows: Vec<Row> = data
        .par_chunks_mut(nx * nch)
        .enumerate()
        .map(|(j, row)| {
            // (the texels' own index j for the checks; the values of the row that computed them)
            let src_j = p.source_row[j];
            let mut max_error = [0.0f64; 3];
            let mut non_finite = None;
            let mut misses = super::Misses::default();
            let n_detail = if detail { nx * nch } else { 0 };
            let (mut dv, mut de) = (vec![0.0; n_detail], vec![0.0; n_detail]);
            let mut put = |i: usize, c: usize, v: f64, e: f64| {
                if detail {
                    dv[i * nch + c] = v;
                    de[i * nch + c] = e;
                }
                let k = (j * nx + i) * nch + c;
                if !(v.is_finite() && (v as f32).is_finite())
                    && non_finite.is_none_or(|(first, _, _)| k < first)
                {
                    non_finite = Some((k, c, v));
                }
                row[i * nch + c] = v as f32;
                max_error[c] = max_error[c].max(e);
                misses.check(limit, j * nx + i, c, e);
            };
            if ctx.pair {
                let pair = pair_src(src_j);
                for i in 0..nx {
                    let at = pair.at(i);
                    for c in 0..2 {
                        put(i, c, pair.line.value[at + c], pair.line.error[at + c]);
                    }
                }
            }
            if ctx.cloth {
                let (i_from, src) = cloth_src(src_j);
                let strip_k = strip_at[src_j].map_or(0, |(_, k)| k);
                for i in 0..nx {
                    let (l, at) = if i < i_from {
                        (&strip[i], strip_k)
                    } else {
                        match &src {
                            Source::Columns(ls, k) => (&ls[i], *k),
                            Source::Strided(s) => (s.line, s.at(i)),
                        }
                    };
                    put(i, pair_nch, l.value[at], l.error[at]);
                }
            }
            (max_error, non_finite, dv, de, misses)
        })
        .collect();
    let mut max_error = vec![0.0f64; nch];
    for (e, ..) in &rows {
        for c in 0..nch {
            max_error[c] = max_error[c].max(e[c]);
        }
    }
    // the first in texel order (then channel order): the lowest index into `data`
    let non_finite = rows
        .iter()
        .filter_map(|r| r.1)
        .min_by_key(|&(k, _, _)| k)
        .map(|(k, c, v)| (k / nch, c, v));
    let detail = detail.then(|| {
        let value = rows.iter().flat_map(|r| r.2.iter().copied()).collect();
        let error = rows.iter().flat_map(|r| r.3.iter().copied()).collect();
        (value, error)
    });
    let mut misses = super::Misses::default();
    for r in rows {
        misses.merge(r.4);
    }
    let out = Dense {
        data,
        max_error,
        evals,
        non_finite,
        misses,
    };
    Some((out, detail))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::lut::{Axis, Convention, Quantity};
    use crate::model::{Fresnel, Masking, NdfKind, RoughnessQuantity};
    use crate::table::{DfgLayout, ModelSpec, Storage, TableKind, TexelResult};

    fn spec(nx: usize, roughness: [f64; 2], ny: usize, cloth: bool, tol: f64) -> TableSpec {
        TableSpec {
            name: "t".into(),
            kind: TableKind::Dfg,
            model: ModelSpec {
                ndf: Some(NdfKind::Ggx),
                masking: Masking::SmithHeightCorrelated,
                fresnel: Fresnel::None,
                diffuse_weight: 0.0,
                diffuse_model: crate::model::DiffuseModel::Lambert,
                classic: None,
            },
            axes: vec![
                Axis {
                    name: "cos_theta_v".into(),
                    quantity: Quantity::Cosine,
                    size: nx,
                    range: [0.0, 1.0],
                    convention: Convention::Centers,
                    warp: Default::default(),
                    clamp: None,
                },
                Axis {
                    name: "roughness".into(),
                    quantity: Quantity::Roughness(RoughnessQuantity::Perceptual),
                    size: ny,
                    range: roughness,
                    convention: Convention::Endpoints,
                    warp: Default::default(),
                    clamp: None,
                },
            ],
            dfg_layout: Some(if cloth {
                DfgLayout::Filament
            } else {
                DfgLayout::Karis
            }),
            cloth,
            cloth_alpha_min: None,
            ltc_channels: None,
            storage: Storage::F32,
            tolerance: tol,
        }
    }

    /// The plan of filament-dfg's axes: at 128² one pair grid (α ≥ 1/40, r ≥ 0.1581: 108
    /// rows) and the other rows by rows; at 512² two pair grids (the bands from 1/256 and
    /// 1/40 up hold 49 and 431 rows); the wide cloth lobes on a grid, the narrow ones by rows, and at 512²
    /// (128 narrow rows) their grazing texels by the strip and most of the rest on a grid.
    #[test]
    fn plan_follows_the_rules() {
        for (n, grids) in [(128, 1), (512, 2)] {
            let mut s = spec(n, [0.0, 1.0], n, true, 1e-7);
            s.axes[1].convention = Convention::Centers;
            let p = plan(n, &s.axes[1], Some(0.0));
            assert_eq!(p.pair_grids.len(), grids, "{n}²");
            let on_grids: usize = p.pair_grids.iter().map(|g| g.row.len()).sum();
            assert_eq!(on_grids + p.pair_rows.len(), n, "every row once");
            let widest = if n == 128 { 108 } else { 431 };
            assert_eq!(p.pair_grids.last().unwrap().row.len(), widest, "{n}²");
            if n == 512 {
                assert_eq!(p.pair_grids[0].row.len(), 49);
            }
            let wide = p.cloth_grid.as_ref().expect("a wide cloth grid");
            assert_eq!(wide.row.len(), 3 * n / 4);
            // from 64 narrow rows on (512²): the strip below μ = 0.01, and above it a grid
            // for α ≥ 1/1024 (r ≥ 1/32: all but 16 rows)
            assert_eq!(p.strip.is_some(), n == 512);
            assert_eq!(p.narrow_grid.is_some(), n == 512);
            let narrow_rows = if n == 512 { n / 4 - 16 } else { 0 };
            assert_eq!(
                p.narrow_grid.as_ref().map_or(0, |g| g.row.len()),
                narrow_rows
            );
            assert_eq!(p.cloth_rows.len(), n / 4 - narrow_rows);
            if let Some(strip) = &p.strip {
                assert_eq!(strip.row.len(), n / 4);
            }
        }
    }

    /// The fine reference of texel (i, j): every channel computed alone at `tol`.
    fn texel_at(ctx: &Ctx, i: usize, j: usize, tol: f64) -> TexelResult {
        let view = View::new(ctx.axes[0].coord(i));
        let mut r = ctx.pair(j, &view, tol);
        let (v, e, n) = cloth_texel(
            Masking::Ashikhmin,
            &view,
            ctx.axes[1].alpha(j).unwrap(),
            tol,
        );
        r.value.push(v);
        r.error.push(e);
        r.evals += n;
        r
    }

    /// Texels of a table baked by lines lie within their own estimates of the same channels
    /// computed texel by texel at a 100× tighter tolerance (whose estimate is added), and
    /// every estimate is within the table's tolerance: all rows of the columns `cols` and all
    /// columns of the rows `rows`. The lines cost fewer evaluations than the texels would
    /// (estimated from the checked texels at the table's tolerance).
    fn check_lines(s: &TableSpec, cols: &[usize], rows: &[usize]) {
        let tol = s.tolerance;
        let (nx, ny) = (s.axes[0].size, s.axes[1].size);
        let (table, detail) =
            bake_with(s, &|| false, true, f64::INFINITY).expect("a GGX dfg table goes by lines");
        let (value, error) = detail.expect("asked for");
        let ctx = Ctx::new(s);
        let (mut checked, mut texel_evals) = (0u64, 0u64);
        for j in 0..ny {
            for i in 0..nx {
                if !cols.contains(&i) && !rows.contains(&j) {
                    continue;
                }
                let fine = texel_at(&ctx, i, j, tol * 1e-2);
                texel_evals += texel_at(&ctx, i, j, tol).evals;
                checked += 1;
                let t = j * nx + i;
                for c in 0..3 {
                    let (v, e) = (value[3 * t + c], error[3 * t + c]);
                    assert_eq!(table.data[3 * t + c], v as f32);
                    let d = (v - fine.value[c]).abs();
                    assert!(
                        d <= e + fine.error[c],
                        "texel ({i}, {j}) channel {c}: {v} vs {} (estimates {e:e} + {:e})",
                        fine.value[c],
                        fine.error[c]
                    );
                    assert!(e <= tol, "texel ({i}, {j}) channel {c}: estimate {e:e}");
                }
            }
        }
        let all = texel_evals as f64 * (nx * ny) as f64 / checked as f64;
        assert!(
            2.0 * (table.evals as f64) < all,
            "{} evaluations by lines vs ~{all:.0} texel by texel",
            table.evals
        );
    }

    /// A 128 × 96 table, r from 0.02 to 1: the pair on a grid (the rows from 14 on, α ≥ 1/40),
    /// the wide cloth lobes on a grid (73 rows with α ≥ 1/16), the other rows by rows; the
    /// columns checked include the grazing ones, the rows lie either side of both edges.
    #[test]
    fn lines_match_texel_values() {
        let s = spec(128, [0.02, 1.0], 96, true, 1e-7);
        let p = plan(128, &s.axes[1], Some(0.0));
        assert_eq!(p.pair_grids.len(), 1);
        assert!(p.cloth_grid.is_some() && p.strip.is_none() && p.narrow_grid.is_none());
        assert_eq!(p.pair_grids[0].row[0], 14);
        check_lines(&s, &[0, 1, 4, 20, 77, 127], &[0, 13, 14, 22, 23, 95]);
    }

    /// A 128 × 70 table of narrow lobes only (r from 0.02 to 0.249): the pair of [1/256, 1/40)
    /// and from 1/40 up on grids, the 13 rows below them (fewer than GRID_MIN_ROWS) by rows;
    /// the cloth channel by the strip below μ = 0.01 (the first column), on a grid above it
    /// for α ≥ 1/1024, by rows below. The rows checked lie either side of each edge.
    #[test]
    fn narrow_lines_match_texel_values() {
        let s = spec(128, [0.02, 0.249], 70, true, 1e-7);
        let p = plan(128, &s.axes[1], Some(0.0));
        let first: Vec<usize> = p.pair_grids.iter().map(|g| g.row[0]).collect();
        assert_eq!(first, [13, 42]);
        assert!(p.strip.is_some() && p.narrow_grid.is_some() && !p.cloth_rows.is_empty());
        check_lines(&s, &[0, 1, 2, 5, 60, 127], &[0, 3, 4, 12, 13, 41, 42, 69]);
    }

    /// The strip's columns (the narrow lobes' cloth in y = ln α, 80 rows from α = 4e-4 to
    /// just below 1/16) at three grazing views lie within their own estimates of the texel
    /// values at a 100× tighter tolerance, within the tolerance, from fewer quadratures than
    /// texels.
    #[test]
    fn strip_columns_match_texel_values() {
        let tol = 1e-7;
        let s = spec(4, [0.02, 0.249], 80, true, tol);
        let ctx = Ctx::new(&s);
        let rl = RoughnessLine::new(&s.axes[1], RoughnessVar::Ln, (0..80).collect())
            .expect("α increases");
        for mu in [0.002, 0.02, 0.035] {
            let col = ctx.cloth_column(&rl, mu, tol, NODE_TOL_FRACTION, &|| false);
            assert!(col.nodes + col.direct < 80, "μ = {mu}: not interpolated");
            for (k, &alpha) in rl.alphas.iter().enumerate() {
                let (r, re, _) = cloth_texel(Masking::Ashikhmin, &View::new(mu), alpha, tol * 1e-2);
                let (v, e) = (col.value[k], col.error[k]);
                assert!(
                    (v - r).abs() <= e + re,
                    "μ = {mu}, α = {alpha}: {v} vs {r} (estimates {e:e} + {re:e})"
                );
                assert!(e <= tol, "estimate {e:e}");
            }
        }
    }

    /// Every channel agrees with the column path (texel by texel) within the two estimates;
    /// a table whose lines are too short to pay is computed texel by texel, bit for bit as
    /// by columns.
    #[test]
    fn short_lines_are_the_column_values() {
        for (nx, short) in [(40, false), (8, true)] {
            let s = spec(nx, [0.1, 0.9], 3, true, 1e-7);
            let (_, detail) = bake_with(&s, &|| false, true, f64::INFINITY).expect("by lines");
            let (value, error) = detail.expect("asked for");
            let column = super::super::dfg::column_fn(&s);
            for i in 0..nx {
                let col = column(i);
                for (j, c) in col.iter().enumerate() {
                    let t = 3 * (j * nx + i);
                    for k in 0..3 {
                        let (v, e) = (value[t + k], error[t + k]);
                        if short {
                            assert_eq!(v.to_bits(), c.value[k].to_bits());
                        } else {
                            assert!((v - c.value[k]).abs() <= e + c.error[k]);
                        }
                    }
                }
            }
        }
    }
}
