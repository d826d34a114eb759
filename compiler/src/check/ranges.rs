//! A node's catalog rules (λ, bound, symmetry, exactness) over every value its parameters may
//! take: the largest λ, the hull of the bounds, the symmetries and exactness all values share.

use super::Checker;
use crate::catalog::{Bound, Ctx, Operator, Primitive};
use crate::diag::{Diagnostic, Span};
use crate::scene::ParamRef;

/// What a node's catalog rules give at one set of argument values.
#[derive(Clone, Copy, Debug)]
pub(super) struct Rules {
    pub lambda: f64,
    pub bound: Bound,
    pub mirror: [bool; 3],
    pub swap: [bool; 3],
    pub unit: bool,
    pub exact: bool,
}

impl Rules {
    /// A primitive's rules.
    pub fn primitive(p: &Primitive, c: &Ctx) -> Rules {
        Rules {
            lambda: (p.lipschitz)(c),
            bound: (p.bound)(c),
            mirror: (p.mirror)(c),
            swap: (p.swap)(c),
            unit: (p.unit_gradient)(c),
            exact: p.exact,
        }
    }

    /// An operator's own rules (its children's exactness and gradients are the node's business).
    pub fn operator(o: &Operator, c: &Ctx) -> Rules {
        Rules {
            lambda: (o.lipschitz)(c),
            bound: (o.bound)(c),
            mirror: (o.mirror)(c),
            swap: (o.swap)(c),
            unit: (o.unit_gradient)(c),
            exact: (o.keeps_exact)(c),
        }
    }
}

/// Samples per ranged component when a node reads one or two of them (a 17 × 17 grid for two):
/// consecutive samples of an angle are then at most 1/16 of its range apart.
const GRID: usize = 17;
/// Random samples, besides the corners, when a node reads three or more ranged components.
const RANDOM: usize = 64;
/// Most ranged components one node may read: all its corners are sampled (a monotone rule's
/// extremes are at corners), 256 of them at most.
const MAX_CORNER_DIMS: usize = 8;

/// The parameter components a context reads, each once.
fn components(ctx: &Ctx) -> Vec<ParamRef> {
    let mut dims: Vec<ParamRef> = Vec::new();
    for f in ctx.sym.iter().flatten().flatten() {
        f.params(&mut |r| {
            if !dims.iter().any(|d| d.index == r.index && d.comp == r.comp) {
                dims.push(*r);
            }
        });
    }
    dims
}

/// Points of the box of ranges `dims` to evaluate rules at.
fn sample_points(dims: &[ParamRef]) -> Vec<Vec<f64>> {
    let d = dims.len();
    let lerp = |k: usize, t: f64| dims[k].lo + (dims[k].hi - dims[k].lo) * t;
    let step = |i: usize| i as f64 / (GRID - 1) as f64;
    match d {
        0 => Vec::new(),
        1 => (0..GRID).map(|i| vec![lerp(0, step(i))]).collect(),
        2 => (0..GRID * GRID)
            .map(|i| vec![lerp(0, step(i % GRID)), lerp(1, step(i / GRID))])
            .collect(),
        _ => {
            // Every corner (the callers refuse more than `MAX_CORNER_DIMS` components).
            let mut pts = Vec::new();
            for corner in 0..1usize << d {
                pts.push(
                    (0..d)
                        .map(|k| lerp(k, ((corner >> k) & 1) as f64))
                        .collect(),
                );
            }
            // A fixed sequence, so that a scene checks the same every time.
            let mut state = 0x9e37_79b9_7f4a_7c15_u64;
            for _ in 0..RANDOM {
                pts.push(
                    (0..d)
                        .map(|k| {
                            state = state
                                .wrapping_mul(6_364_136_223_846_793_005)
                                .wrapping_add(1_442_695_040_888_963_407);
                            lerp(k, (state >> 11) as f64 / (1u64 << 53) as f64)
                        })
                        .collect(),
                );
            }
            pts
        }
    }
}

/// Points of the box of ranges `dims` off the grid of [`sample_points`], at fractions of the
/// golden ratio: symmetries that hold only at special values (a turn by a whole number of
/// eighth turns, equal components) hold at every grid point of a range like 0°..720°, not at
/// these. Only the symmetries and exactness are taken there.
fn generic_points(dims: &[ParamRef]) -> Vec<Vec<f64>> {
    const PHI: f64 = 0.618_033_988_749_894_9;
    (1..=4)
        .map(|k| {
            (0..dims.len())
                .map(|i| {
                    let t = ((k * (i + 1)) as f64 * PHI).fract();
                    dims[i].lo + (dims[i].hi - dims[i].lo) * t
                })
                .collect()
        })
        .collect()
}

/// Values that test whether a rule depends on a parameter without a range.
fn perturbed(x: f64) -> [f64; 6] {
    [x + 1.0, x - 1.0, 2.0 * x + 1.0, -x, 0.5 * x, 10.0 * x + 3.0]
}

