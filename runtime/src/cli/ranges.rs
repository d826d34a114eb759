//! `@lipschitz` annotations checked over the parameters' declared ranges, not only at their
//! defaults (issue 31: an annotation right at the default and too small at one end of a range
//! passed every check, and the render at that end lost whole shapes).

use sdfc_compiler::diag::Diagnostic;
use sdfc_compiler::lipschitz::{Effort, verify_annotations};
use sdfc_compiler::scene::Scene;
use std::collections::HashMap;

/// Parameter values by name (angles in radians), as `--param` gives them.
type Values = HashMap<String, Vec<f64>>;

/// Most parameter settings checked besides the defaults (each compiles the scene once more and
/// samples its annotations).
const MAX_SETTINGS: usize = 12;

/// The settings to check: the values asked for (`--param`, `--time`), every ranged parameter
/// at its low and at its high end together, then each alone at either end.
fn settings(scene: &Scene, asked: &Values) -> Vec<Values> {
    let ranged: Vec<_> = scene.params.iter().filter(|p| p.range.is_some()).collect();
    let n = |p: &sdfc_compiler::scene::ParamDecl, v: glam::DVec3| {
        v.to_array()[..p.kind.components()].to_vec()
    };
    let mut out = Vec::new();
    if !asked.is_empty() {
        out.push(asked.clone());
    }
    for end in [0, 1] {
        let all: Values = ranged
            .iter()
            .map(|p| {
                let (lo, hi) = p.range.expect("ranged");
                (p.name.clone(), n(p, if end == 0 { lo } else { hi }))
            })
            .collect();
        if !all.is_empty() {
            out.push(all);
        }
    }
    for p in &ranged {
        let (lo, hi) = p.range.expect("ranged");
        for v in [lo, hi] {
            out.push(HashMap::from([(p.name.clone(), n(p, v))]));
        }
    }
    out.truncate(MAX_SETTINGS);
    out
}

/// The annotation warnings found at other parameter values than the defaults' (`seen`: the
/// defaults' own, not repeated), each with a note saying at which values; `compile_at` checks
/// the scene's source at given values.
pub fn verify_over_ranges(
    compile_at: &dyn Fn(&Values) -> Option<Scene>,
    scene: &Scene,
    effort: Effort,
    (asked, seen): (&Values, &[Diagnostic]),
) -> Vec<Diagnostic> {
    if !scene.nodes.iter().any(|n| n.lambda < n.inferred_lambda) {
        return Vec::new();
    }
    let mut out: Vec<Diagnostic> = Vec::new();
    for values in settings(scene, asked) {
        let Some(at) = compile_at(&values) else {
            continue;
        };
        for d in verify_annotations(&at, effort) {
            let known = seen
                .iter()
                .chain(&out)
                .any(|k| k.span == d.span && k.message == d.message);
            if known {
                continue;
            }
            let mut shown: Vec<String> = values
                .iter()
                .map(|(k, v)| {
                    let v: Vec<String> = v.iter().map(|x| format!("{x}")).collect();
                    format!("{k} = {}", v.join(", "))
                })
                .collect();
            shown.sort();
            let why = match values == *asked {
                true => "the values asked for",
                false => "ends of their declared ranges",
            };
            out.push(d.note(format!("found with {} ({why})", shown.join("; "))));
        }
    }
    out
}
