//! The Lipschitz promise, case by case: each `implicit` domain error, branch cut and huge
//! argument of the audit; the innermost material tag; the annotation corpus
//! (`tests/lipschitz/`) against the annotation check; the exact box a scale makes; which unions
//! the shader tests bounding boxes in.

use glam::DVec3;
use sdfc_compiler::reference::eval;
use std::collections::BTreeMap;

/// Each `implicit` case of the Lipschitz audit: an error with a span, or a bound that holds;
/// never a hang (the periodic interval search past 2⁵³) and never a NaN field.
#[test]
fn implicit_domains_branch_cuts_and_huge_arguments() {
    let refused = [
        (
            "implicit { sqrt(x) - 1 } @lipschitz(10)",
            "not defined everywhere",
        ),
        (
            "implicit { log(-1 - y^2) + length(x, y, z) } @lipschitz(10)",
            "not defined everywhere",
        ),
        (
            "implicit { log(x) + length(x, y, z) } @lipschitz(10)",
            "not defined everywhere",
        ),
        (
            "implicit { x ^ 1.5 + length(x, y, z) - 1 } @lipschitz(10)",
            "not defined everywhere",
        ),
        (
            "implicit { length(x, y, z) - 1 + 0.1 * atan2(y, -1 - x^2) }",
            "jumps by 2π",
        ),
    ];
    for (source, message) in refused {
        let checked = sdfc_compiler::check::compile(source);
        assert!(checked.scene.is_none(), "accepted: {source}");
        let text = sdfc_compiler::diag::render(&checked.diagnostics, "t.sdf", source);
        assert!(text.contains(message), "{source}:\n{text}");
        assert!(text.contains("t.sdf:1:"), "no location:\n{text}");
    }
    // Whole powers of negative bases are defined (multiplied out, on the GPU too), and a square
    // under a root is known to be ≥ 0.
    for source in [
        "implicit { length(x, y, z) - 1 + 0.001 * x ^ 17 } @lipschitz(1e9)",
        "implicit { sqrt(x * x + z * z) - 1 } @lipschitz(1)",
        "implicit { log(1 + y^2) + length(x, y, z) - 1 } @lipschitz(3)",
    ] {
        let scene = sdfc_tests::scene(source, source);
        let d = eval::distance(&scene, DVec3::new(-1.3, 0.4, 0.2));
        assert!(d.is_finite(), "{source}: {d}");
    }
    // Arguments past f64's integer resolution: the interval of cos is [-1, 1] at once.
    let (done, wait) = std::sync::mpsc::channel();
    std::thread::spawn(move || {
        // (1e300 is beyond f32: an error of its own, but it must not hang either.)
        for (big, fits) in [("1e17", true), ("3e16", true), ("1e300", false)] {
            let source =
                format!("implicit {{ length(x, y, z) - 1 + 0.1 * cos({big} + 0.1 * sin(x)) }}");
            let checked = sdfc_compiler::check::compile(&source);
            assert_eq!(checked.scene.is_some(), fits, "{source}");
        }
        done.send(()).unwrap();
    });
    wait.recv_timeout(std::time::Duration::from_secs(20))
        .expect("checking cos of a huge argument finishes (it hung before)");
}

/// A tag on a shape that already has a material does not replace it (the innermost wins, as
/// the README says), and says so.
#[test]
fn the_innermost_material_tag_wins() {
    let source = "material red { color #c00 }\nmaterial blue { color #00c }\n(sphere(0.7) : red) : blue\nbox(0.3) : blue at (2, 0, 0)";
    let checked = sdfc_compiler::check::compile(source);
    let scene = checked.scene.expect("compiles");
    let red = scene
        .materials
        .iter()
        .position(|m| m.name == "red")
        .unwrap() as u32;
    let blue = scene
        .materials
        .iter()
        .position(|m| m.name == "blue")
        .unwrap() as u32;
    assert_eq!(
        eval::sample(&scene, DVec3::new(0.0, 0.0, -0.9)).mat,
        Some(red)
    );
    assert_eq!(
        eval::sample(&scene, DVec3::new(2.0, 0.0, -0.4)).mat,
        Some(blue)
    );
    assert!(
        checked
            .diagnostics
            .iter()
            .any(|d| d.message.contains("no effect"))
    );
}

