//! Every limit of the front end, just past it and at it: past it the user gets an error with
//! file, line, column, a caret and the limit named; at it the scene compiles (and, for the node
//! count, the module validates). The image-size limit of `render` is tested in
//! `runtime/tests/cli.rs`, device loss in `runtime/tests/device.rs`.

use sdfc_compiler::check::tracer::MAX_STEPS;
use sdfc_compiler::check::{
    self, MAX_DEPTH, MAX_EVALUATIONS, MAX_LIGHTS, MAX_MATERIALS, MAX_NODES,
};
use sdfc_compiler::syntax::{MAX_NESTING, MAX_SOURCE_BYTES};
use sdfc_compiler::{cost, diag, emit, lower};

/// Checks `source` on a large stack; returns the rendered diagnostics and whether it compiled.
fn check(source: String) -> (String, Option<sdfc_compiler::scene::Scene>) {
    let text = source.clone();
    let checked = sdfc_tests::with_stack(move || check::compile(&text));
    (
        diag::render(&checked.diagnostics, "limit.sdf", &source),
        checked.scene,
    )
}

/// Past the limit: one error, at a line and column, with a caret, naming the limit.
fn refused(source: String, message: &str, limit: String) {
    let (text, scene) = check(source);
    assert!(scene.is_none(), "compiled past the limit: {message}");
    assert!(text.contains(message), "{text}");
    assert!(
        text.contains(&limit),
        "the limit {limit} is not named:\n{text}"
    );
    let at = text
        .lines()
        .find(|l| l.contains("limit.sdf:"))
        .unwrap_or("");
    assert!(
        at.split(':')
            .filter(|p| p.trim().parse::<u32>().is_ok())
            .count()
            == 2,
        "no line:column in `{at}`"
    );
    assert!(text.contains('^'), "no caret:\n{text}");
}

fn accepted(source: String) -> sdfc_compiler::scene::Scene {
    let (text, scene) = check(source);
    scene.unwrap_or_else(|| panic!("refused at the limit:\n{text}"))
}

/// A union of `n` spheres: n + 1 nodes.
fn spheres(n: usize) -> String {
    let mut s = String::from("union {\n");
    for i in 0..n {
        s += &format!("sphere({})\n", 1 + i % 100);
    }
    s + "}\n"
}

/// A union of `nodes − 1` nodes under it, in chains of ten (a sphere rounded nine times) so
/// that the primitives stay under the evaluation limit: `nodes` nodes in all.
fn chains(nodes: usize) -> String {
    let mut s = String::from("union {\n");
    let mut left = nodes - 1;
    while left > 0 {
        let len = if left.is_multiple_of(10) {
            10
        } else {
            left % 10
        };
        s += &format!(
            "sphere({}){}\n",
            1 + left % 100,
            " |> round(0.01)".repeat(len - 1)
        );
        left -= len;
    }
    s + "}\n"
}

#[test]
fn nodes() {
    refused(
        chains(MAX_NODES + 1),
        "too many nodes",
        format!("{MAX_NODES} nodes"),
    );
    let scene = accepted(chains(MAX_NODES));
    assert_eq!(scene.nodes.len(), MAX_NODES);
    let settings = lower::tracer::Options::from_scene(&scene);
    let module = sdfc_tests::with_stack(move || {
        emit::module(&scene, lower::Entry::Library, &settings).map(|m| m.0.functions.len())
    });
    assert!(
        module.is_ok(),
        "a scene at the node limit must emit a valid module"
    );
}

/// A scale that a box takes into its size (`catalog::absorb`) is rebuilt in the box's own
/// node, one node more only while it is built: near the limit it makes the scene smaller, and
/// where there is no room even for that the scale stays and is refused with the limit's error —
/// never a shape dropped without a word (the rewrite once swallowed the error).
#[test]
fn a_scale_taken_into_a_box_at_the_node_limit() {
    // A union of `filler` nodes of spheres under rounds (no more spheres than the evaluation
    // limit leaves room for), then the box and its scale: the scale is the last node before
    // the union's own.
    let scene = |filler: usize| {
        let mut s = String::from("union {\n");
        let (lines, extra) = (filler / 10, filler % 10);
        for i in 0..lines {
            let rounds = 9 + if i == 0 { extra } else { 0 };
            s += &format!("sphere(1){}\n", " |> round(0.01)".repeat(rounds));
        }
        s + "box(1) |> scale((2, 1, 1))\n}\n"
    };
    // The filler, the box, its scale and the union: the limit as written; the scale is taken
    // into the box, one node fewer.
    let at = accepted(scene(MAX_NODES - 3));
    assert_eq!(at.nodes.len(), MAX_NODES - 1);
    let last = *at.root_node().children().last().unwrap();
    assert_eq!(at.nodes[last].kind_name(), "box");
    // The box is the limit's last node: no room to rebuild it, and none for the scale.
    refused(
        scene(MAX_NODES - 1),
        "too many nodes",
        format!("{MAX_NODES} nodes"),
    );
}

