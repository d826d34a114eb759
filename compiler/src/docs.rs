//! Text generated from the catalog and the scene graph: the reference table and check summaries.

use crate::catalog::{MATH_FUNCTIONS, OPERATORS, PRIMITIVES};
use crate::check::signature;
use crate::scene::{Epsilon, Scene};
use std::fmt::Write;

/// The Markdown reference table of primitives, operators and math functions (in the README,
/// where a test checks it is current).
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
    for f in MATH_FUNCTIONS {
        let args: Vec<&str> = ["a", "b", "c"][..f.arity].to_vec();
        let _ = writeln!(
            s,
            "| function | `{}({})` | — | {} |",
            f.name,
            args.join(", "),
            cell(f.doc)
        );
    }
    s
}

/// The Markdown table of procedural texture patterns (in the README, where a test checks it
/// is current).
pub fn pattern_table() -> String {
    let mut s = String::from("| pattern | what it is |\n| --- | --- |\n");
    for (name, _, doc) in crate::texture::PATTERNS {
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
    format!(
        "{name}: ok\n  nodes: {reachable}\n  materials: {}\n  root λ: {}\n  bound: {bound}\n  lights: {}\n  tracer: {method} ({} steps, ε {eps})\n  warnings: {warnings}",
        scene.materials.len(),
        scene.root_node().lambda,
        scene.lights.len(),
        t.steps,
    )
}
