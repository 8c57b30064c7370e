//! Measured BRDFs in the MERL BRDF database's binary format (Matusik, Pfister, Brand &
//! McMillan 2003, "A data-driven reflectance model", SIGGRAPH 2003; layout as published with
//! the database's reference reader):
//!
//! - three little-endian int32 dimensions, 90 × 90 × 180 (θh, θd, φd);
//! - then R, G and B, each 90·90·180 little-endian f64, index
//!   `φd_i + 180·(θd_i + 90·θh_i)`;
//! - stored value × scale = BRDF (1/sr), scales R 1/1500, G 1.15/1500, B 1.66/1500;
//! - coordinates are Rusinkiewicz's (1998) half/difference angles: h = (ωi+ωo)/|ωi+ωo|,
//!   (θh, φh) its angles, and d = ωi rotated by −φh about the normal and by −θh about the
//!   bitangent, (θd, φd) its angles. Isotropy drops φh; reciprocity folds φd into [0, π);
//! - index maps: θh_i = ⌊√(θh/(π/2))·90⌋ (non-linear: dense near the specular peak),
//!   θd_i = ⌊θd/(π/2)·90⌋, φd_i = ⌊φd/π·180⌋, each clamped to its range;
//! - a negative value means "not measured".
//!
//! **Nodes.** Entry (i, j, k) is taken as the BRDF at the point the published index map
//! sends exactly to it: θh = (i/90)²·π/2, θd = j/90·π/2, φd = k/180·π. The writer
//! ([`write_bytes`]) samples there; the reader interpolates multilinearly between nodes in
//! (√θh index, θd index, φd index), periodic in φd (period π, by reciprocity) and clamped
//! at the last θh and θd nodes.
//!
//! **Unmeasured entries.** An interpolation corner whose entry is negative is left out and
//! the weights of the measured corners are renormalized; where all corners are unmeasured
//! the BRDF is taken as 0 there (so an albedo with such holes is a lower bound). The reader
//! reports how many entries are unmeasured and how many of those lie above the horizon
//! (entries whose node directions are below the horizon carry no information anyway).

use crate::model::classic::{dot, Dir, Reflectance};
use crate::model::{Brdf, Fresnel, Masking, Ndf, NdfKind, Specular};
use rayon::prelude::*;
use std::f64::consts::{FRAC_PI_2, PI};
use std::path::Path;
use std::sync::Arc;

/// Smallest albedo quadrature tolerance used on measured data (see
/// [`Reflectance::tolerance_floor`]).
pub const MEASURED_TOLERANCE_FLOOR: f64 = 1e-3;

/// θh, θd, φd resolutions.
pub const DIMS: [usize; 3] = [90, 90, 180];
/// Entries per channel.
pub const N: usize = 90 * 90 * 180;
/// Size of a well-formed file in bytes: the header and three channels of f64.
pub const FILE_BYTES: usize = 12 + 3 * N * 8;

/// The largest BRDF value (1/sr, after the channel scales) accepted from a MERL file:
/// measured materials peak orders of magnitude lower at the format's half-angle resolution,
/// and the albedo of values far beyond could not be integrated to an absolute tolerance in
/// f64 (a file of 1e300 kept the quadrature bisecting for minutes).
pub const MAX_MEASURED_VALUE: f64 = 1e6;
/// Per-channel scale: BRDF = stored × scale (R, G, B).
pub const SCALE: [f64; 3] = [1.0 / 1500.0, 1.15 / 1500.0, 1.66 / 1500.0];

/// Why a file could not be read.
#[derive(Debug)]
pub enum MerlError {
    /// The file is not a MERL file (exit code 2).
    Format(String),
    /// Reading failed (exit code 1), or the file does not exist (kind `NotFound`, exit code
    /// 2).
    Io(String, std::io::ErrorKind),
}

impl std::fmt::Display for MerlError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            MerlError::Format(m) | MerlError::Io(m, _) => f.write_str(m),
        }
    }
}

/// A measured BRDF: values already multiplied by the channel scales; negative = unmeasured.
#[derive(Clone, Debug)]
pub struct Merl {
    /// `values[c][index]`.
    pub values: [Vec<f64>; 3],
    /// Unmeasured entries per channel.
    pub unmeasured: [usize; 3],
    /// Unmeasured entries per channel whose node directions are above the horizon.
    pub unmeasured_above_horizon: [usize; 3],
}

