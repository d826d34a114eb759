//! The CPU evaluator against independently computed exact distances (tests/data/iq_reference.csv,
//! made by tests/data/iq_reference.py), hand-derived values, and the operators' definitions.

use glam::DVec3;
use sdfc_compiler::reference::eval;

fn at(source: &str, p: DVec3) -> f64 {
    eval::distance(&sdfc_tests::scene("inline", source), p)
}

#[test]
fn primitives_match_the_independent_reference() {
    let csv =
        std::fs::read_to_string(sdfc_tests::root().join("tests/data/iq_reference.csv")).unwrap();
    let mut rows = 0;
    let mut worst: f64 = 0.0;
    for line in csv.lines().skip(1) {
        let f: Vec<&str> = line.split(',').collect();
        let num = |i: usize| f[i].parse::<f64>().unwrap();
        let (a, b, c) = (f[1], f[2], f[3]);
        let call = match f[0] {
            "box" => format!("box(({a}, {b}, {c}))"),
            "rounded_box" => format!("rounded_box({a}, {b})"),
            "plane" => format!("plane(y, {a})"),
            "cone" => format!("cone({a}, {b}, {c})"),
            "round_cone" => format!("round_cone({a}, {b}, {c})"),
            "rounded_cylinder" => format!("rounded_cylinder({a}, {b}, {c})"),
            "link" => format!("link({a}, {b}, {c})"),
            name if !b.is_empty() => format!("{name}({a}, {b})"),
            name => format!("{name}({a})"),
        };
        let p = DVec3::new(num(4), num(5), num(6));
        let want = num(7);
        let got = at(&call, p);
        let tol = 1e-9 * (1.0 + want.abs());
        if f[8].contains("IQ sdTorus") {
            // Inside a spindle torus (minor > major) IQ's formula is a bound, not the distance.
            assert!(
                got <= 0.0 && got >= want - tol,
                "{call} at {p}: got {got}, want a bound of {want}"
            );
            rows += 1;
            continue;
        }
        assert!(
            (got - want).abs() <= tol,
            "{call} at {p}: got {got}, want {want} ({})",
            f[8]
        );
        worst = worst.max((got - want).abs() / (1.0 + want.abs()));
        rows += 1;
    }
    assert!(rows >= 100, "only {rows} reference rows");
    println!("{rows} reference rows, worst relative difference {worst:e}");
}

#[test]
fn hand_derived_values() {
    let cases: &[(&str, DVec3, f64)] = &[
        // A unit-size box: the corner (0.5, 0.5, 0.5) is at distance √3·0.5 from (1, 1, 1).
        ("box(1)", DVec3::ONE, 3f64.sqrt() * 0.5),
        ("box(1)", DVec3::ZERO, -0.5),
        ("box(0)", DVec3::new(0.0, 3.0, 4.0), 5.0),
        ("sphere(0)", DVec3::new(1e6, 0.0, 0.0), 1e6),
        ("sphere(2)", DVec3::ZERO, -2.0),
        // Torus, ring 1, tube 0.25: the centre is 1 − 0.25 from the tube surface.
        ("torus(1, 0.25)", DVec3::ZERO, 0.75),
        ("torus(1, 0.25)", DVec3::new(1e6, 0.0, 0.0), 1e6 - 1.25),
        ("capsule(0, 1)", DVec3::new(0.0, 2.0, 0.0), 1.0),
        ("plane(y, 0)", DVec3::new(5.0, -3.0, 1.0), -3.0),
        ("plane((0, 0, 2), 1)", DVec3::new(0.0, 0.0, 4.0), 3.0),
        ("cylinder(1, 2)", DVec3::new(2.0, 2.0, 0.0), 2f64.sqrt()),
        (
            "octahedron(1)",
            DVec3::new(1.0, 1.0, 1.0),
            2.0 / 3f64.sqrt(),
        ),
        ("ellipsoid((2, 2, 2))", DVec3::new(0.0, 5.0, 0.0), 3.0),
        // Generalised dodecahedron (max form): along a face normal the distance is exact.
        (
            "dodecahedron(1)",
            DVec3::new(0.0, 1.0, 1.618_033_988_749_895).normalize() * 3.0,
            2.0,
        ),
    ];
    for (src, p, want) in cases {
        let got = at(src, *p);
        assert!(
            (got - want).abs() < 1e-9 * (1.0 + want.abs()),
            "{src} at {p}: {got} vs {want}"
        );
    }
}

