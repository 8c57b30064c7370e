//! Three-vectors as `[f64; 3]`: the cross and dot products the polygon integrals and their
//! checks share.

/// `p × q`.
#[inline]
pub fn cross(p: [f64; 3], q: [f64; 3]) -> [f64; 3] {
    [
        p[1] * q[2] - p[2] * q[1],
        p[2] * q[0] - p[0] * q[2],
        p[0] * q[1] - p[1] * q[0],
    ]
}

/// `p · q`, summed in index order.
#[inline]
pub fn dot(p: [f64; 3], q: [f64; 3]) -> f64 {
    p[0] * q[0] + p[1] * q[1] + p[2] * q[2]
}
