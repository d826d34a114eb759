//! The tracing methods' parameter table, and building [`Trace`] settings from a scene's `trace`
//! block or from command-line overrides with the same types and ranges.

use crate::catalog::{Param, Ty, Val, opt};
use crate::scene::{Epsilon, Method, Trace};

/// Largest step budget a tracer accepts.
pub const MAX_STEPS: f64 = 100_000.0;

/// Most regula falsi or discontinuity-reduction iterations.
pub const MAX_ITERATIONS: u32 = 16;

const STEPS: Param = opt("steps", Ty::CountTo(MAX_STEPS as u32), Val::Num(128.0));
const EPSILON: Param = opt("epsilon", Ty::PositiveOr(&["pixel"]), Val::Word(0));
const MAX_DISTANCE: Param = opt("max_distance", Ty::Positive, Val::Num(100.0));
const DISCONTINUITY: Param = opt("discontinuity", Ty::UpTo(MAX_ITERATIONS), Val::Num(0.0));

/// Tracing methods (`trace enhanced { .. }`) and their parameters; the first is the default.
/// ω is Keinert's over-relaxation factor for `relaxed` and Bálint's relaxation of the inferred
/// planar step for `enhanced` (the reference runs use 0.9); β is the weight of the
/// auto tracer's moving slope average (Bán & Valasek use 0.3).
pub const TRACE_METHODS: &[(&str, Method, &[Param])] = &[
    (
        "basic",
        Method::Basic,
        &[
            STEPS,
            EPSILON,
            MAX_DISTANCE,
            DISCONTINUITY,
            opt("antialias", Ty::Word(&["none", "cone"]), Val::Word(0)),
        ],
    ),
    (
        "relaxed",
        Method::Relaxed,
        &[
            STEPS,
            EPSILON,
            MAX_DISTANCE,
            DISCONTINUITY,
            opt("omega", Ty::Range(1.0, 2.0), Val::Num(1.2)),
            opt("fallback", Ty::Word(&["reset", "keep"]), Val::Word(0)),
        ],
    ),
    (
        "enhanced",
        Method::Enhanced,
        &[
            STEPS,
            EPSILON,
            MAX_DISTANCE,
            DISCONTINUITY,
            opt("omega", Ty::Range(0.5, 2.0), Val::Num(0.9)),
        ],
    ),
    (
        "hybrid",
        Method::Hybrid,
        &[
            STEPS,
            EPSILON,
            MAX_DISTANCE,
            DISCONTINUITY,
            opt("linear", Ty::Range(1.0, 1000.0), Val::Num(4.0)),
            opt("refine", Ty::UpTo(MAX_ITERATIONS), Val::Num(4.0)),
        ],
    ),
    (
        "auto",
        Method::Auto,
        &[
            STEPS,
            EPSILON,
            MAX_DISTANCE,
            DISCONTINUITY,
            opt("beta", Ty::Fraction, Val::Num(0.3)),
        ],
    ),
];

/// The name and parameters of a method.
pub fn method_entry(method: Method) -> (&'static str, &'static [Param]) {
    let m = TRACE_METHODS
        .iter()
        .find(|m| m.1 == method)
        .unwrap_or(&TRACE_METHODS[0]);
    (m.0, m.2)
}

/// Settings of `method` from values by parameter name (missing ones take the table's defaults).
pub fn build(method: Method, get: impl Fn(&str) -> Option<Val>) -> Trace {
    let (_, params) = method_entry(method);
    // Only the method's own parameters: a setting of another method is not carried over.
    let val = |name: &str| {
        let p = params.iter().find(|p| p.name == name)?;
        get(name).or(p.default)
    };
    let num = |name: &str, fallback: f64| val(name).map_or(fallback, Val::num);
    Trace {
        method,
        steps: num("steps", 128.0) as u32,
        epsilon: match val("epsilon") {
            Some(Val::Num(e)) => Epsilon::Absolute(e),
            _ => Epsilon::Pixel,
        },
        max_distance: num("max_distance", 100.0),
        omega: num("omega", 1.0),
        beta: num("beta", 0.3),
        linear: num("linear", 4.0),
        refine: num("refine", 0.0) as u32,
        discontinuity: num("discontinuity", 0.0) as u32,
        antialias: matches!(val("antialias"), Some(Val::Word(1))),
        keep_relaxation: matches!(val("fallback"), Some(Val::Word(1))),
    }
}

