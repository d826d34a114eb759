//! What the Lipschitz tests share (`lipschitz.rs`, `lipschitz_params.rs`): random scenes from
//! every catalog entry (their arguments sometimes parameters with ranges), and the sampler that
//! checks a node's slope and ball promises.
#![allow(dead_code)]

use glam::DVec3;
use sdfc_compiler::catalog::repeat;
use sdfc_compiler::catalog::repeat::{AxisPlan, Plan};
use sdfc_compiler::catalog::{PRIMITIVES, Param, Ty};
use sdfc_compiler::reference::eval;
use sdfc_compiler::scene::{NodeId, NodeKind, Scene};
use sdfc_tests::Rng;
use std::cell::RefCell;
use std::collections::BTreeMap;

/// Points sampled per node.
pub(crate) const POINTS: usize = 48;

/// Directions and lengths for the sampler.
pub(crate) trait Sampling {
    fn dir(&mut self) -> DVec3;
    fn length(&mut self) -> f64;
}

impl Sampling for Rng {
    fn dir(&mut self) -> DVec3 {
        loop {
            let v = DVec3::new(
                self.range(-1.0, 1.0),
                self.range(-1.0, 1.0),
                self.range(-1.0, 1.0),
            );
            let l = v.length();
            if l > 1e-3 && l <= 1.0 {
                return v / l;
            }
        }
    }
    /// A length: mostly ordinary, sometimes degenerate or thin.
    fn length(&mut self) -> f64 {
        match self.below(10) {
            0 => 0.0,
            1 => 1e-3,
            _ => self.range(0.05, 1.5),
        }
    }
}

pub(crate) fn f(x: f64) -> String {
    format!("{x:.4}")
}

pub(crate) fn vec3(r: &mut Rng, g: impl Fn(&mut Rng) -> f64) -> String {
    let (a, b, c) = (g(r), g(r), g(r));
    format!("({}, {}, {})", f(a), f(b), f(c))
}

thread_local! {
    /// While building a parametric scene: the `param` declarations made so far (arguments
    /// become parameters with ranges around their values).
    static PARAMS: RefCell<Option<Vec<String>>> = const { RefCell::new(None) };
}

/// In a parametric scene, now and then: a parameter declared with default `v` and range
/// `lo..hi` (`unit` after each number), used in place of the value.
pub(crate) fn maybe_param(r: &mut Rng, v: f64, (lo, hi): (f64, f64), unit: &str) -> Option<String> {
    PARAMS.with(|p| {
        let mut p = p.borrow_mut();
        let list = p.as_mut()?;
        if r.below(2) == 0 {
            return None;
        }
        let name = format!("p{}", list.len());
        list.push(format!(
            "param {name} = {}{unit} in {}{unit}..{}{unit}",
            f(v),
            f(lo),
            f(hi)
        ));
        Some(name)
    })
}

/// An argument of the given type for `name` of operator or primitive `owner`; in a parametric
/// scene, numbers of the types a parameter may take are sometimes parameters.
pub(crate) fn value(r: &mut Rng, owner: &str, p: &Param) -> String {
    let fixed = ["repeat", "twist", "bend"].contains(&owner);
    let smooth = owner.starts_with("smooth_") && p.name == "radius";
    let text = plain_value(r, owner, p);
    let Ok(v) = text.trim_end_matches("deg").parse::<f64>() else {
        return text;
    };
    let v = (v * 1e4).round() / 1e4;
    let range = match p.ty {
        _ if fixed => None,
        _ if smooth => Some((0.0, v * 2.0 + 0.1)),
        Ty::Number => Some((v - 1.0, v + 1.0)),
        Ty::Length | Ty::Size => Some((v * 0.5, v * 1.5 + 0.1)),
        Ty::Positive | Ty::Scale => Some((v * 0.5, v * 2.0)),
        Ty::Fraction => Some(((v - 0.3).max(0.0), (v + 0.3).min(1.0))),
        Ty::Angle => Some((v - 90.0, v + 90.0)),
        Ty::Range(lo, hi) => Some((lo.max(v - 1.0), v + (hi.min(lo + 8.0) - v) * 0.5)),
        _ => None,
    };
    let unit = if p.ty == Ty::Angle { "deg" } else { "" };
    match range.and_then(|range| maybe_param(r, v, range, unit)) {
        Some(name) => name,
        None => text,
    }
}