/// The annotation corpus (`tests/lipschitz/`, its README says how each constant was derived):
/// every too-small annotation is caught by the thorough check with a warning located at the
/// annotated shape, no correct one is flagged, and neither is any example. The quick check that
/// `render` and `emit` run is reported (and must catch most).
#[test]
fn the_annotation_check_finds_planted_errors_and_only_those() {
    use sdfc_compiler::lipschitz::{Effort, Values, verify_annotations, verify_over_ranges};
    let dir = sdfc_tests::root().join("tests/lipschitz");
    let mut tally: BTreeMap<(&str, &str), usize> = BTreeMap::new();
    // Per (corpus, class): files, flagged by the quick check, by the thorough one.
    let mut classes: BTreeMap<(&str, String), [usize; 3]> = BTreeMap::new();
    let mut missed = Vec::new();
    for kind in ["wrong", "right"] {
        let mut files: Vec<_> = std::fs::read_dir(dir.join(kind))
            .expect("corpus folder")
            .map(|e| e.expect("entry").path())
            .filter(|p| p.extension().is_some_and(|e| e == "sdf"))
            .collect();
        files.sort();
        for path in files {
            let source = std::fs::read_to_string(&path).expect("read");
            let expect = source.lines().next().unwrap_or_default();
            assert_eq!(expect, format!("// expect: {kind}"), "{}", path.display());
            let scene = sdfc_tests::scene(&path.display().to_string(), &source);
            let annotated_line = source
                .lines()
                .position(|l| l.contains("@lipschitz") && !l.trim_start().starts_with("//"))
                .expect("an annotation");
            let class = source
                .lines()
                .find_map(|l| l.strip_prefix("// class: "))
                .and_then(|c| c.split_whitespace().next())
                .unwrap_or("?")
                .to_string();
            let at = |v: &Values| sdfc_compiler::check::compile_with(&source, v).scene;
            for (effort, name) in [(Effort::Fast, "quick"), (Effort::Thorough, "thorough")] {
                let mut found = verify_annotations(&scene, effort);
                let more = verify_over_ranges(&at, &scene, effort, (&Values::new(), &found));
                found.extend(more);
                found.retain(|d| d.message.contains("too small"));
                for d in &found {
                    let line = source[..d.span.start].matches('\n').count();
                    assert!(
                        line <= annotated_line,
                        "{}: the warning is on line {} but the annotation on {}",
                        path.display(),
                        line + 1,
                        annotated_line + 1
                    );
                }
                let flagged = !found.is_empty();
                *tally.entry((kind, name)).or_default() += usize::from(flagged);
                let row = classes.entry((kind, class.clone())).or_default();
                row[0] += usize::from(name == "quick");
                row[1 + usize::from(name == "thorough")] += usize::from(flagged);
                if kind == "wrong" && name == "thorough" && !flagged {
                    missed.push(path.display().to_string());
                }
                assert!(
                    kind == "wrong" || !flagged,
                    "{} ({name}): a correct annotation was flagged: {}",
                    path.display(),
                    found[0].label
                );
            }
        }
    }
    println!("flagged per (corpus, check): {tally:?}");
    println!("corpus | class | files | quick | thorough");
    for ((kind, class), [n, quick, thorough]) in &classes {
        println!("{kind} | {class} | {n} | {quick} | {thorough}");
    }
    assert!(missed.is_empty(), "the thorough check missed {missed:?}");
    assert!(
        tally[&("wrong", "thorough")] >= 30,
        "the corpus has at least 30 planted errors"
    );
    assert!(
        tally[&("wrong", "quick")] * 10 >= tally[&("wrong", "thorough")] * 9,
        "the quick check catches too few"
    );
    for path in sdfc_tests::examples() {
        let scene = sdfc_tests::example(&path);
        let source = std::fs::read_to_string(&path).expect("read");
        let at = |v: &Values| sdfc_compiler::check::compile_with(&source, v).scene;
        let mut flags = verify_annotations(&scene, Effort::Thorough);
        flags.extend(verify_over_ranges(
            &at,
            &scene,
            Effort::Thorough,
            (&Values::new(), &[]),
        ));
        assert!(flags.is_empty(), "{}: {}", path.display(), flags[0].message);
    }
}

