//! Imports: a scene of three files (one imported twice, through two paths) is the scene
//! written in one file; cycles, missing files and errors inside imported files are reported
//! in the file they are in; the standard library checks, and each of its functions draws a
//! bounded shape whose λ holds where sampled.

use glam::DVec3;
use sdfc_compiler::reference::eval;
use sdfc_compiler::syntax::{FsLoader, MapLoader};
use sdfc_compiler::{check, diag};
use std::path::PathBuf;

fn files(list: &[(&str, &str)]) -> MapLoader {
    MapLoader(
        list.iter()
            .map(|(p, t)| (PathBuf::from(p), t.to_string()))
            .collect(),
    )
}

fn compile(main: &str, loader: &MapLoader) -> check::Checked {
    let text = loader.0[&PathBuf::from(main)].clone();
    check::compile_file(main, &text, &Default::default(), loader)
}

fn report(c: &check::Checked) -> String {
    diag::render_sources(&c.diagnostics, &c.sources, false)
}

#[test]
fn a_three_file_scene_is_the_scene_in_one_file() {
    let vfs = files(&[
        (
            "scenes/main.sdf",
            "import \"../lib/furniture.sdf\"\nimport \"../lib/shapes.sdf\"\nmaterial oak { color #8a6a40 }\ntable(1.2) : oak\nstool() at (1, 0, 0)\n",
        ),
        (
            "lib/furniture.sdf",
            "import \"shapes.sdf\"\nfn table(w, h = 0.75) = union {\n  slab(w, 0.05) at (0, h, 0)\n  leg(h) at (w / 2 - 0.05, h / 2, 0)\n  leg(h) at (0.05 - w / 2, h / 2, 0)\n}\nfn stool(h = 0.45) = union { slab(0.35, 0.04) at (0, h, 0)  leg(h) at (0, h / 2, 0) }\n",
        ),
        (
            "lib/shapes.sdf",
            "fn slab(w, t) = box((w, t, w))\nfn leg(h) = cylinder(0.03, h)\n",
        ),
    ]);
    let checked = compile("scenes/main.sdf", &vfs);
    assert!(checked.diagnostics.is_empty(), "{}", report(&checked));
    let scene = checked.scene.expect("compiles");
    assert_eq!(scene.nodes[scene.root].lambda, 1.0);
    // Three files read, the one imported twice once.
    let names: Vec<&str> = checked
        .sources
        .files
        .iter()
        .map(|f| f.name.as_str())
        .collect();
    assert_eq!(
        names,
        ["scenes/main.sdf", "lib/furniture.sdf", "lib/shapes.sdf"]
    );
    let flat = sdfc_tests::scene(
        "flat",
        "material oak { color #8a6a40 }\nunion {\n  box((1.2, 0.05, 1.2)) at (0, 0.75, 0)\n  cylinder(0.03, 0.75) at (0.55, 0.375, 0)\n  cylinder(0.03, 0.75) at (-0.55, 0.375, 0)\n} : oak\nunion { box((0.35, 0.04, 0.35)) at (0, 0.45, 0)  cylinder(0.03, 0.45) at (0, 0.225, 0) } at (1, 0, 0)\n",
    );
    let mut rng = sdfc_tests::Rng::new(3);
    for _ in 0..5000 {
        let p = DVec3::new(
            rng.range(-2.0, 2.5),
            rng.range(-0.5, 1.5),
            rng.range(-1.5, 1.5),
        );
        let (a, b) = (eval::distance(&scene, p), eval::distance(&flat, p));
        assert!((a - b).abs() < 1e-12, "at {p}: {a} vs {b}");
        assert_eq!(
            eval::surface(&scene, p).0,
            eval::surface(&flat, p).0,
            "material at {p}"
        );
    }
}