/// Flat index of (θh_i, θd_i, φd_i).
#[inline]
pub fn index(i: usize, j: usize, k: usize) -> usize {
    k + DIMS[2] * (j + DIMS[1] * i)
}

/// The node angles (θh, θd, φd) of entry (i, j, k) (see the module documentation).
pub fn node_angles(i: usize, j: usize, k: usize) -> (f64, f64, f64) {
    let t = i as f64 / 90.0;
    (
        t * t * FRAC_PI_2,
        j as f64 / 90.0 * FRAC_PI_2,
        k as f64 / 180.0 * PI,
    )
}

/// (ωi, ωo) from half/difference angles with φh = 0 (Rusinkiewicz 1998, inverted).
pub fn directions(theta_h: f64, theta_d: f64, phi_d: f64) -> (Dir, Dir) {
    let (sd, cd) = theta_d.sin_cos();
    let (sp, cp) = phi_d.sin_cos();
    let d = [sd * cp, sd * sp, cd];
    let (sh, ch) = theta_h.sin_cos();
    // rotate d by +θh about the bitangent (y)
    let wi = [d[0] * ch + d[2] * sh, d[1], -d[0] * sh + d[2] * ch];
    let h = [sh, 0.0, ch];
    let k = 2.0 * dot(wi, h);
    let wo = [k * h[0] - wi[0], k * h[1] - wi[1], k * h[2] - wi[2]];
    (wi, wo)
}

/// Half/difference angles (θh, θd, φd ∈ [0, π)) of a pair of directions.
pub fn half_diff(wi: Dir, wo: Dir) -> Option<(f64, f64, f64)> {
    let s = [wi[0] + wo[0], wi[1] + wo[1], wi[2] + wo[2]];
    let len = dot(s, s).sqrt();
    if len == 0.0 {
        return None;
    }
    let h = [s[0] / len, s[1] / len, s[2] / len];
    let rh = h[0].hypot(h[1]);
    let theta_h = rh.atan2(h[2]);
    let (sph, cph) = if rh > 0.0 {
        (h[1] / rh, h[0] / rh)
    } else {
        (0.0, 1.0)
    };
    // rotate ωi by −φh about z, then by −θh about y
    let t = [cph * wi[0] + sph * wi[1], -sph * wi[0] + cph * wi[1], wi[2]];
    let (sth, cth) = (rh, h[2]);
    let d = [t[0] * cth - t[2] * sth, t[1], t[0] * sth + t[2] * cth];
    let theta_d = d[0].hypot(d[1]).atan2(d[2]);
    let mut phi_d = d[1].atan2(d[0]);
    if phi_d < 0.0 {
        phi_d += PI;
    }
    if phi_d >= PI {
        phi_d -= PI;
    }
    Some((theta_h, theta_d, phi_d))
}

fn read_i32(b: &[u8], at: usize) -> i32 {
    i32::from_le_bytes([b[at], b[at + 1], b[at + 2], b[at + 3]])
}

impl Merl {
    /// Reads and validates a file (see [`Merl::parse`]).
    pub fn read(path: &Path) -> Result<Merl, MerlError> {
        // (one byte more than a MERL file, so that trailing bytes are reported as such)
        let bytes = crate::input::read_regular(path, FILE_BYTES as u64 + 1, "a MERL .binary file")
            .map_err(|e| match e {
                crate::input::InputError::Input(m) => MerlError::Format(m),
                crate::input::InputError::Io(m) => MerlError::Io(m, std::io::ErrorKind::Other),
            })?;
        let p = path.display();
        Merl::parse(&bytes).map_err(|m| MerlError::Format(format!("{p}: {m}")))
    }

