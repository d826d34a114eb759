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

use crate::lipschitz_sampler::{
    POINTS, Sampling, Tally, args, promised_nodes, sample_node, scene_source, shape, vec3,
};
use glam::DVec3;
use sdfc_compiler::catalog::PRIMITIVES;
use sdfc_compiler::reference::eval;
use sdfc_compiler::scene::{NodeId, NodeKind};
use sdfc_tests::Rng;

/// Scenes per CI run (each contributes sampled points at every node).
const SCENES: usize = 760;

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
            for id in promised_nodes(&scene) {
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
        tally.assert_no_violations(5);
        assert!(tally.points >= 100_000, "only {} points", tally.points);
        // (The generator's sanity: most random scenes check. Some implicit bodies and twists of
        // unbounded shapes are refused by design; 79% were valid when repeat_polar joined.)
        assert!(
            valid * 4 >= scenes * 3,
            "too few valid scenes: {valid} of {scenes}"
        );
    });
}

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
                    _ if p.planar => {
                        let s = format!("{}({})", p.name, args(&mut r, p.name, p.params));
                        sdfc_tests::solid_of_2d(&mut r, s)
                    }
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

/// A random shape built to exercise the symmetry rules (`Primitive::mirror`/`swap` and the
/// operators' rules over them): shapes with and without square cross-sections, turned by whole
/// and fractional eighth turns about each axis, moved and scaled by vectors with and without
/// equal components, combined.
fn symmetric_source(r: &mut Rng, depth: usize) -> String {
    let len = |r: &mut Rng| format!("{:.3}", r.range(0.2, 1.2));
    let pair = |r: &mut Rng| {
        let (a, b) = (len(r), len(r));
        match r.below(4) {
            0 => format!("({a}, {a}, {b})"),
            1 => format!("({a}, {b}, {a})"),
            2 => format!("({b}, {a}, {a})"),
            _ => format!("({a}, {b}, {})", len(r)),
        }
    };
    let s = if depth == 0 || r.below(3) == 0 {
        match r.below(9) {
            0 => format!("box({})", pair(r)),
            1 => format!("rounded_box({}, 0.05)", pair(r)),
            2 => format!("ellipsoid({})", pair(r)),
            3 => format!("sphere({})", len(r)),
            4 => format!("cylinder({}, {})", len(r), len(r)),
            5 => format!("cone({}, {})", len(r), len(r)),
            6 => format!("torus({}, 0.1)", len(r)),
            7 => format!("octahedron({})", len(r)),
            _ => format!("capsule({}, 0.2)", len(r)),
        }
    } else {
        let a = symmetric_source(r, depth - 1);
        match r.below(4) {
            0 => format!("union {{ {a} {} }}", symmetric_source(r, depth - 1)),
            1 => format!(
                "smooth_union(0.1) {{ {a} {} }}",
                symmetric_source(r, depth - 1)
            ),
            2 => format!("round(0.05) {{ {a} }}"),
            _ => a,
        }
    };
    let axis = *r.pick(&["x", "y", "z"]);
    match r.below(6) {
        0 | 1 => format!("{s} |> rotate({axis}, {}deg)", 45 * r.below(9)),
        2 => format!("{s} |> rotate({axis}, {}deg)", r.below(360)),
        3 => format!("{s} at {}", pair(r)),
        4 => format!("{s} |> scale({})", pair(r)),
        _ => s,
    }
}