#[test]
fn operators_follow_their_definitions() {
    let p = DVec3::new(0.3, -0.2, 0.9);
    let a = at("sphere(1)", p);
    let b = at("box((1, 2, 0.5)) at (0.5, 0, 0)", p);
    let close = |x: f64, y: f64| (x - y).abs() < 1e-12;
    assert!(close(
        at("union { sphere(1) box((1, 2, 0.5)) at (0.5, 0, 0) }", p),
        a.min(b)
    ));
    assert!(close(
        at("intersect { sphere(1) box((1, 2, 0.5)) at (0.5, 0, 0) }", p),
        a.max(b)
    ));
    assert!(close(
        at("subtract { sphere(1) box((1, 2, 0.5)) at (0.5, 0, 0) }", p),
        a.max(-b)
    ));
    assert!(close(at("complement { sphere(1) }", p), -a));
    assert!(close(
        at("mix(0.25) { sphere(1) box((1, 2, 0.5)) at (0.5, 0, 0) }", p),
        0.75 * a + 0.25 * b
    ));
    assert!(close(at("sphere(1) |> round(0.5)", p), a - 0.5));
    assert!(close(at("sphere(1) |> onion(0.1)", p), a.abs() - 0.1));
    // Smooth union is at most the union and at least the union minus radius/4.
    let s = at(
        "smooth_union(0.4) { sphere(1) box((1, 2, 0.5)) at (0.5, 0, 0) }",
        p,
    );
    assert!(s <= a.min(b) && s >= a.min(b) - 0.1);
    // Uniform scale is exact: a sphere of radius 1 scaled by 3 is a sphere of radius 3.
    assert!(close(
        at("scale(3) { sphere(1) }", DVec3::new(0.0, 7.0, 0.0)),
        4.0
    ));
    // Rotation by 90° about y takes +x to −z.
    assert!(close(
        at(
            "box((2, 0.2, 0.2)) |> rotate(y, 90deg)",
            DVec3::new(0.0, 0.0, -1.0)
        ),
        0.0
    ));
    assert!(close(at("sphere(1) |> rotate(y, 360deg)", p), a));
    // Repetition: the copy at spacing 4 looks like the original.
    assert!(close(
        at(
            "sphere(1) |> repeat((4, 0, 0))",
            p + DVec3::new(8.0, 0.0, 0.0)
        ),
        a
    ));
    // A finite repetition of 3 copies stops after the third.
    let far = at(
        "sphere(1) |> repeat((4, 0, 0), (3, 1, 1))",
        DVec3::new(12.0, 0.0, 0.0),
    );
    assert!(close(far, 7.0));
    // Mirror in x: the point at −x sees the shape at +x.
    assert!(close(
        at(
            "sphere(1) at (2, 0, 0) |> mirror(x)",
            DVec3::new(-2.0, 0.0, 0.0)
        ),
        -1.0
    ));
    // Elongating a sphere by 2 along x makes a capsule-like shape: (2, 0, 0) is on the axis, 1 inside.
    assert!(close(
        at(
            "sphere(1) |> elongate((2, 0, 0))",
            DVec3::new(2.0, 0.0, 0.0)
        ),
        0.0
    ));
}

#[test]
fn annotation_divides_the_root_field() {
    let p = DVec3::new(0.0, 5.0, 0.0);
    assert!((at("sphere(1) @lipschitz(2)", p) - 2.0).abs() < 1e-12);
}

#[test]
fn implicit_bounds_are_inferred_or_refused() {
    let lambda = |src: &str| sdfc_tests::scene("inline", src).root_node().lambda;
    assert!((lambda("implicit { length(x, y, z) - 1 }") - 3f64.sqrt()).abs() < 1e-12);
    assert!((lambda("implicit { y + 0.5 * sin(x) }") - 1.25f64.sqrt()).abs() < 1e-12);
    assert!((lambda("implicit { 2 * x - 3 * z }") - 13f64.sqrt()).abs() < 1e-12);
    let refused = sdfc_compiler::check::compile("implicit { x * x - 1 }");
    assert!(refused.scene.is_none());
}

