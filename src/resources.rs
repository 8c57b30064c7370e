//! Resource guards: how much memory and time a bake will need, estimated from the
//! requested sizes before anything is allocated, and the checks that refuse a bake over a
//! limit (`brdfbake bake --max-memory SIZE --max-time SECONDS`) instead of letting it
//! thrash, be killed, or hold a CI job for hours.
//!
//! The estimate is deliberately an upper bound of what the pipeline holds at its peak: a
//! bake keeps every table's texels and every encoded file in memory until all are written
//! atomically ([`crate::pipeline`]), and while a table bakes it also holds one result per
//! texel (two small `Vec<f64>` of value and error estimate).

use crate::numfmt::{human_bytes, human_seconds};
use crate::preset::{Format, Preset, PresetTable};

/// The default `--max-memory`: 2 GiB.
pub const DEFAULT_MAX_MEMORY: u64 = 2 << 30;

/// Bytes per texel of the bake's per-texel results while a table bakes: two `Vec<f64>`
/// headers (2 × 24 bytes) and two heap blocks of at most 4 channels × 8 bytes each, which
/// the allocator rounds up with its own header (≤ 48 bytes each); 160 rounds that up.
const SCRATCH_PER_TEXEL: u64 = 160;

/// Bytes per value of the text formats (C header, Rust source): a value printed with its
/// separator takes at most ~16 characters (`-1.23456789e-12, ` style, or `0x3c00, ` for
/// half), and the `String` may have grown to twice its length while being built.
const TEXT_BYTES_PER_VALUE: u64 = 32;

/// Fixed allowance per table: sidecar JSON, headers, shader snippets, small vectors.
const PER_TABLE: u64 = 1 << 20;

/// The estimated peak memory of baking one table into `formats`, split into what stays
/// until the write (`kept`: texels and encoded files) and what is freed when the table is
/// done (`scratch`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Estimate {
    /// Texels of all tables.
    pub texels: u64,
    /// Bytes held until the files are written.
    pub kept: u64,
    /// Largest transient allocation of one table's bake.
    pub scratch: u64,
}

impl Estimate {
    /// Estimated peak bytes: everything kept plus the largest table's scratch.
    pub fn peak(&self) -> u64 {
        self.kept.saturating_add(self.scratch)
    }
}

/// Estimates one table (see [`Estimate`]); `formats` are the formats it is written in.
pub fn estimate_table(t: &PresetTable, formats: &[Format]) -> Estimate {
    let texels = t
        .spec
        .axes
        .iter()
        .fold(1u64, |n, a| n.saturating_mul(a.size as u64));
    // (the kind's channels and the stored ones both live while a table is stored)
    let channels = crate::table::channels(&t.spec)
        .len()
        .max(t.stored_channels().len()) as u64;
    let stored = t.spec.storage.bytes() as u64;
    // the Lut's f32 texels
    let mut per_texel: u64 = channels * 4;
    for f in formats {
        per_texel += match f {
            // encoder buffer + the encoded file (KTX2 pads 3 channels to 4)
            Format::Exr => 2 * channels * stored,
            Format::Ktx2 | Format::Dds => {
                2 * channels.max(if channels == 3 { 4 } else { 1 }) * stored
            }
            // and the compressed level
            Format::Ktx2Zstd => 3 * channels.max(if channels == 3 { 4 } else { 1 }) * stored,
            // 16-bit grey image per channel + 16-bit RGB false colour, raw and compressed
            Format::Png => 2 * (channels * 2 + 6),
            // the codes (u16), the image rows (at most 4 components) raw and compressed
            Format::PngData => channels * 2 + 2 * 4 * stored,
            // the RGBA codes, raw and compressed
            Format::PngRgbd => 2 * 4,
            Format::H | Format::Rs => channels * TEXT_BYTES_PER_VALUE,
            // a lookup function: no texels
            Format::Glsl | Format::Hlsl | Format::Wgsl => 0,
            // the stored texels (after f16 values or unorm codes of 2 bytes), and each
            // container's copy of them: the .npy, and the .npz's .npy and archive
            Format::Bin => channels * (stored + 2),
            Format::Npy => channels * (2 * stored + 2),
            Format::Npz => channels * (3 * stored + 2),
        };
    }
    // a fit's search (`fit`): its validation points' rows, while the table is kept
    let fit_scratch = t.fit.as_ref().map_or(0, |_| {
        crate::fit::grid::points(&t.spec).map_or(0, |n| {
            (n as u64).saturating_mul(crate::fit::grid::BYTES_PER_POINT)
        })
    });
    Estimate {
        texels,
        kept: texels.saturating_mul(per_texel).saturating_add(PER_TABLE),
        scratch: texels.saturating_mul(SCRATCH_PER_TEXEL).max(fit_scratch),
    }
}