pub(crate) fn plain_value(r: &mut Rng, owner: &str, p: &Param) -> String {
    match (owner, p.name) {
        ("twist" | "bend", "rate") => return f(*r.pick(&[0.5, 3.0, -10.0, 100.0])),
        ("scale", "factor") => {
            return match r.below(3) {
                0 => f(r.range(0.2, 3.0)),
                1 => vec3(r, |r| r.range(0.3, 3.0)),
                _ => format!("(1, 1, {})", f(*r.pick(&[10.0, 1e4, 0.01]))),
            };
        }
        ("repeat", "spacing") => {
            return vec3(r, |r| {
                if r.below(3) == 0 {
                    0.0
                } else {
                    r.range(0.5, 3.0)
                }
            });
        }
        ("repeat", "count") => return vec3(r, |r| r.below(4) as f64),
        ("smooth_union" | "smooth_intersect" | "smooth_subtract", "radius") => {
            return f(*r.pick(&[0.0, 0.1, 0.5, 2.0, 5.0]));
        }
        _ => {}
    }
    match p.ty {
        Ty::Number => f(r.range(-1.5, 1.5)),
        Ty::Length => f(r.length()),
        Ty::Positive => f(r.range(0.05, 2.0)),
        Ty::Fraction => f(*r.pick(&[0.0, 0.3, 0.5, 0.8, 1.0])),
        Ty::Angle => format!("{}deg", r.range(-200.0, 200.0).round()),
        Ty::Count => format!("{}", 1 + r.below(4)),
        Ty::CountTo(n) => format!("{}", 1 + r.below(n.min(8) as usize)),
        Ty::WholeIn(lo, hi) => format!("{}", lo as usize + r.below((hi - lo).min(8) as usize + 1)),
        Ty::UpTo(n) => format!("{}", r.below(n.min(4) as usize + 1)),
        Ty::ZeroOrAtLeast(lo) => f(if r.below(2) == 0 { 0.0 } else { lo.max(1.0) }),
        Ty::Range(lo, hi) => f(r.range(lo, hi.min(lo + 8.0))),
        Ty::Vec3 => vec3(r, |r| r.range(-1.0, 1.0)),
        Ty::Size => match r.below(4) {
            0 => format!(
                "(0.001, {}, {})",
                f(r.range(0.3, 2.0)),
                f(r.range(0.3, 2.0))
            ),
            _ => vec3(r, |r| r.length()),
        },
        Ty::Scale => f(r.range(0.2, 3.0)),
        Ty::Counts => vec3(r, |r| r.below(4) as f64),
        Ty::Axis => r
            .pick(&["x", "y", "z", "(1, 1, 0)", "(0.3, -1, 0.5)"])
            .to_string(),
        Ty::Color => "#888".to_string(),
        Ty::PositiveOr(words) | Ty::Word(words) => words[0].to_string(),
    }
}

pub(crate) fn args(r: &mut Rng, owner: &str, params: &[Param]) -> String {
    let mut out = Vec::new();
    for p in params {
        // A bake's `res` always given (small, as `scenes::args` says why).
        if p.default.is_some() && p.name != "res" && r.below(3) == 0 {
            continue;
        }
        out.push(format!("{} = {}", p.name, value(r, owner, p)));
    }
    out.join(", ")
}

/// An `implicit` body of a few terms whose bound the checker infers by intervals.
pub(crate) fn implicit(r: &mut Rng) -> String {
    let a = f(r.range(0.2, 1.5));
    let k = f(r.range(0.5, 6.0));
    let c = f(r.range(0.02, 0.3));
    match r.below(5) {
        0 => format!("length(x, y, z) - {a} + {c} * sin({k} * x) * cos({k} * z)"),
        1 => format!("max(abs(x) - {a}, length(x, 0, z) - {a} * 0.7) + {c} * sin({k} * y)"),
        2 => format!("length(x, y - {c}, z) * {a} - {c} + {c} * exp(-(x^2))"),
        3 => format!("min(length(x, y, z) - {a}, y + {a}) + {c} * atan2(y, x * x + 1)"),
        _ => format!("sqrt(x^2 + z^2 + {c}) - {a} + {c} * log(1 + y^2)"),
    }
}

