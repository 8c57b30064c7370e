//! Synthetic tables for the encoder tests: any sizes, channel names and values, with
//! cosine axes on [0, 1] at texel centres.

#![allow(dead_code)]

use brdfbake::lut::{Axis, Channel, Convention, Lut, Quantity};

/// A table of axes `sizes` (fastest first) and channels `names`, texel `[x, y, z]` channel
/// `c` holding `f([x, y, z], c)`.
pub fn lut(sizes: &[usize], names: &[&str], f: impl Fn([usize; 3], usize) -> f32) -> Lut {
    let axes: Vec<Axis> = sizes
        .iter()
        .enumerate()
        .map(|(k, &size)| Axis {
            name: format!("axis{k}"),
            quantity: Quantity::Cosine,
            size,
            range: [0.0, 1.0],
            convention: Convention::Centers,
            warp: Default::default(),
            clamp: None,
        })
        .collect();
    let dim = |k: usize| sizes.get(k).copied().unwrap_or(1);
    let mut data = Vec::new();
    for z in 0..dim(2) {
        for y in 0..dim(1) {
            for x in 0..dim(0) {
                for c in 0..names.len() {
                    data.push(f([x, y, z], c));
                }
            }
        }
    }
    Lut {
        axes,
        channels: names
            .iter()
            .map(|n| Channel {
                name: n.to_string(),
                meaning: format!("test channel {n}"),
            })
            .collect(),
        data,
        error_estimate: vec![0.0; names.len()],
        evaluations: 0,
    }
}
