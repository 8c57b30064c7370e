//! A chosen fit, and its files: the functions (`crate::encode::function`) and the
//! `brdfbake.fit/1` sidecar that `brdfbake verify` re-checks. Shared by `brdfbake fit
//! --max-error` and the preset field `"fit"`, which `bake` writes beside the table.

use super::search::{self, Candidate, Weight};
use super::target::{self, Target};
use crate::encode::function;
use crate::numfmt::num;
use crate::table::TableSpec;
use serde_json::json;
use std::path::{Path, PathBuf};

/// Search CPU seconds per validation point (measured: 66k points, 2 threads, 80 s wall).
pub const SECONDS_PER_POINT: f64 = 2.5e-3;
/// Peak bytes per validation point (the exchange's rows: up to 66 unknowns of 8 bytes, the
/// coarse copy, variables and values).
pub const BYTES_PER_POINT: u64 = 1200;

/// Which fit of the front to take.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Goal {
    /// The cheapest whose max error plus f32 bound is at most this.
    MaxError(f64),
    /// The most accurate of at most this many operations.
    MaxOps(usize),
}

/// A preset table's `"fit"`: `{"max_error": E}` or `{"max_ops": N}`, optionally `"weight"`
/// (absolute, relative) and `"emit"` (languages; default all).
#[derive(Clone, Debug, PartialEq)]
pub struct Request {
    pub goal: Goal,
    pub weight: Weight,
    pub emit: Vec<String>,
}

/// The preset's JSON form of [`Request`].
#[derive(serde::Deserialize, serde::Serialize, Clone, Debug)]
#[serde(deny_unknown_fields)]
pub struct RawRequest {
    #[serde(default)]
    pub max_error: Option<f64>,
    #[serde(default)]
    pub max_ops: Option<usize>,
    #[serde(default)]
    pub weight: Option<Weight>,
    #[serde(default)]
    pub emit: Option<Vec<String>>,
}

impl RawRequest {
    /// The request, or what is wrong with it.
    pub fn check(&self) -> Result<Request, String> {
        let goal = match (self.max_error, self.max_ops) {
            (Some(e), None) if e.is_finite() && e > 0.0 => Goal::MaxError(e),
            (Some(e), None) => {
                return Err(format!("max_error must be a positive number, got {}", num(e)))
            }
            (None, Some(n)) if n >= 1 => Goal::MaxOps(n),
            (None, Some(_)) => return Err("max_ops must be at least 1".into()),
            _ => {
                return Err(
                    "needs exactly one of max_error (the cheapest fit within it) or max_ops (the most accurate fit of at most that many operations)"
                        .into(),
                )
            }
        };
        let emit = self
            .emit
            .clone()
            .unwrap_or_else(|| function::LANGUAGES.iter().map(|s| s.to_string()).collect());
        if emit.is_empty() {
            return Err("emit lists no language".into());
        }
        for l in &emit {
            if function::dialect(l).is_none() {
                return Err(format!(
                    "emit: unknown language {l:?} (accepted: {})",
                    function::LANGUAGES.join(", ")
                ));
            }
        }
        Ok(Request {
            goal,
            weight: self.weight.unwrap_or(Weight::Absolute),
            emit,
        })
    }
}

/// The fit of `front` (as [`search::search`] orders it: cheapest first, each more accurate
/// than the one before) that `goal` asks for, or why none does.
pub fn choose<'a>(front: &'a [Candidate], goal: Goal, what: &str) -> Result<&'a Candidate, String> {
    let best = front.last();
    let picked = match goal {
        Goal::MaxError(e) => front.iter().find(|c| c.max_total() <= e),
        Goal::MaxOps(n) => front.iter().rev().find(|c| c.counts.ops <= n),
    };
    picked.ok_or_else(|| match goal {
        Goal::MaxError(e) => format!(
            "no fit of {what} reaches max error {} (the best: {} with {} operations); ask for more error or bake a texture",
            num(e),
            num(best.map_or(f64::NAN, |c| c.max_total())),
            best.map_or(0, |c| c.counts.ops)
        ),
        Goal::MaxOps(n) => format!(
            "no fit of {what} has at most {n} operations (the cheapest has {})",
            front.first().map_or(0, |c| c.counts.ops)
        ),
    })
}