/// Estimates a whole invocation: every table of every preset, each in `formats` when
/// given (the `--format` override) or in its own.
pub fn estimate(presets: &[Preset], formats: Option<&[Format]>) -> Estimate {
    let mut total = Estimate::default();
    for p in presets {
        for t in &p.tables {
            let e = estimate_table(t, formats.unwrap_or(&t.formats));
            total.texels = total.texels.saturating_add(e.texels);
            total.kept = total.kept.saturating_add(e.kept);
            total.scratch = total.scratch.max(e.scratch);
        }
    }
    total
}

/// The default `--max-time`: 10 minutes (every default preset together takes seconds).
pub const DEFAULT_MAX_SECONDS: f64 = 600.0;

/// CPU time per integrand evaluation assumed by the time estimate: 100 ns. Measured on the
/// benchmark machine (BENCHMARKS.md: 2-core Xeon, 2026-11-29) at 79–97 ns per evaluation
/// (CPU time / evaluations of filament-dfg, dielectric-btdf and the V-groove albedo),
/// rounded up.
pub const SECONDS_PER_EVALUATION: f64 = 100e-9;

/// CPU time per texel of a closed-form table (ndf, closed-form g1/g2, vgroove), per-texel
/// overhead included: 1 µs (measured 0.2–0.7 µs per texel on the benchmark machine).
const SECONDS_PER_CLOSED_FORM_TEXEL: f64 = 1e-6;

/// Integrand evaluations a numeric Smith G1 (NDFs without a closed-form Λ) costs per
/// roughness value: 17 Chebyshev nodes per panel, up to a few hundred panels near delta
/// lobes, each node a G7/K15 quadrature of ~300 nodes; 10⁶ is the near-delta worst case
/// (α = 1e-9: 25–36 ms on the benchmark machine), ~10× the typical case.
const EVALS_PER_NUMERIC_G1: f64 = 1e6;

