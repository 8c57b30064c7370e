//! Reference integrals over spherical polygons by adaptive quadrature: the ground truth that
//! LTC tables are measured against (the BRDF·cos over a polygonal light), and the check of
//! the closed-form polygon integral ([`super::ltc_polygon`]) on the LTC itself.
//!
//! **Parameterization.** Polar coordinates about a centre `c` (the lobe's peak): a direction
//! is `ω(ρ, φ) = cos ρ·c + sin ρ·(cos φ·e₁ + sin φ·e₂)`, `dω = sin ρ dρ dφ`. For a convex
//! polygon each ray from `c` meets it in one arc `[ρ_in(φ), ρ_out(φ)]`: with an edge's
//! inward normal `n` (interior: `n·ω ≥ 0`), `A = n·c`, `B = n·t(φ)`, the ray is inside for
//! `A cos ρ + B sin ρ = R sin(ρ + δ) ≥ 0`, `δ = atan2(A, B)`, which on `ρ ∈ [0, π]` is
//! `ρ ≤ π − δ` when `δ ≥ 0` and `ρ ≥ −δ` when `δ < 0`; intersecting over the edges gives
//! the arc. These bounds are smooth in φ between the azimuths of the vertices, so the φ
//! range (the full circle when `c` is inside, else the wedge the polygon subtends) is split
//! there. No cancellation: every panel integrates a positive integrand over a part of the
//! polygon itself, so a light far out in the BRDF's tail gets a relative accuracy as good
//! as one on the peak.
//!
//! **Warp.** The radial variable is `ρ = s·sinh u` (`s` the lobe's angular width), which
//! spreads a peak of width `s` at `c` over an O(1) range of `u`, whatever `s` is (the same
//! device as the hemisphere integrator's `asinh(tan θh/α)`).
//!
//! **Accuracy.** Nested adaptive Gauss–Kronrod ([`crate::quadrature::integrate`], G7/K15
//! error estimates, which bound the error in practice), to a relative tolerance: a first
//! pass at 1e-3 gives the scale, the second runs at `rel_tol` of it. `examples/ltc_check.rs`
//! checks the result against a second centre and a tighter tolerance.

use crate::model::ltc::LtcError;
use crate::quadrature::{integrate, Tolerance};
use std::f64::consts::PI;

use crate::numerics::vec3::{cross, dot};

fn normalize(p: [f64; 3]) -> Option<[f64; 3]> {
    let l = dot(p, p).sqrt();
    (l > 0.0 && l.is_finite()).then(|| [p[0] / l, p[1] / l, p[2] / l])
}

/// The polygon (vertex directions) clipped to the half-space `n·ω > 0`, Sutherland–Hodgman
/// (the crossing points `p + t(q − p)`, `t = n·p/(n·p − n·q)`).
pub fn clip_to_halfspace(verts: &[[f64; 3]], n: [f64; 3]) -> Vec<[f64; 3]> {
    let mut out = Vec::with_capacity(verts.len() + 1);
    let Some(&last) = verts.last() else {
        return out;
    };
    let mut p = last;
    for &q in verts {
        let (dp, dq) = (dot(n, p), dot(n, q));
        if (dp > 0.0) != (dq > 0.0) {
            let t = dp / (dp - dq);
            out.push([
                p[0] + t * (q[0] - p[0]),
                p[1] + t * (q[1] - p[1]),
                p[2] + t * (q[2] - p[2]),
            ]);
        }
        if dq > 0.0 {
            out.push(q);
        }
        p = q;
    }
    out
}

/// The error of a reference quadrature stopped by its thread's deadline
/// ([`crate::deadline::scoped`]).
pub const STOPPED: &str = "stopped at the time limit";

/// A reference value: the integral, its estimated absolute error and the evaluations spent.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Reference {
    pub value: f64,
    pub error: f64,
    pub evals: u64,
}

/// A unit vector orthogonal to `c` and a third completing a right-handed frame.
fn frame(c: [f64; 3]) -> ([f64; 3], [f64; 3]) {
    let a = if c[0].abs() < 0.9 {
        [1.0, 0.0, 0.0]
    } else {
        [0.0, 1.0, 0.0]
    };
    let e1 = normalize(cross(a, c)).expect("a is not parallel to c");
    let e2 = cross(c, e1);
    (e1, e2)
}

