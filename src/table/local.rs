//! Tables of closed-form (or pre-integrated) functions of the texel coordinates alone:
//! `ndf`, `g1`, `g2` and `vgroove`. No hemisphere integral is needed.

use super::{TableKind, TableSpec, TexelResult};
use crate::model::masking::vgroove_from_cosines;
use crate::model::Ndf;

pub(crate) fn texel_fn(spec: &TableSpec) -> Box<dyn Fn([usize; 3]) -> TexelResult + Sync> {
    let kind = spec.kind;
    let axes = spec.axes.clone();
    // The NDF per roughness texel, built once (the numeric G1 interpolant of the Gaussian
    // and Blinn-Phong NDFs is built lazily inside, once per roughness).
    let ndfs: Vec<Ndf> = match (kind, spec.model.ndf) {
        (TableKind::Vgroove, _) | (_, None) => Vec::new(),
        (_, Some(k)) => {
            let r = axes.last().expect("roughness axis");
            (0..r.size)
                .map(|i| Ndf::new(k, r.alpha(i).expect("roughness axis")).expect("validated"))
                .collect()
        }
    };
    let masking = spec.model.masking;
    Box::new(move |idx| match kind {
        TableKind::Ndf => TexelResult::exact(vec![ndfs[idx[1]].d(axes[0].coord(idx[0]))]),
        TableKind::G1 => {
            let ndf = &ndfs[idx[1]];
            let mut r = TexelResult::exact(vec![ndf.g1(axes[0].coord(idx[0]))]);
            r.error[0] = ndf.g1_error_estimate();
            r
        }
        TableKind::G2 => {
            let ndf = &ndfs[idx[2]];
            let (mv, ml) = (axes[0].coord(idx[0]), axes[1].coord(idx[1]));
            // every G2 a g2 table accepts depends on n.v and n.l only; h is not used
            let mut r = TexelResult::exact(vec![masking.g(ndf, mv, ml, 1.0, 1.0)]);
            // (only Smith's terms use the NDF's G1, numeric for some NDFs)
            if masking.is_smith() {
                r.error[0] = 2.0 * ndf.g1_error_estimate();
            }
            r
        }
        TableKind::Vgroove => {
            let (nl, nh, nv) = (
                axes[0].coord(idx[0]),
                axes[1].coord(idx[1]),
                axes[2].coord(idx[2]),
            );
            let (g, ok) = vgroove_from_cosines(nl, nh, nv);
            TexelResult::exact(vec![g, if ok { 1.0 } else { 0.0 }])
        }
        _ => unreachable!("local tables only"),
    })
}
