//! Every example compiles without errors or warnings, the examples together use every catalog
//! entry, the language reference's tables are current and name every keyword and standard-library
//! file, the README's tutorial scenes compile, and every example's field respects its λ.

use glam::DVec3;
use sdfc_compiler::catalog::{OPERATORS, PRIMITIVES};
use sdfc_compiler::reference::eval;
use sdfc_compiler::scene::NodeKind;
use sdfc_compiler::{check, docs};
use std::collections::BTreeSet;

#[test]
fn every_example_checks_clean() {
    let examples = sdfc_tests::examples();
    assert!(examples.len() >= 10, "only {} examples", examples.len());
    for path in examples {
        let source = std::fs::read_to_string(&path).unwrap();
        let checked = check::compile(&source);
        let name = path.display().to_string();
        assert!(
            checked.diagnostics.is_empty() && checked.scene.is_some(),
            "{name}:\n{}",
            sdfc_compiler::diag::render(&checked.diagnostics, &name, &source)
        );
    }
}

#[test]
fn examples_cover_the_catalog() {
    let mut used = BTreeSet::new();
    for path in sdfc_tests::examples() {
        let scene = sdfc_tests::example(&path);
        for id in scene.reachable() {
            used.insert(scene.nodes[id].kind_name());
        }
    }
    let missing: Vec<&str> = PRIMITIVES
        .iter()
        .map(|p| p.name)
        .chain(OPERATORS.iter().map(|o| o.name))
        .chain(["implicit"])
        .filter(|n| !used.contains(n))
        .collect();
    assert!(missing.is_empty(), "no example uses: {missing:?}");
}

/// The language reference's table of primitives, operators and functions is the catalog's.
#[test]
fn language_reference_table_is_current() {
    let doc = std::fs::read_to_string(sdfc_tests::root().join("docs/language.md")).unwrap();
    let start = "<!-- catalog:start -->\n";
    let end = "<!-- catalog:end -->";
    let a = doc
        .find(start)
        .expect("docs/language.md has the catalog start marker")
        + start.len();
    let b = doc
        .find(end)
        .expect("docs/language.md has the catalog end marker");
    assert!(
        doc[a..b] == docs::catalog_table(),
        "docs/language.md's reference table is stale: replace it with the output of `sdfc check --list`"
    );
}

/// The language reference names (in backticks) every block keyword, the statements' keywords,
/// the built-in names and every file of the standard library.
#[test]
fn language_reference_names_every_keyword_and_std_file() {
    let doc = std::fs::read_to_string(sdfc_tests::root().join("docs/language.md")).unwrap();
    let keywords = sdfc_compiler::syntax::BLOCK_KEYWORDS
        .iter()
        .chain(sdfc_compiler::syntax::DEFINITION_KEYWORDS)
        .chain(sdfc_compiler::syntax::VALUE_KEYWORDS)
        .copied();
    let built_in = ["time", "pi", "tau"];
    let std_files = sdfc_compiler::syntax::STD.iter().map(|(path, _)| *path);
    let missing: Vec<&str> = keywords
        .chain(built_in)
        .chain(std_files)
        .filter(|name| !doc.contains(&format!("`{name}`")))
        .collect();
    assert!(
        missing.is_empty(),
        "docs/language.md does not mention: {missing:?}"
    );
    // Each standard-library function with its signature as the library writes it.
    for (path, text) in sdfc_compiler::syntax::STD {
        for line in text.lines().filter_map(|l| l.strip_prefix("fn ")) {
            let head = &line[..=line.find(") =").expect("fn NAME(…) = BODY")];
            assert!(
                doc.contains(&format!("`{head}`")),
                "docs/language.md does not show `{head}` of {path}"
            );
        }
    }
}

/// Every scene in the README's tutorial (its ```sdf blocks) compiles without a diagnostic.
#[test]
fn readme_tutorial_scenes_compile() {
    let readme = std::fs::read_to_string(sdfc_tests::root().join("README.md")).unwrap();
    let blocks: Vec<&str> = readme
        .split("```sdf\n")
        .skip(1)
        .map(|b| b.split("```").next().unwrap())
        .collect();
    assert!(
        blocks.len() >= 3,
        "the tutorial has {} scenes",
        blocks.len()
    );
    for block in blocks {
        let checked = sdfc_compiler::check::compile(block);
        assert!(
            checked.scene.is_some() && checked.diagnostics.is_empty(),
            "{}",
            sdfc_compiler::diag::render(&checked.diagnostics, "README.md", block)
        );
    }
}