/// Every symmetry a node claims holds where sampled: f(p) = f(p reflected across a coordinate
/// plane) for each claimed `mirror` axis, and f(p) = f(p with the other two coordinates
/// exchanged) for each claimed `swap` axis. `repeat` and `repeat_polar` evaluate fewer copies
/// on the strength of these claims, so a false one is a wrong field there.
#[test]
fn every_claimed_symmetry_holds_where_sampled() {
    sdfc_tests::with_stack(|| {
        let seed = sdfc_tests::fuzz_seed(0x5e_3e77);
        let mut r = Rng::new(seed);
        let (mut claims, mut eighths) = ([0usize; 2], 0);
        for k in 0..1_200 {
            let source = if k % 3 == 0 {
                scene_source(r.bits())
            } else {
                symmetric_source(&mut r, 1 + k % 3)
            };
            let Some(scene) = sdfc_compiler::check::compile(&source).scene else {
                continue;
            };
            for id in scene.reachable() {
                let n = &scene.nodes[id];
                if let NodeKind::Operator { op, ctx, children } = &n.kind
                    && op.name == "rotate"
                    && (ctx.num(1) / std::f64::consts::FRAC_PI_4).fract().abs() < 1e-9
                    && (ctx.num(1) / std::f64::consts::FRAC_PI_2).fract().abs() > 1e-9
                    && n.mirror != scene.nodes[children[0]].mirror
                {
                    eighths += 1;
                }
                for _ in 0..16 {
                    let p = DVec3::new(r.range(-2.5, 2.5), r.range(-2.5, 2.5), r.range(-2.5, 2.5));
                    let f = eval::node(&scene, id, p).d;
                    let same = |q: DVec3| {
                        let g = eval::node(&scene, id, q).d;
                        (f - g).abs() <= 1e-9 * (1.0 + f.abs()) || (f.is_nan() && g.is_nan())
                    };
                    for i in 0..3 {
                        let (j, l) = ((i + 1) % 3, (i + 2) % 3);
                        if n.mirror[i] {
                            let mut q = p;
                            q[i] = -q[i];
                            claims[0] += 1;
                            assert!(same(q), "node {id} mirror {i} at {p}\n{source}");
                        }
                        if n.swap[i] {
                            let mut q = p;
                            q[j] = p[l];
                            q[l] = p[j];
                            claims[1] += 1;
                            assert!(same(q), "node {id} swap {i} at {p}\n{source}");
                        }
                    }
                }
            }
        }
        println!(
            "{} mirror and {} swap claims held; {eighths} eighth turns kept a mirror",
            claims[0], claims[1]
        );
        assert!(
            claims[1] >= 10_000 && eighths >= 50,
            "{claims:?}, {eighths}"
        );
    });
}

/// Copies of one shape written out on a lattice in a union (`check::lattice`) become one
/// `repeat` of it: the same field (to rounding of the offsets) and the same materials as the
/// copies written so that they cannot be grouped (each moved once more by zero), for random
/// shapes on random lattices, some with a copy missing. A copy moved off the lattice keeps the
/// group apart; one with a material or an annotation of its own stays a part of its own.
#[test]
fn lattices_of_copies_leave_the_field_unchanged() {
    sdfc_tests::with_stack(|| {
        let mut r = Rng::new(sdfc_tests::fuzz_seed(0x1a77_1ce5));
        let (mut grouped, mut kept, mut points) = (0, 0, 0);
        // The parts of the scene's union.
        let parts = |scene: &sdfc_compiler::scene::Scene| scene.nodes[scene.root].children().len();
        for case in 0..300 {
            let body = if case % 3 != 0 {
                symmetric_source(&mut r, 1)
            } else {
                shape(&mut r, 1)
            };
            let body = match r.below(3) {
                0 => format!("({body}) : a"),
                1 => format!("union {{ ({body}) : a  sphere(0.2) : b }}"),
                _ => body,
            };
            let n = [2 + r.below(3), 1 + r.below(2), 1 + r.below(3)];
            let s = DVec3::new(r.range(1.0, 4.0), r.range(1.0, 4.0), r.range(1.0, 4.0));
            let first = DVec3::new(r.range(-3.0, 3.0), r.range(-1.0, 1.0), r.range(-3.0, 3.0));
            let mut at: Vec<DVec3> = Vec::new();
            for k in 0..n[0] * n[1] * n[2] {
                let k = DVec3::new(
                    (k % n[0]) as f64,
                    ((k / n[0]) % n[1]) as f64,
                    (k / (n[0] * n[1])) as f64,
                );
                at.push(first + k * s);
            }
            let spoil = if case % 2 == 0 { 1 + r.below(4) } else { 0 };
            let mut tag = vec![""; at.len()];
            match spoil {
                1 => {
                    at.remove(r.below(at.len()));
                }
                2 => {
                    let k = r.below(at.len());
                    at[k].x += 0.01;
                }
                3 => tag[r.below(at.len())] = " : b",
                4 => tag[r.below(at.len())] = " @lipschitz(3)",
                _ => {}
            }
            let copies = |zero: &str| {
                at.iter()
                    .zip(&tag)
                    .map(|(p, t)| format!("  ({body}) at ({}, {}, {}){zero}{t}", p.x, p.y, p.z))
                    .collect::<Vec<_>>()
                    .join("\n")
            };
            let head = "material a { color #f00 }\nmaterial b { color #0f0 }\n";
            let source = format!(
                "{head}union {{\n{}\n  box(0.3) at (0, 9, 0)\n}}\n",
                copies("")
            );
            let apart = format!(
                "{head}union {{\n{}\n  box(0.3) at (0, 9, 0)\n}}\n",
                copies(" at (0, 0, 0)")
            );
            let (Some(scene), Some(plain)) = (
                sdfc_compiler::check::compile(&source).scene,
                sdfc_compiler::check::compile(&apart).scene,
            ) else {
                continue;
            };
            assert_eq!(parts(&plain), at.len() + 1, "{apart}");
            let tries = if parts(&scene) < parts(&plain) {
                // A copy off the lattice spoils the whole group. Without an end copy, or with an
                // end copy tagged or annotated (which stays a part of its own), the rest may
                // still fill a lattice: the field tells.
                assert!(spoil != 2, "a copy off the lattice was grouped\n{source}");
                assert!(
                    spoil < 3 || parts(&scene) >= 3,
                    "a tagged or annotated copy was grouped\n{source}"
                );
                grouped += 1;
                200
            } else {
                kept += 1;
                10
            };
            for _ in 0..tries {
                let p = DVec3::new(r.range(-6.0, 12.0), r.range(-2.0, 5.0), r.range(-6.0, 12.0));
                let (a, b) = (eval::sample(&scene, p), eval::sample(&plain, p));
                assert!(
                    (a.d - b.d).abs() <= 1e-9 * (1.0 + a.d.abs()) && a.mat == b.mat,
                    "at {p}: grouped {a:?}, written out {b:?}\n{source}"
                );
                points += 1;
            }
        }
        println!(
            "{grouped} unions grouped, {kept} kept as written; {points} points, the same field"
        );
        assert!(
            grouped >= 30 && kept >= 100,
            "{grouped} grouped, {kept} kept"
        );
    });
}

