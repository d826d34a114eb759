//! Random scenes from the catalog for the fuzzers: the front end's (`fuzz_scenes.rs`) and the
//! renders' (`runtime/tests/fuzz_render.rs`).

use crate::Rng;
use sdfc_compiler::catalog::{PRIMITIVES, Param, Ty};

/// A magnitude: mostly ordinary, sometimes tiny or huge, and one time in 40 beyond what f32
/// holds or near its edges (the checker must refuse those with a span, never pass them on).
fn magnitude(r: &mut Rng) -> f64 {
    if r.below(40) == 0 {
        return *r.pick(&[1e-45, 1e-30, 1e-19, 1e18, 1e19, 1e39, 1e300]);
    }
    *r.pick(&[
        0.0, 1e-4, 0.01, 0.1, 0.3, 0.5, 1.0, 1.5, 2.0, 7.0, 100.0, 1e4,
    ])
}

fn number(r: &mut Rng, ty: Ty) -> String {
    let m = magnitude(r);
    match ty {
        Ty::Number => format!("{}", if r.below(2) == 0 { m } else { -m }),
        Ty::Length => format!("{m}"),
        Ty::Positive | Ty::Scale => format!("{}", if m == 0.0 { 0.5 } else { m }),
        Ty::Fraction => format!("{}", *r.pick(&[0.0, 0.25, 0.5, 1.0])),
        Ty::Angle => format!("{}deg", *r.pick(&[0.0, 30.0, 90.0, 360.0, -45.0, 720.0])),
        Ty::Count => format!("{}", 1 + r.below(6)),
        Ty::CountTo(n) => format!("{}", 1 + r.below(n.min(8) as usize)),
        Ty::WholeIn(lo, hi) => format!("{}", lo as usize + r.below((hi - lo).min(8) as usize + 1)),
        Ty::UpTo(n) => format!("{}", r.below(n.min(8) as usize + 1)),
        Ty::ZeroOrAtLeast(lo) => format!("{}", if r.below(2) == 0 { 0.0 } else { lo.max(m) }),
        Ty::Range(lo, hi) => format!("{}", lo + (hi - lo) * 0.5 * r.below(2) as f64),
        _ => format!("{m}"),
    }
}

fn value(r: &mut Rng, ty: Ty) -> String {
    match ty {
        Ty::Vec3 | Ty::Size | Ty::Scale | Ty::Counts if r.below(2) == 0 => {
            let inner = match ty {
                Ty::Vec3 => Ty::Number,
                Ty::Size => Ty::Length,
                Ty::Counts => Ty::UpTo(3),
                _ => Ty::Positive,
            };
            let c: Vec<String> = (0..3).map(|_| number(r, inner)).collect();
            format!("({})", c.join(", "))
        }
        Ty::Vec3 => format!(
            "({}, {}, {})",
            number(r, Ty::Number),
            number(r, Ty::Number),
            number(r, Ty::Number)
        ),
        Ty::Size => number(r, Ty::Length),
        Ty::Counts => number(r, Ty::UpTo(3)),
        Ty::Axis => r.pick(&["x", "y", "z", "(1, 1, 0)", "-y"]).to_string(),
        Ty::Color => r.pick(&["#f80", "#102030", "(0.2, 0.4, 0.6)"]).to_string(),
        Ty::PositiveOr(words) | Ty::Word(words) if r.below(2) == 0 => r.pick(words).to_string(),
        Ty::Word(words) => r.pick(words).to_string(),
        t => number(r, t),
    }
}

fn args(r: &mut Rng, params: &[Param]) -> String {
    let mut out = Vec::new();
    for p in params {
        // Optional parameters are given half of the time, by name — but a bake's `res` always
        // (7…15): its default 64 around a costly random shape is up to a minute of CPU
        // sampling (`bake::MAX_WORK`), which made one CI seed's fuzzer take 4.6 minutes.
        if p.default.is_some() && p.name != "res" && r.below(2) == 0 {
            continue;
        }
        out.push(format!("{} = {}", p.name, value(r, p.ty)));
    }
    out.join(", ")
}

fn shape(r: &mut Rng, depth: usize) -> String {
    if depth == 0 || r.below(3) == 0 {
        let p = r.pick(PRIMITIVES);
        let s = format!("{}({})", p.name, args(r, p.params));
        let s = if p.planar {
            crate::solid_of_2d(r, s)
        } else {
            s
        };
        return match r.below(4) {
            0 => format!(
                "{s} at ({}, {}, {})",
                number(r, Ty::Number),
                number(r, Ty::Number),
                number(r, Ty::Number)
            ),
            _ => s,
        };
    }
    crate::operator_block(r, |r, op| args(r, op.params), |r| shape(r, depth - 1))
}

/// A random scene (its text) from `seed`: a tracer, shapes of every primitive and operator
/// nested up to four deep with ordinary and extreme arguments, sometimes shared through `let`s
/// or functions. About two in three check.
pub fn scene(seed: u64) -> String {
    // Xorshift needs a non-zero state.
    let mut r = Rng::new(seed);
    let tracer = r
        .pick(&["basic", "relaxed", "enhanced", "hybrid", "auto"])
        .to_string();
    let depth = 1 + r.below(4);
    // One scene in four shares a shape through `let`s, each level using the one before twice
    // (2^levels evaluations: past 13 levels the checker refuses the cost).
    let (lets, body) = if r.below(4) == 0 {
        let levels = 1 + r.below(15);
        let mut lets = format!("let s0 = {}\n", shape(&mut r, depth.min(2)));
        for k in 1..=levels {
            lets += &format!(
                "let s{k} = union {{ s{}  s{} at ({}, 0, 0) }}\n",
                k - 1,
                k - 1,
                number(&mut r, Ty::Number)
            );
        }
        (lets, format!("s{levels}"))
    } else if r.below(3) == 0 {
        // Functions: the shape as a body, called through others (a shape argument, a
        // default and a named argument), and the standard library's.
        let defs = format!(
            "import \"std/gears.sdf\"\nfn body() = {}\nfn pair(s: shape, d = 1.5) = union {{ s  s at (d, 0, 0) }}\nfn ring(s: shape, n) = repeat_polar(n) {{ s at ({}, 0, 0) }}\n",
            shape(&mut r, depth),
            number(&mut r, Ty::Length)
        );
        let call = match r.below(3) {
            0 => format!("pair(body(), d = {})", number(&mut r, Ty::Number)),
            1 => format!("ring(pair(body()), {})", 1 + r.below(9)),
            _ => format!(
                "union {{ body()  gear(teeth = {}, radius = {}) }}",
                1 + r.below(40),
                number(&mut r, Ty::Positive)
            ),
        };
        (defs, call)
    } else {
        (String::new(), shape(&mut r, depth))
    };
    format!(
        "camera {{ eye (0, 2, -6) target (0, 0, 0) }}\ntrace {tracer} {{ steps 64 }}\n{lets}{body}\n"
    )
}