/// The value of parameter `name` in `trace` (for any method's parameter name).
fn value(trace: &Trace, name: &str) -> Option<Val> {
    Some(match name {
        "steps" => Val::Num(trace.steps as f64),
        "epsilon" => match trace.epsilon {
            Epsilon::Pixel => Val::Word(0),
            Epsilon::Absolute(e) => Val::Num(e),
        },
        "max_distance" => Val::Num(trace.max_distance),
        "discontinuity" => Val::Num(trace.discontinuity as f64),
        "antialias" => Val::Word(trace.antialias as usize),
        "fallback" => Val::Word(trace.keep_relaxation as usize),
        "omega" => Val::Num(trace.omega),
        "beta" => Val::Num(trace.beta),
        "linear" => Val::Num(trace.linear),
        "refine" => Val::Num(trace.refine as f64),
        _ => return None,
    })
}

/// The method's name and each of its parameters with its value in `trace`, written as a
/// scene's `trace` block or an override takes it (`("epsilon", "pixel")`, `("steps", "128")`).
pub fn settings(trace: &Trace) -> (&'static str, Vec<(&'static str, String)>) {
    let (name, params) = method_entry(trace.method);
    let text = |p: &Param| match (value(trace, p.name), p.ty) {
        (Some(Val::Word(i)), Ty::PositiveOr(words) | Ty::Word(words)) => {
            words.get(i).map_or(String::new(), |w| w.to_string())
        }
        (Some(v), _) => v.num().to_string(),
        (None, _) => String::new(),
    };
    (name, params.iter().map(|p| (p.name, text(p))).collect())
}

/// The default settings (basic tracing).
pub fn default_trace() -> Trace {
    build(Method::Basic, |_| None)
}

/// Applies command-line overrides to a scene's settings: a new method keeps the scene's budget,
/// ε, distance and discontinuity reduction and takes its own defaults for the rest; each value
/// is checked against the method's parameter table. The error names the flag's parameter.
pub fn with_overrides(
    scene: Trace,
    method: Option<&str>,
    values: &[(&str, &str)],
) -> Result<Trace, String> {
    let method = match method {
        None => scene.method,
        Some(name) => match TRACE_METHODS.iter().find(|m| m.0 == name) {
            Some(m) => m.1,
            None => {
                let names: Vec<&str> = TRACE_METHODS.iter().map(|m| m.0).collect();
                return Err(format!(
                    "unknown tracer `{name}`; the tracers are: {}",
                    names.join(", ")
                ));
            }
        },
    };
    let (name, params) = method_entry(method);
    let mut given: Vec<(&str, Val)> = Vec::new();
    for (key, text) in values {
        let Some(p) = params.iter().find(|p| p.name == *key) else {
            return Err(format!("the `{name}` tracer has no parameter `{key}`"));
        };
        let v = match (p.ty, *text) {
            (Ty::PositiveOr(words) | Ty::Word(words), w) if words.contains(&w) => {
                Val::Word(words.iter().position(|x| *x == w).unwrap_or(0))
            }
            (ty, t) => match t.trim().parse::<f64>() {
                Ok(x) if ty.accepts_number(x) && !crate::catalog::fits_gpu(x) => {
                    let (lo, hi) = crate::catalog::GPU_RANGE;
                    return Err(format!(
                        "`--{}` = {text} is beyond what the GPU's f32 arithmetic can use (numbers must be 0 or between {lo:e} and {hi:e} in size)",
                        key.replace('_', "-")
                    ));
                }
                Ok(x) if ty.accepts_number(x) => Val::Num(x),
                _ => {
                    return Err(format!(
                        "`--{}` must be {}; found `{text}`",
                        key.replace('_', "-"),
                        p.ty.describe()
                    ));
                }
            },
        };
        given.push((p.name, v));
    }
    // A method's own parameters are kept only when the method is kept.
    let kept = |name: &str| match name {
        "omega" | "beta" | "linear" | "refine" | "fallback" if method != scene.method => None,
        _ => value(&scene, name),
    };
    Ok(build(method, |n| {
        given
            .iter()
            .find(|g| g.0 == n)
            .map(|g| g.1)
            .or_else(|| kept(n))
    }))
}
