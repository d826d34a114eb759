//! The Lipschitz promise, sampled: for random scenes built from every catalog entry and
//! operator (random parameters, including asymmetric and rotated children of `repeat`, counts,
//! non-uniform scales up to 10⁴, twist and bend rates up to 100, thin and degenerate shapes,
//! smooth radii larger than the shapes, nesting, `implicit` bodies), at every node:
//! - **slope**: |f(p) − f(q)| ≤ λ·|p − q|·(1 + 1e-6) (plus f64 rounding) for pairs of points;
//! - **ball test**: for a point outside (f > 0), no point of the ball of radius f/λ around it is
//!   inside (f < 0) — probed along the descent direction and at random directions.
//!
//! Fixed seed in CI; `SDFC_LIPSCHITZ_SCENES` and `SDFC_FUZZ_SEED` for larger runs by hand. The
//! per-rule tightness (each node's steepest sampled slope over λ, median and loosest node) is
//! printed for `docs/lipschitz.md`. The Mandelbulb, an estimate rather than a bound, is left out.

use glam::DVec3;
use sdfc_compiler::catalog::repeat::{AxisPlan, Plan};
use sdfc_compiler::catalog::{PRIMITIVES, Param, Ty};
use sdfc_compiler::eval;
use sdfc_compiler::scene::{NodeId, NodeKind, Scene};
use sdfc_tests::Rng;
use std::cell::RefCell;
use std::collections::{BTreeMap, HashMap};

/// Scenes per CI run (each contributes sampled points at every node).
const SCENES: usize = 700;
/// Points sampled per node.
const POINTS: usize = 48;