/// The typical integrand evaluations per texel of an integrated table kind at the default
/// tolerance (1e-7), measured with `scripts/bench.sh` on the default presets (evaluations ÷
/// texels, rounded up): smooth albedo 1,473 (`energy-albedo`/e before the GGX polar kernel),
/// V-groove albedo 2,076 (`cook-torrance-1982`/albedo; 12,985 before its fast path,
/// [`vgroove`](crate::kernels::vgroove); its E_avg 83,000–190,000 per roughness), average
/// albedo 159,453 per roughness (`e-avg` before the polar kernel), cloth channel 1,750
/// (`filament-dfg` − `karis-envbrdf`), Fresnel albedo 1,111, dielectric BTDF 19,551 (all
/// 2026-11-29). GGX with Smith masking goes through the 1D polar kernel
/// (src/kernels/ggx_polar.rs; 2026-11-29, 23:00 UTC): albedo 83 (`energy-albedo`/e),
/// average albedo 6,965 per roughness (`e-avg`), DFG 915 (`karis-envbrdf`). Grazing views
/// and near-delta lobes cost more, smooth wide lobes less; the estimate is a guide, the
/// run-time check of the same limit ([`Deadline`]) is the guarantee.
fn evals_per_texel(t: &PresetTable) -> (f64, f64) {
    use crate::model::Masking;
    use crate::table::TableKind as K;
    let spec = &t.spec;
    let vgroove = spec.model.masking == Masking::VGroove;
    let polar = crate::table::methods::split_sum_uses_kernel(spec.model.ndf, spec.model.masking);
    let polar_albedo = polar && crate::table::methods::albedo_uses_kernel(&spec.model);
    // Charlie + Ashikhmin albedo through the cloth kernels (src/table/albedo.rs
    // `charlie_kernels`, column by column): 78 per texel with the θh kernel
    // (src/kernels/sheen_azimuth.rs; `sheen-charlie`, 80,305 evaluations over 1,024
    // texels, 2026-11-30), most of them an `exp` on node data the column shares; 1,359 with
    // the light-direction kernels, 1,756 with the half-vector kernel alone
    let cloth_albedo = crate::table::methods::albedo_uses_kernel(&spec.model)
        && spec.model.ndf == Some(crate::model::NdfKind::Charlie);
    // V-groove albedo: 1,923 per texel with the closed-form Beckmann kernel and the ordered
    // tolerance sharing (`cook-torrance-1982`/albedo, 1,968,969 evaluations over 1,024
    // texels, 2026-11-30; 2,075 before), at ~40 ns each rather than 100 ns
    let albedo = if vgroove {
        2_000.0
    } else if polar_albedo || cloth_albedo {
        100.0
    } else {
        1_500.0
    };
    let avg = if polar_albedo { 7_000.0 } else { 160_000.0 };
    let dfg = if polar { 950.0 } else { 1_600.0 };
    // (per texel, per roughness row)
    match spec.kind {
        K::Ndf | K::G1 | K::G2 | K::Vgroove => (0.0, 0.0),
        K::Albedo => (albedo, 0.0),
        K::AlbedoAvg => (avg, 0.0),
        // cloth: 1,585 per texel measured with its light-direction path for narrow lobes
        // (cloth4), 1,286 with the one for wide lobes too (cloth5: filament-dfg 36,066,234
        // evaluations with cloth, 14,992,751 without, over 16,384 texels). GGX rows
        // interpolated in √μ (src/quadrature/interp1d.rs) cost per row about 40,000 + 85 per
        // texel (measured: 50,700 per 128-texel row, 82,800 per 512-texel row of
        // karis-envbrdf, 2026-11-30), never more than texel by texel. The cloth channel
        // interpolated too (narrow lobes along rows, wide ones along columns): filament-dfg
        // 7.24 M cloth evaluations at 128² (442 per texel), 53.1 M at 512² (203).
        // With grids (src/table/dfg_lines.rs, tables of ≥ 128 columns; 2026-11-30): a fixed
        // cost plus a little per texel, the pair from karis-envbrdf (5.0 M at 128², 13.5 M
        // at 512²: 4.4 M + 35 per texel), the cloth channel from filament-dfg less that
        // (7.1 M and 13.4 M: 6.7 M + 26 per texel); the fixed cost is spread over the rows.
        // Since (2026-11-30, the θh cloth kernel and the polar kernel's nested outer rule):
        // the pair 3.08 M at 128², 6.90 M at 512² (2.8 M + 16 per texel), the cloth channel
        // 0.87 M and 1.31 M (0.85 M + 2 per texel)
        K::Dfg => {
            let interpolated = crate::table::methods::split_sum_by_lines(spec);
            let nx = spec.axes[0].size as f64;
            if interpolated && nx >= crate::table::methods::GRID_MIN_COLUMNS as f64 {
                let (cloth, cloth_fixed) = if spec.cloth {
                    (2.0, 0.85e6)
                } else {
                    (0.0, 0.0)
                };
                let rows = spec.axes.get(1).map_or(1.0, |a| a.size as f64);
                return (16.0 + cloth, (2.8e6 + cloth_fixed) / rows);
            }
            // (the θh cloth kernel: 114 per texel at 64², where the narrow lobes go by rows
            // and the wide ones by columns; ~80 texel by texel, as `sheen-charlie`)
            let cloth = match (spec.cloth, interpolated) {
                (false, _) => 0.0,
                (true, true) => 120.0,
                (true, false) => 100.0,
            };
            if interpolated {
                let row = (40_000.0 + 85.0 * nx).min(dfg * nx);
                (cloth, row)
            } else {
                (dfg + cloth, 0.0)
            }
        }
        K::KullaConty => (albedo, avg),
        // exact Fresnel slices go by fibres (all slices of one (μ, r) as the channels of one
        // rule, nodes counted once): 141 per texel on `fresnel-albedo`/e-dielectric (847 texel
        // by texel; fib6, 2026-11-30, `examples/fibre_check.rs`)
        K::AlbedoFresnel if crate::table::methods::uses_fresnel_fibre(spec) => (150.0, 0.0),
        K::AlbedoFresnel => (1_200.0, 0.0),
        // measured 5,042 per texel (`dielectric-btdf`, 2026-11-29; 19,551 in the paragraph
        // above was before the closed-form kinks and Clenshaw–Curtis panels of
        // src/table/dielectric.rs). By fibres (fib6, 2026-11-30, `examples/fibre_check.rs`):
        // the η ≥ 1 slices of one (μ, r) share one rule, 2,812 nodes per group of 4 (~700
        // per texel, nodes counted once). The η < 1 slices go by roughness fibres
        // (src/kernels/roughness_fibre.rs), whose nodes serve up to 15 texels at ~3× the cost
        // of one, so they are counted by CPU time: 157 µs per texel on eevee-btdf-split-sum-ggx,
        // 1,570 evaluations at 100 ns (2026-12-03, a slow phase of the benchmark machine):
        // counted as 2,000
        K::DielectricBtdf => {
            let frac = below_one_fraction(spec);
            (2_000.0 * frac + 750.0 * (1.0 - frac), 0.0)
        }
        // dielectric-albedo: measured on Cycles' glass_E layout; η < 1 by roughness fibres,
        // by CPU time as above: 249 µs per texel on cycles-glass-inv-e (tolerance 1e-7,
        // height-correlated), counted as 2,500
        K::DielectricAlbedo => {
            let frac = below_one_fraction(spec);
            (2_500.0 * frac + 1_000.0 * (1.0 - frac), 0.0)
        }
        K::DielectricAlbedoAvg => (100_000.0, 0.0),
        // dielectric-schlick: η < 1 by roughness fibres, by CPU time as for dielectric-btdf:
        // 171 µs per texel on eevee-bsdf-ggx (2026-12-03), counted as 2,000; η ≥ 1 fibres of
        // 8 slices per rule, measured 324 nodes per texel (eevee-btdf-ggx, 2026-12-02), each
        // node with 8 refractions: counted as 400
        K::DielectricSchlick => {
            let frac = below_one_fraction(spec);
            (2_000.0 * frac + 400.0 * (1.0 - frac), 0.0)
        }
        // schlick-weight-*: measured 1,165 (exponent axis) and 1,186 (eta axis) per texel on
        // the cycles-ggx-gen-schlick-* presets (2026-12-02, fibres of 8 slices)
        K::SchlickWeightVndf | K::SchlickWeightAlbedo => (1_200.0, 0.0),
        // the laws' adaptive integrator over the full azimuth: ~10⁴ per albedo; the
        // anisotropic kind takes ~20 albedos per texel (azimuth average + two azimuths).
        // Models with the 1D fast path (src/kernels/classic_lobes.rs) measured on the
        // `classic-albedo` preset (2026-11-30): blinn-phong 46, modified-phong 29 (phong the
        // same), ward-gmd 86 per texel; each evaluation costs a few transcendental
        // functions (~0.2-0.6 us), more than the 100 ns assumed.
        K::ClassicAlbedo => (classic_evals_per_texel(spec.model.classic.as_ref()), 0.0),
        K::ClassicAlbedoAniso => (300_000.0, 0.0),
        // the LTC fit: 1.4–1.7 s of CPU for the 64² GGX table (0.37 ms a texel, the fit's
        // normal equations over 216 nodes and ~50 probe lights a pass; examples/ltc_check.rs,
        // 2026-12-02), i.e. ~3,700 evaluations' worth at 100 ns, plus the norm and Fresnel
        // integrals (two albedos); without matrix channels the integrals alone; the sphere
        // table is a closed form
        // Per model, the 64² table on Heitz's grid on 1 thread (fit, norm and Fresnel;
        // `examples/ltc_models_check.rs --heitz 64` with RAYON_NUM_THREADS=1, 2026-12-02, a
        // loaded machine): GGX 0.8–1.0 s, Lambert 0.84, Burley 3.6, Beckmann 4.4, Charlie +
        // Ashikhmin 1.4, Charlie + Conty–Kulla 7.2: the fit scaled by 4, 5, 2 and 8 (their
        // BRDFs cost more per evaluation, and the optimizer takes more passes)
        K::Ltc => {
            use crate::model::{DiffuseModel, Masking, NdfKind};
            let chans = crate::table::ltc::ltc_channels(spec);
            let m = &spec.model;
            let scale = match (m.ndf, m.masking) {
                (Some(NdfKind::Ggx), _) => 1.0,
                (Some(NdfKind::Charlie), Masking::ContyKulla | Masking::ContyKullaSoftened) => 8.0,
                (Some(NdfKind::Charlie), _) => 2.0,
                (Some(_), _) => 5.0,
                (None, _) if m.diffuse_model == DiffuseModel::Burley => 4.0,
                (None, _) => 1.0,
            };
            let fit = if chans.iter().any(|c| c.is_matrix()) {
                4_000.0 * scale
            } else {
                0.0
            };
            let integrals = if chans.iter().any(|c| {
                c.is_matrix()
                    || matches!(
                        c,
                        crate::table::LtcChannel::Norm | crate::table::LtcChannel::Fresnel
                    )
            }) {
                2.0 * albedo
            } else {
                0.0
            };
            (fit + integrals, 0.0)
        }
        K::LtcSphere => (0.0, 0.0),
    }
}