/// A tag the lowering takes as one constant (`lower::constant_materials`,
/// `constant_looseness`: the material or tag function then calls the part's field, or returns
/// the constant without walking) is that constant at every sampled point of the CPU walk:
/// random shapes in materials `a`, `b` or none, nested so that inner materials win and smooth
/// blends make parts loose.
#[test]
fn constant_tags_hold_where_sampled() {
    sdfc_tests::with_stack(|| {
        let seed = sdfc_tests::fuzz_seed(0x7a65_c0de);
        let mut r = Rng::new(seed);
        let (mut claims, mut varying, mut points) = (0, 0, 0);
        let tags = [""; 2]
            .into_iter()
            .chain([" : a", " : b"])
            .collect::<Vec<_>>();
        for _ in 0..200 {
            let part = |r: &mut Rng| {
                let depth = 1 + r.below(2);
                let s = shape(r, depth);
                let s = if r.below(3) == 0 {
                    let op = r.pick(&["union", "smooth_union(0.3)", "intersect", "subtract"]);
                    let t = *r.pick(&tags);
                    let other = shape(r, 1);
                    format!("{op} {{ ({s}){t}  ({other}){} }}", r.pick(&tags))
                } else {
                    s
                };
                format!("({s}){}", r.pick(&tags))
            };
            let parts: Vec<String> = (0..1 + r.below(4)).map(|_| part(&mut r)).collect();
            let op = r.pick(&["union", "smooth_union(0.2)", "intersect"]);
            let head = "material a { color #f00 }\nmaterial b { color #0f0 }\n";
            let source = format!("{head}{op} {{\n  {}\n}}\n", parts.join("\n  "));
            let Some(scene) = sdfc_compiler::check::compile(&source).scene else {
                continue;
            };
            let materials = sdfc_compiler::lower::constant_materials(&scene);
            let loose = sdfc_compiler::lower::constant_looseness(&scene);
            for id in scene.reachable() {
                let Some(c) = materials[id] else {
                    varying += 1;
                    continue;
                };
                claims += 1;
                for _ in 0..20 {
                    let p = r.dir() * r.range(0.0, 4.0);
                    points += 1;
                    let got = eval::node(&scene, id, p).mat.map_or(0, |m| m + 1);
                    assert_eq!(
                        got, c,
                        "node {id} at {p}: material {got}, taken as {c}\n{source}"
                    );
                }
            }
            if let Some(c) = loose[scene.root] {
                claims += 1;
                for _ in 0..20 {
                    let p = r.dir() * r.range(0.0, 4.0);
                    points += 1;
                    let got = u32::from(eval::loose(&scene, p));
                    assert_eq!(got, c, "at {p}: loose {got}, taken as {c}\n{source}");
                }
            }
        }
        println!("{claims} constant tags, {varying} varying materials; {points} points");
        assert!(
            claims >= 500 && varying >= 100,
            "{claims} claims, {varying} varying"
        );
    });
}
