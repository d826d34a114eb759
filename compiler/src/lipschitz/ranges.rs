//! `@lipschitz` annotations checked at other parameter values than the defaults: the values
//! asked for, the declared ranges' ends and points inside them, and parameters without a range
//! perturbed (issue 31: an annotation right at the default and too small elsewhere in a range
//! passed every check, and the render there lost whole shapes).

use super::Effort;
use super::verify::{WORK, verify_where};
use super::{Rng, annotated};
use crate::diag::Diagnostic;
use crate::scene::{NodeId, NodeKind, ParamDecl, ParamKind, Scene};
use std::collections::{BTreeSet, HashMap};

/// Parameter values by name (angles in radians), as `--param` gives them.
pub type Values = HashMap<String, Vec<f64>>;

/// Why a setting is checked: what its warnings' note says.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Why {
    Asked,
    Ends,
    Inside,
    Unranged,
}

impl Why {
    fn say(self) -> &'static str {
        match self {
            Why::Asked => "the values asked for",
            Why::Ends => "ends of their declared ranges",
            Why::Inside => "inside their declared ranges",
            Why::Unranged => "a parameter without a declared range may take any value",
        }
    }
}

/// How many settings an effort checks: points inside each range alone, random points of the
/// box of ranges (two or more ranged parameters), and the most settings in all (each compiles
/// the scene once more and samples its annotations).
fn sizes(effort: Effort) -> (usize, usize, usize) {
    match effort {
        Effort::Fast => (3, 4, 32),
        Effort::Thorough => (7, 24, 80),
    }
}

/// The parameters (indices into `scene.params`) that some annotated node's subtree reads:
/// only they can make an annotation wrong.
fn read_by_annotations(scene: &Scene) -> BTreeSet<usize> {
    annotated(scene)
        .into_iter()
        .flat_map(|id| reads(scene, id))
        .collect()
}

/// Whether node `id`'s subtree reads one of the parameters `values` sets: at those values only
/// such annotated shapes can change.
fn reads_any(scene: &Scene, values: &Values, id: NodeId) -> bool {
    reads(scene, id)
        .into_iter()
        .any(|i| values.contains_key(&scene.params[i].name))
}

/// The parameters node `id`'s subtree reads.
fn reads(scene: &Scene, id: NodeId) -> BTreeSet<usize> {
    let mut read = BTreeSet::new();
    let mut stack = vec![id];
    let mut seen = BTreeSet::new();
    while let Some(id) = stack.pop() {
        if !seen.insert(id) {
            continue;
        }
        let node = &scene.nodes[id];
        let mut note = |r: &crate::catalog::field::ParamRef| {
            read.insert(r.index);
        };
        match &node.kind {
            NodeKind::Implicit { field } => field.params(&mut note),
            NodeKind::Primitive { ctx, .. } | NodeKind::Operator { ctx, .. } => {
                for f in ctx.sym.iter().flatten().flatten() {
                    f.params(&mut note);
                }
            }
        }
        stack.extend(node.children());
    }
    read
}

/// Values that test an annotation against a parameter without a range (as the catalog's rules
/// are tested, `check/ranges.rs`).
fn perturbed(x: f64) -> [f64; 6] {
    [x + 1.0, x - 1.0, 2.0 * x + 1.0, -x, 0.5 * x, 10.0 * x + 3.0]
}

/// Most ranged components whose every corner is a setting (16 corners).
const MAX_CORNER_DIMS: usize = 4;

