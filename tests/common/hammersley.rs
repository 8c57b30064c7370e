//! The Hammersley point set engines' split-sum generators share (Karis 2013, LearnOpenGL,
//! Godot's `integrate_dfg.glsl`): ξ = (i/n, the base-2 radical inverse of i, as
//! `reversebits(i)·2⁻³²`).

#![allow(dead_code)]

use std::f64::consts::PI;

/// The `n` points kept as (cos 2πξ₁, sin 2πξ₁, ξ₂).
pub fn hammersley(n: usize) -> Vec<[f64; 3]> {
    (0..n)
        .map(|i| {
            let r = (i as u32).reverse_bits() as f64 / 4_294_967_296.0;
            let phi = 2.0 * PI * i as f64 / n as f64;
            [phi.cos(), phi.sin(), r]
        })
        .collect()
}