/// A non-uniform scale of a box, through a move and a turn about a coordinate axis whose other
/// two factors are equal, is taken into the box's size (`catalog::absorb`): the field is the
/// exact distance, computed here from the box with scaled sizes turned and moved (a turn by θ
/// about axis k maps p to the point turned by −θ, right-handed). Where the other two factors
/// differ, the scale stays (a bound, not exact); so does it for a cylinder scaled unlike in x
/// and z.
#[test]
fn a_scaled_box_is_the_box_with_scaled_sizes() {
    let mut r = sdfc_tests::Rng::new(0x00ab_504b);
    let hundredths =
        |r: &mut sdfc_tests::Rng, lo: usize, n: usize| (lo + r.below(n)) as f64 / 100.0;
    let (mut absorbed, mut kept, mut worst) = (0, 0, 0.0f64);
    for case in 0..400 {
        let k = r.below(3);
        let s = DVec3::new(
            hundredths(&mut r, 20, 200),
            hundredths(&mut r, 20, 200),
            hundredths(&mut r, 20, 200),
        );
        let theta = r.below(360) as f64;
        let mut v = DVec3::splat(hundredths(&mut r, 30, 300));
        v[k] = hundredths(&mut r, 30, 300);
        let spoil = case % 4 == 0;
        if spoil {
            v[(k + 1) % 3] += 0.25;
        }
        let t = DVec3::new(
            hundredths(&mut r, 0, 200) - 1.0,
            hundredths(&mut r, 0, 200) - 1.0,
            hundredths(&mut r, 0, 200) - 1.0,
        );
        let source = format!(
            "box(({}, {}, {})) |> rotate({}, {theta}deg) at ({}, {}, {}) |> scale(({}, {}, {}))",
            s.x,
            s.y,
            s.z,
            ["x", "y", "z"][k],
            t.x,
            t.y,
            t.z,
            v.x,
            v.y,
            v.z
        );
        let scene = sdfc_tests::scene("inline", &source);
        let exact = scene.root_node().exact;
        if spoil && theta % 90.0 != 0.0 {
            assert!(!exact, "{source}: taken as exact");
            kept += 1;
            continue;
        }
        if spoil {
            continue;
        }
        assert!(
            exact && scene.root_node().lambda == 1.0,
            "{source}: not taken into the box"
        );
        absorbed += 1;
        let (sin, cos) = (-theta.to_radians()).sin_cos();
        let half = s * v / 2.0;
        for _ in 0..50 {
            let p = DVec3::new(r.range(-4.0, 4.0), r.range(-4.0, 4.0), r.range(-4.0, 4.0));
            // Into the box's frame: undo the move (t·v), then the turn.
            let q = p - t * v;
            let (i, j) = ((k + 1) % 3, (k + 2) % 3);
            let mut local = q;
            local[i] = cos * q[i] - sin * q[j];
            local[j] = sin * q[i] + cos * q[j];
            let d = local.abs() - half;
            let want = d.max(DVec3::ZERO).length() + d.max_element().min(0.0);
            let got = eval::distance(&scene, p);
            worst = worst.max((got - want).abs());
            assert!(
                (got - want).abs() < 1e-9,
                "{source} at {p}: {got}, want {want}"
            );
        }
    }
    let cylinder =
        |v: &str| sdfc_tests::scene("inline", &format!("cylinder(0.5, 1) |> scale({v})"));
    assert!(cylinder("(2, 3, 2)").root_node().exact);
    assert!(!cylinder("(2, 3, 1)").root_node().exact);
    println!("{absorbed} scales taken into the box (worst difference {worst:.1e}), {kept} kept");
    assert!(
        absorbed >= 250 && kept >= 80,
        "{absorbed} absorbed, {kept} kept"
    );
}