/// The settings to check, in order: the values asked for; the corners of the box of ranges of
/// the parameters annotations read (its lowest and highest corners only, past four ranged
/// components); each component alone at either end; each parameter without a range
/// perturbed; each component alone at points inside its range; random points of the box.
fn settings(scene: &Scene, asked: &Values, effort: Effort) -> Vec<(Values, Why)> {
    let read = read_by_annotations(scene);
    let used: Vec<&ParamDecl> = read
        .iter()
        .map(|&i| &scene.params[i])
        .filter(|p| p.kind != ParamKind::Color)
        .collect();
    // (parameter, component) of every ranged component.
    let dims: Vec<(&ParamDecl, usize)> = used
        .iter()
        .filter(|p| p.range.is_some())
        .flat_map(|&p| (0..p.kind.components()).map(move |c| (p, c)))
        .collect();
    let (inside, random, most) = sizes(effort);
    let mut out = Vec::new();
    if !asked.is_empty() && !read.is_empty() {
        out.push((asked.clone(), Why::Asked));
    }
    // A setting from a value in [0, 1] per dimension (the fraction of its range; `None`: the
    // parameter's own value).
    let setting = |t: &dyn Fn(usize) -> Option<f64>| -> Values {
        let mut v = Values::new();
        for (k, &(p, c)) in dims.iter().enumerate() {
            if let Some(t) = t(k) {
                let (lo, hi) = p.range.expect("ranged");
                let e = v.entry(p.name.clone()).or_insert_with(|| p.values());
                e[c] = lo[c] + (hi[c] - lo[c]) * t;
            }
        }
        v
    };
    let corners: Vec<usize> = if dims.len() <= MAX_CORNER_DIMS {
        (0..1usize << dims.len()).collect()
    } else {
        vec![0, (1usize << MAX_CORNER_DIMS) - 1]
    };
    if dims.len() > 1 {
        for bits in corners {
            let high = |k: usize| {
                Some(if bits >> k.min(MAX_CORNER_DIMS - 1) & 1 == 1 {
                    1.0
                } else {
                    0.0
                })
            };
            out.push((setting(&high), Why::Ends));
        }
    }
    for k in 0..dims.len() {
        for t in [0.0, 1.0] {
            out.push((setting(&|i| (i == k).then_some(t)), Why::Ends));
        }
    }
    for p in used.iter().filter(|p| p.range.is_none()) {
        for k in 0..6 {
            let v = p.values().iter().map(|&x| perturbed(x)[k]).collect();
            out.push((HashMap::from([(p.name.clone(), v)]), Why::Unranged));
        }
    }
    for k in 0..dims.len() {
        for i in 1..=inside {
            let t = i as f64 / (inside + 1) as f64;
            out.push((setting(&|j| (j == k).then_some(t)), Why::Inside));
        }
    }
    if dims.len() > 1 {
        let mut rng = Rng(0x7a6e_5e77_1e55_0001);
        for _ in 0..random {
            let t: Vec<f64> = dims.iter().map(|_| rng.unit()).collect();
            out.push((setting(&|k| Some(t[k])), Why::Inside));
        }
    }
    out.truncate(most);
    out
}

/// The annotation warnings a check gives: at the scene's own values ([`verify_annotations`]),
/// then at other values over the parameters' ranges ([`verify_over_ranges`], `asked` the values
/// asked for, `compile_at` checking the source at given values).
pub fn verify_everywhere(
    compile_at: &dyn Fn(&Values) -> Option<Scene>,
    scene: &Scene,
    effort: Effort,
    asked: &Values,
) -> Vec<Diagnostic> {
    let mut found = super::verify_annotations(scene, effort);
    let more = verify_over_ranges(compile_at, scene, effort, (asked, &found));
    found.extend(more);
    found
}

/// The annotation warnings found at other parameter values than the defaults' (`seen`: the
/// defaults' own, not repeated), each with a note saying at which values and why those;
/// `compile_at` checks the scene's source at given values (`None` where it does not check).
pub fn verify_over_ranges(
    compile_at: &dyn Fn(&Values) -> Option<Scene>,
    scene: &Scene,
    effort: Effort,
    (asked, seen): (&Values, &[Diagnostic]),
) -> Vec<Diagnostic> {
    if annotated(scene).is_empty() {
        return Vec::new();
    }
    let mut out: Vec<Diagnostic> = Vec::new();
    let settings = settings(scene, asked, effort);
    // The settings share one check's work (a large scene gets fewer points at each).
    let work = WORK / settings.len().max(1);
    for (values, why) in settings {
        let Some(at) = compile_at(&values) else {
            continue;
        };
        // Only the annotated shapes that read the parameters set here can change.
        for d in verify_where(&at, effort, &|id| reads_any(&at, &values, id), work) {
            // (How fast rays arrive matters where they are traced: at the values asked for.)
            if why != Why::Asked && !d.message.contains("too small") {
                continue;
            }
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
                    let v: Vec<String> = v.iter().map(|&x| six_digits(x)).collect();
                    format!("{k} = {}", v.join(", "))
                })
                .collect();
            shown.sort();
            let mut d = d.note(format!("found with {} ({})", shown.join("; "), why.say()));
            if why == Why::Unranged {
                let names: Vec<&str> = values.keys().map(String::as_str).collect();
                d = d.help(format!(
                    "declare the range `{}` may take (`param {} = … in LOW..HIGH`): the bound is then checked over it",
                    names.join("`, `"),
                    names[0]
                ));
            }
            out.push(d);
        }
    }
    out
}

/// A value with at most six significant digits (`2.5`, `1.12346`).
fn six_digits(x: f64) -> String {
    let r: f64 = format!("{x:.5e}").parse().unwrap_or(x);
    format!("{r}")
}

/// The annotations too small at `values` (the quick check of the scene with its parameters
/// set, λ and bounds as checked; only those whose shapes read a parameter set, and nothing is
/// done when none does): what the viewer's keys and the frames of an animation are checked by.
pub fn too_small_at(scene: &Scene, values: &Values) -> Vec<Diagnostic> {
    let touched = |id: NodeId| reads_any(scene, values, id);
    if !annotated(scene).into_iter().any(touched) {
        return Vec::new();
    }
    // (`with_values` keeps the nodes: the same ones read the same parameters.)
    let mut found = verify_where(&scene.with_values(values), Effort::Fast, &touched, WORK);
    found.retain(|d| d.message.contains("too small"));
    found
}