/// The language reference's table of texture patterns is the one the texture module documents.
#[test]
fn language_pattern_table_is_current() {
    let doc = std::fs::read_to_string(sdfc_tests::root().join("docs/language.md")).unwrap();
    let table = docs::pattern_table();
    assert!(
        doc.contains(&table),
        "docs/language.md's pattern table is stale; it should read:\n{table}"
    );
}

/// The tracer steps by f/λ; that is safe only if |∇(f/λ)| ≤ 1 everywhere. Sample it.
#[test]
fn every_example_respects_its_lipschitz_bound() {
    let mut report = String::new();
    for path in sdfc_tests::examples() {
        let scene = sdfc_tests::example(&path);
        let b = scene.root_node().bound;
        let (center, extent) = if b.radius.is_finite() {
            (b.center, b.radius * 1.2)
        } else {
            (
                scene.camera.target,
                (scene.camera.eye - scene.camera.target).length(),
            )
        };
        let slope = steepest(|p| eval::distance(&scene, p), center, extent, 20_000);
        let estimate_only = scene
            .reachable()
            .iter()
            .any(|&n| matches!(&scene.nodes[n].kind, NodeKind::Primitive { prim, .. } if prim.name == "mandelbulb"));
        report += &format!("{}: max |∇(f/λ)| = {slope:.4}\n", path.display());
        if !estimate_only {
            assert!(slope <= 1.0 + 1e-3, "{}: slope {slope} > 1", path.display());
        }
    }
    println!("{report}");
}

#[test]
fn every_example_is_finite_at_awkward_points() {
    let points = [
        DVec3::ZERO,
        DVec3::splat(1e-12),
        DVec3::new(1e6, 0.0, 0.0),
        DVec3::new(-1e6, 1e6, -1e6),
        DVec3::new(0.0, 1e-300, 0.0),
        DVec3::new(3.0, -2.0, 7.5),
    ];
    for path in sdfc_tests::examples() {
        let scene = sdfc_tests::example(&path);
        for p in points {
            let s = eval::sample(&scene, p);
            assert!(s.d.is_finite(), "{}: f({p}) = {}", path.display(), s.d);
            let n = eval::normal(&scene, p, 1e-4);
            assert!(n.is_finite(), "{}: normal({p}) = {n}", path.display());
        }
    }
}

/// Largest |∇f| seen by central differences at `samples` points of the cube of half size
/// `extent` around `center` (R3 quasi-random points, so repeatable): a lower estimate of the
/// true constant.
fn steepest(f: impl Fn(DVec3) -> f64, center: DVec3, extent: f64, samples: usize) -> f64 {
    let h = extent * 1e-5;
    let g = 1.220_744_084_605_759_5_f64;
    let a = DVec3::new(1.0 / g, 1.0 / (g * g), 1.0 / (g * g * g));
    let mut best: f64 = 0.0;
    for i in 0..samples {
        let u = (DVec3::splat(0.5) + a * i as f64).fract();
        let p = center + (u * 2.0 - DVec3::ONE) * extent;
        let grad = DVec3::new(
            f(p + DVec3::X * h) - f(p - DVec3::X * h),
            f(p + DVec3::Y * h) - f(p - DVec3::Y * h),
            f(p + DVec3::Z * h) - f(p - DVec3::Z * h),
        ) / (2.0 * h);
        if grad.is_finite() {
            best = best.max(grad.length());
        }
    }
    best
}

/// Every `sdf` code block of docs/language.md checks without errors or warnings (the reference
/// says so of its examples).
#[test]
fn language_reference_examples_check() {
    let doc = std::fs::read_to_string(sdfc_tests::root().join("docs/language.md")).unwrap();
    let mut blocks = 0;
    for (i, part) in doc.split("```sdf\n").enumerate().skip(1) {
        let code = part.split("```").next().unwrap();
        let checked = check::compile(code);
        assert!(
            checked.diagnostics.is_empty() && checked.scene.is_some(),
            "block {i} of docs/language.md:\n{code}\n{}",
            sdfc_compiler::diag::render(&checked.diagnostics, "docs/language.md", code)
        );
        blocks += 1;
    }
    assert!(blocks >= 10, "only {blocks} examples in docs/language.md");
}
