//! `brdfbake eval QUANTITY ...`: one quantity computed directly, without a table.

use super::CliError;
use crate::lut::{Axis, Convention, Quantity};
use crate::model::{Fresnel, Masking, NdfKind, RoughnessQuantity};
use crate::table::{DfgLayout, ModelSpec, Storage, TableKind, TableSpec};
use serde_json::json;

#[derive(clap::ValueEnum, Clone, Copy, Debug, PartialEq, Eq)]
pub enum EvalQuantity {
    /// The NDF D(cos theta_h) (modern normalization); needs --cos-theta (= n.h).
    D,
    /// Smith G1(cos theta); needs --cos-theta.
    G1,
    /// G2(cos theta_v, cos theta_l) of --masking; needs --cos-theta and --cos-theta-l.
    G2,
    /// Directional albedo E(mu) of the BRDF (with --f0 Schlick Fresnel, default F = 1); needs --cos-theta.
    E,
    /// Average albedo E_avg = 2 int E(mu) mu dmu.
    EAvg,
    /// Split sum: A = int (1-Fc) f cos, B = int Fc f cos (and Filament's R = B, G = A + B); needs --cos-theta.
    Dfg,
    /// Sheen albedo int D_Charlie V_Ashikhmin cos (Filament's cloth DFG channel); needs --cos-theta.
    Sheen,
}

#[derive(clap::Args, Debug)]
pub struct EvalArgs {
    /// What to compute.
    #[arg(value_enum)]
    pub quantity: EvalQuantity,
    /// NDF: beckmann, ggx (default), gaussian, blinn-phong, charlie. Not for sheen (Charlie).
    #[arg(long)]
    pub ndf: Option<String>,
    /// The NDF's alpha.
    #[arg(long, conflicts_with = "roughness", allow_negative_numbers = true)]
    pub alpha: Option<f64>,
    /// Perceptual roughness r (alpha = r^2).
    #[arg(long, allow_negative_numbers = true)]
    pub roughness: Option<f64>,
    /// cos theta (n.h for D, n.v for G1, G2, E, dfg, sheen).
    #[arg(long, allow_negative_numbers = true)]
    pub cos_theta: Option<f64>,
    /// cos theta_l (G2 only).
    #[arg(long, allow_negative_numbers = true)]
    pub cos_theta_l: Option<f64>,
    /// Masking of G2, E, E_avg and dfg: none, v-groove, smith-separable,
    /// smith-height-correlated (default), ashikhmin.
    #[arg(long)]
    pub masking: Option<String>,
    /// Schlick Fresnel F0 for E and E_avg (default: F = 1).
    #[arg(long, allow_negative_numbers = true)]
    pub f0: Option<f64>,
    /// Quadrature tolerance (estimated absolute error), in [1e-12, 1e-2]; a result whose
    /// estimate exceeds it is an error (exit 1).
    #[arg(long, default_value_t = 1e-10, allow_negative_numbers = true)]
    pub tolerance: f64,
    /// Print one JSON document instead of text.
    #[arg(long)]
    pub json: bool,
    #[command(flatten)]
    pub guards: super::guards::Guards,
}

fn parse_named<T: serde::de::DeserializeOwned>(
    flag: &str,
    s: &str,
    accepted: &str,
) -> Result<T, CliError> {
    serde_json::from_value(json!(s)).map_err(|_| {
        CliError::input(format!(
            "{flag}: unknown value {s:?} (accepted: {accepted})"
        ))
    })
}

fn cos_axis(name: &str, x: f64) -> Axis {
    Axis {
        name: name.into(),
        quantity: Quantity::Cosine,
        size: 1,
        range: [x, x],
        convention: Convention::Centers,
        warp: Default::default(),
        clamp: None,
    }
}

/// The optional flags a quantity takes: (`--ndf`, `--masking`, `--cos-theta`,
/// `--cos-theta-l`, `--f0`). A flag given to a quantity that does not take it is an error,
/// not silently ignored.
fn takes(q: EvalQuantity) -> [bool; 5] {
    use EvalQuantity as Q;
    match q {
        Q::D | Q::G1 => [true, false, true, false, false],
        Q::G2 => [true, true, true, true, false],
        Q::E => [true, true, true, false, true],
        Q::EAvg => [true, true, false, false, true],
        Q::Dfg => [true, true, true, false, false],
        Q::Sheen => [false, false, true, false, false],
    }
}

fn quantity_name(q: EvalQuantity) -> String {
    clap::ValueEnum::to_possible_value(&q)
        .map(|v| v.get_name().to_string())
        .unwrap_or_default()
}