#[test]
fn materials_follow_csg() {
    let src = "material red { color #f00 }\nmaterial blue { color #00f }\n\
               union { sphere(1) : red  sphere(1) at (3, 0, 0) : blue }";
    let scene = sdfc_tests::scene("inline", src);
    assert_eq!(
        eval::sample(&scene, DVec3::new(-1.5, 0.0, 0.0)).mat,
        Some(0)
    );
    assert_eq!(eval::sample(&scene, DVec3::new(4.5, 0.0, 0.0)).mat, Some(1));
    // The inner material wins over the outer one; untagged parts take the outer one.
    let src = "material red { color #f00 }\nmaterial blue { color #00f }\n\
               union { box(1) : blue  sphere(0.1) at (5, 0, 0) } : red";
    let scene = sdfc_tests::scene("inline", src);
    assert_eq!(
        eval::sample(&scene, DVec3::new(-2.0, 0.0, 0.0)).mat,
        Some(1)
    );
    assert_eq!(eval::sample(&scene, DVec3::new(6.0, 0.0, 0.0)).mat, Some(0));
}

/// A fog without a colour takes the scene's background (whatever line declares it).
#[test]
fn fog_defaults_to_the_background() {
    let s = sdfc_tests::scene("f", "fog { density 0.5 }\nbackground #ff0000\nsphere(1)");
    let fog = s.fog.expect("a fog");
    assert_eq!(
        (fog.color, fog.density),
        (glam::DVec3::new(1.0, 0.0, 0.0), 0.5)
    );
    let s = sdfc_tests::scene("g", "fog { density 0.5  color #00ff00 }\nsphere(1)");
    assert_eq!(s.fog.unwrap().color, glam::DVec3::new(0.0, 1.0, 0.0));
    assert!(sdfc_tests::scene("h", "sphere(1)").fog.is_none());
}

/// A pattern follows its shape's transforms: the colour at a point of a marble ball equals the
/// colour at the same point of the ball turned and moved (`eval::surface` gives the point in
/// the ball's own coordinates; the material is given to the ball before it is turned).
#[test]
fn patterns_follow_their_shapes_transforms() {
    use glam::{DMat3, DVec3};
    let marble = "material m { color marble(#ffffff, #203040, 0.4, 5) }\n";
    let here = sdfc_tests::scene("here", &format!("{marble}sphere(1) : m"));
    let moved = sdfc_tests::scene(
        "moved",
        &format!("{marble}(sphere(1) : m) |> rotate(z, 40deg) |> translate((3, -1, 2))"),
    );
    let turn = DMat3::from_rotation_z(40f64.to_radians());
    for k in 0..200 {
        let a = k as f64 * 0.7;
        let p = DVec3::new(
            a.cos() * (a * 0.3).sin(),
            (a * 0.3).cos(),
            a.sin() * (a * 0.3).sin(),
        );
        let p = p.normalize();
        let q = turn * p + DVec3::new(3.0, -1.0, 2.0);
        let c1 = sdfc_compiler::reference::shading::albedo(&here, 1, p, p);
        let c2 = sdfc_compiler::reference::shading::albedo(&moved, 1, q, turn * p);
        assert!((c1 - c2).length() < 1e-9, "at {p}: {c1} against {c2}");
        // The point's material is the one `eval::sample` gives.
        let id = sdfc_compiler::reference::eval::sample(&moved, q)
            .mat
            .map_or(0, |m| m + 1);
        assert_eq!(sdfc_compiler::reference::eval::surface(&moved, q).0, id);
    }
    // And the pattern is not uniform (the comparison could not fail otherwise).
    let c = |p: DVec3| sdfc_compiler::reference::shading::albedo(&here, 1, p, p);
    assert!((c(DVec3::X) - c(DVec3::Z)).length() > 0.05);
}

/// Noise's lattice repeats every 65 536 cells, so that its integer coordinates never leave the
/// i32 range: far points give the same values as near ones, huge ones a value in [0, 1]
/// (before, `as i32` saturated and `+ 1` overflowed).
#[test]
fn noise_is_periodic_and_defined_everywhere() {
    use glam::DVec3;
    use sdfc_compiler::reference::texture::{LATTICE_PERIOD, noise};
    for k in 0..50 {
        let q = DVec3::new(k as f64 * 0.37, 1.3 - k as f64 * 0.11, k as f64 * 0.05);
        let far = q + DVec3::new(3.0, -7.0, 11.0) * LATTICE_PERIOD;
        assert!((noise(q) - noise(far)).abs() < 1e-6, "{q}");
    }
    for q in [
        DVec3::splat(1e12),
        DVec3::splat(-1e15),
        DVec3::new(3e9, -2e9, 7.5),
    ] {
        let v = noise(q);
        assert!((0.0..=1.0).contains(&v), "{q}: {v}");
    }
}