/// The fraction of a dielectric table's slices whose relative index η < 1 (integrated by
/// roughness fibres, the costly ones); all of them without a fresnel axis, none on a fresnel
/// axis that does not give η (which the dielectric kinds refuse).
fn below_one_fraction(spec: &crate::table::TableSpec) -> f64 {
    spec.axes.get(2).map_or(1.0, |z| {
        if !matches!(z.quantity, crate::lut::Quantity::Fresnel(q) if q.is_eta()) {
            return 0.0;
        }
        let below = (0..z.size)
            .filter(|&k| z.fresnel_parameter(k).is_some_and(|eta| eta < 1.0))
            .count();
        below as f64 / z.size.max(1) as f64
    })
}

/// Typical evaluations per texel of a `classic-albedo` table (see [`evals_per_texel`]).
fn classic_evals_per_texel(c: Option<&crate::table::classic::ClassicModel>) -> f64 {
    use crate::table::classic::ClassicModel as C;
    match c {
        Some(C::BlinnPhong { .. }) => 50.0,
        Some(C::ModifiedPhong { .. } | C::Phong { .. }) => 30.0,
        Some(C::WardGmd { .. }) => 90.0,
        _ => 15_000.0,
    }
}

/// Estimated CPU seconds and integrand evaluations of baking one table.
pub fn estimate_table_time(t: &PresetTable) -> TimeEstimate {
    let axes = &t.spec.axes;
    let texels = axes.iter().map(|a| a.size as f64).product::<f64>();
    let rows = axes
        .iter()
        .find(|a| a.name == "roughness")
        .map_or(1.0, |a| a.size as f64);
    let (per_texel, per_row) = evals_per_texel(t);
    let numeric_g1 = t.spec.model.ndf.is_some_and(|k| !k.closed_form_lambda())
        && matches!(
            t.spec.model.masking,
            crate::model::Masking::SmithSeparable | crate::model::Masking::SmithHeightCorrelated
        );
    // the numeric G1 is built once per roughness value (per Fresnel slice for 3D kinds)
    let g1_builds = if numeric_g1 {
        texels / axes.first().map_or(1.0, |a| a.size as f64)
    } else {
        0.0
    };
    let evaluations = texels * per_texel + rows * per_row + g1_builds * EVALS_PER_NUMERIC_G1;
    // a fit (`fit`): its exact values at the validation points are a table of those points,
    // and its search costs per point
    let fit_seconds = t.fit.as_ref().map_or(0.0, |_| {
        crate::fit::grid::points(&t.spec).map_or(0.0, |n| {
            let per_point = per_texel * SECONDS_PER_EVALUATION;
            n as f64 * (per_point + crate::fit::grid::SECONDS_PER_POINT)
        })
    });
    TimeEstimate {
        evaluations,
        cpu_seconds: evaluations * SECONDS_PER_EVALUATION
            + texels * SECONDS_PER_CLOSED_FORM_TEXEL
            + fit_seconds,
    }
}