    /// Parses the bytes of a MERL file. Errors say what is wrong and where.
    pub fn parse(b: &[u8]) -> Result<Merl, String> {
        if b.len() < 12 {
            return Err(format!(
                "truncated: {} bytes, shorter than the 12-byte header (three int32 dimensions 90 90 180)",
                b.len()
            ));
        }
        let dims = [read_i32(b, 0), read_i32(b, 4), read_i32(b, 8)];
        if dims != [90, 90, 180] {
            return Err(format!(
                "header dimensions {} {} {}: the MERL format has 90 90 180 (theta_h, theta_d, phi_d)",
                dims[0], dims[1], dims[2]
            ));
        }
        if b.len() < FILE_BYTES {
            return Err(format!(
                "truncated: {} bytes, a MERL file has {FILE_BYTES} (12-byte header + 3 x {N} f64); \
                 the data end in channel {} at entry {}",
                b.len(),
                ["R", "G", "B"][((b.len() - 12) / 8 / N).min(2)],
                ((b.len() - 12) / 8) % N
            ));
        }
        if b.len() > FILE_BYTES {
            return Err(format!(
                "{} trailing bytes after the {FILE_BYTES} bytes of a MERL file",
                b.len() - FILE_BYTES
            ));
        }
        let mut values: [Vec<f64>; 3] = [vec![0.0; N], vec![0.0; N], vec![0.0; N]];
        let mut unmeasured = [0usize; 3];
        let mut above = [0usize; 3];
        for c in 0..3 {
            let base = 12 + c * N * 8;
            for (n, v) in values[c].iter_mut().enumerate() {
                let at = base + n * 8;
                let mut a = [0u8; 8];
                a.copy_from_slice(&b[at..at + 8]);
                let x = f64::from_le_bytes(a);
                if !x.is_finite() {
                    let (i, j, k) = (n / (90 * 180), (n / 180) % 90, n % 180);
                    return Err(format!(
                        "channel {} entry {n} (theta_h {i}, theta_d {j}, phi_d {k}) is {x}; values must be finite (negative = unmeasured)",
                        ["R", "G", "B"][c]
                    ));
                }
                if x < 0.0 {
                    unmeasured[c] += 1;
                    let (i, j, k) = (n / (90 * 180), (n / 180) % 90, n % 180);
                    let (th, td, pd) = node_angles(i, j, k);
                    let (wi, wo) = directions(th, td, pd);
                    if wi[2] > 0.0 && wo[2] > 0.0 {
                        above[c] += 1;
                    }
                    *v = -1.0;
                } else {
                    *v = x * SCALE[c];
                    if *v > MAX_MEASURED_VALUE {
                        let (i, j, k) = (n / (90 * 180), (n / 180) % 90, n % 180);
                        return Err(format!(
                            "channel {} entry {n} (theta_h {i}, theta_d {j}, phi_d {k}) is {}/sr after the channel scale, \
                             above {}/sr, which no measured material reaches: this is not measured BRDF data",
                            ["R", "G", "B"][c],
                            crate::numfmt::num(*v),
                            crate::numfmt::num(MAX_MEASURED_VALUE)
                        ));
                    }
                }
            }
        }
        Ok(Merl {
            values,
            unmeasured,
            unmeasured_above_horizon: above,
        })
    }

    /// The BRDF of channel `c` at (ωi, ωo) by multilinear interpolation between nodes
    /// (unmeasured corners left out); `None` below the horizon or where every corner is
    /// unmeasured.
    pub fn eval(&self, c: usize, wi: Dir, wo: Dir) -> Option<f64> {
        if wi[2] <= 0.0 || wo[2] <= 0.0 {
            return None;
        }
        let (th, td, pd) = half_diff(wi, wo)?;
        let a = (th.max(0.0) / FRAC_PI_2).sqrt() * 90.0;
        let b = td / FRAC_PI_2 * 90.0;
        let cc = pd / PI * 180.0;
        let clamp_axis = |x: f64, n: usize| -> (usize, f64) {
            let i0 = (x.floor().max(0.0) as usize).min(n - 2);
            (i0, (x - i0 as f64).clamp(0.0, 1.0))
        };
        let (i0, ti) = clamp_axis(a, 90);
        let (j0, tj) = clamp_axis(b, 90);
        let kf = cc.floor();
        let k0 = (kf.max(0.0) as usize) % 180;
        let tk = (cc - kf).clamp(0.0, 1.0);
        let k1 = (k0 + 1) % 180;
        let v = &self.values[c];
        let (mut sum, mut wsum) = (0.0, 0.0);
        for (i, wi_) in [(i0, 1.0 - ti), (i0 + 1, ti)] {
            for (j, wj) in [(j0, 1.0 - tj), (j0 + 1, tj)] {
                for (k, wk) in [(k0, 1.0 - tk), (k1, tk)] {
                    let w = wi_ * wj * wk;
                    let x = v[index(i, j, k)];
                    if w > 0.0 && x >= 0.0 {
                        sum += w * x;
                        wsum += w;
                    }
                }
            }
        }
        if wsum > 0.0 {
            Some(sum / wsum)
        } else {
            None
        }
    }
}

