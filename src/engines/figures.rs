//! The figures the docs quote about engines' shipped tables, rendered from comparisons
//! ([`super::Comparison`]): a row of the README's engine table and a row of the per-channel
//! table in docs/engines.md. The docs hold these rows between markers and a test renders them
//! again from `compare` over `tests/data/engines` and fails when they differ, so a figure
//! about a shipped table is never typed by hand
//! (`cargo run --release --example engine_figures -- --write` rewrites them).

use super::compare::{ChannelComparison, Fault};
use super::Comparison;
use crate::numfmt::fig;

/// Lines `[first, last]` of axis `a` in a few words: `n·v ≤ 0.0054`, `r ≥ 0.66`,
/// `n·v 0.053 to 0.15`, `η = 0.992`.
fn range_words(a: &crate::lut::Axis, r: [usize; 2]) -> String {
    let at = |i: usize| a.physical_short(a.coord(i));
    let value = |i: usize| at(i).split(" = ").nth(1).unwrap_or("").to_string();
    let sym = a.physical_symbol();
    let (lo, hi) = (r[0].min(r[1]), r[0].max(r[1]));
    // (an axis may run either way: name its range by its coordinates' order)
    let increasing = a.coord(a.size - 1) >= a.coord(0);
    let (first, last) = if increasing { (lo, hi) } else { (hi, lo) };
    if lo == hi {
        at(lo)
    } else if lo == 0 && hi + 1 < a.size {
        format!(
            "{sym} {} {}",
            if increasing { "≤" } else { "≥" },
            value(if increasing { hi } else { lo })
        )
    } else if hi + 1 == a.size && lo > 0 {
        format!(
            "{sym} {} {}",
            if increasing { "≥" } else { "≤" },
            value(if increasing { lo } else { hi })
        )
    } else {
        format!("{sym} {} to {}", value(first), value(last))
    }
}

/// The grade of a channel's verdict in a few words: `within its 6 decimals`,
/// `25× its 6 decimals: noise`, `12× its 8-bit UNORM: worst at n·v ≤ 0.0054`.
fn grade_words(c: &ChannelComparison, axes: &[crate::lut::Axis]) -> String {
    let v = &c.verdict;
    // (a quotes file's storage text carries the quoted count: the storage is its first part)
    let storage = v.storage.split(", ").next().unwrap_or(&v.storage);
    if v.within_storage {
        return format!("within its {storage}");
    }
    let head = format!("{}× its {storage}", fig(v.ratio));
    let first = v.faults.iter().find(|f| !matches!(f, Fault::Noise { .. }));
    match (v.grade, first) {
        ("near-storage", _) | (_, Some(Fault::Outliers { .. })) => head,
        ("noise", _) | (_, None) => format!("{head}: noise"),
        (_, Some(f)) => format!("{head}: {}", fault_words(f, axes)),
    }
}

/// A fault in a few words.
fn fault_words(f: &Fault, axes: &[crate::lut::Axis]) -> String {
    let axis = |name: &str| axes.iter().find(|a| a.name == name);
    match f {
        Fault::ShiftedGrid { axis, .. } => format!("grid one texel off along {axis}"),
        Fault::WrongQuantity { .. } => "another quantity".into(),
        Fault::Clamped { value, count } => format!("{count} texels clamped at {value}"),
        Fault::Lines {
            axis: name, ranges, ..
        } => match axis(name) {
            Some(a) => {
                let mut w = format!("worst at {}", range_words(a, ranges[0]));
                if ranges.len() > 1 {
                    w.push_str(" and elsewhere");
                }
                w
            }
            None => "worst on a few lines".into(),
        },
        Fault::Bias {
            mean_signed,
            axis: name,
            range,
            ..
        } => {
            let dir = if *mean_signed < 0.0 { "low" } else { "high" };
            match (name.as_deref().and_then(axis), range) {
                (Some(a), Some(r)) => format!("biased {dir} at {}", range_words(a, *r)),
                _ => format!("biased {dir}"),
            }
        }
        Fault::Noise { .. } => "noise".into(),
        Fault::Outliers { count, .. } => format!("{count} texels above 4× it"),
    }
}

/// The header of the README's engine table.
pub const README_HEADER: &str = "| preset | engine's table | the shipped table's largest error per channel (its verdict) |\n|---|---|---|";

/// The header of docs/engines.md's table of verdicts.
pub const DETAIL_HEADER: &str =
    "| preset | channel | the shipped table's largest error, where | verdict |\n|---|---|---|---|";

/// The row of the README's engine table: `| preset | engine's table | per channel the
/// largest error of the shipped table and its verdict |`.
pub fn readme_row(c: &Comparison) -> String {
    let quoted = c.storage.contains("quoted");
    let mut parts: Vec<String> = c
        .channels
        .iter()
        .map(|ch| {
            let s = ch.shipped_regular.as_ref().unwrap_or(&ch.shipped);
            // (where it lies: docs/engines.md's table of verdicts)
            format!(
                "{} {} ({})",
                ch.name,
                fig(s.max_abs),
                grade_words(ch, &c.errors.axes)
            )
        })
        .collect();
    for e in &c.excluded {
        parts.push(format!("{} slice (left out) {}", e.at, fig(e.max_abs)));
    }
    let mut table = c.source_table.clone();
    if quoted {
        let n = c.channels.first().map_or(0, |ch| ch.shipped.texels);
        table.push_str(&format!(", {n} texels quoted"));
    }
    format!("| `{}` | {table} | {} |", c.preset, parts.join("; "))
}

/// The rows of the per-channel table in docs/engines.md: `| preset | channel | the shipped
/// table's largest error, where | verdict |`.
pub fn detail_rows(c: &Comparison) -> Vec<String> {
    c.channels
        .iter()
        .map(|ch| {
            let s = ch.shipped_regular.as_ref().unwrap_or(&ch.shipped);
            let mut at = format!(
                "{} at {} ({} vs exact {})",
                fig(s.max_abs),
                s.worst_physical,
                crate::numfmt::num(s.worst_value),
                crate::numfmt::num(s.worst_exact)
            );
            if ch.shipped_regular.is_some() {
                at.push_str(&format!(
                    "; {} with the left-out slices, at {}",
                    fig(ch.shipped.max_abs),
                    ch.shipped.worst_physical
                ));
            }
            format!(
                "| `{}` | {} | {} | {} |",
                c.preset, ch.name, at, ch.verdict.text
            )
        })
        .collect()
}

/// Replaces the text between the lines `<!-- begin NAME ... -->` and `<!-- end NAME -->` of
/// `doc` with `body` (the marker lines stay); `None` when the markers are missing.
pub fn replace_block(doc: &str, name: &str, body: &str) -> Option<String> {
    let begin = format!("<!-- begin {name}");
    let end = format!("<!-- end {name} -->");
    let b = doc.find(&begin)?;
    let after_begin = b + doc[b..].find('\n')? + 1;
    let e = doc[after_begin..].find(&end)? + after_begin;
    Some(format!("{}{}{}", &doc[..after_begin], body, &doc[e..]))
}

#[cfg(test)]
mod tests {
    use super::replace_block;

    #[test]
    fn blocks_are_replaced_between_their_markers() {
        let doc = "a\n<!-- begin t (generated) -->\nold\n<!-- end t -->\nb\n";
        assert_eq!(
            replace_block(doc, "t", "new\n").unwrap(),
            "a\n<!-- begin t (generated) -->\nnew\n<!-- end t -->\nb\n"
        );
        assert!(replace_block(doc, "u", "x").is_none());
    }
}