/// An estimated cost: integrand evaluations and CPU seconds.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct TimeEstimate {
    pub evaluations: f64,
    pub cpu_seconds: f64,
}

/// Estimates every table of every preset.
pub fn estimate_time(presets: &[Preset]) -> TimeEstimate {
    let mut total = TimeEstimate::default();
    for p in presets {
        for t in &p.tables {
            let e = estimate_table_time(t);
            total.evaluations += e.evaluations;
            total.cpu_seconds += e.cpu_seconds;
        }
    }
    total
}

/// Parses `--max-time`: seconds, a finite number > 0 (fractions allowed).
pub fn parse_seconds(s: &str) -> Result<f64, String> {
    match s.trim().parse::<f64>() {
        Ok(v) if v.is_finite() && v > 0.0 => Ok(v),
        _ => Err(format!(
            "{s:?} is not a time limit: expected a number of seconds > 0, e.g. 600 or 0.5"
        )),
    }
}

/// Refuses a bake whose estimated wall time on `threads` threads exceeds `limit` seconds,
/// with the estimate and how to raise the limit.
pub fn check_time(est: &TimeEstimate, threads: usize, limit: f64) -> Result<(), String> {
    check_time_of(
        "this bake",
        "bake fewer or smaller tables",
        est,
        threads,
        limit,
    )
}