pub(crate) fn shape(r: &mut Rng, depth: usize) -> String {
    let s = if depth == 0 || r.below(3) == 0 {
        if r.below(8) == 0 {
            format!("implicit {{ {} }}", implicit(r))
        } else {
            let p = r.pick(PRIMITIVES);
            if p.name == "mandelbulb" {
                // An estimate, not a bound (see docs/lipschitz.md): left out.
                return shape(r, depth);
            }
            let s = format!("{}({})", p.name, args(r, p.name, p.params));
            if p.planar {
                sdfc_tests::solid_of_2d(r, s)
            } else {
                s
            }
        }
    } else {
        sdfc_tests::operator_block(
            r,
            |r, op| args(r, op.name, op.params),
            |r| shape(r, depth - 1),
        )
    };
    // Children placed off-centre and turned, so that `repeat` and `mirror` see asymmetric shapes.
    match r.below(5) {
        0 => {
            let x = (r.range(-0.8, 0.8) * 1e4).round() / 1e4;
            let x = maybe_param(r, x, (x - 0.5, x + 0.5), "").unwrap_or_else(|| f(x));
            format!(
                "{s} at ({x}, {}, {})",
                f(r.range(-0.8, 0.8)),
                f(r.range(-0.8, 0.8))
            )
        }
        1 => format!(
            "{s} |> rotate({}, {}deg)",
            r.pick(&["x", "y", "z", "(1, 2, 3)"]),
            r.below(360)
        ),
        _ => s,
    }
}

pub(crate) fn scene_source(seed: u64) -> String {
    let mut r = Rng::new(seed);
    let depth = 1 + r.below(3);
    format!("{}\n", shape(&mut r, depth))
}

/// A random scene whose arguments are sometimes parameters with ranges, and its declarations.
pub(crate) fn parametric_source(seed: u64) -> String {
    PARAMS.with(|p| *p.borrow_mut() = Some(Vec::new()));
    let body = scene_source(seed);
    let decls = PARAMS.with(|p| p.borrow_mut().take()).unwrap_or_default();
    format!("{}\n{body}", decls.join("\n"))
}

/// What the sampling found, per rule.
#[derive(Default)]
pub(crate) struct Tally {
    /// Points sampled.
    pub points: usize,
    /// Pairs whose slope was not checked (see `steps_allowed`).
    pub slope_exempt: usize,
    /// Per rule name, each sampled node's largest slope / λ.
    pub tightness: BTreeMap<&'static str, Vec<f64>>,
    /// What broke the promise, for the report.
    pub violations: Vec<String>,
}

impl Tally {
    /// Fails with the first `shown` violations, if there are any.
    pub(crate) fn assert_no_violations(&self, shown: usize) {
        let first: Vec<&str> = self
            .violations
            .iter()
            .take(shown)
            .map(String::as_str)
            .collect();
        assert!(
            self.violations.is_empty(),
            "{} violations, first ones:\n{}",
            self.violations.len(),
            first.join("\n\n")
        );
    }
}

/// Whether a node's field is, outside its surface, its exact distance times λ (built from
/// exact primitives by operators that keep that): copies of such a shape are ordered like their
/// distances, which is what keeps a `repeat` window continuous where it moves on.
pub(crate) fn exact(scene: &Scene, id: NodeId) -> bool {
    let node = &scene.nodes[id];
    match &node.kind {
        NodeKind::Primitive { prim, .. } => prim.exact,
        NodeKind::Implicit { .. } => false,
        NodeKind::Operator { op, ctx, children } => {
            let keeps = match op.name {
                "union" | "translate" | "rotate" | "round" | "repeat" | "repeat_polar" => true,
                "scale" => ctx.vec(0).min_element() == ctx.vec(0).max_element(),
                _ => false,
            };
            keeps && children.iter().all(|&c| exact(scene, c))
        }
    }
}