/// The validation points a table's fit uses (the search's time and memory grow with them),
/// or why the table cannot be fitted.
pub fn points(spec: &TableSpec) -> Result<usize, String> {
    let axes = target::grid_axes(spec)?;
    Ok(axes.iter().map(|x| x.size).product::<usize>() + target::CHECK_POINTS)
}

/// The Pareto front of a table's fits, against its exact function (`None` when `stop` said
/// stop).
pub fn front(
    spec: &TableSpec,
    weight: Weight,
    deadline: Option<&crate::deadline::Deadline>,
) -> Result<Option<(Target, Vec<Candidate>)>, String> {
    let tg = target::build(spec, deadline)?;
    let corner = spec.model.ndf.is_some();
    let stop = || deadline.is_some_and(|d| d.passed());
    let front = search::search(&tg, weight, corner, &search::Limits::default(), &stop);
    if stop() {
        return Ok(None);
    }
    Ok(Some((tg, front)))
}

/// The files of a chosen fit, named `{base}.{ext}` in `dir`: one function per language of
/// `emit` (named `function`, with the error, operation count and source in a comment) and
/// the sidecar `{base}.json`. `extra` adds fields to the sidecar (a bake's input hash).
#[allow(clippy::too_many_arguments)]
pub fn files(
    preset: &str,
    table: &str,
    tg: &Target,
    weight: Weight,
    c: &Candidate,
    emit: &[String],
    dir: &Path,
    base: &str,
    extra: serde_json::Map<String, serde_json::Value>,
) -> Vec<(PathBuf, Vec<u8>)> {
    let fname = format!("{preset}_{table}_fit").replace('-', "_");
    let program = c.fitted.program(&tg.inputs, &tg.channels);
    let comment = vec![
        format!("brdfbake fit {preset} --table {table}: {}", c.description),
        format!(
            "inputs ({}), outputs ({})",
            program.inputs.join(", "),
            tg.channels.join(", ")
        ),
        format!(
            "max {} error per channel {:?} (f64 evaluation), f32 rounding bound {:?}",
            weight.name(),
            c.error.iter().map(|e| num(*e)).collect::<Vec<_>>(),
            c.f32_bound.iter().map(|e| num(*e)).collect::<Vec<_>>()
        ),
        format!(
            "{} operations ({} div/sqrt/exp2), {} constants",
            c.counts.ops, c.counts.special, c.counts.constants
        ),
    ];
    let mut files: Vec<(PathBuf, Vec<u8>)> = Vec::new();
    for l in emit {
        let Some(d) = function::dialect(l) else {
            continue; // (checked by the callers: RawRequest::check, `fit --emit`)
        };
        let text = function::encode(&*d, &fname, &program, &comment);
        files.push((
            dir.join(format!("{base}.{}", d.extension())),
            text.into_bytes(),
        ));
    }
    let mut sidecar = json!({
        "schema": "brdfbake.fit/1",
        "preset": preset,
        "table": table,
        "function": fname,
        "inputs": tg.inputs.iter().map(|i| json!({"name": i.name, "domain": i.domain})).collect::<Vec<_>>(),
        "channels": tg.channels,
        "weight": weight.name(),
        "form": c.description,
        "max_error": c.error,
        "f32_bound": c.f32_bound,
        "ops": c.counts,
        "fit": c.fitted,
    });
    if let Some(m) = sidecar.as_object_mut() {
        m.extend(extra);
    }
    files.push((
        dir.join(format!("{base}.json")),
        serde_json::to_string_pretty(&sidecar)
            .expect("serializable")
            .into_bytes(),
    ));
    files
}