/// Refuses flags that do not apply to `a.quantity`, naming them and why.
fn check_flags(a: &EvalArgs) -> Result<(), CliError> {
    let why = |flag: &str| -> String {
        use EvalQuantity as Q;
        match (a.quantity, flag) {
            (Q::Sheen, "--ndf") => "sheen is always Charlie's NDF".into(),
            (Q::Sheen, "--masking") => "sheen is always Ashikhmin's visibility".into(),
            (Q::D, "--masking") => "D has no masking term".into(),
            (Q::G1, "--masking") => "G1 is Smith's, from the NDF alone".into(),
            (Q::EAvg, "--cos-theta") => "E_avg is averaged over every cos theta".into(),
            (_, "--cos-theta-l") => "only g2 has a light direction".into(),
            (Q::Dfg, "--f0") => "the split sum factors F0 out: E = F0 A + B".into(),
            (_, "--f0") => "only e and e-avg take a Fresnel term".into(),
            _ => "it has no such parameter".into(),
        }
    };
    let given = [
        a.ndf.is_some(),
        a.masking.is_some(),
        a.cos_theta.is_some(),
        a.cos_theta_l.is_some(),
        a.f0.is_some(),
    ];
    let flags = ["--ndf", "--masking", "--cos-theta", "--cos-theta-l", "--f0"];
    for ((flag, g), t) in flags.iter().zip(given).zip(takes(a.quantity)) {
        if g && !t {
            return Err(CliError::input(format!(
                "{flag} does not apply to `eval {}`: {}",
                quantity_name(a.quantity),
                why(flag)
            )));
        }
    }
    Ok(())
}