/// Whether the subtree holds a `repeat` that looks at several copies of a shape whose field is
/// a bound rather than a distance: such a field is a bound at every point (the ball test
/// applies) but may step where the window of copies moves on (docs/lipschitz.md).
pub(crate) fn steps_allowed(scene: &Scene, id: NodeId) -> bool {
    let node = &scene.nodes[id];
    let here = match &node.kind {
        NodeKind::Operator { op, ctx, children } if op.name == "repeat" => {
            let plan = Plan::new(ctx);
            let several = plan.axes.iter().any(|a| matches!(a, AxisPlan::Window(_)));
            several && !exact(scene, children[0])
        }
        NodeKind::Operator { op, ctx, children } if op.name == "repeat_polar" => {
            let several = matches!(repeat::polar_plan(ctx).1, repeat::PolarPlan::Window(_));
            several && !exact(scene, children[0])
        }
        _ => false,
    };
    here || node.children().iter().any(|&c| steps_allowed(scene, c))
}

/// The reachable nodes whose λ is a promise: all but those inside a `bake`, whose shape may
/// have no bound (its λ only combines parts before baking; the map's λ is proven from its
/// values, and `tests/bake.rs` tests that).
pub(crate) fn promised_nodes(scene: &Scene) -> Vec<NodeId> {
    let mut seen = vec![false; scene.nodes.len()];
    let mut stack = vec![scene.root];
    while let Some(n) = stack.pop() {
        if std::mem::replace(&mut seen[n], true) {
            continue;
        }
        let bakes =
            matches!(&scene.nodes[n].kind, NodeKind::Operator { op, .. } if op.traits.bakes);
        if !bakes {
            stack.extend(scene.nodes[n].children());
        }
    }
    (0..scene.nodes.len()).filter(|&n| seen[n]).collect()
}

/// Samples one node: pairs for the slope, balls for the bound.
pub(crate) fn sample_node(scene: &Scene, id: NodeId, r: &mut Rng, source: &str, tally: &mut Tally) {
    let node = &scene.nodes[id];
    let lambda = node.lambda;
    let field = |p: DVec3| eval::node(scene, id, p).d;
    // Where to look: the node's box grown by half its size (or 1), else a cube around the origin.
    let (lo, hi) = if node.bound.is_finite() {
        let grow = ((node.bound.hi - node.bound.lo) * 0.5).max(DVec3::splat(0.5));
        (node.bound.lo - grow, node.bound.hi + grow)
    } else {
        (DVec3::splat(-4.0), DVec3::splat(4.0))
    };
    let scale = (hi - lo).max_element();
    let name = node.kind_name();
    let check_slope = !steps_allowed(scene, id);
    let mut steepest: f64 = 0.0;
    for _ in 0..POINTS {
        let p = lo + (hi - lo) * DVec3::new(r.unit(), r.unit(), r.unit());
        let fp = field(p);
        assert!(fp.is_finite(), "non-finite field {fp} at {p} in\n{source}");
        tally.points += 1;
        // Slope over a short and a long separation.
        for h in [scale * 1e-4, scale * r.range(0.01, 0.3)] {
            let q = p + r.dir() * h;
            let fq = field(q);
            let slope = (fp - fq).abs() / h;
            let rounding = 1e-12 * (fp.abs() + fq.abs() + scale) / h;
            if !check_slope {
                tally.slope_exempt += 1;
                continue;
            }
            steepest = steepest.max(slope / lambda);
            if slope > lambda * (1.0 + 1e-6) + rounding {
                tally.violations.push(format!(
                    "slope {slope:.6} > λ = {lambda} at `{name}` between {p} and {q} (f {fp} / {fq}) in\n{source}"
                ));
            }
        }
        // Ball test: no inside point within f/λ.
        if fp > 0.0 {
            let radius = fp / lambda * (1.0 - 1e-9);
            let g = DVec3::new(
                field(p + DVec3::X * 1e-6 * scale) - fp,
                field(p + DVec3::Y * 1e-6 * scale) - fp,
                field(p + DVec3::Z * 1e-6 * scale) - fp,
            );
            let mut dirs = vec![r.dir(), r.dir(), r.dir(), r.dir()];
            if let Some(down) = (-g).try_normalize() {
                dirs.push(down);
            }
            for d in dirs {
                for frac in [0.25, 0.5, 0.75, 1.0] {
                    let q = p + d * radius * frac;
                    let fq = field(q);
                    if fq < -1e-9 * (scale + fp.abs()) {
                        tally.violations.push(format!(
                            "ball test: f = {fq} < 0 at {q}, within f/λ = {radius} of {p} at `{name}` in\n{source}"
                        ));
                    }
                }
            }
        }
    }
    if check_slope {
        tally.tightness.entry(name).or_default().push(steepest);
    }
}
