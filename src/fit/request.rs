//! What a preset's `fit` asks for ([`RawRequest`] as written, [`Request`] checked) and the
//! error weight a fit minimizes ([`Weight`]): plain data, apart from the search, so that
//! presets and sidecars can name a fit without depending on how one is found.

use crate::encode::function;
use crate::numfmt::num;

/// A weight of the minimax error.
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Weight {
    /// |fit − exact|.
    Absolute,
    /// |fit − exact| / max(|exact|, 10⁻³·max|exact|): relative, floored where the channel
    /// is near 0 (stated in the sidecar).
    Relative,
}

impl Weight {
    pub fn name(self) -> &'static str {
        match self {
            Weight::Absolute => "absolute",
            Weight::Relative => "relative",
        }
    }
}

/// Which fit of the front to take.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Goal {
    /// The cheapest whose max error plus f32 bound is at most this.
    MaxError(f64),
    /// The most accurate of at most this many operations.
    MaxOps(usize),
}

/// A preset table's `"fit"`: `{"max_error": E}` or `{"max_ops": N}`, optionally `"weight"`
/// (absolute, relative) and `"emit"` (languages; default all).
#[derive(Clone, Debug, PartialEq)]
pub struct Request {
    pub goal: Goal,
    pub weight: Weight,
    pub emit: Vec<String>,
}

/// The preset's JSON form of [`Request`].
#[derive(serde::Deserialize, serde::Serialize, Clone, Debug)]
#[serde(deny_unknown_fields)]
pub struct RawRequest {
    #[serde(default)]
    pub max_error: Option<f64>,
    #[serde(default)]
    pub max_ops: Option<usize>,
    #[serde(default)]
    pub weight: Option<Weight>,
    #[serde(default)]
    pub emit: Option<Vec<String>>,
}

impl RawRequest {
    /// The request, or what is wrong with it.
    pub fn check(&self) -> Result<Request, String> {
        let goal = match (self.max_error, self.max_ops) {
            (Some(e), None) if e.is_finite() && e > 0.0 => Goal::MaxError(e),
            (Some(e), None) => {
                return Err(format!("max_error must be a positive number, got {}", num(e)))
            }
            (None, Some(n)) if n >= 1 => Goal::MaxOps(n),
            (None, Some(_)) => return Err("max_ops must be at least 1".into()),
            _ => {
                return Err(
                    "needs exactly one of max_error (the cheapest fit within it) or max_ops (the most accurate fit of at most that many operations)"
                        .into(),
                )
            }
        };
        let emit = self
            .emit
            .clone()
            .unwrap_or_else(|| function::LANGUAGES.iter().map(|s| s.to_string()).collect());
        if emit.is_empty() {
            return Err("emit lists no language".into());
        }
        for l in &emit {
            if function::dialect(l).is_none() {
                return Err(format!(
                    "emit: unknown language {l:?} (accepted: {})",
                    function::LANGUAGES.join(", ")
                ));
            }
        }
        Ok(Request {
            goal,
            weight: self.weight.unwrap_or(Weight::Absolute),
            emit,
        })
    }
}