#[test]
fn bracket_nesting() {
    // `sphere(` is one level, so deep(n) nests n + 1 brackets.
    let deep = |n: usize| format!("sphere({}1{})", "(".repeat(n), ")".repeat(n));
    refused(
        deep(MAX_NESTING),
        "nesting is too deep",
        format!("{MAX_NESTING} levels"),
    );
    accepted(deep(MAX_NESTING - 1));
}

/// Regression (found by this file): the grammar tried `(` as a vector before a parenthesised
/// expression, so each level of parentheses was parsed twice — 18 levels took 0.65 s, the
/// 198 allowed would have taken days. Each kind of bracket, nested as deep as allowed.
#[test]
fn deep_brackets_of_every_kind_parse() {
    let n = MAX_NESTING - 4;
    for source in [
        format!("sphere(1) at ({}1{}, 2, 3)", "(".repeat(n), ")".repeat(n)),
        format!("sphere({}1{})", "sqrt(".repeat(n), ")".repeat(n)),
        format!("{}sphere(1){}", "union { ".repeat(n), " }".repeat(n)),
        format!(
            "sphere(1) @lipschitz({}1{})",
            "(-".repeat(n / 2),
            ")".repeat(n / 2)
        ),
    ] {
        accepted(source);
    }
}

#[test]
fn expression_depth() {
    // A chain of additions: deep without brackets (those have their own limit, above).
    let deep = |n: usize| format!("sphere({}1)", "1 + ".repeat(n));
    // The call and its argument take two levels, each addition one more.
    refused(
        deep(MAX_DEPTH - 1),
        "expression nested too deeply",
        format!("{MAX_DEPTH} levels"),
    );
    accepted(deep(MAX_DEPTH - 2));
}

#[test]
fn step_budget() {
    let steps = |n: f64| format!("trace basic {{ steps {n} }}\nsphere(1)");
    refused(
        steps(MAX_STEPS + 1.0),
        "`steps` must be a whole number from 1 to",
        format!("{MAX_STEPS}"),
    );
    accepted(steps(MAX_STEPS));
}

#[test]
fn source_size() {
    let file = |bytes: usize| {
        let mut s = String::from("sphere(1)\n");
        s += &" ".repeat(bytes - s.len());
        s
    };
    refused(
        file(MAX_SOURCE_BYTES + 1),
        "too large",
        format!("{MAX_SOURCE_BYTES} bytes"),
    );
    accepted(file(MAX_SOURCE_BYTES));
}

/// `let` sharing and `repeat` copies multiply work without adding nodes: the evaluations one
/// evaluation of the field costs are limited, exactly at the limit and one past it.
#[test]
fn evaluations() {
    let limit = MAX_EVALUATIONS as usize;
    let _ = accepted(spheres(limit));
    refused(
        spheres(limit + 1),
        "too many evaluations",
        format!("the limit is {limit}"),
    );
    // 2^13 uses of one sphere through 13 shared lets pass, 2^14 do not (16 levels grew the
    // render to 7 GB): the error names the count and sits on the `let` that crosses the limit.
    let shared = |levels: usize| {
        let mut s = String::from("let s0 = sphere(0.1)\n");
        for i in 1..=levels {
            s += &format!(
                "let s{i} = union {{ s{}  s{} at (0.001, 0, 0) }}\n",
                i - 1,
                i - 1
            );
        }
        s + &format!("s{levels}\n")
    };
    let _ = accepted(shared(13));
    refused(
        shared(14),
        "too many evaluations",
        "16384 primitives".to_string(),
    );
}

#[test]
fn materials() {
    // n materials, each on its own sphere.
    let scene = |n: usize| {
        let mut s = String::new();
        for i in 0..n {
            s += &format!("material m{i} {{ color #{:03x} }}\n", i % 4096);
        }
        s += "union {\n";
        for i in 0..n {
            s += &format!("  sphere(0.1) at ({i}, 0, 0) : m{i}\n");
        }
        s + "}\n"
    };
    refused(
        scene(MAX_MATERIALS + 1),
        "too many materials",
        format!("{MAX_MATERIALS} materials"),
    );
    assert_eq!(
        accepted(scene(MAX_MATERIALS)).materials.len(),
        MAX_MATERIALS
    );
}