/// The integral of `g` (a function of unit directions) over the convex spherical polygon
/// `verts` (either winding; positive result for a positive `g`), by polar coordinates about
/// the unit direction `center` with radial scale `scale` (module doc), to relative tolerance
/// `rel_tol`. The polygon must not contain `−center`. Empty or degenerate polygons give 0.
pub fn polygon_integral(
    g: &dyn Fn([f64; 3]) -> f64,
    verts: &[[f64; 3]],
    center: [f64; 3],
    scale: f64,
    rel_tol: f64,
) -> Result<Reference, LtcError> {
    if !(scale > 0.0 && scale.is_finite() && rel_tol > 0.0) {
        return Err(LtcError::Domain(format!(
            "reference quadrature needs scale > 0 and rel_tol > 0, got {scale}, {rel_tol}"
        )));
    }
    let c = normalize(center).ok_or(LtcError::ZeroVector { what: "the centre" })?;
    let mut p = Vec::with_capacity(verts.len());
    for v in verts {
        if !v.iter().all(|x| x.is_finite()) {
            return Err(LtcError::NotFinite {
                what: "a polygon vertex",
            });
        }
        p.push(normalize(*v).ok_or(LtcError::ZeroVector {
            what: "a polygon vertex",
        })?);
    }
    // drop repeated vertices (clipping can produce them)
    p.dedup_by(|a, b| dot(cross(*a, *b), cross(*a, *b)) == 0.0 && dot(*a, *b) > 0.0);
    while p.len() > 1 && {
        let (a, b) = (p[0], p[p.len() - 1]);
        dot(cross(a, b), cross(a, b)) == 0.0 && dot(a, b) > 0.0
    } {
        p.pop();
    }
    let n = p.len();
    if n < 3 {
        return Ok(Reference {
            value: 0.0,
            error: 0.0,
            evals: 0,
        });
    }
    // inward edge normals: orient by the polygon's mean direction
    let mean = p
        .iter()
        .fold([0.0; 3], |m, v| [m[0] + v[0], m[1] + v[1], m[2] + v[2]]);
    let orient = (0..n)
        .map(|i| dot(cross(p[i], p[(i + 1) % n]), mean))
        .sum::<f64>();
    if orient == 0.0 {
        return Ok(Reference {
            value: 0.0,
            error: 0.0,
            evals: 0,
        });
    }
    let sign = orient.signum();
    let normals: Vec<[f64; 3]> = (0..n)
        .map(|i| cross(p[i], p[(i + 1) % n]).map(|x| x * sign))
        .collect();
    let (e1, e2) = frame(c);
    let inside = normals.iter().all(|m| dot(*m, c) >= 0.0);
    // vertex azimuths about c; the φ pieces
    let az: Vec<f64> = p.iter().map(|v| dot(*v, e2).atan2(dot(*v, e1))).collect();
    let mut cuts: Vec<f64>;
    if inside {
        cuts = az.iter().map(|&a| a.rem_euclid(2.0 * PI)).collect();
        cuts.sort_by(f64::total_cmp);
        cuts.dedup();
        let first = cuts[0];
        cuts.push(first + 2.0 * PI);
    } else {
        // the wedge: azimuths unwrapped about the mean direction's
        let am = dot(mean, e2).atan2(dot(mean, e1));
        cuts = az
            .iter()
            .map(|&a| am + (a - am + PI).rem_euclid(2.0 * PI) - PI)
            .collect();
        cuts.sort_by(f64::total_cmp);
        cuts.dedup();
    }
    let bounds = |phi: f64| -> (f64, f64, [f64; 3]) {
        let (s, co) = phi.sin_cos();
        let t = [
            co * e1[0] + s * e2[0],
            co * e1[1] + s * e2[1],
            co * e1[2] + s * e2[2],
        ];
        let (mut lo, mut hi) = (0.0f64, PI);
        for m in &normals {
            let (a, b) = (dot(*m, c), dot(*m, t));
            if a == 0.0 && b == 0.0 {
                continue;
            }
            let d = a.atan2(b);
            if d >= 0.0 {
                hi = hi.min(PI - d);
            } else {
                lo = lo.max(-d);
            }
        }
        (lo, hi, t)
    };
    let stopped = std::cell::Cell::new(false);
    let run = |abs: f64| -> Reference {
        let total_phi = cuts[cuts.len() - 1] - cuts[0];
        // inner tolerance per unit of φ, its error is noise to the outer rule
        let inner_abs = 0.25 * abs / total_phi.max(1e-300);
        let evals = std::cell::Cell::new(0u64);
        let inner_err = std::cell::Cell::new(0.0f64);
        let outer_tol = Tolerance {
            abs: 0.5 * abs,
            initial_panels: 2,
            max_depth: 40,
            noise_floor: 4.0 * inner_abs,
            max_evals: 200_000,
        };
        let mut value = 0.0;
        let mut error = 0.0;
        for w in cuts.windows(2) {
            let (a, b) = (w[0], w[1]);
            if b <= a {
                continue;
            }
            let share = Tolerance {
                abs: outer_tol.abs * (b - a) / total_phi,
                ..outer_tol
            };
            let e = integrate(
                |phi: f64| {
                    let (lo, hi, t) = bounds(phi);
                    if hi <= lo {
                        return [0.0];
                    }
                    let (u0, u1) = ((lo / scale).asinh(), (hi / scale).asinh());
                    // the caller's time limit (deadline::scoped), between inner integrals
                    if stopped.get() || crate::deadline::current_passed() {
                        stopped.set(true);
                        return [0.0];
                    }
                    let inner = integrate(
                        |u: f64| {
                            let rho = scale * u.sinh();
                            let (sr, cr) = rho.sin_cos();
                            let w = [
                                cr * c[0] + sr * t[0],
                                cr * c[1] + sr * t[1],
                                cr * c[2] + sr * t[2],
                            ];
                            [g(w) * sr * scale * u.cosh()]
                        },
                        u0,
                        u1,
                        Tolerance {
                            abs: inner_abs,
                            initial_panels: 2,
                            max_depth: 40,
                            noise_floor: 0.0,
                            max_evals: 200_000,
                        },
                    );
                    evals.set(evals.get() + inner.evals);
                    inner_err.set(inner_err.get().max(inner.error[0]));
                    inner.value
                },
                a,
                b,
                share,
            );
            value += e.value[0];
            error += e.error[0];
        }
        Reference {
            value,
            error: error + inner_err.get() * total_phi,
            evals: evals.get(),
        }
    };
    // the scale first, then the requested relative accuracy
    let coarse = run(1e-3 * 4.0 * PI * max_abs_sample(g, &p, c));
    let target = (rel_tol * coarse.value.abs()).max(f64::MIN_POSITIVE);
    let mut fine = run(target);
    fine.evals += coarse.evals;
    if stopped.get() {
        return Err(LtcError::Domain(STOPPED.into()));
    }
    Ok(fine)
}

