//! The house's rules (issue 29): no import cycle between sibling modules, no function over 100
//! lines, operator and primitive names compared only in the catalog, and an operator added
//! through the table alone — each with a check that the rule's test can fail.

use sdfc_compiler::catalog::gpu::{ChildLower, args, norm};
use sdfc_compiler::catalog::traits::PLAIN;
use sdfc_compiler::catalog::{
    self, Arity, Bound, ChildEval, Ctx, MatRule, OPERATORS, Operator, PRIMITIVES, Ty,
};
use sdfc_compiler::ir::{Ex, FnBuilder};
use std::path::{Path, PathBuf};
use std::process::Command;

/// Runs `python3 scripts/<script> <args>` at the workspace root: (exit 0, stdout + stderr).
fn script(script: &str, args: &[&Path]) -> (bool, String) {
    let root = sdfc_tests::root();
    let out = Command::new("python3")
        .arg(root.join("scripts").join(script))
        .args(args)
        .current_dir(&root)
        .output()
        .expect("python3 runs (the house's scripts are Python; .ci/run installs it)");
    let text =
        String::from_utf8_lossy(&out.stdout).to_string() + &String::from_utf8_lossy(&out.stderr);
    (out.status.success(), text)
}

/// A folder of Rust files written for a test of a script.
fn tree(name: &str, files: &[(&str, String)]) -> PathBuf {
    let dir = sdfc_tests::tempdir().join(format!("house-{name}"));
    let _ = std::fs::remove_dir_all(&dir);
    for (path, text) in files {
        let p = dir.join(path);
        std::fs::create_dir_all(p.parent().unwrap()).unwrap();
        std::fs::write(p, text).unwrap();
    }
    dir
}

#[test]
fn the_import_graph_has_no_cycle() {
    let root = sdfc_tests::root();
    let (ok, out) = script(
        "import_graph.py",
        &[&root.join("compiler/src"), &root.join("runtime/src")],
    );
    assert!(ok, "{out}");
    assert!(out.contains("no cycle"), "{out}");
}

#[test]
fn the_import_graph_script_finds_a_cycle() {
    let lib = "//! x\nmod a;\nmod b;\nmod c;\n".to_string();
    let a = "//! a\nuse crate::b::{B, Other};\npub struct A;\n".to_string();
    let b = "//! b\npub struct B;\npub fn f() { let _ = super::c::C; }\n".to_string();
    // c names a through a nested brace group: the cycle is a -> b -> c -> a.
    let c = "//! c\nuse crate::{x::y, a::{self, A}};\npub struct C;\n".to_string();
    let dir = tree(
        "cycle",
        &[
            ("lib.rs", lib.clone()),
            ("a.rs", a),
            ("b.rs", b),
            ("c.rs", c),
        ],
    );
    let (ok, out) = script("import_graph.py", &[&dir]);
    assert!(!ok, "{out}");
    assert!(out.contains("cycle among a, b, c"), "{out}");
    // A child naming its parent is how a folder is made, not a cycle.
    let parent = "//! p\nmod kid;\npub struct P;\npub fn g() { kid::k(); }\n".to_string();
    let kid = "//! k\nuse super::P;\npub fn k() {}\n".to_string();
    let dir = tree(
        "parent",
        &[
            ("lib.rs", "//! x\nmod p;\n".into()),
            ("p/mod.rs", parent),
            ("p/kid.rs", kid),
        ],
    );
    let (ok, out) = script("import_graph.py", &[&dir]);
    assert!(ok, "{out}");
}

#[test]
fn no_function_is_over_100_lines() {
    let root = sdfc_tests::root();
    let (ok, out) = script(
        "long_functions.py",
        &[&root.join("compiler/src"), &root.join("runtime/src")],
    );
    assert!(ok, "functions over 100 lines (split them):\n{out}");
}

#[test]
fn the_length_script_finds_a_long_function() {
    let body = |n: usize| {
        (0..n)
            .map(|i| format!("    let _x{i} = {i};\n"))
            .collect::<String>()
    };
    // 100 lines in all (signature, 98 statements, brace), then 101.
    let text = format!(
        "//! x\nfn fits() {{\n{}}}\n\nfn over() {{\n{}}}\n",
        body(98),
        body(99)
    );
    let dir = tree("long", &[("lib.rs", text)]);
    let (ok, out) = script("long_functions.py", &[&dir]);
    assert!(!ok, "{out}");
    assert!(out.contains(" over 101"), "{out}");
    assert!(!out.contains("fits"), "{out}");
}

/// Places where a catalog name is compared as a word of another table, with the reason.
const NOT_CATALOG_NAMES: &[(&str, &str, &str)] = &[(
    "compiler/src/check/settings.rs",
    "sphere|box",
    "the `bound` setting's kinds (`BOUND_KINDS`), a table of their own",
)];

/// Where a line compares a string literal equal to one of `names` (`== "x"`, `!= "x"`, a match
/// arm `"x" =>` or `"x" | …`, or inside `matches!`): the names found.
fn compared_names(line: &str, names: &[&str]) -> Vec<String> {
    let code = line.split("//").next().unwrap_or("");
    let mut found = Vec::new();
    for n in names {
        let q = format!("\"{n}\"");
        let compared = code.match_indices(&q).any(|(at, _)| {
            let before = code[..at].trim_end();
            let after = code[at + q.len()..].trim_start();
            before.ends_with("==")
                || before.ends_with("!=")
                || after.starts_with("==")
                || after.starts_with("!=")
                || after.starts_with("=>")
                || after.starts_with('|')
                || after.starts_with("if ")
                || before.ends_with('|')
                || code.contains("matches!(")
        });
        if compared {
            found.push(n.to_string());
        }
    }
    found
}