/// `repeat_polar` is the union of its copies: its field (own sector, window or every copy)
/// equals the smallest of the shape's field at the point turned back by each copy's angle, for
/// random shapes placed off the axis, across it and turned (so every plan is taken).
#[test]
fn polar_repeat_is_the_union_of_its_copies() {
    use sdfc_compiler::catalog::repeat::{self, PolarPlan};
    let shapes = [
        "sphere(0.3)",
        "box((0.4, 0.2, 0.1))",
        "torus(0.3, 0.08)",
        "cone(0.3, 0.5, 0.1)",
        "capsule(0.6, 0.1) |> rotate(x, 70deg)",
        "octahedron(0.4)",
    ];
    let mut rng = sdfc_tests::Rng::new(11);
    let mut plans = [0usize; 3];
    let mut compared = 0;
    for case in 0..120 {
        let shape = shapes[case % shapes.len()];
        let n = 1 + rng.below(12);
        let r = match case % 4 {
            0 => 0.0,
            _ => rng.range(0.1, 2.0),
        };
        let (y, z) = (rng.range(-0.5, 0.5), [0.0, rng.range(-0.4, 0.4)][case % 2]);
        let source = format!("repeat_polar({n}) {{ {shape} at ({r:.4}, {y:.4}, {z:.4}) }}");
        let scene = sdfc_compiler::check::compile(&source)
            .scene
            .unwrap_or_else(|| panic!("{source} checks"));
        let sdfc_compiler::scene::NodeKind::Operator { ctx, children, .. } =
            &scene.nodes[scene.root].kind
        else {
            panic!("{source}: the root is the operator");
        };
        plans[match repeat::polar_plan(ctx).1 {
            PolarPlan::Own => 0,
            PolarPlan::Window(_) => 1,
            PolarPlan::All => 2,
        }] += 1;
        let alpha = std::f64::consts::TAU / n as f64;
        for _ in 0..200 {
            let p = DVec3::new(
                rng.range(-3.0, 3.0),
                rng.range(-1.0, 1.0),
                rng.range(-3.0, 3.0),
            );
            let copies = (0..n)
                .map(|k| {
                    let (s, c) = (k as f64 * alpha).sin_cos();
                    let q = DVec3::new(p.x * c + p.z * s, p.y, -p.x * s + p.z * c);
                    eval::node(&scene, children[0], q).d
                })
                .fold(f64::INFINITY, f64::min);
            let field = eval::distance(&scene, p);
            assert!(
                (field - copies).abs() < 1e-9,
                "{source} at {p}: {field}, the copies {copies}"
            );
            compared += 1;
        }
    }
    assert!(plans.iter().all(|&k| k > 5), "plans taken: {plans:?}");
    assert_eq!(compared, 24_000);
}