/// The bytes of a MERL file holding `f(ωi, ωo) = [R, G, B]` sampled at the nodes; entries
/// whose node directions are below the horizon are written as −1 (unmeasured).
pub fn write_bytes<F: Fn(Dir, Dir) -> [f64; 3] + Sync>(f: F) -> Vec<u8> {
    let rows: Vec<[f64; 3]> = (0..N)
        .into_par_iter()
        .map(|n| {
            let (i, j, k) = (n / (90 * 180), (n / 180) % 90, n % 180);
            let (th, td, pd) = node_angles(i, j, k);
            let (wi, wo) = directions(th, td, pd);
            if wi[2] <= 0.0 || wo[2] <= 0.0 {
                [-1.0; 3]
            } else {
                let v = f(wi, wo);
                [v[0] / SCALE[0], v[1] / SCALE[1], v[2] / SCALE[2]]
            }
        })
        .collect();
    let mut out = Vec::with_capacity(FILE_BYTES);
    for d in [90i32, 90, 180] {
        out.extend_from_slice(&d.to_le_bytes());
    }
    for c in 0..3 {
        for r in &rows {
            out.extend_from_slice(&r[c].to_le_bytes());
        }
    }
    out
}

/// One channel of a measured BRDF as a [`Reflectance`] (0 where unmeasured everywhere
/// around, see the module documentation).
#[derive(Clone, Debug)]
pub struct MerlChannel {
    pub merl: Arc<Merl>,
    pub channel: usize,
    pub label: String,
}

impl Reflectance for MerlChannel {
    fn eval(&self, wi: Dir, wo: Dir) -> f64 {
        self.merl.eval(self.channel, wi, wo).unwrap_or(0.0)
    }
    fn label(&self) -> String {
        self.label.clone()
    }
    fn formula(&self) -> String {
        "measured; multilinear in (sqrt(theta_h) index, theta_d, phi_d), unmeasured corners left out".into()
    }
    fn source(&self) -> &'static str {
        "Matusik, Pfister, Brand & McMillan 2003, 'A data-driven reflectance model' (MERL BRDF database format)"
    }
    fn lobe_width(&self) -> f64 {
        // the first θh node spacing is (1/90)²·π/2 ≈ 2e-4 rad; lobes that narrow are not
        // resolved by the data, 0.05 is a good warp for everything the grid can hold
        0.05
    }
    fn tolerance_floor(&self) -> f64 {
        // the interpolant has ~10⁶ kinks (grid lines); its own error against a smooth
        // BRDF is of order 1e-3..1e-2 in albedo (tests/merl.rs measures it)
        MEASURED_TOLERANCE_FLOOR
    }
}

/// A microfacet + Lambert fit of one channel:
/// `f = kd/π + D(α) G2 F_Schlick(F0) / (4 cos θi cos θo)`, height-correlated Smith G2, D
/// GGX ([`fit_ggx_lambert`]) or Beckmann ([`fit_beckmann_lambert`]).
#[derive(Clone, Copy, Debug, serde::Serialize)]
pub struct Fit {
    /// The fitted NDF: `ggx` or `beckmann`.
    pub ndf: &'static str,
    /// Its masking term: `smith-height-correlated`, or `v-groove` for Cook–Torrance.
    pub masking: &'static str,
    pub kd: f64,
    pub f0: f64,
    pub alpha: f64,
    /// √(Σ w r² / Σ w), r = model − measured, w = cos θi cos θo, over the fitted nodes.
    pub rms: f64,
    /// √(Σ w r² / Σ w y²): the rms relative to the weighted rms of the data.
    pub rel_rms: f64,
    /// Largest |r| over the fitted nodes.
    pub max_abs: f64,
    /// Nodes used.
    pub nodes: usize,
    /// Whether α ended at an end of [`FIT_ALPHA_RANGE`] (the data want a value outside it,
    /// or a shape the model cannot take: the fit is then only the best within the range).
    pub alpha_at_limit: bool,
}