/// A scale read from a `param` is taken into the box as a constant one is, so the parameter
/// does not change the shape: `round`, a smooth blend or `onion` over the scaled box (which
/// read its field off the surface) give the same field with the factor written as a number and
/// as a parameter at that value — at the default and at another value set by the host.
#[test]
fn a_scale_read_from_a_param_is_taken_in_alike() {
    let bodies = [
        "round(0.3) { box(1) |> scale((F, 1, 1)) }",
        "smooth_union(0.4) { box((1, 2, 0.5)) |> rotate(x, 30deg) at (0.2, 0, 0) |> scale((F, 2, 2))  sphere(0.6) at (1, 0, 0) }",
        "onion(0.1) { cylinder(0.5, 1) |> scale((F, 1.5, F)) }",
    ];
    let mut r = sdfc_tests::Rng::new(0x5ca1_e0ff);
    for body in bodies {
        for k in [3.0, 1.7] {
            let written = sdfc_tests::scene("inline", &body.replace('F', &k.to_string()));
            let source = format!("param k = 3 in 1..4\n{}", body.replace('F', "k"));
            let values = std::collections::HashMap::from([("k".to_string(), vec![k])]);
            let param = sdfc_compiler::check::compile_with(&source, &values)
                .scene
                .unwrap_or_else(|| panic!("{source}"));
            assert!(
                param.root_node().lambda == written.root_node().lambda,
                "{source}"
            );
            same_field(&written, &param, &mut r, &format!("{source} at k = {k}"));
            let options = sdfc_compiler::lower::tracer::Options::from_scene(&param);
            sdfc_compiler::emit::module(&param, sdfc_compiler::lower::Entry::Compute, &options)
                .unwrap_or_else(|e| panic!("{source}: {}", e.0));
        }
    }
}

/// A uniform scale of a box is taken in too, through turns about any axis: one node fewer, and
/// an outer non-uniform scale then reaches the box. Each scene's field equals the box written
/// with its sizes.
#[test]
fn a_uniform_scale_is_taken_in_and_lets_an_outer_one_through() {
    let pairs = [
        (
            "scale(2) { box(1) |> rotate((1, 1, 0), 30deg) }",
            "box(2) |> rotate((1, 1, 0), 30deg)",
        ),
        ("scale((2, 1, 1)) { scale(2) { box(1) } }", "box((4, 2, 2))"),
        (
            "scale(0.5) { box((1, 2, 3)) at (1, 0, 0) }",
            "box((0.5, 1, 1.5)) at (0.5, 0, 0)",
        ),
    ];
    let mut r = sdfc_tests::Rng::new(0x0a11_5ca1);
    for (scaled, written) in pairs {
        let (a, b) = (
            sdfc_tests::scene("inline", scaled),
            sdfc_tests::scene("inline", written),
        );
        assert_eq!(a.reachable().len(), b.reachable().len(), "{scaled}: nodes");
        assert!(a.root_node().exact, "{scaled}: not exact");
        same_field(&b, &a, &mut r, &format!("{scaled} against {written}"));
    }
}

/// `a` and `b` have the same field (within 1e-12) at 300 random points of [−4, 4]³.
fn same_field(
    a: &sdfc_compiler::scene::Scene,
    b: &sdfc_compiler::scene::Scene,
    r: &mut sdfc_tests::Rng,
    what: &str,
) {
    for _ in 0..300 {
        let p = DVec3::new(r.range(-4.0, 4.0), r.range(-4.0, 4.0), r.range(-4.0, 4.0));
        let (x, y) = (eval::distance(a, p), eval::distance(b, p));
        assert!((x - y).abs() < 1e-12, "{what} at {p}: {y}, against {x}");
    }
}

