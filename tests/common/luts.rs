//! Synthetic tables for the encoder tests: any sizes, channel names and values, with
//! cosine axes on [0, 1] at texel centres.

#![allow(dead_code)]

use brdfbake::lut::{Axis, Channel, Convention, Lut, Quantity};
use brdfbake::table::Storage;

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

/// Values that differ in every texel and channel, with signs, small and large magnitudes
/// and f16 rounding cases (ties, subnormals, the largest finite half).
pub fn value(t: [usize; 3], c: usize) -> f32 {
    const SPECIAL: [f32; 8] = [
        0.0,
        -0.0,
        1.0 + 1.0 / 2048.0, // halfway between two halves: ties to even
        6.0e-8,             // f16 subnormal
        65504.0,
        -65519.0, // rounds to -65504 in f16
        1.0e-30,  // f16 underflows to 0
        0.333_333_34,
    ];
    let i = (t[2] * 7 + t[1]) * 13 + t[0];
    if (i + c).is_multiple_of(5) {
        SPECIAL[(i / 5 + c) % SPECIAL.len()]
    } else {
        (i as f32 * 0.37 + c as f32 * 1.91).sin() * 10f32.powi((i % 7) as i32 - 3)
    }
}

/// Values in [0, 1] (what a UNORM table holds) that differ in every texel and channel, with
/// the rounding cases: the ends, an exact tie (0.5 is 127.5 and 32767.5 codes), values within
/// half a step outside [0, 1] (they round to the end codes).
pub fn unorm_value(t: [usize; 3], c: usize) -> f32 {
    const SPECIAL: [f32; 7] = [0.0, 1.0, 0.5, 1.0 + 1e-6, -1e-6, 1e-8, 0.999_999];
    let i = (t[2] * 7 + t[1]) * 13 + t[0];
    if (i + c).is_multiple_of(4) {
        SPECIAL[(i / 4 + c) % SPECIAL.len()]
    } else {
        0.5 + 0.5 * (i as f32 * 0.37 + c as f32 * 1.91).sin()
    }
}

/// The test values for `storage`.
pub fn values_for(storage: Storage) -> fn([usize; 3], usize) -> f32 {
    if storage.is_unorm() {
        unorm_value
    } else {
        value
    }
}

/// The UNORM code of `v` computed here, independently of the encoder: the nearest integer to
/// v·max, a tie going to the even one.
pub fn unorm_code(v: f32, max: u32) -> u16 {
    let x = v as f64 * max as f64;
    let f = x.floor();
    let c = if x - f > 0.5 || (x - f == 0.5 && f % 2.0 == 1.0) {
        f + 1.0
    } else {
        f
    };
    assert!((0.0..=max as f64).contains(&c), "{v} is not storable");
    c as u16
}