/// A node used by the fit: geometry and measured value.
struct FitNode {
    wi: Dir,
    wo: Dir,
    w: f64,
    x5: f64,
    y: f64,
}

/// The model of [`Fit`] at α (F = 1, no diffuse): S = D G2/(4 cos θi cos θo).
fn specular(ndf: NdfKind, masking: Masking, alpha: f64) -> Specular {
    Specular {
        ndf: Ndf::new(ndf, alpha).expect("alpha within the searched range"),
        masking,
        fresnel: Fresnel::None,
    }
}

/// Per α: the 2×2 weighted least squares in (kd, F0) (f is linear in them:
/// f = kd·(1/π) + F0·S(1 − x⁵) + S·x⁵, x = 1 − h·ωi), with kd ≥ 0 and F0 ∈ [0, 1].
/// Returns (J, kd, F0). Partial sums over fixed chunks, added in order: deterministic.
fn solve_at(nodes: &[FitNode], (ndf, masking): (NdfKind, Masking), alpha: f64) -> (f64, f64, f64) {
    let sp = specular(ndf, masking, alpha);
    let parts: Vec<[f64; 8]> = nodes
        .par_chunks(2048)
        .map(|ch| {
            let mut s = [0.0; 8];
            for n in ch {
                let sv = sp.eval(n.wo, n.wi);
                let a = 1.0 / PI;
                let b = sv * (1.0 - n.x5);
                let r = n.y - sv * n.x5;
                s[0] += n.w * a * a;
                s[1] += n.w * a * b;
                s[2] += n.w * b * b;
                s[3] += n.w * a * r;
                s[4] += n.w * b * r;
                s[5] += n.w * r * r;
            }
            s
        })
        .collect();
    let mut s = [0.0; 8];
    for p in parts {
        for i in 0..8 {
            s[i] += p[i];
        }
    }
    let j = |kd: f64, f0: f64| {
        // Σ w (kd a + f0 b − r)²
        s[5] - 2.0 * (kd * s[3] + f0 * s[4])
            + kd * kd * s[0]
            + 2.0 * kd * f0 * s[1]
            + f0 * f0 * s[2]
    };
    let det = s[0] * s[2] - s[1] * s[1];
    let mut cands = Vec::new();
    if det > 0.0 {
        let kd = (s[3] * s[2] - s[4] * s[1]) / det;
        let f0 = (s[0] * s[4] - s[1] * s[3]) / det;
        if kd >= 0.0 && (0.0..=1.0).contains(&f0) {
            cands.push((kd, f0));
        }
    }
    // the boundary: one parameter fixed at a bound, the other optimal and clamped
    for f0 in [0.0, 1.0] {
        let kd = ((s[3] - f0 * s[1]) / s[0]).max(0.0);
        cands.push((kd, f0));
    }
    if s[2] > 0.0 {
        let f0 = (s[4] / s[2]).clamp(0.0, 1.0);
        cands.push((0.0, f0));
    }
    let mut best = (f64::INFINITY, 0.0, 0.0);
    for (kd, f0) in cands {
        let v = j(kd, f0).max(0.0);
        if v < best.0 {
            best = (v, kd, f0);
        }
    }
    best
}

/// Smallest and largest α searched.
pub const FIT_ALPHA_RANGE: [f64; 2] = [0.005, 1.0];

/// Fits GGX + Lambert to channel `c` over the measured nodes above the horizon with
/// θh_i every 1, θd_i every `stride[0]`, φd_i every `stride[1]`, weights cos θi cos θo:
/// for each α the best (kd, F0) is linear least squares; α minimizes the weighted sum of
/// squares by a 40-point search in ln α over [`FIT_ALPHA_RANGE`] and golden-section
/// refinement to |Δ ln α| < 1e-10. `None` if no node is measured.
pub fn fit_ggx_lambert(m: &Merl, c: usize, stride: [usize; 2]) -> Option<Fit> {
    fit_microfacet_lambert(m, c, stride, NdfKind::Ggx)
}

