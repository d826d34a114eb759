//! Text generated from the catalog and the scene graph: the reference table and check summaries.

use crate::catalog::{MATH_FUNCTIONS, OPERATORS, PRIMITIVES};
use crate::check::signature;
use crate::scene::{Epsilon, Scene};
use std::fmt::Write;

/// The Markdown reference table of primitives, operators and math functions (in
/// docs/language.md, where a test checks it is current).
pub fn catalog_table() -> String {
    let mut s = String::new();
    s.push_str("| kind | signature | exact | what it is |\n| --- | --- | --- | --- |\n");
    for p in PRIMITIVES {
        let exact = if p.exact { "yes" } else { "bound" };
        let _ = writeln!(
            s,
            "| primitive | `{}` | {exact} | {} |",
            signature(p.name, p.params),
            cell(p.doc)
        );
    }
    let _ = writeln!(
        s,
        "| primitive | `implicit {{ expr }}` | bound | Any expression of x, y, z; λ inferred by interval arithmetic, or `@lipschitz(L)`. |"
    );
    for o in OPERATORS {
        let head = match o.params {
            [] => o.name.to_string(),
            ps => signature(o.name, ps),
        };
        let _ = writeln!(s, "| operator | `{head} {{ … }}` | — | {} |", cell(o.doc));
    }
    let functions = MATH_FUNCTIONS.iter().map(|f| (f.name, f.arity, f.doc));
    let derived = crate::catalog::DERIVED_FUNCTIONS
        .iter()
        .map(|f| (f.name, f.arity, f.doc));
    for (name, arity, doc) in functions.chain(derived) {
        let args: Vec<&str> = ["a", "b", "c"][..arity].to_vec();
        let _ = writeln!(
            s,
            "| function | `{name}({})` | — | {} |",
            args.join(", "),
            cell(doc)
        );
    }
    s
}

/// The Markdown table of procedural texture patterns (in docs/language.md, where a test
/// checks it is current).
pub fn pattern_table() -> String {
    let mut s = String::from("| pattern | what it is |\n| --- | --- |\n");
    for (name, _, doc) in crate::reference::texture::PATTERNS {
        let _ = writeln!(s, "| `{name}` | {} |", cell(doc));
    }
    s
}

/// A table cell: `|` escaped.
fn cell(text: &str) -> String {
    text.replace('|', "\\|")
}

/// The one-paragraph summary `sdfc check` prints for a good file.
pub fn summary(name: &str, scene: &Scene, warnings: usize) -> String {
    let reachable = scene.reachable().len();
    let t = &scene.trace;
    let eps = match t.epsilon {
        Epsilon::Pixel => "pixel".to_string(),
        Epsilon::Absolute(e) => format!("{e}"),
    };
    let method = crate::check::tracer::method_entry(t.method).0;
    let bound = scene.root_node().bound;
    let mut bound = if bound.radius.is_finite() {
        format!("radius {:.3}", bound.radius)
    } else {
        "unbounded".to_string()
    };
    if let Some(c) = &scene.bound {
        let shape = match c.shape {
            crate::scene::BoundShape::Sphere { center, radius } => {
                format!("sphere at {center} radius {radius:.3}")
            }
            crate::scene::BoundShape::Box { center, half } => {
                format!("box at {center} size {}", half * 2.0)
            }
        };
        let convex = if c.convex { ", convex object" } else { "" };
        bound += &format!("; rays clipped to a {shape}{convex}");
    }
    let mut text = format!(
        "{name}: ok\n  nodes: {reachable}\n  materials: {}\n  root λ: {}\n  bound: {bound}\n  lights: {}\n  tracer: {method} ({} steps, ε {eps})\n  warnings: {warnings}",
        scene.materials.len(),
        scene.root_node().lambda,
        scene.lights.len(),
        t.steps,
    );
    if !scene.params.is_empty() {
        text += "\n  parameters:";
        for p in &scene.params {
            text += &format!("\n    {}", describe_param(p));
        }
    }
    text
}

/// `r = 1 in 0.5..1.5 (number)`: a parameter as `sdfc check` lists it.
pub fn describe_param(p: &crate::scene::ParamDecl) -> String {
    use crate::scene::ParamKind;
    let n = p.kind.components();
    let show = |v: glam::DVec3| match p.kind {
        ParamKind::Angle => format!("{}deg", short(v.x.to_degrees())),
        _ if n == 1 => short(v.x),
        _ => format!("({}, {}, {})", short(v.x), short(v.y), short(v.z)),
    };
    let range = match p.range {
        Some((lo, hi)) => format!(" in {}..{}", show(lo), show(hi)),
        None => String::new(),
    };
    let set = if p.value != p.default {
        format!(" (set to {})", show(p.value))
    } else {
        String::new()
    };
    let builtin = if p.name == crate::check::TIME && p.span.start == p.span.end {
        ", built in"
    } else {
        ""
    };
    format!(
        "{} = {}{range}{set} ({}{builtin})",
        p.name,
        show(p.default),
        p.kind.name()
    )
}

/// A number printed with at most 6 decimals, trailing zeros dropped.
fn short(x: f64) -> String {
    let s = format!("{x:.6}");
    let s = s.trim_end_matches('0').trim_end_matches('.');
    if s == "-0" { "0".into() } else { s.into() }
}