pub fn run(a: EvalArgs) -> Result<(), CliError> {
    check_flags(&a)?;
    // one value: typically 10³–10⁵ evaluations, at most one integral's budget (~2 s)
    let deadline = a.guards.admit(&super::guards::Work {
        what: "this eval",
        memory: 16 << 20,
        memory_detail: "one value".into(),
        time: crate::resources::time_of_evaluations(1e5),
        threads: 1,
        smaller: "nothing smaller exists",
    })?;
    super::guards::check_tolerance(a.tolerance)?;
    let ndf: NdfKind = parse_named(
        "--ndf",
        a.ndf.as_deref().unwrap_or("ggx"),
        &NdfKind::ALL.map(|n| n.name()).join(", "),
    )?;
    let masking: Masking = parse_named(
        "--masking",
        a.masking.as_deref().unwrap_or("smith-height-correlated"),
        &Masking::ALL.map(|n| n.name()).join(", "),
    )?;
    let (q, r) = match (a.alpha, a.roughness) {
        (Some(x), _) => (RoughnessQuantity::Alpha, x),
        (None, Some(x)) => (RoughnessQuantity::Perceptual, x),
        (None, None) => {
            return Err(CliError::input(
                "give the roughness: --alpha A (the NDF's alpha) or --roughness R (perceptual, alpha = R^2)",
            ))
        }
    };
    if !r.is_finite() {
        return Err(CliError::input(
            "--alpha/--roughness must be a finite number",
        ));
    }
    let alpha = q.to_alpha(r);
    use crate::model::ndf::{MAX_ALPHA, MIN_ALPHA};
    if !(MIN_ALPHA..=MAX_ALPHA).contains(&alpha) {
        return Err(CliError::input(format!(
            "alpha {alpha} is outside [{MIN_ALPHA:e}, {MAX_ALPHA}] (--roughness R gives alpha = R^2)"
        )));
    }
    let need = |v: Option<f64>, flag: &str| -> Result<f64, CliError> {
        match v {
            None => Err(CliError::input(format!(
                "`eval {}` needs {flag} (a cosine in [0, 1])",
                quantity_name(a.quantity)
            ))),
            Some(x) if !(0.0..=1.0).contains(&x) => Err(CliError::input(format!(
                "{flag} {} is not a cosine: give a number in [0, 1]",
                crate::numfmt::num(x)
            ))),
            Some(x) => Ok(x),
        }
    };
    let rough = Axis {
        name: "roughness".into(),
        quantity: Quantity::Roughness(q),
        size: 1,
        range: [r, r],
        convention: Convention::Centers,
        warp: Default::default(),
        clamp: None,
    };
    let fresnel = match a.f0 {
        Some(f0) if !(0.0..=1.0).contains(&f0) => {
            return Err(CliError::input(format!(
                "--f0 {} is not a reflectance: give Schlick's F0 in [0, 1]",
                crate::numfmt::num(f0)
            )))
        }
        Some(f0) => Fresnel::Schlick { f0 },
        None => Fresnel::None,
    };
    let (kind, axes, masking, layout, cloth, fresnel) = match a.quantity {
        EvalQuantity::D => (
            TableKind::Ndf,
            vec![
                cos_axis("cos_theta_h", need(a.cos_theta, "--cos-theta")?),
                rough,
            ],
            Masking::None,
            None,
            false,
            Fresnel::None,
        ),
        EvalQuantity::G1 => (
            TableKind::G1,
            vec![
                cos_axis("cos_theta", need(a.cos_theta, "--cos-theta")?),
                rough,
            ],
            Masking::SmithSeparable,
            None,
            false,
            Fresnel::None,
        ),
        EvalQuantity::G2 => (
            TableKind::G2,
            vec![
                cos_axis("cos_theta_v", need(a.cos_theta, "--cos-theta")?),
                cos_axis("cos_theta_l", need(a.cos_theta_l, "--cos-theta-l")?),
                rough,
            ],
            masking,
            None,
            false,
            Fresnel::None,
        ),
        EvalQuantity::E => (
            TableKind::Albedo,
            vec![
                cos_axis("cos_theta_v", need(a.cos_theta, "--cos-theta")?),
                rough,
            ],
            masking,
            None,
            false,
            fresnel,
        ),
        EvalQuantity::EAvg => (
            TableKind::AlbedoAvg,
            vec![rough],
            masking,
            None,
            false,
            fresnel,
        ),
        EvalQuantity::Dfg => (
            TableKind::Dfg,
            vec![
                cos_axis("cos_theta_v", need(a.cos_theta, "--cos-theta")?),
                rough,
            ],
            masking,
            Some(DfgLayout::Karis),
            false,
            Fresnel::None,
        ),
        EvalQuantity::Sheen => (
            TableKind::Dfg,
            vec![
                cos_axis("cos_theta_v", need(a.cos_theta, "--cos-theta")?),
                rough,
            ],
            masking,
            Some(DfgLayout::Filament),
            true,
            Fresnel::None,
        ),
    };
    let spec = TableSpec {
        name: "eval".into(),
        kind,
        model: ModelSpec {
            ndf: Some(ndf),
            masking,
            fresnel,
            diffuse_weight: 0.0,
            diffuse_model: crate::model::DiffuseModel::Lambert,
            classic: None,
        },
        axes,
        dfg_layout: layout,
        cloth,
        cloth_alpha_min: None,
        ltc_channels: None,
        storage: Storage::F32,
        tolerance: a.tolerance,
    };
    let x: Vec<f64> = spec.axes.iter().map(|ax| ax.range[0]).collect();
    let (mut v, mut e) =
        crate::readback::exact_at(&spec, &x, a.tolerance).map_err(CliError::input)?;
    if deadline.passed() {
        return Err(super::guards::stopped("this eval", &deadline));
    }
    if let Some(c) = v.iter().position(|x| !x.is_finite()) {
        return Err(CliError::input(format!(
            "the value is not finite there ({} in channel {c}): the model is undefined at this point",
            v[c]
        )));
    }
    if let Some(c) = e.iter().position(|x| x.is_nan() || *x > a.tolerance) {
        return Err(CliError::env(format!(
            "the quadrature's error estimate {} exceeds --tolerance {} (channel {c}, value {}): \
             the integrand cannot be resolved to that accuracy here; raise --tolerance",
            crate::numfmt::num(e[c]),
            crate::numfmt::num(a.tolerance),
            v[c]
        )));
    }
    let mut names: Vec<String> = crate::table::channels(&spec)
        .into_iter()
        .map(|c| c.name)
        .collect();
    match a.quantity {
        EvalQuantity::Sheen => {
            v = vec![v[2]];
            e = vec![e[2]];
            names = vec!["sheen".into()];
        }
        EvalQuantity::Dfg => {
            // also Filament's layout: R = B, G = A + B
            v.extend([v[1], v[0] + v[1]]);
            e.extend([e[1], e[0] + e[1]]);
            names.extend(["R".to_string(), "G (= A + B)".to_string()]);
        }
        _ => {}
    }
    let model = if a.quantity == EvalQuantity::Sheen {
        "charlie / ashikhmin (sheen)".to_string()
    } else {
        crate::meta::model_summary(&spec)
    };
    if a.json {
        let doc = json!({
            "quantity": format!("{:?}", a.quantity).to_lowercase(),
            "model": model,
            "alpha": alpha,
            "values": names.iter().zip(&v).map(|(n, x)| (n.clone(), json!(x))).collect::<serde_json::Map<_, _>>(),
            "error_estimates": names.iter().zip(&e).map(|(n, x)| (n.clone(), json!(x))).collect::<serde_json::Map<_, _>>(),
        });
        outln!(
            "{}",
            serde_json::to_string_pretty(&doc).expect("serializable")
        );
        return Ok(());
    }
    outln!("{model} at alpha = {alpha}");
    for ((n, x), err) in names.iter().zip(&v).zip(&e) {
        if *err > 0.0 {
            outln!("{n} = {x:.15}  (estimated error {err:.1e})");
        } else {
            outln!("{n} = {x:.15}");
        }
    }
    Ok(())
}