/// As [`fit_ggx_lambert`] with the Beckmann NDF
/// `D = exp(−tan²θh/α²)/(π α² cos⁴θh)` (Walter et al. 2007, eq. 25; Cook & Torrance 1982's
/// distribution with m = α) and its Smith G2 (height-correlated).
pub fn fit_beckmann_lambert(m: &Merl, c: usize, stride: [usize; 2]) -> Option<Fit> {
    fit_microfacet_lambert(m, c, stride, NdfKind::Beckmann)
}

/// As [`fit_ggx_lambert`] with Cook & Torrance's (1982) model: the Beckmann NDF (their D
/// with m = α, eq. 12 up to the form's π/4, see the README's conventions) and the V-groove
/// masking G = min(1, 2(n·h)(n·v)/(v·h), 2(n·h)(n·l)/(v·h)) (their eq. 6).
pub fn fit_cook_torrance_lambert(m: &Merl, c: usize, stride: [usize; 2]) -> Option<Fit> {
    fit_model_lambert(m, c, stride, NdfKind::Beckmann, Masking::VGroove)
}

/// The fits the `measured` command accepts (`--fit`): name, NDF, masking.
pub const FIT_MODELS: [(&str, NdfKind, Masking); 3] = [
    ("ggx", NdfKind::Ggx, Masking::SmithHeightCorrelated),
    (
        "beckmann",
        NdfKind::Beckmann,
        Masking::SmithHeightCorrelated,
    ),
    ("cook-torrance", NdfKind::Beckmann, Masking::VGroove),
];

/// The fit of [`fit_ggx_lambert`] with the NDF `ndf` (GGX or Beckmann: any NDF with a
/// Smith G2 works, these two have closed-form Λ).
pub fn fit_microfacet_lambert(m: &Merl, c: usize, stride: [usize; 2], ndf: NdfKind) -> Option<Fit> {
    fit_model_lambert(m, c, stride, ndf, Masking::SmithHeightCorrelated)
}

