//! Names typed by users: the nearest known name to a typo, for the errors' hints.

/// The name of `known` nearest to `typed` by edit distance, when it is near enough to be a
/// typo (at most a third of its letters, and at least one, differ).
pub fn did_you_mean<'a>(typed: &str, known: impl Iterator<Item = &'a str>) -> Option<&'a str> {
    let typed_l = typed.to_lowercase();
    let limit = (typed.chars().count() / 3).max(1);
    known
        .map(|k| (edit_distance(&typed_l, &k.to_lowercase()), k))
        .filter(|(d, _)| *d <= limit)
        .min_by_key(|(d, k)| (*d, *k))
        .map(|(_, k)| k)
}

/// The Levenshtein distance of two strings, in characters.
fn edit_distance(a: &str, b: &str) -> usize {
    let b: Vec<char> = b.chars().collect();
    let mut prev: Vec<usize> = (0..=b.len()).collect();
    for (i, ca) in a.chars().enumerate() {
        let mut cur = vec![i + 1; b.len() + 1];
        for (j, cb) in b.iter().enumerate() {
            cur[j + 1] = (prev[j] + usize::from(ca != *cb))
                .min(prev[j + 1] + 1)
                .min(cur[j] + 1);
        }
        prev = cur;
    }
    prev[b.len()]
}

#[cfg(test)]
mod tests {
    use super::did_you_mean;

    #[test]
    fn typos_get_the_nearest_name() {
        let known = [
            "filament-dfg",
            "karis-envbrdf",
            "cycles-ggx-e",
            "cycles-ggx-eavg",
        ];
        assert_eq!(
            did_you_mean("filament-dgf", known.iter().copied()),
            Some("filament-dfg")
        );
        assert_eq!(
            did_you_mean("Filament-DFG", known.iter().copied()),
            Some("filament-dfg")
        );
        assert_eq!(
            did_you_mean("cycles-ggx-eav", known.iter().copied()),
            Some("cycles-ggx-eavg")
        );
        assert_eq!(did_you_mean("something-else", known.iter().copied()), None);
    }
}
