//! Published analytic fits, kept as test data and measured exactly like ours: each is
//! written as a [`Program`] (so its operation count is counted by the same rules) and
//! evaluated on the same validation set against the same exact values.
//!
//! - **Karis' `EnvBRDFApprox`**: B. Karis, "Physically Based Shading on Mobile", Unreal
//!   Engine blog, 2014 (after Lazarov 2013). Inputs n·v and perceptual roughness r;
//!   outputs the split-sum (A, B). Fitted by hand to a GGX table with Schlick–Smith
//!   masking; as Unreal mobile, Bevy and three.js (`DFGApprox`) ship it.
//! - **The sheen-albedo approximation of glTF `KHR_materials_sheen` renderers**:
//!   E(μ, r) = 0.65584461·(1 − μ)³ + 1/(4.16526551 + exp(−7.97291361·r + 6.33516894)),
//!   r the perceptual sheen roughness (√α): Dassault Systèmes' Enterprise PBR path tracer
//!   `dspbr-pt`, `packages/lib/shader/bsdfs/sheen.glsl` at commit e7cfa6e9 (Apache-2.0),
//!   which the Khronos glTF-Sample-Viewer cites for its `albedoSheenScalingFactor`. The
//!   Charlie NDF with Ashikhmin's visibility: the model of the `sheen-charlie` preset.

use super::target::Target;
use crate::approx::program::{Arg, Op, OpCount, Program};

/// A published fit.
#[derive(Clone, Debug)]
pub struct Reference {
    pub name: &'static str,
    /// Where it comes from.
    pub source: &'static str,
    pub program: Program,
}

/// The preset (and its table) a reference is measured against.
pub fn preset_of(name: &str) -> Option<&'static str> {
    match name {
        "karis-envbrdfapprox" => Some("karis-envbrdf"),
        "gltf-sheen-albedo" => Some("sheen-charlie"),
        _ => None,
    }
}

/// Every reference fit.
pub fn all() -> Vec<Reference> {
    vec![karis(), sheen()]
}

/// Karis' `EnvBRDFApprox` (mobile, 2014): inputs (n·v, r), outputs (A, B).
///
/// ```text
/// c0 = (−1, −0.0275, −0.572, 0.022); c1 = (1, 0.0425, 1.04, −0.04)
/// v = r·c0 + c1; a = min(v.x², 2^(−9.28 n·v))·v.x + v.y
/// (A, B) = (−1.04, 1.04)·a + (v.z, v.w)
/// ```
pub fn karis() -> Reference {
    let mut p = Program::new(&["cos_theta_v", "roughness"]);
    let (mu, r) = (Arg::Input(0), Arg::Input(1));
    let c = |v: f32| Arg::Const(v);
    let v0 = p.op(Op::Fma(r, c(-1.0), c(1.0)));
    let v1 = p.op(Op::Fma(r, c(-0.0275), c(0.0425)));
    let v2 = p.op(Op::Fma(r, c(-0.572), c(1.04)));
    let v3 = p.op(Op::Fma(r, c(0.022), c(-0.04)));
    let t = p.op(Op::Mul(mu, c(-9.28)));
    let e = p.op(Op::Exp2(t));
    let s = p.op(Op::Mul(v0, v0));
    let m = p.op(Op::Min(s, e));
    let a004 = p.op(Op::Fma(m, v0, v1));
    let a = p.op(Op::Fma(a004, c(-1.04), v2));
    let b = p.op(Op::Fma(a004, c(1.04), v3));
    p.outputs.push(("a".into(), a));
    p.outputs.push(("b".into(), b));
    Reference {
        name: "karis-envbrdfapprox",
        source:
            "Karis 2014, 'Physically Based Shading on Mobile' (Unreal Engine blog), EnvBRDFApprox",
        program: p,
    }
}

/// The sheen approximation's constants as published (c₀, c₁, c₂, c₃):
/// E = c₀(1 − μ)³ + 1/(c₁ + exp(c₂ r + c₃)).
pub const SHEEN: [f64; 4] = [0.65584461, 4.16526551, -7.97291361, 6.33516894];

