//! Comparison with a DFG table as Filament ships it: the `dfg.inc` that Filament's `cmgen
//! --ibl-dfg=FILE.inc [--ibl-dfg-multiscatter] [--ibl-dfg-cloth]` writes and
//! `filament/src/details/DFG.cpp` includes into `const uint16_t DFG_LUT[]`.
//!
//! Facts about that file, read from Filament's sources (tools/cmgen/src/cmgen.cpp
//! `iblLutDfg`, libs/ibl/src/CubemapIBL.cpp `CubemapIBL::DFG`):
//! * half-float bit patterns written as `0xhhhh, ` — 2 per texel (R, G) or 3 with cloth
//!   (R, G, B), row-major in "GL order": the first row is the bottom of the texture, read by
//!   the shader at `v = (y + 0.5)/N` as perceptual roughness, `u = n·v`;
//! * the table's values are Filament's multiscatter layout (R = ∫Fc f cos, G = ∫ f cos,
//!   B = cloth ∫ D_Charlie V_Ashikhmin cos) for GGX with height-correlated Smith;
//! * cmgen computes image row `y` at `coord = saturate((N − y + 0.5)/N)` and writes image row
//!   `N − 1 − y` as file row `y`, so file row `y` was computed at perceptual roughness
//!   `min((y + 1.5)/N, 1)`: one texel above where the shader reads it.
//!
//! brdfbake therefore compares the file twice: with the exact values where the shader samples
//! each texel (what a renderer gets), and where cmgen computed it (its integration error
//! alone).

use crate::lut::{Axis, Channel, Convention, Lut, Quantity};
use crate::model::{Fresnel, Masking, Ndf, NdfKind, RoughnessQuantity, Specular};
use crate::table::dfg::{sheen_albedo, split_sum};
use rayon::prelude::*;

/// A parsed `dfg.inc`.
#[derive(Clone, Debug, PartialEq)]
pub struct ShippedDfg {
    /// Texels per side (the table is square).
    pub size: usize,
    /// 2 (R, G) or 3 (R, G, cloth).
    pub channels: usize,
    /// Values, file order: `(y·size + x)·channels + c`, row 0 = roughness texel 0.
    pub values: Vec<f32>,
}

/// Parses the text of a `dfg.inc` (or of the `.h` form with `const uint16_t DFG_LUT[] = {…};`
/// around it): comments are skipped, values are 16-bit integers in hex (`0x3c00`) or decimal,
/// separated by commas and/or white space.
pub fn parse_inc(text: &str) -> Result<ShippedDfg, String> {
    let mut body = strip_comments(text);
    if let (Some(a), Some(b)) = (body.find('{'), body.rfind('}')) {
        if a < b {
            body = body[a + 1..b].to_string();
        }
    }
    let mut bits = Vec::new();
    for (k, tok) in body
        .split(|c: char| c == ',' || c.is_whitespace())
        .filter(|t| !t.is_empty())
        .enumerate()
    {
        let v = match tok.strip_prefix("0x").or_else(|| tok.strip_prefix("0X")) {
            Some(h) => u16::from_str_radix(h, 16).ok(),
            None => tok.parse::<u16>().ok(),
        };
        bits.push(v.ok_or_else(|| {
            format!(
                "value {} ({tok:?}) is not a 16-bit integer; a dfg.inc holds half-float bit \
                 patterns such as 0x3c00, separated by commas",
                k + 1
            )
        })?);
    }
    let n = bits.len();
    let side = |c: usize| {
        let s = ((n / c) as f64).sqrt().round() as usize;
        (n > 0 && s * s * c == n).then_some(s)
    };
    let (size, channels) = match (side(2), side(3)) {
        (Some(s), _) => (s, 2),
        (None, Some(s)) => (s, 3),
        (None, None) => {
            return Err(format!(
                "{n} values is neither 2·N² (an RG table) nor 3·N² (RGB, with cloth) for a \
                 square N×N table"
            ))
        }
    };
    let mut values = Vec::with_capacity(n);
    for (k, b) in bits.iter().enumerate() {
        let v = half::f16::from_bits(*b).to_f32();
        if !v.is_finite() {
            let t = k / channels;
            return Err(format!(
                "texel x = {}, y = {} channel {} is {v} (0x{b:04x}); a DFG table holds finite values",
                t % size,
                t / size,
                k % channels
            ));
        }
        values.push(v);
    }
    Ok(ShippedDfg {
        size,
        channels,
        values,
    })
}

fn strip_comments(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    let mut rest = text;
    while !rest.is_empty() {
        if let Some(r) = rest.strip_prefix("//") {
            rest = r.find('\n').map_or("", |i| &r[i..]);
        } else if let Some(r) = rest.strip_prefix("/*") {
            rest = r.find("*/").map_or("", |i| &r[i + 2..]);
            out.push(' ');
        } else {
            let c = rest.chars().next().expect("non-empty");
            out.push(c);
            rest = &rest[c.len_utf8()..];
        }
    }
    out
}