#[test]
fn a_cycle_is_reported_with_its_chain() {
    let vfs = files(&[
        ("main.sdf", "import \"a.sdf\"\nsphere(1)\n"),
        ("a.sdf", "import \"b.sdf\"\nfn fa() = sphere(1)\n"),
        ("b.sdf", "import \"a.sdf\"\nfn fb() = sphere(1)\n"),
    ]);
    let c = compile("main.sdf", &vfs);
    let text = report(&c);
    assert!(c.scene.is_none());
    assert!(text.contains("import cycle"), "{text}");
    assert!(text.contains("a.sdf → b.sdf → a.sdf"), "{text}");
    assert!(
        text.contains("┌─ b.sdf:1:8"),
        "the error is in the file that closes the cycle:\n{text}"
    );
}

#[test]
fn a_missing_file_is_reported_at_the_import() {
    let vfs = files(&[("dir/main.sdf", "import \"lib/none.sdf\"\nsphere(1)\n")]);
    let c = compile("dir/main.sdf", &vfs);
    let text = report(&c);
    assert!(text.contains("cannot import `lib/none.sdf`"), "{text}");
    assert!(text.contains("┌─ dir/main.sdf:1:8"), "{text}");
    assert!(text.contains("looked for `dir/lib/none.sdf`"), "{text}");
}

#[test]
fn an_error_inside_an_imported_file_names_that_file_and_line() {
    let vfs = files(&[
        (
            "main.sdf",
            "// the scene\nimport \"parts.sdf\"\n\nshelf(2)\n",
        ),
        (
            "parts.sdf",
            "// parts\n\nfn shelf(w) = box((w, 0.1, 0.4)) at (0, heigth, 0)\n",
        ),
    ]);
    let c = compile("main.sdf", &vfs);
    let text = report(&c);
    assert!(c.scene.is_none());
    assert!(text.contains("unknown name `heigth`"), "{text}");
    assert!(
        text.contains("┌─ parts.sdf:3:41"),
        "the error's place:\n{text}"
    );
    assert!(
        text.contains("┌─ main.sdf:4:1"),
        "the call's place:\n{text}"
    );
    // A syntax error in an imported file, too.
    let vfs = files(&[
        ("main.sdf", "import \"parts.sdf\"\nsphere(1)\n"),
        ("parts.sdf", "\n\nlet a = (1, 2\n"),
    ]);
    let text = report(&compile("main.sdf", &vfs));
    assert!(text.contains("┌─ parts.sdf:3:"), "{text}");
}

#[test]
fn the_standard_library_checks_and_each_function_is_bounded() {
    for (name, _) in sdfc_compiler::syntax::STD {
        let stem = name.trim_start_matches("std/");
        let text = std::fs::read_to_string(sdfc_tests::root().join("compiler/std").join(stem))
            .expect("the library's source");
        let fns: Vec<String> = text
            .lines()
            .filter_map(|l| l.strip_prefix("fn "))
            .map(|l| l[..l.find('(').expect("a parameter list")].to_string())
            .collect();
        assert!(!fns.is_empty(), "{name} defines no function");
        for f in fns {
            let source = format!("import \"{name}\"\n{f}()\n");
            let c = check::compile_file("main.sdf", &source, &Default::default(), &FsLoader);
            assert!(c.diagnostics.is_empty(), "{f} of {name}:\n{}", report(&c));
            let scene = c.scene.expect("compiles");
            let root = &scene.nodes[scene.root];
            assert!(root.bound.is_finite(), "{f}: unbounded");
            // The catalog's slope check at random points of the shape's box.
            let (lo, hi) = (root.bound.lo - 0.5, root.bound.hi + 0.5);
            let mut rng = sdfc_tests::Rng::new(5);
            for _ in 0..400 {
                let at = |r: &mut sdfc_tests::Rng| {
                    lo + (hi - lo) * DVec3::new(r.unit(), r.unit(), r.unit())
                };
                let (p, q) = (at(&mut rng), at(&mut rng));
                let slope = (eval::distance(&scene, p) - eval::distance(&scene, q)).abs()
                    / (p - q).length();
                assert!(
                    slope <= 1.0 + 1e-9,
                    "{f}: slope {slope} between {p} and {q}"
                );
            }
        }
    }
}