impl Checker<'_> {
    /// `rules` over every value the context's parameters may take: λ the largest, the bound the
    /// hull of the bounds grown by half the largest distance between neighbouring samples'
    /// centres (exact for moves and scales, linear in their parameters, and enough for turns of
    /// up to 180° between samples), symmetries and exactness only where all values have them.
    /// A parameter without a range must not change λ (an error says so); if it changes the
    /// bound, the bound is infinite.
    pub(super) fn rules_over_ranges(
        &mut self,
        ctx: &Ctx,
        span: Span,
        what: &str,
        rules: &dyn Fn(&Ctx) -> Rules,
    ) -> Option<Rules> {
        let here = rules(ctx);
        if ctx.sym.iter().all(Option::is_none) {
            return Some(here);
        }
        let (ranged, free): (Vec<ParamRef>, Vec<ParamRef>) =
            components(ctx).into_iter().partition(ParamRef::ranged);
        if ranged.len() > MAX_CORNER_DIMS {
            self.diags.push(
                Diagnostic::error(span, format!("this `{what}` reads too many ranged parameter components"))
                    .label(format!("{} components (a vector is 3)", ranged.len()))
                    .note(format!(
                        "its Lipschitz bound and bounds are taken over every corner of the parameters' box, at most {MAX_CORNER_DIMS} components"
                    ))
                    .help("split it: move by one vector with `at`, then by the other"),
            );
            return None;
        }
        let mut out = here;
        let at_point = |pt: &[f64]| {
            let value = |r: &ParamRef| {
                ranged
                    .iter()
                    .position(|d| d.index == r.index && d.comp == r.comp)
                    .map_or(r.value, |k| pt[k])
            };
            rules(&ctx.at_values(&value))
        };
        let samples: Vec<Rules> = sample_points(&ranged)
            .iter()
            .map(|pt| at_point(pt))
            .collect();
        for s in &samples {
            out.lambda = out.lambda.max(s.lambda);
            out.bound = out.bound.union(s.bound);
            combine(&mut out, s);
        }
        for pt in generic_points(&ranged) {
            combine(&mut out, &at_point(&pt));
        }
        let some_side = (0..3).any(|i| out.bound.lo[i].is_finite() || out.bound.hi[i].is_finite());
        if (out.bound.is_finite() || some_side) && samples.len() > 1 {
            out.bound = out.bound.grown(sample_gap(&samples) / 2.0);
        }
        if let Err(d) = over_free_params(ctx, rules, &free, &here, &mut out) {
            let name = self.params[d.index].name.clone();
            self.diags.push(
                Diagnostic::error(
                    span,
                    format!("the Lipschitz bound of this `{what}` depends on `{name}`, which has no range"),
                )
                .label(format!("λ changes with `{name}`"))
                .note("λ must hold for every value the host may set")
                .help(format!(
                    "give `{name}` a range: `param {name} = … in low..high` (λ is then the largest over it)"
                )),
            );
            return None;
        }
        Some(out)
    }
}

/// Each parameter without a range, perturbed: the bound becomes infinite if it changes, and
/// symmetries and exactness must hold throughout; `Err` with the first parameter that
/// changes λ (which must not).
fn over_free_params(
    ctx: &Ctx,
    rules: &dyn Fn(&Ctx) -> Rules,
    free: &[ParamRef],
    here: &Rules,
    out: &mut Rules,
) -> Result<(), ParamRef> {
    for d in free.iter().copied() {
        for x in perturbed(d.value) {
            let value = |r: &ParamRef| {
                if r.index == d.index && r.comp == d.comp {
                    x
                } else {
                    r.value
                }
            };
            let s = rules(&ctx.at_values(&value));
            if (s.lambda - here.lambda).abs() > 1e-9 * here.lambda.abs().max(1.0)
                || !s.lambda.is_finite()
            {
                return Err(d);
            }
            if s.bound != here.bound {
                out.bound = Bound::INFINITE;
            }
            combine(out, &s);
        }
    }
    Ok(())
}

/// Half of this is how far the bound may move between a point of the ranges and its nearest
/// sample: the largest, over the samples, of the distance to the nearest other sample whose
/// bound differs.
fn sample_gap(samples: &[Rules]) -> f64 {
    // How far a bound moves between neighbouring samples: its centre, and each side
    // of its box (a shape turned about its own centre moves its box, not its centre);
    // the finite sides only (a 2D shape's box is finite in x and y).
    let step = |a: &Rules, b: &Rules| {
        let moved = |x: f64, y: f64| {
            if x.is_finite() && y.is_finite() {
                (x - y).abs()
            } else {
                0.0
            }
        };
        let sides = (0..3)
            .map(|i| moved(a.bound.lo[i], b.bound.lo[i]).max(moved(a.bound.hi[i], b.bound.hi[i])))
            .fold(0.0, f64::max);
        let centre = if a.bound.is_finite() && b.bound.is_finite() {
            (a.bound.center - b.bound.center).length()
        } else {
            0.0
        };
        centre.max(sides)
    };
    samples
        .iter()
        .map(|a| {
            samples
                .iter()
                .map(|b| step(a, b))
                .filter(|&d| d > 0.0)
                .fold(0.0_f64, |m, d| if m == 0.0 { d } else { m.min(d) })
        })
        .fold(0.0, f64::max)
}

/// Keeps only the symmetries and exactness both `out` and `s` have.
fn combine(out: &mut Rules, s: &Rules) {
    for i in 0..3 {
        out.mirror[i] &= s.mirror[i];
        out.swap[i] &= s.swap[i];
    }
    out.unit &= s.unit;
    out.exact &= s.exact;
}