/// Directions and lengths for the sampler.
trait Sampling {
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

fn f(x: f64) -> String {
    format!("{x:.4}")
}

fn vec3(r: &mut Rng, g: impl Fn(&mut Rng) -> f64) -> String {
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
fn maybe_param(r: &mut Rng, v: f64, (lo, hi): (f64, f64), unit: &str) -> Option<String> {
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
fn value(r: &mut Rng, owner: &str, p: &Param) -> String {
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

fn plain_value(r: &mut Rng, owner: &str, p: &Param) -> String {
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

fn args(r: &mut Rng, owner: &str, params: &[Param]) -> String {
    let mut out = Vec::new();
    for p in params {
        if p.default.is_some() && r.below(3) == 0 {
            continue;
        }
        out.push(format!("{} = {}", p.name, value(r, owner, p)));
    }
    out.join(", ")
}

/// An `implicit` body of a few terms whose bound the checker infers by intervals.
fn implicit(r: &mut Rng) -> String {
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

fn shape(r: &mut Rng, depth: usize) -> String {
    let s = if depth == 0 || r.below(3) == 0 {
        if r.below(8) == 0 {
            format!("implicit {{ {} }}", implicit(r))
        } else {
            let p = r.pick(PRIMITIVES);
            if p.name == "mandelbulb" {
                // An estimate, not a bound (see docs/lipschitz.md): left out.
                return shape(r, depth);
            }
            format!("{}({})", p.name, args(r, p.name, p.params))
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

fn scene_source(seed: u64) -> String {
    let mut r = Rng::new(seed);
    let depth = 1 + r.below(3);
    format!("{}\n", shape(&mut r, depth))
}

/// A random scene whose arguments are sometimes parameters with ranges, and its declarations.
fn parametric_source(seed: u64) -> String {
    PARAMS.with(|p| *p.borrow_mut() = Some(Vec::new()));
    let body = scene_source(seed);
    let decls = PARAMS.with(|p| p.borrow_mut().take()).unwrap_or_default();
    format!("{}\n{body}", decls.join("\n"))
}

/// What the sampling found, per rule.
#[derive(Default)]
struct Tally {
    points: usize,
    /// Pairs whose slope was not checked (see `steps_allowed`).
    slope_exempt: usize,
    /// Per rule name, each sampled node's largest slope / λ.
    tightness: BTreeMap<&'static str, Vec<f64>>,
    violations: Vec<String>,
}

/// Whether a node's field is, outside its surface, its exact distance times λ (built from
/// exact primitives by operators that keep that): copies of such a shape are ordered like their
/// distances, which is what keeps a `repeat` window continuous where it moves on.
fn exact(scene: &Scene, id: NodeId) -> bool {
    let node = &scene.nodes[id];
    match &node.kind {
        NodeKind::Primitive { prim, .. } => prim.exact,
        NodeKind::Implicit { .. } => false,
        NodeKind::Operator { op, ctx, children } => {
            let keeps = match op.name {
                "union" | "translate" | "rotate" | "round" | "repeat" => true,
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
fn steps_allowed(scene: &Scene, id: NodeId) -> bool {
    let node = &scene.nodes[id];
    let here = match &node.kind {
        NodeKind::Operator { op, ctx, children } if op.name == "repeat" => {
            let plan = Plan::new(ctx);
            let several = plan.axes.iter().any(|a| matches!(a, AxisPlan::Window(_)));
            several && !exact(scene, children[0])
        }
        _ => false,
    };
    here || node.children().iter().any(|&c| steps_allowed(scene, c))
}

/// Samples one node: pairs for the slope, balls for the bound.
fn sample_node(scene: &Scene, id: NodeId, r: &mut Rng, source: &str, tally: &mut Tally) {
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

#[test]
fn every_rule_is_a_true_bound_where_sampled() {
    sdfc_tests::with_stack(|| {
        let scenes = sdfc_tests::env_number("SDFC_LIPSCHITZ_SCENES").unwrap_or(SCENES);
        let seed = sdfc_tests::fuzz_seed(0x11b5_c412);
        let mut tally = Tally::default();
        let mut valid = 0;
        let mut r = Rng::new(seed);
        for _ in 0..scenes {
            let source = scene_source(r.bits());
            let checked = sdfc_compiler::check::compile(&source);
            let Some(scene) = checked.scene else {
                continue;
            };
            valid += 1;
            for id in scene.reachable() {
                sample_node(&scene, id, &mut r, &source, &mut tally);
            }
        }
        println!(
            "{valid} of {scenes} scenes valid; {} points sampled ({} slope pairs exempt: a window of copies of a bound)",
            tally.points, tally.slope_exempt
        );
        // Per rule: over the sampled nodes, the steepest slope seen relative to λ (1 = tight),
        // as the median node and the loosest node.
        println!("| rule | nodes | median slope/λ | loosest slope/λ |\n|---|---|---|---|");
        for (name, t) in &mut tally.tightness {
            t.sort_by(f64::total_cmp);
            println!(
                "| `{name}` | {} | {:.3} | {:.3} |",
                t.len(),
                t[t.len() / 2],
                t[0]
            );
        }
        let shown: Vec<&String> = tally.violations.iter().take(5).collect();
        assert!(
            tally.violations.is_empty(),
            "{} violations, first ones:\n{}",
            tally.violations.len(),
            shown
                .iter()
                .map(|s| s.as_str())
                .collect::<Vec<_>>()
                .join("\n\n")
        );
        assert!(tally.points >= 100_000, "only {} points", tally.points);
        assert!(
            valid * 10 >= scenes * 8,
            "too few valid scenes: {valid} of {scenes}"
        );
    });
}

/// Scenes whose arguments are parameters (`param`, with ranges): λ, bounds and symmetries hold
/// for every value of the range, so the sampling test passes at the range's ends and at random
/// values inside: the scene as checked with its defaults, its parameters then set to those
/// values (`Scene::with_values`, what the shader does with the uniform).
#[test]
fn bounds_hold_over_parameter_ranges() {
    sdfc_tests::with_stack(|| {
        let scenes =
            sdfc_tests::env_number("SDFC_LIPSCHITZ_SCENES").map_or(PARAMETRIC, |n: usize| n / 4);
        let seed = sdfc_tests::fuzz_seed(0x9a4a_3e71);
        let mut tally = Tally::default();
        let (mut valid, mut with_params, mut settings) = (0, 0, 0);
        let mut r = Rng::new(seed);
        let fixed = FIXED_PARAMETRIC.iter().map(|s| s.to_string());
        let random: Vec<String> = (0..scenes).map(|_| parametric_source(r.bits())).collect();
        for (k, source) in fixed.chain(random).enumerate() {
            let Some(scene) = sdfc_compiler::check::compile(&source).scene else {
                assert!(k >= FIXED_PARAMETRIC.len(), "{source}\ndoes not check");
                continue;
            };
            valid += 1;
            let ranged: Vec<_> = scene.params.iter().filter(|p| p.range.is_some()).collect();
            if ranged.is_empty() {
                continue;
            }
            with_params += 1;
            // The low ends, the high ends, and two random points of the box of ranges.
            for k in 0..4 {
                let values: HashMap<String, Vec<f64>> = ranged
                    .iter()
                    .map(|p| {
                        let (lo, hi) = p.range.expect("ranged");
                        let v = match k {
                            0 => lo.x,
                            1 => hi.x,
                            _ => lo.x + (hi.x - lo.x) * r.unit(),
                        };
                        (p.name.clone(), vec![v.clamp(lo.x, hi.x)])
                    })
                    .collect();
                // The values are valid ones (checked as `render --param` checks them)...
                let at = sdfc_compiler::check::compile_with(&source, &values);
                assert!(
                    at.scene.is_some(),
                    "{source}\nfails to check at {values:?}: {:?}",
                    at.diagnostics
                );
                // ...and the field there is the default scene's, as the shader computes it:
                // λ, bounds and `repeat`'s copies from the check, the arguments from the values.
                let here = scene.with_values(&values);
                settings += 1;
                let note = format!("{source}\n(at {values:?})");
                for id in here.reachable() {
                    sample_node(&here, id, &mut r, &note, &mut tally);
                }
            }
        }
        println!(
            "{valid} of {scenes} parametric scenes valid, {with_params} with parameters, checked at {settings} settings; {} points sampled",
            tally.points
        );
        let shown: Vec<&String> = tally.violations.iter().take(3).collect();
        assert!(
            tally.violations.is_empty(),
            "{} violations, first ones:\n{}",
            tally.violations.len(),
            shown
                .iter()
                .map(|s| s.as_str())
                .collect::<Vec<_>>()
                .join("\n\n")
        );
        assert!(
            with_params * 10 >= scenes * 4,
            "too few scenes with parameters: {with_params} of {scenes}"
        );
        assert!(tally.points >= 20_000, "only {} points", tally.points);
    });
}

/// Scenes whose bounds depend on their parameters, tightly: `mix`'s λ is (1 − w)·3 + w·1
/// (the implicit's gradient is 3 everywhere), largest at w = 0, the default being 1; a
/// `repeat` must look at enough copies for the largest radius and offset; a turned bar.
const FIXED_PARAMETRIC: &[&str] = &[
    "param w = 1 in 0..1\nmix(w) { implicit { 3 * (length(x, y, z) - 1) }  sphere(1) }",
    "param r = 0.3 in 0.2..1.4\nparam d = 0 in -1..1\nrepeat(spacing = (3, 3, 3)) { sphere(r) at (d, 0, 0) }",
    "param a = 0deg in 0deg..90deg\nrepeat(spacing = (3, 0, 0)) { box((2.4, 0.3, 0.3)) |> rotate(z, a) }",
];

/// `repeat` looks at the copies the bound of its shape over the whole range calls for: with
/// the shape's radius and offset at other values than the defaults, the repeated field is
/// still the union of every copy (an exact field, so they agree to rounding).
#[test]
fn repeat_of_a_parametric_shape_is_the_union_of_its_copies() {
    let source = "param r = 0.2 in 0.2..0.95\nparam d = 0 in -1.5..1.5\nrepeat(spacing = (2, 0, 0)) { sphere(r) at (d, 0, 0) }";
    let scene = sdfc_compiler::check::compile(source).scene.expect("checks");
    let mut rng = Rng::new(7);
    let mut compared = 0;
    for (r, d) in [
        (0.95, 1.5),
        (0.95, -1.5),
        (0.6, 1.2),
        (0.2, -1.5),
        (0.9, 0.9),
    ] {
        let values = HashMap::from([("r".to_string(), vec![r]), ("d".to_string(), vec![d])]);
        let here = scene.with_values(&values);
        for _ in 0..2000 {
            let p = DVec3::new(
                rng.range(-4.0, 4.0),
                rng.range(-1.5, 1.5),
                rng.range(-1.5, 1.5),
            );
            let union = (-6..=6)
                .map(|k| (p - DVec3::new(f64::from(k) * 2.0 + d, 0.0, 0.0)).length() - r)
                .fold(f64::INFINITY, f64::min);
            let field = eval::distance(&here, p);
            assert!(
                (field - union).abs() < 1e-9,
                "at r = {r}, d = {d}, p = {p}: repeat gives {field}, the copies {union}"
            );
            compared += 1;
        }
    }
    assert_eq!(compared, 10_000);
}

/// Parametric scenes per CI run.
const PARAMETRIC: usize = 400;

/// A union of 5–16 random shapes scattered over a few units (exact and loose, bounded and not):
/// what a union's bounding-volume tree groups.
fn crowd_source(seed: u64) -> String {
    let mut r = Rng::new(seed);
    let n = 5 + r.below(12);
    let parts: Vec<String> = (0..n)
        .map(|_| {
            let s = if r.below(4) == 0 {
                shape(&mut r, 1)
            } else {
                let p = r.pick(PRIMITIVES);
                match p.name {
                    "mandelbulb" => "sphere(0.5)".to_string(),
                    _ => format!("{}({})", p.name, args(&mut r, p.name, p.params)),
                }
            };
            format!("  {s} at {}", vec3(&mut r, |r| r.range(-4.0, 4.0)))
        })
        .collect();
    format!("union {{\n{}\n}}\n", parts.join("\n"))
}

/// The bounding-volume tree of a union (`catalog::prune`) changes the work, not the field: at
/// random points near and far, the scene's field and material and each union's own field with
/// the trees equal (bit for bit: a skipped part can only be ≥ the minimum) those with every
/// child evaluated. A wrong
/// `exact` flag or a box that misses part of its surface fails here.
#[test]
fn bounding_volumes_leave_the_field_unchanged() {
    sdfc_tests::with_stack(|| {
        let scenes = sdfc_tests::env_number("SDFC_LIPSCHITZ_SCENES").unwrap_or(SCENES);
        let seed = sdfc_tests::fuzz_seed(0x05ee_db0b);
        let mut r = Rng::new(seed);
        let (mut trees, mut points) = (0, 0);
        for k in 0..scenes {
            let source = if k % 2 == 0 {
                crowd_source(r.bits())
            } else {
                scene_source(r.bits())
            };
            let Some(scene) = sdfc_compiler::check::compile(&source).scene else {
                continue;
            };
            let plain = scene.without_bounding_volumes();
            let with: Vec<NodeId> = scene
                .reachable()
                .into_iter()
                .filter(|&id| {
                    matches!(&scene.nodes[id].kind, NodeKind::Operator { ctx, .. } if ctx.prune.is_some())
                })
                .collect();
            trees += with.len();
            if with.is_empty() {
                continue;
            }
            for _ in 0..POINTS {
                let p = r.dir() * r.range(0.0, 12.0);
                points += 1;
                let (a, b) = (eval::distance(&scene, p), eval::distance(&plain, p));
                let (sa, sb) = (eval::sample(&scene, p), eval::sample(&plain, p));
                assert!(
                    a.to_bits() == b.to_bits() && sa == sb,
                    "at {p}: with the trees {a} ({sa:?}), without {b} ({sb:?})\n{source}"
                );
                // Each union with a tree on its own (an outer minimum could hide a wrong one).
                for &id in &with {
                    let (x, y) = (eval::node(&scene, id, p).d, eval::node(&plain, id, p).d);
                    assert!(
                        x.to_bits() == y.to_bits(),
                        "node {id} at {p}: with its tree {x}, without {y}\n{source}"
                    );
                }
            }
        }
        println!("{trees} unions with a tree; {points} points, the same field at each");
        assert!(trees >= 100, "only {trees} unions with a tree");
    });
}