/// Solids made of 2D shapes are the solids written directly (whose fields the independent
/// reference checks): extrusions of a rectangle and a circle are a box and a cylinder, a
/// revolved circle is a torus (a negative radius too) — equal everywhere; a revolved rectangle
/// touching the axis is a
/// cylinder — equal outside, and inside never farther from zero than the true distance (its
/// 2D distance counts the edge on the axis, which is inside the solid).
#[test]
fn extruded_and_revolved_shapes_are_exact() {
    let mut rng = sdfc_tests::Rng::new(17);
    let cases = [
        (
            "extrude(0.6) { rectangle(1.2, 0.8) }",
            "box((1.2, 0.8, 0.6))",
            true,
        ),
        (
            "extrude(1.4) { circle(0.5) }",
            "cylinder(0.5, 1.4) |> rotate(x, 90deg)",
            true,
        ),
        ("revolve(1.1) { circle(0.3) }", "torus(1.1, 0.3)", true),
        (
            "revolve(0) { rectangle(0.7, 1.5) at (0.35, 0, 0) }",
            "cylinder(0.7, 1.5)",
            false,
        ),
        (
            "revolve(-0.2) { circle(0.1) at (0.6, 0, 0) }",
            "torus(0.4, 0.1)",
            true,
        ),
    ];
    let mut compared = 0;
    for (made, direct, everywhere) in cases {
        let (a, b) = (
            sdfc_tests::scene("made", made),
            sdfc_tests::scene("direct", direct),
        );
        assert!(a.nodes[a.root].exact, "{made} is exact by its rules");
        for _ in 0..4000 {
            let p = DVec3::new(
                rng.range(-2.0, 2.0),
                rng.range(-1.5, 1.5),
                rng.range(-2.0, 2.0),
            );
            let (f, t) = (eval::distance(&a, p), eval::distance(&b, p));
            if everywhere || t >= 0.0 {
                assert!((f - t).abs() < 1e-12, "{made} at {p}: {f}, {direct} {t}");
            } else {
                assert!(
                    f <= 0.0 && f >= t - 1e-12,
                    "{made} at {p}: {f} inside, the distance {t}"
                );
            }
            compared += 1;
        }
    }
    assert_eq!(compared, 20_000);
}

/// Every primitive's bound holds its solid: at random arguments (degenerate ones included), no
/// point outside its box or sphere has a field ≤ 0. (The sampled region is the box grown by
/// its size; 2D shapes are extruded, the sampling then covering their box in x and y.)
#[test]
fn every_primitive_bound_holds_its_solid() {
    use sdfc_compiler::catalog::{PRIMITIVES, Ty};
    let mut rng = sdfc_tests::Rng::new(23);
    let mut checked = 0;
    for prim in PRIMITIVES {
        if prim.name == "mandelbulb" {
            continue; // an estimate of a fractal: its bound is its escape radius, tested apart
        }
        for _ in 0..12 {
            let args: Vec<String> = prim
                .params
                .iter()
                .map(|p| {
                    let len = |r: &mut sdfc_tests::Rng| *r.pick(&[0.0, 0.05, 0.3, 0.7, 1.0, 1.6]);
                    match p.ty {
                        Ty::Length => format!("{}", len(&mut rng)),
                        Ty::Positive => format!("{}", len(&mut rng) + 0.1),
                        Ty::Number => format!("{}", rng.range(-1.0, 1.0)),
                        Ty::Size => {
                            format!("({}, {}, {})", len(&mut rng), len(&mut rng), len(&mut rng))
                        }
                        Ty::WholeIn(lo, _) => format!("{}", lo as usize + rng.below(6)),
                        Ty::CountTo(_) | Ty::Count => format!("{}", 1 + rng.below(6)),
                        Ty::Axis => "(0.3, 1, -0.2)".to_string(),
                        _ => p.default.map_or("1".to_string(), |_| String::new()),
                    }
                })
                .collect();
            let named: Vec<String> = prim
                .params
                .iter()
                .zip(&args)
                .filter(|(_, a)| !a.is_empty())
                .map(|(p, a)| format!("{} = {a}", p.name))
                .collect();
            let mut source = format!("{}({})", prim.name, named.join(", "));
            let planar = prim.planar;
            if planar {
                source = format!("extrude(2) {{ {source} }}");
            }
            let Some(scene) = sdfc_compiler::check::compile(&source).scene else {
                continue;
            };
            let b = scene.nodes[scene.root].bound;
            if !(b.lo.is_finite() && b.hi.is_finite()) {
                continue; // the plane
            }
            let grow = (b.hi - b.lo).max(DVec3::splat(0.5));
            for _ in 0..3000 {
                let t = DVec3::new(rng.unit(), rng.unit(), rng.unit());
                let p = b.lo - grow + (b.hi - b.lo + 2.0 * grow) * t;
                let inside_box = (p.cmpge(b.lo - 1e-9) & p.cmple(b.hi + 1e-9)).all();
                let inside_sphere = (p - b.center).length() <= b.radius + 1e-9;
                if eval::distance(&scene, p) <= 0.0 {
                    assert!(
                        inside_box && inside_sphere,
                        "{source}: {p} is inside the solid, outside its bound {b:?}"
                    );
                }
                checked += 1;
            }
        }
    }
    assert!(checked > 300_000, "{checked}");
}