/// [`check_time`] for any command: `what` is what needs the time (`"this verify"`),
/// `smaller` how to ask for less.
pub fn check_time_of(
    what: &str,
    smaller: &str,
    est: &TimeEstimate,
    threads: usize,
    limit: f64,
) -> Result<(), String> {
    let wall = est.cpu_seconds / threads.max(1) as f64;
    if wall <= limit {
        return Ok(());
    }
    Err(format!(
        "{what} needs an estimated {} on {threads} thread(s) (~{:.2e} integrand evaluations at ~{} ns each, \
         typical costs measured on a 2-core machine), more than the limit of {}: raise it with --max-time SECONDS \
         (e.g. --max-time {}), use more threads, or {smaller}",
        human_seconds(wall),
        est.evaluations,
        SECONDS_PER_EVALUATION * 1e9,
        human_seconds(limit),
        (wall * 1.5).ceil()
    ))
}

/// The CPU time of `evaluations` integrand evaluations.
pub fn time_of_evaluations(evaluations: f64) -> TimeEstimate {
    TimeEstimate {
        evaluations,
        cpu_seconds: evaluations * SECONDS_PER_EVALUATION,
    }
}

impl std::ops::Add for TimeEstimate {
    type Output = TimeEstimate;
    fn add(self, o: TimeEstimate) -> TimeEstimate {
        TimeEstimate {
            evaluations: self.evaluations + o.evaluations,
            cpu_seconds: self.cpu_seconds + o.cpu_seconds,
        }
    }
}

