//! Annotation warnings that reach where the user can act (issue 31): bounds so large that no
//! ray arrives within its step budget (λ from 2.4·10³ to 10¹⁸ was accepted silently and the
//! picture was blank; a bound a few times loose is not warned about), and a warning inside a
//! function body naming the call whose arguments make it.

use sdfc_compiler::check;
use sdfc_compiler::lipschitz::{Effort, verify_annotations};

/// The checker's warnings and the annotation check's, as text.
fn warnings(source: &str) -> Vec<String> {
    let checked = check::compile(source);
    let scene = checked.scene.expect("the scene checks");
    checked
        .diagnostics
        .iter()
        .chain(&verify_annotations(&scene, Effort::Fast))
        .map(|d| format!("{} | {} | {}", d.message, d.label, d.notes.join(" ")))
        .collect()
}

#[test]
fn bounds_too_large_to_converge_are_warned() {
    let camera = "camera { eye (0, 1, -6) target (0, 0, 0) }\n";
    // Above the catalog's own rule: the checker's warning says how much shorter the steps are.
    let source = format!("{camera}implicit {{ y - 0.5 }} @lipschitz(1e18)\n");
    let said = warnings(&source);
    assert!(
        said.iter()
            .any(|w| w.contains("looser than the inferred bound")),
        "{said:?}"
    );
    // Below the rule (none is finite for these) but far above the slope rays meet.
    for (body, lambda) in [
        ("sin(x*x) * 0.01 + y", "2400"),
        ("x*x + y*y + z*z - 1", "100000"),
    ] {
        let source = format!("{camera}implicit {{ {body} }} @lipschitz({lambda})\n");
        let said = warnings(&source);
        assert!(
            said.iter()
                .any(|w| w.contains("rays cannot arrive") && w.contains("the budget is 128")),
            "{source}: {said:?}"
        );
    }
    // Loose but workable: twice the slope, or an exact bound.
    for (body, lambda) in [("x*x + y*y + z*z - 1", "400"), ("length(x, y, z) - 1", "1")] {
        let source = format!("{camera}implicit {{ {body} }} @lipschitz({lambda})\n");
        assert!(warnings(&source).is_empty(), "{source}");
    }
}

/// An annotation inside a function body that only some calls make wrong: the warning points
/// into the body and names the call whose arguments make it so (as errors do), not the others.
#[test]
fn a_warning_in_a_function_names_the_call_that_makes_it() {
    let source = "camera { eye (0, 1, -8) target (0, 0, 0) }\nfn wave(a) = implicit { y - a * sin(x) } @lipschitz(1.5)\nwave(0.5) at (-2, 0, 0)\nwave(3) at (2, 0, 0)\n";
    let checked = check::compile(source);
    let scene = checked.scene.expect("the scene checks");
    let found = verify_annotations(&scene, Effort::Fast);
    let too_small: Vec<_> = found
        .iter()
        .filter(|d| d.message.contains("too small"))
        .collect();
    assert_eq!(too_small.len(), 1, "{found:?}");
    let calls: Vec<&str> = too_small[0]
        .secondary
        .iter()
        .map(|(s, _)| &source[s.start..s.end])
        .collect();
    assert_eq!(calls, ["wave(3)"], "{:?}", too_small[0]);
}