/// The fit of [`fit_ggx_lambert`] with any NDF and masking term.
pub fn fit_model_lambert(
    m: &Merl,
    c: usize,
    stride: [usize; 2],
    ndf: NdfKind,
    masking: Masking,
) -> Option<Fit> {
    let model_kind = (ndf, masking);
    let mut nodes = Vec::new();
    for i in 0..90 {
        for j in (0..90).step_by(stride[0].max(1)) {
            for k in (0..180).step_by(stride[1].max(1)) {
                let y = m.values[c][index(i, j, k)];
                if y < 0.0 {
                    continue;
                }
                let (th, td, pd) = node_angles(i, j, k);
                let (wi, wo) = directions(th, td, pd);
                if wi[2] <= 0.0 || wo[2] <= 0.0 {
                    continue;
                }
                let h = [
                    (wi[0] + wo[0]) * 0.5,
                    (wi[1] + wo[1]) * 0.5,
                    (wi[2] + wo[2]) * 0.5,
                ];
                let hl = dot(h, h).sqrt();
                let x = (1.0 - dot(wi, h) / hl).max(0.0);
                nodes.push(FitNode {
                    wi,
                    wo,
                    w: wi[2] * wo[2],
                    x5: x.powi(5),
                    y,
                });
            }
        }
    }
    if nodes.is_empty() {
        return None;
    }
    let (lo, hi) = (FIT_ALPHA_RANGE[0].ln(), FIT_ALPHA_RANGE[1].ln());
    let n = 40;
    let grid: Vec<f64> = (0..n)
        .map(|i| lo + (hi - lo) * i as f64 / (n - 1) as f64)
        .collect();
    let js: Vec<f64> = grid
        .iter()
        .map(|&g| solve_at(&nodes, model_kind, g.exp()).0)
        .collect();
    let best = (0..n)
        .min_by(|&a, &b| js[a].total_cmp(&js[b]))
        .expect("grid is not empty");
    let (mut a, mut b) = (grid[best.saturating_sub(1)], grid[(best + 1).min(n - 1)]);
    let g = (5f64.sqrt() - 1.0) / 2.0;
    let mut x1 = b - g * (b - a);
    let mut x2 = a + g * (b - a);
    let mut f1 = solve_at(&nodes, model_kind, x1.exp()).0;
    let mut f2 = solve_at(&nodes, model_kind, x2.exp()).0;
    while b - a > 1e-10 {
        if f1 <= f2 {
            b = x2;
            x2 = x1;
            f2 = f1;
            x1 = b - g * (b - a);
            f1 = solve_at(&nodes, model_kind, x1.exp()).0;
        } else {
            a = x1;
            x1 = x2;
            f1 = f2;
            x2 = a + g * (b - a);
            f2 = solve_at(&nodes, model_kind, x2.exp()).0;
        }
    }
    let mut la = 0.5 * (a + b);
    if js[best] < solve_at(&nodes, model_kind, la.exp()).0 {
        la = grid[best];
    }
    let alpha = la.exp();
    let (jmin, kd, f0) = solve_at(&nodes, model_kind, alpha);
    let model = Brdf {
        specular: Some(Specular {
            fresnel: Fresnel::Schlick { f0 },
            ..specular(ndf, masking, alpha)
        }),
        diffuse_weight: kd,
        diffuse: crate::model::DiffuseLobe::Lambert,
    };
    let (mut sw, mut swy2, mut max_abs) = (0.0, 0.0, 0.0f64);
    for nd in &nodes {
        sw += nd.w;
        swy2 += nd.w * nd.y * nd.y;
        max_abs = max_abs.max((model.eval(nd.wo, nd.wi) - nd.y).abs());
    }
    Some(Fit {
        ndf: ndf.name(),
        masking: masking.name(),
        kd,
        f0,
        alpha,
        rms: (jmin / sw).sqrt(),
        rel_rms: if swy2 > 0.0 {
            (jmin / swy2).sqrt()
        } else {
            0.0
        },
        max_abs,
        nodes: nodes.len(),
        alpha_at_limit: (alpha / FIT_ALPHA_RANGE[0] - 1.0).abs() < 1e-6
            || (alpha / FIT_ALPHA_RANGE[1] - 1.0).abs() < 1e-6,
    })
}

/// One row of a measured albedo table: E(μ) per channel.
#[derive(Clone, Copy, Debug, serde::Serialize)]
pub struct AlbedoRow {
    pub mu: f64,
    pub albedo: [f64; 3],
    pub error: [f64; 3],
}

/// Directional albedo `E(μ) = ∫ f(ωi, ωo) cos θo dωo` per channel at `n` cosines μ at
/// texel centres (μ = (i + 0.5)/n), by [`crate::laws::directional_albedo`] of the
/// interpolated data (see the module documentation for unmeasured entries) to `tol`.
pub fn albedo_table(m: &Arc<Merl>, n: usize, tol: f64) -> Vec<AlbedoRow> {
    albedo_table_until(m, n, tol, None).expect("no deadline")
}

/// [`albedo_table`], giving up (`None`) once `deadline` has passed (checked before every
/// row).
pub fn albedo_table_until(
    m: &Arc<Merl>,
    n: usize,
    tol: f64,
    deadline: Option<&crate::deadline::Deadline>,
) -> Option<Vec<AlbedoRow>> {
    let rows: Vec<Option<AlbedoRow>> = (0..n)
        .into_par_iter()
        .map(|i| {
            if deadline.is_some_and(|d| d.passed()) {
                return None;
            }
            let mu = (i as f64 + 0.5) / n as f64;
            let mut row = AlbedoRow {
                mu,
                albedo: [0.0; 3],
                error: [0.0; 3],
            };
            for c in 0..3 {
                let ch = MerlChannel {
                    merl: m.clone(),
                    channel: c,
                    label: String::new(),
                };
                let a = crate::laws::directional_albedo(&ch, mu.acos(), 0.0, tol);
                row.albedo[c] = a.value;
                row.error[c] = a.error;
            }
            Some(row)
        })
        .collect();
    rows.into_iter().collect()
}
