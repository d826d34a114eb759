//! `repeat` with neighbours: which copies of the shape an evaluation looks at, so that the
//! repeated field is the union of every copy for any shape (Inigo Quilez, "domain repetition":
//! a shape that is not symmetric about its cell, or overflows it, needs the neighbouring cells).
//!
//! Per repeated axis (spacing s; the shape's extent [lo, hi] along it, from its bounding box):
//! - **own cell** when the shape fits its cell (−s/2 ≤ lo, hi ≤ s/2) and is symmetric under
//!   reflection of that coordinate: every other copy is the mirror image of the own one across a
//!   plane between them, so the own copy is the nearest (the folded field is exact);
//! - **every copy** when a finite count is no more than the window below would be;
//! - otherwise a **window** from K₋ = ⌊(x − hi)/s⌋, the last copy whose extent ends at or before
//!   the point, to K₊ = ⌈(x − lo)/s⌉, the first that starts at or after it (x measured from the
//!   first copy's centre). A copy k beyond K₊ is never nearer than K₊: the point of copy K₊ that
//!   corresponds to the nearest point of copy k lies (k − K₊)·s closer along the axis and still
//!   on the far side of the point, so it is nearer (likewise below K₋). The window holds at most
//!   ⌊(hi − lo)/s⌋ + 3 copies, unrolled; no copy outside it is nearer, so the result is the
//!   union's field for exact shapes, and a bound at every point for any shape.

use super::traits::Copies;
use super::{Bound, ChildEval, Ctx};
use crate::diag::{Diagnostic, Span};
use glam::{DVec2, DVec3};
use std::f64::consts::{PI, TAU};

/// The most copies one evaluation of a `repeat` may look at; the checker refuses more.
pub const MAX_COPIES: usize = 64;

/// How one axis of a `repeat` is evaluated.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum AxisPlan {
    /// Not repeated along this axis (spacing 0).
    Plain,
    /// The own cell only.
    Own,
    /// Every copy (a finite count).
    All,
    /// This many copies from K₋ on (clamped to the existing ones).
    Window(u32),
}

/// The evaluation plan of one `repeat` node.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Plan {
    /// Spacing per axis (0: not repeated).
    pub spacing: DVec3,
    /// Copies per axis (0: without end).
    pub count: DVec3,
    /// How each axis is evaluated.
    pub axes: [AxisPlan; 3],
    /// The shape's box (its extent along each axis around its cell's centre).
    pub lo: DVec3,
    /// The shape's box, upper corner.
    pub hi: DVec3,
}

impl Plan {
    /// The plan for a `repeat` node's arguments and child.
    pub fn new(c: &Ctx) -> Plan {
        let (spacing, count) = (c.vec(0), c.vec(1));
        let b = c.child_bound[0];
        let axes = [0, 1, 2].map(|i| {
            let s = spacing[i];
            if s <= 0.0 {
                return AxisPlan::Plain;
            }
            let (lo, hi) = (b.lo[i], b.hi[i]);
            if !(lo.is_finite() && hi.is_finite()) {
                // A shape without end along the axis: no window holds its copies (λ is then
                // infinite and the node annotated); the own cell.
                return AxisPlan::Own;
            }
            if c.child_mirror[0][i] && lo >= -s / 2.0 && hi <= s / 2.0 {
                return AxisPlan::Own;
            }
            // (An empty shape, whose box is inverted, still takes one copy.)
            let window = (((hi - lo) / s).floor() + 3.0).max(1.0);
            let n = count[i];
            if n > 0.0 && n <= window {
                AxisPlan::All
            } else {
                AxisPlan::Window(window.min(f64::from(u32::MAX / 4)) as u32)
            }
        });
        Plan {
            spacing,
            count,
            axes,
            lo: b.lo,
            hi: b.hi,
        }
    }

    /// How many copies one evaluation looks at.
    pub fn copies(&self) -> f64 {
        (0..3)
            .map(|i| match self.axes[i] {
                AxisPlan::Window(n) => f64::from(n),
                AxisPlan::All => self.count[i],
                _ => 1.0,
            })
            .product()
    }

    /// Half the number of copies less one along axis `i` (0 without a count): the index of
    /// the copy at the centre.
    pub fn half(&self, i: usize) -> f64 {
        let n = self.count[i];
        if n == 0.0 { 0.0 } else { (n - 1.0) / 2.0 }
    }