#[test]
fn operator_and_primitive_names_are_compared_only_in_the_catalog() {
    let names: Vec<&str> = PRIMITIVES
        .iter()
        .map(|p| p.name)
        .chain(OPERATORS.iter().map(|o| o.name))
        .collect();
    // The check itself finds what it looks for, and not a name passed to a function.
    for (line, hit) in [
        ("if op.name == \"union\" {", true),
        (
            "        \"scale\" => (ctx.args.clone(), ctx.sym.clone()),",
            true,
        ),
        ("let axis = matches!(name, \"rotate\" | \"mirror\");", true),
        ("self.operator_node(\"union\", args, roots, span)", false),
        ("// when op.name == \"union\"", false),
        ("f(\"union\"); if name == \"union\" {", true),
    ] {
        assert_eq!(!compared_names(line, &names).is_empty(), hit, "{line}");
    }
    let root = sdfc_tests::root();
    let mut files = Vec::new();
    for dir in ["compiler/src", "runtime/src"] {
        sdfc_tests::rust_files(&root.join(dir), &mut files);
    }
    let catalog = root.join("compiler/src/catalog");
    let mut problems = Vec::new();
    // (Unit tests, in `tests.rs` files, may name what they test.)
    let tests = |f: &PathBuf| f.file_name().is_some_and(|n| n == "tests.rs");
    for f in files
        .iter()
        .filter(|f| !f.starts_with(&catalog) && !tests(f))
    {
        let rel = f
            .strip_prefix(&root)
            .unwrap()
            .to_string_lossy()
            .replace('\\', "/");
        let text = std::fs::read_to_string(f).unwrap();
        for (i, line) in text.lines().enumerate() {
            for n in compared_names(line, &names) {
                let allowed = NOT_CATALOG_NAMES
                    .iter()
                    .any(|(file, which, _)| *file == rel && which.split('|').any(|w| w == n));
                if !allowed {
                    problems.push(format!("{rel}:{}: `{n}` compared: {}", i + 1, line.trim()));
                }
            }
        }
    }
    assert!(
        problems.is_empty(),
        "what a stage decides by an operator's or primitive's name belongs in its catalog entry \
         (catalog/traits.rs):\n{}",
        problems.join("\n")
    );
}

/// The throwaway operator: its shape moved out by `amount` along its normals, f/λ − amount.
fn offset_ir(b: &mut FnBuilder, c: &Ctx, p: Ex, child: ChildLower) -> Ex {
    let d = norm(b, c, child, 0, p);
    let amount = args::num(b, c, 0, p);
    b.sub(d, amount)
}

fn offset_eval(c: &Ctx, p: glam::DVec3, child: ChildEval) -> f64 {
    child(0, p) / c.child_lambda[0] - c.num(0)
}

static OFFSET: Operator = Operator {
    name: "house_test_offset",
    doc: "Moves its shape's surface out by `amount`: f/λ − amount (λ = 1).",
    params: &[catalog::req("amount", Ty::Length)],
    arity: Arity::Exactly(1),
    lipschitz: |_| 1.0,
    bound: |_| Bound::INFINITE,
    mirror: |c| c.child_mirror[0],
    swap: |c| c.child_swap[0],
    eval: offset_eval,
    unit_gradient: |_| true,
    keeps_exact: |_| false,
    materials: MatRule::Pass,
    fixed_args: false,
    lower: offset_ir,
    traits: PLAIN,
};

#[test]
fn an_operator_is_added_through_the_table_alone() {
    catalog::register_operator(&OFFSET).expect("a new name");
    assert!(
        catalog::register_operator(&OFFSET).is_err(),
        "a name taken twice"
    );
    let source = "house_test_offset(0.25) { sphere(1) |> scale(2) }";
    let checked = sdfc_compiler::check::compile(source);
    let scene = checked
        .scene
        .unwrap_or_else(|| panic!("{:?}", checked.diagnostics));
    // The CPU evaluator: a sphere of radius 2 moved out by 0.25.
    for p in [
        glam::DVec3::ZERO,
        glam::DVec3::new(3.0, 1.0, -2.0),
        glam::DVec3::X * 2.25,
    ] {
        let want = p.length() - 2.25;
        let got = sdfc_compiler::reference::eval::distance(&scene, p);
        assert!((got - want).abs() < 1e-12, "{p}: {got} against {want}");
    }
    // The Lipschitz rule, and a module the validator passes for every entry.
    assert_eq!(scene.root_node().lambda, 1.0);
    for entry in [
        sdfc_compiler::lower::Entry::Compute,
        sdfc_compiler::lower::Entry::Fragment,
        sdfc_compiler::lower::Entry::Library,
    ] {
        let options = sdfc_compiler::lower::tracer::Options::from_scene(&scene);
        let (module, _) = sdfc_compiler::emit::module(&scene, entry, &options)
            .unwrap_or_else(|e| panic!("{}", e.0));
        assert!(
            module
                .functions
                .iter()
                .any(|(_, f)| f.name.as_deref() == Some("map"))
        );
    }
}