/// Parses a memory size: a whole number of bytes with an optional unit `K`, `M`, `G`, `T`
/// (powers of 1024; `KiB`, `MiB`, ... and `KB`, `MB`, ... are read the same), e.g. `4GiB`,
/// `512M`, `1000000`. Zero is refused.
pub fn parse_size(s: &str) -> Result<u64, String> {
    let t = s.trim();
    let split = t.find(|c: char| !c.is_ascii_digit()).unwrap_or(t.len());
    let (num, unit) = t.split_at(split);
    let accepted = "a whole number of bytes with an optional unit K, M, G or T (powers of 1024), e.g. 4GiB or 512M";
    if num.is_empty() {
        return Err(format!("{s:?} is not a size: expected {accepted}"));
    }
    let n: u64 = num
        .parse()
        .map_err(|_| format!("{s:?} is too large a size (at most {} bytes)", u64::MAX))?;
    let shift = match unit.trim().to_ascii_lowercase().as_str() {
        "" | "b" => 0,
        "k" | "kb" | "kib" => 10,
        "m" | "mb" | "mib" => 20,
        "g" | "gb" | "gib" => 30,
        "t" | "tb" | "tib" => 40,
        _ => return Err(format!("{s:?}: unknown unit {unit:?}; expected {accepted}")),
    };
    let bytes = n
        .checked_mul(1u64 << shift)
        .ok_or_else(|| format!("{s:?} is too large a size (at most {} bytes)", u64::MAX))?;
    if bytes == 0 {
        return Err(format!("{s:?}: the limit must be more than 0 bytes"));
    }
    Ok(bytes)
}

/// Refuses `est` over `limit` with a message giving the estimate and how to raise the limit.
pub fn check(est: &Estimate, limit: u64) -> Result<(), String> {
    check_memory_of(
        "this bake",
        &format!(
            "{} texels in all; texels and encoded files are kept until the atomic write",
            est.texels
        ),
        "bake fewer or smaller tables or fewer formats",
        est.peak(),
        limit,
    )
}

/// [`check`] for any command: `what` needs `bytes` (`detail` says of what), `smaller` says
/// how to ask for less.
pub fn check_memory_of(
    what: &str,
    detail: &str,
    smaller: &str,
    bytes: u64,
    limit: u64,
) -> Result<(), String> {
    if bytes <= limit {
        return address_space_check(what, detail, smaller, bytes);
    }
    Err(format!(
        "{what} needs an estimated {} of memory ({detail}), more than the limit of {}: raise it with \
         --max-memory SIZE (e.g. --max-memory {}), or {smaller}",
        human_bytes(bytes),
        human_bytes(limit),
        suggest(bytes)
    ))
}

/// What each worker thread may map besides the work's own memory (its stack and the C
/// allocator's arena), for [`address_space_check`].
const PER_THREAD_MAPPING: u64 = 80 << 20;

/// The work must also fit the process's address-space limit (`ulimit -v`, RLIMIT_AS, and
/// RLIMIT_DATA), which `--max-memory` knows nothing of: past it an allocation fails, and Rust
/// aborts the process. Refused here instead, naming the limit: what is mapped now, the work's
/// estimate and [`PER_THREAD_MAPPING`] per thread must fit under it.
fn address_space_check(what: &str, detail: &str, smaller: &str, bytes: u64) -> Result<(), String> {
    let Some((limit, name)) = address_space_limit() else {
        return Ok(());
    };
    let mapped = mapped_bytes().unwrap_or(0);
    let threads = rayon::current_num_threads() as u64;
    let need = mapped
        .saturating_add(bytes)
        .saturating_add(threads.saturating_mul(PER_THREAD_MAPPING));
    if need <= limit {
        return Ok(());
    }
    Err(format!(
        "{what} needs an estimated {} of memory ({detail}), and with the {} this process has mapped \
         and its {threads} thread(s) more than the address-space limit of {} ({name}, `ulimit -v`): \
         raise that limit, use fewer --threads, or {smaller}",
        human_bytes(bytes),
        human_bytes(mapped),
        human_bytes(limit)
    ))
}