    /// The centre of copy `k` along axis `i` (k counts from 0 for a finite count).
    pub fn center(&self, i: usize, k: f64) -> f64 {
        (k - self.half(i)) * self.spacing[i]
    }

    /// The index of the copy whose cell holds coordinate `x` along axis `i`.
    pub fn cell(&self, i: usize, x: f64) -> f64 {
        let k = round_half_up(x / self.spacing[i] + self.half(i));
        self.clamp(i, k)
    }

    /// The first copy of the window along axis `i` for coordinate `x`: K₋ (not clamped).
    pub fn first(&self, i: usize, x: f64) -> f64 {
        ((x - self.hi[i]) / self.spacing[i] + self.half(i)).floor()
    }

    /// The copy index `k` clamped to the existing copies along axis `i`.
    pub fn clamp(&self, i: usize, k: f64) -> f64 {
        let n = self.count[i];
        if n == 0.0 { k } else { k.clamp(0.0, n - 1.0) }
    }

    /// Coordinate `x` along axis `i` relative to each copy the plan looks at, in order.
    pub fn local(&self, i: usize, x: f64) -> Vec<f64> {
        match self.axes[i] {
            AxisPlan::Plain => vec![x],
            AxisPlan::Own => vec![x - self.center(i, self.cell(i, x))],
            AxisPlan::All => (0..self.count[i] as u32)
                .map(|k| x - self.center(i, f64::from(k)))
                .collect(),
            AxisPlan::Window(n) => {
                let first = self.first(i, x);
                (0..n)
                    .map(|j| x - self.center(i, self.clamp(i, first + f64::from(j))))
                    .collect()
            }
        }
    }
}

/// The repeated field at `p`: the smallest of the copies the plan looks at (a raw field, with
/// the child's λ).
pub fn field(c: &Ctx, p: DVec3, child: ChildEval) -> f64 {
    let plan = Plan::new(c);
    let [xs, ys, zs] = [0, 1, 2].map(|i| plan.local(i, p[i]));
    let mut d = f64::INFINITY;
    for &x in &xs {
        for &y in &ys {
            for &z in &zs {
                d = d.min(child(0, DVec3::new(x, y, z)));
            }
        }
    }
    d
}

/// floor(x + 0.5): the rounding the shaders use too, so cells agree at exact halves.
pub fn round_half_up(x: f64) -> f64 {
    (x + 0.5).floor()
}

/// `repeat`'s copies per evaluation: its plan's; more than [`MAX_COPIES`] is an error.
pub const COPIES: Copies = Copies {
    count: |c| Plan::new(c).copies(),
    diagnose: too_many_cells,
};

fn too_many_cells(c: &Ctx, copies: f64, span: Span) -> Vec<Diagnostic> {
    if copies <= MAX_COPIES as f64 {
        return Vec::new();
    }
    let size = c.child_bound[0].hi - c.child_bound[0].lo;
    let s = c.vec(0);
    vec![
        Diagnostic::error(span, "the repeated shape spans too many cells")
            .label(format!(
                "each evaluation would look at {copies:.0} copies (the shape is {:.3} × {:.3} × {:.3}, the spacing {} × {} × {})",
                size.x, size.y, size.z, s.x, s.y, s.z
            ))
            .note(format!("at most {MAX_COPIES} copies are evaluated per point"))
            .help("use a larger spacing, or a smaller shape"),
    ]
}

/// `repeat_polar`'s copies per evaluation: its plan's; more than [`MAX_COPIES`] is an error,
/// and every copy of an unbounded shape a warning.
pub const POLAR_COPIES: Copies = Copies {
    count: polar_copies,
    diagnose: too_many_sectors,
};

fn too_many_sectors(c: &Ctx, copies: f64, span: Span) -> Vec<Diagnostic> {
    let mut out = Vec::new();
    if copies > MAX_COPIES as f64 {
        out.push(
            Diagnostic::error(span, "the turned shape spans too many sectors")
                .label(format!("each evaluation would look at {copies:.0} copies"))
                .note(format!("at most {MAX_COPIES} copies are evaluated per point; a shape around the y axis needs every copy"))
                .help("use fewer copies, or move the shape away from the axis (`at (r, 0, 0)`)"),
        );
    }
    if copies > 4.0 && !c.child_bound[0].is_finite() {
        out.push(
            Diagnostic::warning(span, format!("every one of the {copies:.0} copies is evaluated at every point"))
                .label("the shape's bound is not known")
                .note("with a bounded shape only the own sector, or the few copies that can be nearest, are evaluated; a smooth blend, `round` or `onion` of a shape whose field is not a distance has no bound")
                .help("use `union` instead of a smooth blend inside the repeated shape"),
        );
    }
    out
}