/// Differences of one channel under one alignment.
#[derive(Clone, Debug, PartialEq)]
pub struct ChannelStats {
    pub max_abs: f64,
    /// (n·v, perceptual roughness) where `max_abs` occurs (the shader's coordinates).
    pub at: (f64, f64),
    pub mean_abs: f64,
}

/// The result of comparing a shipped table with exact values.
#[derive(Clone, Debug)]
pub struct Comparison {
    pub size: usize,
    pub channels: usize,
    /// Per channel, against the exact values at the shader's sample positions.
    pub as_sampled: Vec<ChannelStats>,
    /// Per channel, against the exact values where cmgen computed each row.
    pub as_computed: Vec<ChannelStats>,
    /// Per channel, the largest difference that rounding the exact values to f16 alone makes:
    /// half an f16 ulp of each value, maximized over the exact values of both alignments.
    pub f16_floor: Vec<f64>,
    /// Signed difference shipped − exact at the shader's sample positions, as a table with
    /// the shipped table's axes (for heatmaps).
    pub diff: Lut,
}

/// Half an ulp of `v` in f16 (normal range), i.e. the largest round-to-nearest error.
fn f16_half_ulp(v: f64) -> f64 {
    let a = v.abs().max(f64::from(half::f16::MIN_POSITIVE));
    (2f64).powi(a.log2().floor() as i32 - 11)
}

/// Exact Filament DFG values at (n·v, perceptual roughness): [R, G, cloth].
fn exact(mu: f64, r: f64, tol: f64) -> [f64; 3] {
    let alpha = r * r;
    let spec = Specular {
        ndf: Ndf::new(NdfKind::Ggx, alpha).expect("alpha in (0, 1]"),
        masking: Masking::SmithHeightCorrelated,
        fresnel: Fresnel::None,
    };
    let ([a, b], _, _) = split_sum(&spec, mu, tol);
    let (cloth, _, _) = sheen_albedo(alpha, mu, tol);
    [b, a + b, cloth]
}

/// Compares `shipped` with exact values computed to absolute tolerance `tol` (use ≤ 1e-6:
/// the differences of interest are f16-sized, ~1e-4 and up).
pub fn compare(shipped: &ShippedDfg, tol: f64) -> Comparison {
    compare_until(shipped, tol, None).expect("no deadline")
}

/// The exact values [`compare`] computes: (size + 1) rows of `size` texels.
pub fn exact_values(shipped: &ShippedDfg) -> usize {
    (shipped.size + 1) * shipped.size
}