/// A rough size of `g` on the polygon (its largest value at the vertices, the centre and the
/// vertex midpoints), for the first pass's absolute tolerance.
fn max_abs_sample(g: &dyn Fn([f64; 3]) -> f64, p: &[[f64; 3]], c: [f64; 3]) -> f64 {
    let mut m = g(c).abs();
    for i in 0..p.len() {
        let q = p[(i + 1) % p.len()];
        m = m.max(g(p[i]).abs());
        if let Some(mid) = normalize([p[i][0] + q[0], p[i][1] + q[1], p[i][2] + q[2]]) {
            m = m.max(g(mid).abs());
        }
    }
    if m.is_finite() && m > 0.0 {
        m
    } else {
        1.0
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::kernels::ltc_polygon::clamped_cosine_integral;

    #[test]
    fn cosine_over_a_quad_matches_lamberts_formula() {
        let q = [
            [0.3, -0.2, 1.0],
            [0.9, -0.1, 0.8],
            [0.8, 0.5, 0.9],
            [0.2, 0.4, 1.1],
        ];
        let want = clamped_cosine_integral(&q).unwrap();
        for (center, scale) in [([0.0, 0.0, 1.0], 1.0), ([0.5, 0.1, 1.0], 0.05)] {
            let r = polygon_integral(&|w| w[2].max(0.0) / PI, &q, center, scale, 1e-10).unwrap();
            assert!((r.value - want).abs() < 1e-9 * want, "{r:?} {want}");
        }
        let cl = clip_to_halfspace(
            &[[1.0, 0.0, 1.0], [0.0, 1.0, -1.0], [-1.0, 0.0, 1.0]],
            [0.0, 0.0, 1.0],
        );
        assert_eq!(cl.len(), 4);
    }

    /// A deadline that has passed stops the quadrature between inner integrals: an error,
    /// not a value computed to the end.
    #[test]
    fn a_passed_deadline_stops_the_quadrature() {
        let g = |w: [f64; 3]| w[2].max(0.0);
        let quad = [
            [-1.0, -1.0, 1.0],
            [1.0, -1.0, 1.0],
            [1.0, 1.0, 1.0],
            [-1.0, 1.0, 1.0],
        ];
        let ok = polygon_integral(&g, &quad, [0.0, 0.0, 1.0], 0.5, 1e-9).unwrap();
        assert!(ok.value > 0.0);
        let past = crate::deadline::Deadline::after(0.0);
        let e = crate::deadline::scoped(&past, || {
            polygon_integral(&g, &quad, [0.0, 0.0, 1.0], 0.5, 1e-9)
        })
        .unwrap_err();
        assert!(e.to_string().contains(STOPPED), "{e}");
        // and the scope ends with the call
        assert!(polygon_integral(&g, &quad, [0.0, 0.0, 1.0], 0.5, 1e-9).is_ok());
    }
}