/// How a `repeat_polar` node is evaluated.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum PolarPlan {
    /// The own sector only.
    Own,
    /// Every copy.
    All,
    /// This many copies from K₋ on.
    Window(u32),
}

/// `repeat_polar`: the angle between copies and the plan for a node (`catalog/polar.rs` says
/// why the window holds the nearest copy).
pub fn polar_plan(c: &Ctx) -> (f64, PolarPlan) {
    let n = c.num(0).max(1.0);
    let alpha = TAU / n;
    let Some((lo, hi)) = polar_extent(c.child_bound[0]) else {
        return (alpha, PolarPlan::All);
    };
    if c.child_mirror[0][2] && lo >= -alpha / 2.0 && hi <= alpha / 2.0 {
        return (alpha, PolarPlan::Own);
    }
    let window = ((hi - lo) / alpha).floor() + 3.0;
    if n <= window {
        (alpha, PolarPlan::All)
    } else {
        (alpha, PolarPlan::Window(window as u32))
    }
}

/// How many copies one evaluation looks at.
pub fn polar_copies(c: &Ctx) -> f64 {
    match polar_plan(c).1 {
        PolarPlan::Own => 1.0,
        PolarPlan::All => c.num(0),
        PolarPlan::Window(w) => f64::from(w),
    }
}

/// The angles about the y axis (from +x towards +z) the bound spans, if it keeps away from
/// the axis: the tighter of its box's corners and its sphere's cone.
pub fn polar_extent(b: Bound) -> Option<(f64, f64)> {
    if !b.is_finite() {
        return None;
    }
    let mut best: Option<(f64, f64)> = None;
    let mut narrow = |lo: f64, hi: f64| {
        best = Some(match best {
            Some((a, b)) => (a.max(lo), b.min(hi)),
            None => (lo, hi),
        });
    };
    // The rectangle of the box in xz, when the axis is outside it.
    let (x0, x1, z0, z1) = (b.lo.x, b.hi.x, b.lo.z, b.hi.z);
    if x0 > 0.0 || x1 < 0.0 || z0 > 0.0 || z1 < 0.0 {
        let centre = DVec2::new((x0 + x1) / 2.0, (z0 + z1) / 2.0);
        let mid = centre.y.atan2(centre.x);
        let rel = [(x0, z0), (x0, z1), (x1, z0), (x1, z1)].map(|(x, z)| wrap(z.atan2(x) - mid));
        let lo = rel.iter().copied().fold(f64::INFINITY, f64::min);
        let hi = rel.iter().copied().fold(f64::NEG_INFINITY, f64::max);
        narrow(mid + lo, mid + hi);
    }
    // The cone of the sphere seen from the axis, when the axis is outside it.
    let r = DVec2::new(b.center.x, b.center.z).length();
    if r > b.radius {
        let mid = b.center.z.atan2(b.center.x);
        let half = (b.radius / r).asin();
        narrow(mid - half, mid + half);
    }
    // The two descriptions of the same region overlap: their intersection is the extent (it
    // may straddle ±π, the copies' angles are taken modulo a turn).
    best.filter(|(lo, hi)| lo <= hi)
}

/// An angle moved into (−π, π].
fn wrap(a: f64) -> f64 {
    let w = a - TAU * ((a + PI) / TAU).floor();
    if w <= -PI { w + TAU } else { w }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::{PI, TAU};

    #[test]
    fn wrap_keeps_angles_in_a_half_turn() {
        for a in [-7.0, -PI, -1.0, 0.0, 1.0, PI, 4.0, 10.0] {
            let w = wrap(a);
            assert!(w > -PI && w <= PI, "{a} → {w}");
            assert!(((w - a) / TAU - ((w - a) / TAU).round()).abs() < 1e-12);
        }
    }

    #[test]
    fn extent_of_a_box_beside_the_axis() {
        let b = Bound::centered_box(DVec3::splat(0.5)).moved(DVec3::new(2.0, 0.0, 0.0));
        let (lo, hi) = polar_extent(b).expect("away from the axis");
        assert!((hi - (0.5f64).atan2(1.5)).abs() < 1e-12, "{hi}");
        assert!((lo + hi).abs() < 1e-12);
        assert!(polar_extent(Bound::origin(1.0)).is_none());
    }
}