/// The smaller of RLIMIT_AS and RLIMIT_DATA, with its name, if either is set.
fn address_space_limit() -> Option<(u64, &'static str)> {
    #[cfg(unix)]
    {
        let get = |r| {
            let mut l = libc::rlimit {
                rlim_cur: 0,
                rlim_max: 0,
            };
            // SAFETY: getrlimit writes the struct we own
            let ok = unsafe { libc::getrlimit(r, &mut l) } == 0;
            (ok && l.rlim_cur != libc::RLIM_INFINITY).then_some(l.rlim_cur)
        };
        let as_ = get(libc::RLIMIT_AS).map(|v| (v, "RLIMIT_AS"));
        let data = get(libc::RLIMIT_DATA).map(|v| (v, "RLIMIT_DATA"));
        match (as_, data) {
            (Some(a), Some(d)) => Some(if a.0 <= d.0 { a } else { d }),
            (a, d) => a.or(d),
        }
    }
    #[cfg(not(unix))]
    None
}

/// The process's mapped virtual memory now (Linux: /proc/self/statm), if known.
fn mapped_bytes() -> Option<u64> {
    let text = std::fs::read_to_string("/proc/self/statm").ok()?;
    let pages: u64 = text.split_whitespace().next()?.parse().ok()?;
    #[cfg(unix)]
    // SAFETY: sysconf has no preconditions
    let page = unsafe { libc::sysconf(libc::_SC_PAGESIZE) }.max(4096) as u64;
    #[cfg(not(unix))]
    let page = 4096;
    Some(pages * page)
}

/// A round `--max-memory` value at least `bytes`: whole GiB, or whole MiB below 1 GiB.
fn suggest(bytes: u64) -> String {
    if bytes >= 1 << 30 {
        format!("{}GiB", bytes.div_ceil(1 << 30))
    } else {
        format!("{}MiB", bytes.div_ceil(1 << 20).max(1))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sizes_parse_with_binary_units() {
        assert_eq!(parse_size("1000").unwrap(), 1000);
        assert_eq!(parse_size("4GiB").unwrap(), 4 << 30);
        assert_eq!(parse_size("512M").unwrap(), 512 << 20);
        assert_eq!(parse_size("3 kb").unwrap(), 3 << 10);
        assert_eq!(parse_size("1T").unwrap(), 1 << 40);
        for bad in [
            "",
            "GiB",
            "-1",
            "1.5G",
            "12 parsecs",
            "0",
            "0M",
            "99999999999999999999",
        ] {
            assert!(parse_size(bad).is_err(), "{bad:?} accepted");
        }
        // overflow of the unit multiplication is refused, not wrapped
        assert!(parse_size("17179869184G").is_err());
    }

    #[test]
    fn seconds_parse() {
        assert_eq!(parse_seconds("600").unwrap(), 600.0);
        assert_eq!(parse_seconds(" 0.5 ").unwrap(), 0.5);
        for bad in ["", "0", "-1", "NaN", "inf", "1e400", "ten", "5s"] {
            assert!(parse_seconds(bad).is_err(), "{bad:?} accepted");
        }
    }

    #[test]
    fn time_check_divides_by_threads_and_suggests_enough() {
        let e = TimeEstimate {
            evaluations: 1e9,
            cpu_seconds: 100.0,
        };
        assert!(check_time(&e, 2, 50.0).is_ok());
        let msg = check_time(&e, 1, 50.0).unwrap_err();
        assert!(msg.contains("--max-time 150"), "{msg}");
        assert!(msg.contains("100.0 s") && msg.contains("50.0 s"), "{msg}");
    }

    #[test]
    fn human_sizes() {
        assert_eq!(human_bytes(512), "512 bytes");
        assert_eq!(human_bytes(3 << 20), "3.0 MiB");
        assert_eq!(human_bytes(3 << 29), "1.5 GiB");
    }

    #[test]
    fn suggestion_is_at_least_the_estimate() {
        for b in [1u64, 1 << 20, (1 << 20) + 1, 5 << 29, (3 << 30) + 7] {
            let s = suggest(b);
            assert!(parse_size(&s).unwrap() >= b, "{b}: {s}");
        }
    }
}
