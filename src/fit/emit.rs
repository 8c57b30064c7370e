//! A chosen fit, and its files: the functions (`crate::encode::function`) and the
//! `brdfbake.fit/1` sidecar that `brdfbake verify` re-checks. Shared by `brdfbake fit
//! --max-error` and the preset field `"fit"`, which `bake` writes beside the table.

pub use super::grid::{points, BYTES_PER_POINT, SECONDS_PER_POINT};
pub use super::request::{Goal, RawRequest, Request};
use super::search::{self, Candidate, Weight};
use super::target::{self, Target};
use crate::encode::function;
use crate::numfmt::num;
use crate::table::TableSpec;
use serde_json::json;
use std::path::{Path, PathBuf};

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
