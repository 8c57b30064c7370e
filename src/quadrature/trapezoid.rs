//! Nested trapezoid sums on a period: the sum with N = 2^l intervals reuses every node of
//! N/2 and adds its midpoints, so nodes are stored by level and each level adds a block.

/// Where each level's new nodes start when nodes are stored level by level: level 0 is the
/// two ends (N = 1), level l ≥ 1 the 2^(l−1) midpoints that N = 2^l adds. `starts[l + 1]` is
/// where level l ends; the array covers levels 0 to `L − 2`.
pub const fn level_starts<const L: usize>() -> [usize; L] {
    let mut t = [0; L];
    if L > 1 {
        t[1] = 2;
    }
    let mut l = 1;
    while l + 1 < L {
        t[l + 1] = t[l] + (1 << (l - 1));
        l += 1;
    }
    t
}

/// The node indices k of the trapezoid sum with `2^max_log2` intervals (node k at k/2^max_log2
/// of the period) in the order [`level_starts`] lays them out: the two ends, then each
/// level's midpoints in increasing order.
pub fn level_order(max_log2: usize) -> impl Iterator<Item = usize> {
    let n = 1usize << max_log2;
    [0, n].into_iter().chain((1..=max_log2).flat_map(move |l| {
        let stride = n >> (l - 1);
        (stride / 2..n).step_by(stride)
    }))
}

#[cfg(test)]
mod tests {
    /// Levels 0..=3 hold 2, 1, 2 and 4 nodes: 9 in all, the nodes of N = 8.
    #[test]
    fn levels_add_the_midpoints() {
        assert_eq!(super::level_starts::<5>(), [0, 2, 3, 5, 9]);
    }

    /// N = 8: the ends, 4; 2, 6; then the odd nodes — each level where `level_starts` puts it.
    #[test]
    fn level_order_matches_level_starts() {
        let order: Vec<usize> = super::level_order(3).collect();
        assert_eq!(order, [0, 8, 4, 2, 6, 1, 3, 5, 7]);
    }
}