/// The sheen directional albedo approximation (see the module doc): inputs (n·v, r).
pub fn sheen() -> Reference {
    let mut p = Program::new(&["cos_theta_v", "roughness"]);
    let (mu, r) = (Arg::Input(0), Arg::Input(1));
    let c = |v: f32| Arg::Const(v);
    let l2e = std::f64::consts::LOG2_E;
    let one_minus = p.op(Op::Sub(c(1.0), mu));
    let c2 = p.op(Op::Mul(one_minus, one_minus));
    let c3 = p.op(Op::Mul(c2, one_minus));
    // exp(x) = 2^(x·log2 e), the constants pre-multiplied
    let t = p.op(Op::Fma(
        r,
        c((SHEEN[2] * l2e) as f32),
        c((SHEEN[3] * l2e) as f32),
    ));
    let e = p.op(Op::Exp2(t));
    let d = p.op(Op::Add(e, c(SHEEN[1] as f32)));
    let q = p.op(Op::Div(c(1.0), d));
    let out = p.op(Op::Fma(c3, c(SHEEN[0] as f32), q));
    p.outputs.push(("e".into(), out));
    Reference {
        name: "gltf-sheen-albedo",
        source: "dspbr-pt sheen.glsl e7cfa6e9 (Dassault Systemes, Apache-2.0), as cited by Khronos glTF-Sample-Viewer for KHR_materials_sheen",
        program: p,
    }
}

/// A program's error on a target's validation set and check set: per channel the max |program − exact|
/// and the point (coordinates) where it occurs.
#[derive(Clone, Debug)]
pub struct Measured {
    pub error: Vec<f64>,
    pub argmax: Vec<Vec<f64>>,
    pub counts: OpCount,
}

impl Measured {
    pub fn max_error(&self) -> f64 {
        self.error.iter().cloned().fold(0.0, f64::max)
    }
}

/// Measures `program` (inputs: the target's axes, outputs: its channels in order) on the
/// validation set, the coordinates clamped to the domain as a caller clamps them.
pub fn measure(program: &Program, target: &Target) -> Measured {
    let nc = target.values.len();
    let mut error = vec![0.0f64; nc];
    let mut argmax = vec![Vec::new(); nc];
    // the grid's points, then the check set's (as a fit's error is measured)
    let grid = (0..target.points()).map(|i| {
        let exact: Vec<f64> = target.values.iter().map(|v| v[i]).collect();
        (target.point(i), exact)
    });
    let check = target
        .check
        .iter()
        .cloned()
        .zip(target.check_values.iter().cloned());
    for (x, exact) in grid.chain(check) {
        let x = super::vars::clamp_inputs(&target.inputs, &x);
        let y = program.eval(&x);
        for c in 0..nc {
            let e = (y[c] - exact[c]).abs();
            if e > error[c] || argmax[c].is_empty() {
                error[c] = error[c].max(e);
                argmax[c] = x.clone();
            }
        }
    }
    Measured {
        error,
        argmax,
        counts: program.counts(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The programs are the published formulas: Karis' against `report::env_brdf_approx`
    /// (written independently, in f64), the sheen one against its formula in f64; both to
    /// f32 rounding of their constants (a few 1e-7 relative).
    #[test]
    fn programs_are_the_published_formulas() {
        let k = karis().program;
        let s = sheen().program;
        for i in 0..=20 {
            for j in 0..=20 {
                let (mu, r) = (i as f64 / 20.0, j as f64 / 20.0);
                let (a, b) = crate::report::env_brdf_approx(r, mu);
                let y = k.eval(&[mu, r]);
                assert!(
                    (y[0] - a).abs() < 1e-6 && (y[1] - b).abs() < 1e-6,
                    "{mu} {r}"
                );
                let c = 1.0 - mu;
                let e = SHEEN[0] * c * c * c + 1.0 / (SHEEN[1] + (SHEEN[2] * r + SHEEN[3]).exp());
                assert!((s.eval(&[mu, r])[0] - e).abs() < 1e-6, "{mu} {r}");
            }
        }
        // the counts the comparison states
        assert_eq!((k.counts().ops, k.counts().special), (11, 1));
        assert_eq!((s.counts().ops, s.counts().special), (8, 2));
    }
}
