use brdfbake::lut::*;
use brdfbake::model::*;
use brdfbake::table::*;
fn main() {
    let n: usize = std::env::args()
        .nth(1)
        .map(|s| s.parse().unwrap())
        .unwrap_or(32);
    let tol: f64 = std::env::args()
        .nth(2)
        .map(|s| s.parse().unwrap())
        .unwrap_or(1e-7);
    let spec = TableSpec {
        name: "dfg".into(),
        kind: TableKind::Dfg,
        model: ModelSpec {
            ndf: Some(NdfKind::Ggx),
            masking: Masking::SmithHeightCorrelated,
            fresnel: Fresnel::None,
            diffuse_weight: 0.0,
        },
        axes: vec![
            Axis {
                name: "cos_theta_v".into(),
                quantity: Quantity::Cosine,
                size: n,
                range: [0.0, 1.0],
                convention: Convention::Centers,
            },
            Axis {
                name: "roughness".into(),
                quantity: Quantity::Roughness(RoughnessQuantity::Perceptual),
                size: n,
                range: [0.0, 1.0],
                convention: Convention::Centers,
            },
        ],
        dfg_layout: Some(DfgLayout::Filament),
        cloth: true,
        storage: Storage::F32,
        tolerance: tol,
    };
    let t = std::time::Instant::now();
    let lut = bake(&spec).unwrap();
    println!(
        "{n}x{n} tol {tol}: {:?}, evals/texel {}, err est {:?}",
        t.elapsed(),
        lut.evaluations / (n * n) as u64,
        lut.error_estimate
    );
    // GGX a=1 mu=1: E = 1 - ln2 (with Smith)
    let b = Brdf {
        specular: Some(Specular {
            ndf: Ndf::new(NdfKind::Ggx, 1.0).unwrap(),
            masking: Masking::SmithHeightCorrelated,
            fresnel: Fresnel::None,
        }),
        diffuse_weight: 0.0,
    };
    let (v, e, ev) = brdfbake::table::albedo::directional_albedo(&b, 1.0, 1e-9);
    println!(
        "E(1; a=1) = {:.12} exact {:.12} diff {:e} est {:e} evals {ev}",
        v[0],
        1.0 - 2f64.ln(),
        v[0] - (1.0 - 2f64.ln()),
        e[0]
    );
    let b = Brdf {
        specular: Some(Specular {
            ndf: Ndf::new(NdfKind::Ggx, 1.0).unwrap(),
            masking: Masking::VGroove,
            fresnel: Fresnel::None,
        }),
        diffuse_weight: 0.0,
    };
    let (v, e, ev) = brdfbake::table::albedo::directional_albedo(&b, 1.0, 1e-9);
    println!(
        "Vgroove E(1; a=1) = {:.12} exact 0.375 diff {:e} est {:e} evals {ev}",
        v[0],
        v[0] - 0.375,
        e[0]
    );
}