#[test]
fn lights() {
    let scene = |n: usize| {
        let mut s = String::new();
        for i in 0..n {
            s += &format!("light point {{ position ({i}, 5, 0)  intensity 0.01 }}\n");
        }
        s + "sphere(1)\n"
    };
    refused(
        scene(MAX_LIGHTS + 1),
        "too many lights",
        format!("{MAX_LIGHTS} lights"),
    );
    assert_eq!(accepted(scene(MAX_LIGHTS)).lights.len(), MAX_LIGHTS);
}

/// What the compile-cost model (`cost`) counts: the normal's four samples are one call of
/// `map` in a loop (four calls compiled `map` four times); a shared `let` used three times is
/// one function written out at each call; the prediction grows with the scene, every example
/// is under the limit and a flat union of 4 096 spheres far over it.
#[test]
fn compile_cost_counts_the_inlined_shader() {
    let module = |source: String| {
        let scene = accepted(source);
        let options = lower::tracer::Options::from_scene(&scene);
        emit::module(&scene, lower::Entry::Compute, &options)
            .unwrap()
            .0
    };
    let m = module(spheres(8));
    let (_, normal) = m
        .functions
        .iter()
        .find(|(_, f)| f.name.as_deref() == Some("normal"))
        .expect("a normal function");
    let calls = normal
        .expressions
        .iter()
        .filter(|(_, e)| matches!(e, naga::Expression::CallResult(_)))
        .count();
    assert_eq!(calls, 1, "normal calls map once");
    let shared = "let a = union { sphere(1)  box(1) at (2, 0, 0) }\nunion { a  a at (5, 0, 0)  a at (10, 0, 0) }\n";
    let once = "union { sphere(1)  box(1) at (2, 0, 0) }\n";
    let (three, one) = (
        cost::inlined(&module(shared.to_string())),
        cost::inlined(&module(once.to_string())),
    );
    // Three copies of the let's body where the single union has one: 2 more calls of each of
    // its two shapes per copy of `map` (and 3 of the let's function).
    assert!(three.calls > one.calls + 4, "{three:?} {one:?}");
    assert!(three.size > one.size, "{three:?} {one:?}");
    let predicted = |n| cost::predict(&cost::inlined(&module(spheres(n))));
    let (small, medium, large) = (predicted(64), predicted(512), predicted(4096));
    assert!(small.seconds < medium.seconds && medium.seconds < large.seconds);
    assert!(!small.too_slow(), "{small:?}");
    assert!(large.too_slow() && large.seconds > 60.0, "{large:?}");
    for file in sdfc_tests::examples() {
        let source = std::fs::read_to_string(&file).unwrap();
        let name = file.to_string_lossy();
        let loader = sdfc_compiler::syntax::FsLoader;
        let checked = check::compile_file(&name, &source, &Default::default(), &loader);
        let scene = checked.scene.expect("an example checks");
        let options = lower::tracer::Options::from_scene(&scene);
        let m = emit::module(&scene, lower::Entry::Compute, &options)
            .unwrap()
            .0;
        let p = cost::predict(&cost::inlined(&m));
        assert!(!p.too_slow(), "{name}: {p:?}");
    }
}

/// A function of 100 000 parameters called with as many arguments checks (duplicates were
/// found by searching the parameters before each one: 26 s); 10 000 misspelt argument names
/// against 10 000 parameters get a suggestion for the first `MAX_SHOWN` (the ones a report
/// shows; all of them took 35 s) and a signature cut to its first twelve parameters.
#[test]
fn long_parameter_lists_stay_linear() {
    let names = |n: usize, p: &str| (0..n).map(|i| format!("{p}{i}")).collect::<Vec<_>>();
    let n = 100_000;
    let source = format!(
        "fn f({}) = sphere(a0)\nf({})\n",
        names(n, "a").join(", "),
        vec!["1"; n].join(", ")
    );
    let (text, scene) = check(source);
    assert!(scene.is_some(), "{}", &text[..text.len().min(400)]);
    let n = 10_000;
    let args: Vec<String> = names(n, "arx").iter().map(|a| format!("{a} = 1")).collect();
    let source = format!(
        "fn f({}) = sphere(arg0)\nf({})\n",
        names(n, "arg").join(", "),
        args.join(", ")
    );
    let text = sdfc_tests::with_stack(move || check::compile(&source));
    let d = &text.diagnostics;
    assert_eq!(d.iter().filter(|d| d.is_error()).count(), n);
    let suggested = d
        .iter()
        .filter(|d| d.notes.iter().any(|n| n.contains("did you mean `arg")))
        .count();
    assert_eq!(suggested, diag::MAX_SHOWN);
    let listed = d
        .iter()
        .find(|d| d.notes.iter().any(|n| n.contains("the parameters are")));
    let note = listed.map(|d| d.notes.join(" ")).unwrap_or_default();
    assert!(note.contains("arg11, … 9988 more)"), "{note}");
}