/// The shader tests a union's bounding boxes by default only where the union groups at least
/// `GPU_MIN_GROUPED` parts (fewer measured slower on lavapipe); `--bvh` (`All`) tests every
/// tree and `--no-bvh` (`Off`) none. Spheres spread along x, one per 3 units, on a plane
/// (each of its own radius, or they would be grouped into a `repeat`).
#[test]
fn bounding_boxes_are_tested_by_default_only_in_large_unions() {
    use sdfc_compiler::catalog::prune::GPU_MIN_GROUPED;
    use sdfc_compiler::emit::{self, Output, Target};
    use sdfc_compiler::lower::{Entry, tracer::BoundingVolumes, tracer::Options};
    let tests = |n: usize, trees: BoundingVolumes| {
        let parts: String = (0..n)
            .map(|i| format!("  sphere(0.5 + 0.01 * {i}) at ({}, 0.5, 0)\n", 3 * i))
            .collect();
        let scene = sdfc_tests::scene("spheres", &format!("union {{\n{parts}  plane()\n}}"));
        let mut options = Options::from_scene(&scene);
        options.bounding_volumes = trees;
        let (m, info) =
            emit::module(&scene, Entry::Trace, &options).unwrap_or_else(|e| panic!("{}", e.0));
        let Ok(Output::Text(wgsl)) = emit::write(&m, &info, Target::Wgsl, Entry::Trace) else {
            panic!("no WGSL");
        };
        wgsl.matches("if (dot(").count()
    };
    let (few, enough) = (GPU_MIN_GROUPED - 1, GPU_MIN_GROUPED);
    assert_eq!(tests(few, BoundingVolumes::Large), 0, "{few} spheres");
    assert!(
        tests(enough, BoundingVolumes::Large) > 0,
        "{enough} spheres"
    );
    assert!(tests(few, BoundingVolumes::All) > 0, "{few} spheres, --bvh");
    assert_eq!(tests(40, BoundingVolumes::Off), 0, "40 spheres, --no-bvh");
    assert_eq!(BoundingVolumes::default(), BoundingVolumes::Large);
}

/// The annotation check on random scenes of the fuzzers' generator, annotated with random
/// (mostly wrong) bounds, lit with shadows, in a material that reflects and lets light through,
/// beside an annotated part that reads a ranged parameter: every sampling path (camera,
/// shadow, mirror and glass rays, the box, the search, the ranges' settings) runs, and none
/// panics. The slowest check is printed (timing is not asserted).
#[test]
fn the_annotation_check_survives_random_annotated_scenes() {
    use sdfc_compiler::lipschitz::{Effort, Values, verify_annotations, verify_over_ranges};
    let cases = sdfc_tests::fuzz_cases(24);
    let seed = sdfc_tests::fuzz_seed(3131);
    let mut r = sdfc_tests::Rng::new(seed);
    let (mut checked, mut warned, mut slowest) = (0, 0, (0.0f64, 0u64));
    for i in 0..u64::from(cases) {
        let source = sdfc_tests::scenes::scene(seed + i);
        let mut lines: Vec<&str> = source.lines().collect();
        let Some(body) = lines.pop() else { continue };
        let lambda = [0.05, 0.3, 0.9, 1.0, 2.5][r.below(5)];
        let annotated = format!(
            "param a = 1 in 0.5..2\nlight {{ direction (0.3, 1, -0.2)  shadow hard }}\nlight point {{ position (0, 4, 0)  shadow soft }}\nmaterial glass {{ color #def  reflect 0.3  transparent 0.5  ior 1.5 }}\n{}\nunion {{\n  ({body}) @lipschitz({lambda}) : glass\n  implicit {{ y + 2 + 0.3 * a * sin(x) }} @lipschitz(0.8)\n}}\n",
            lines.join("\n")
        );
        let Some(scene) = sdfc_compiler::check::compile(&annotated).scene else {
            continue;
        };
        let at = |v: &Values| sdfc_compiler::check::compile_with(&annotated, v).scene;
        let started = std::time::Instant::now();
        let mut found = verify_annotations(&scene, Effort::Fast);
        found.extend(verify_over_ranges(
            &at,
            &scene,
            Effort::Fast,
            (&Values::new(), &found.clone()),
        ));
        let took = started.elapsed().as_secs_f64();
        if took > slowest.0 {
            slowest = (took, seed + i);
        }
        checked += 1;
        warned += usize::from(!found.is_empty());
    }
    println!(
        "{checked} annotated scenes checked, {warned} with warnings; slowest {:.2} s (seed {})",
        slowest.0, slowest.1
    );
    assert!(
        checked * 3 >= cases as usize,
        "only {checked} of {cases} checked"
    );
}