/// [`compare`], giving up (`None`) once `deadline` has passed (checked before every texel).
pub fn compare_until(
    shipped: &ShippedDfg,
    tol: f64,
    deadline: Option<&crate::deadline::Deadline>,
) -> Option<Comparison> {
    let n = shipped.size;
    let nc = shipped.channels;
    let stopped = std::sync::atomic::AtomicBool::new(false);
    let out_of_time = || {
        use std::sync::atomic::Ordering::Relaxed;
        if stopped.load(Relaxed) || deadline.is_some_and(|d| d.passed()) {
            stopped.store(true, Relaxed);
            return true;
        }
        false
    };
    // exact rows at r_j = (j + 0.5)/n, j < n, and r_n = 1 (cmgen's saturated last row)
    let rows: Vec<Vec<[f64; 3]>> = (0..=n)
        .into_par_iter()
        .map(|j| {
            let r = if j < n {
                (j as f64 + 0.5) / n as f64
            } else {
                1.0
            };
            (0..n)
                .map(|x| {
                    if out_of_time() {
                        return [0.0; 3];
                    }
                    exact((x as f64 + 0.5) / n as f64, r, tol)
                })
                .collect()
        })
        .collect();
    if stopped.into_inner() {
        return None;
    }
    let stats = |shift: usize| -> Vec<ChannelStats> {
        (0..nc)
            .map(|c| {
                let mut s = ChannelStats {
                    max_abs: 0.0,
                    at: (0.0, 0.0),
                    mean_abs: 0.0,
                };
                for y in 0..n {
                    for (x, e) in rows[y + shift].iter().enumerate() {
                        let v = f64::from(shipped.values[(y * n + x) * nc + c]);
                        let d = (v - e[c]).abs();
                        s.mean_abs += d;
                        if d > s.max_abs {
                            s.max_abs = d;
                            s.at = ((x as f64 + 0.5) / n as f64, (y as f64 + 0.5) / n as f64);
                        }
                    }
                }
                s.mean_abs /= (n * n) as f64;
                s
            })
            .collect()
    };
    let f16_floor = (0..nc)
        .map(|c| {
            rows.iter()
                .flatten()
                .map(|e| f16_half_ulp(e[c]))
                .fold(0.0, f64::max)
        })
        .collect();
    let axis = |name: &str, quantity| Axis {
        name: name.into(),
        quantity,
        size: n,
        range: [0.0, 1.0],
        convention: Convention::Centers,
        warp: Default::default(),
        clamp: None,
    };
    let names = ["R", "G", "B"];
    let diff = Lut {
        axes: vec![
            axis("cos_theta_v", Quantity::Cosine),
            axis(
                "roughness",
                Quantity::Roughness(RoughnessQuantity::Perceptual),
            ),
        ],
        channels: (0..nc)
            .map(|c| Channel {
                name: format!("d{}", names[c]),
                meaning: format!("shipped {} − exact", names[c]),
            })
            .collect(),
        data: (0..n * n * nc)
            .map(|k| {
                let (t, c) = (k / nc, k % nc);
                (f64::from(shipped.values[k]) - rows[t / n][t % n][c]) as f32
            })
            .collect(),
        error_estimate: vec![0.0; nc],
        evaluations: 0,
    };
    Some(Comparison {
        size: n,
        channels: nc,
        as_sampled: stats(0),
        as_computed: stats(1),
        f16_floor,
        diff,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Correctly rounded f64 → f16 (positive values): `half::f16::from_f64` rounds through
    /// f32 first, and that double rounding can miss the nearest f16 by a hair.
    fn nearest_f16_bits(v: f64) -> u16 {
        let b = half::f16::from_f64(v).to_bits();
        [b.saturating_sub(1), b, b + 1]
            .into_iter()
            .min_by(|x, y| {
                let d = |k: u16| (half::f16::from_bits(k).to_f64() - v).abs();
                d(*x).total_cmp(&d(*y))
            })
            .expect("three candidates")
    }

    fn to_inc(vals: &[f64]) -> String {
        let mut s = String::from("// generated with: cmgen --ibl-dfg=dfg.inc\n");
        for (k, v) in vals.iter().enumerate() {
            if k % 6 == 0 {
                s.push_str("\n    ");
            }
            s.push_str(&format!("0x{:04x}, ", nearest_f16_bits(*v)));
        }
        s
    }

    #[test]
    fn parses_hex_decimal_comments_and_wrapper() {
        let t = "/* x */ const uint16_t DFG_LUT[] = { 0x3c00,\n// c, 0x0000\n 15360 };";
        let d = parse_inc(t).unwrap();
        assert_eq!((d.size, d.channels), (1, 2));
        assert_eq!(d.values, vec![1.0, 1.0]);
        let d = parse_inc("0X0000 ,0x4000 0x3800\t0x3400\n0,0,0,0").unwrap();
        assert_eq!((d.size, d.channels), (2, 2));
        assert_eq!(d.values[..4], [0.0, 2.0, 0.5, 0.25]);
        let d = parse_inc(&"0x3c00,".repeat(12)).unwrap();
        assert_eq!((d.size, d.channels), (2, 3));
    }

    #[test]
    fn rejects_what_is_not_a_dfg_inc() {
        let e = parse_inc("0x3c00, 0x3c00, 0x3c00, 0x3c00, 0x3c00").unwrap_err();
        assert!(e.contains("5 values") && e.contains("3·N²"), "{e}");
        let e = parse_inc("0x3c00, 0x1ffff").unwrap_err();
        assert!(e.contains("value 2") && e.contains("0x1ffff"), "{e}");
        let e = parse_inc("0x3c00, 0x7c00").unwrap_err();
        assert!(e.contains("channel 1") && e.contains("inf"), "{e}");
        assert!(parse_inc("").is_err());
    }

    /// A table made the way cmgen makes it (rows computed one texel up), exact otherwise and
    /// rounded to f16: "as computed" must be within the f16 rounding floor (plus the 1e-7
    /// quadrature tolerance of both sides), "as sampled" must show the one-texel shift,
    /// which at N = 8 moves G by far more than f16 rounding (> 1e-3).
    #[test]
    fn detects_the_one_texel_shift() {
        let n = 8;
        let mut vals = Vec::new();
        for y in 0..n {
            let r = ((y as f64 + 1.5) / n as f64).min(1.0);
            for x in 0..n {
                let e = exact((x as f64 + 0.5) / n as f64, r, 1e-8);
                vals.extend_from_slice(&e);
            }
        }
        let shipped = parse_inc(&to_inc(&vals)).unwrap();
        assert_eq!((shipped.size, shipped.channels), (n, 3));
        let c = compare(&shipped, 1e-8);
        for ch in 0..3 {
            assert!(
                c.as_computed[ch].max_abs <= c.f16_floor[ch] + 2e-8,
                "channel {ch}: {:?} floor {}",
                c.as_computed[ch],
                c.f16_floor[ch]
            );
        }
        assert!(c.as_sampled[1].max_abs > 1e-3, "{:?}", c.as_sampled[1]);
        // the signed difference table holds the as-sampled differences
        let m = c
            .diff
            .data
            .iter()
            .map(|v| f64::from(v.abs()))
            .fold(0.0, f64::max);
        assert!((m - c.as_sampled.iter().map(|s| s.max_abs).fold(0.0, f64::max)).abs() < 1e-6);
    }
}
