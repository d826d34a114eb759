//! The searches along one grid edge, in lockstep batches: where the surface crosses it
//! ([`Root`]) and whether the field dips across it between ends on one side ([`Dip`]).

use super::field::{Field, inside};
use super::search::{self, Illinois, Search};
use glam::{DVec3, IVec3};

/// The iterations of the search for a crossing along an edge (Illinois regula falsi; f64
/// reaches its tolerance in far fewer on a smooth field).
const ROOT_STEPS: usize = 48;

/// A crossing is kept this fraction of the edge away from its ends, so that a corner exactly
/// on the surface does not give several crossings the same position.
const END_GAP: f64 = 1e-4;

/// The distance between the samples of a crossing's normal in cells of `h`: on the CPU a
/// millionth of a cell, a hundredth of [`Field::gradient_step`] — a crease passing nearer the
/// crossing than the samples' spread gives it a blend of its two planes' normals, and where
/// two or three corners share a cell that blend was one plane too many (the capped turned box
/// at 53.8 cells: one cell 2.4e-3 off at a ten-thousandth of a cell; 3.5e-7 at this); on the
/// GPU the batches' step (f32 resolves no finer; [`super::edges::sharpen`] takes the normals
/// that matter again on the CPU).
pub fn normal_step(field: &Field, h: f64) -> f64 {
    match field.batched() {
        true => field.gradient_step(h),
        false => 1e-2 * field.gradient_step(h),
    }
}

/// The evaluations a [`Dip`] spends at most on one edge (8 missed a box's crease poking a
/// hundredth of a cell through an edge near its end, which 16 finds; 16 missed one 0.003 of a
/// cell through, which 32 finds; 64 found no more on the turned box at 168 placements).
const DIP_STEPS: usize = 32;

/// The search, along an edge whose ends lie on the same side, for a point on the other side:
/// the field being 1-Lipschitz, |d| over a stretch from s to t is at least the lower of the
/// two cones |d(s)| − (x − s) and |d(t)| − (t − x), lowest where they meet, at
/// (|d(s)| + |d(t)| − (t − s)) / 2. The stretch of the lowest such bound is sampled next where
/// its cones meet (Piyavskii's and Shubert's search for a Lipschitz function's minimum), the
/// stretches the bound keeps on the ends' side dropped, until a point on the other side is
/// found, none is left or [`DIP_STEPS`] are spent. (Halving the stretches instead missed the
/// dip of a crease passing 0.04 of a cell from an edge: the smaller end drew the search away.)
pub struct Dip {
    /// The edge's start, extent, and the field at its ends.
    a: DVec3,
    along: DVec3,
    pub ends: (f64, f64),
    /// The grid edge.
    pub edge: (IVec3, usize),
    /// The ends' side.
    side: bool,
    /// The stretches not yet ruled out: parameters and the field there.
    open: Vec<(f64, f64, f64, f64)>,
    steps: usize,
    /// The shortest stretch halved (f32's resolution on the GPU).
    shortest: f64,
    /// The point found on the other side: its parameter and the field there.
    pub found: Option<(f64, f64)>,
}

impl Dip {
    pub fn new(
        field: &Field,
        a: DVec3,
        along: DVec3,
        ends: (f64, f64),
        edge: (IVec3, usize),
    ) -> Dip {
        Dip {
            a,
            along,
            ends,
            edge,
            side: inside(ends.0),
            open: vec![(0.0, ends.0, 1.0, ends.1)],
            steps: 0,
            shortest: (2.0 * field.resolution() / along.length()).max(1e-6),
            found: None,
        }
    }

    /// The open stretch nearest to holding a dip (its ends' distances least over its length).
    fn next(&self) -> Option<usize> {
        let len = self.along.length();
        let low = |&(t0, d0, t1, d1): &(f64, f64, f64, f64)| d0.abs() + d1.abs() - (t1 - t0) * len;
        (0..self.open.len()).min_by(|&i, &j| low(&self.open[i]).total_cmp(&low(&self.open[j])))
    }

    /// Where the cones of the stretch from `t0` to `t1` meet, kept a twentieth of it off its
    /// ends.
    fn apex(&self, (t0, d0, t1, d1): (f64, f64, f64, f64)) -> f64 {
        let meet = 0.5 * (t0 + t1) + (d0.abs() - d1.abs()) / (2.0 * self.along.length());
        let margin = 0.05 * (t1 - t0);
        meet.clamp(t0 + margin, t1 - margin)
    }
}

impl Search for Dip {
    fn ask(&self, points: &mut Vec<DVec3>) {
        if self.found.is_some() || self.steps == DIP_STEPS {
            return;
        }
        if let Some(i) = self.next() {
            points.push(self.a + self.along * self.apex(self.open[i]));
        }
    }

    fn tell(&mut self, values: &[f64]) {
        let Some(i) = self.next() else { return };
        let (t0, d0, t1, d1) = self.open.swap_remove(i);
        let (tm, dm) = (self.apex((t0, d0, t1, d1)), values[0]);
        self.steps += 1;
        if inside(dm) != self.side && !dm.is_nan() {
            self.found = Some((tm, dm));
            return;
        }
        let len = self.along.length();
        for (s0, e0, s1, e1) in [(t0, d0, tm, dm), (tm, dm, t1, d1)] {
            // (NaN fails the test and is dropped.)
            if e0.abs() + e1.abs() < (s1 - s0) * len && s1 - s0 > self.shortest {
                self.open.push((s0, e0, s1, e1));
            }
        }
    }
}

/// The search for where the surface crosses a grid edge (or a part of one) from `a` (field
/// `fa`) to the point of field `fb`: Illinois regula falsi on the side change, kept [`END_GAP`] off
/// the ends; then the unit normal there.
pub struct Root {
    /// The edge's start and its extent.
    a: DVec3,
    along: DVec3,
    /// The bracket: parameters along the edge and the field there.
    bracket: Illinois<f64>,
    /// The parameter evaluated next.
    t: f64,
    steps: usize,
    /// Stop once |f| or the bracket's length in scene units is below these.
    tol_f: f64,
    tol_t: f64,
    /// The gradient's sample distance.
    step: f64,
    pub stage: Stage,
}

/// Where a [`Root`] search is.
pub enum Stage {
    Root,
    Normal(DVec3),
    Done(DVec3, DVec3),
}

impl Root {
    /// The search along `along` from `a` (field `fa`) to `a + along` (field `fb`), on a grid of
    /// cells `h`.
    pub fn new(field: &Field, h: f64, (a, fa): (DVec3, f64), along: DVec3, fb: f64) -> Root {
        let res = field.resolution();
        let mut root = Root {
            a,
            along,
            bracket: Illinois::new((0.0, fa), (1.0, fb)),
            t: 0.5,
            steps: 0,
            tol_f: (1e-9 * h).max(res),
            tol_t: 1e-9f64.max(res / along.length()),
            step: normal_step(field, h),
            stage: Stage::Root,
        };
        root.guess();
        root
    }

    /// Takes the field `f` at the parameter asked for: the bracket narrowed (Illinois), or the
    /// root taken and its normal asked for next.
    fn step(&mut self, f: f64) {
        let t = self.t;
        self.steps += 1;
        let short = self.bracket.hi.0 - self.bracket.lo.0 < self.tol_t;
        if f.abs() < self.tol_f || short || self.steps == ROOT_STEPS {
            let p = self.a + self.along * t.clamp(END_GAP, 1.0 - END_GAP);
            self.stage = Stage::Normal(p);
            return;
        }
        self.bracket.narrow(t, f);
        self.guess();
    }

    /// The next parameter: the secant's root inside the bracket, else its middle.
    fn guess(&mut self) {
        let ((t0, f0), (t1, f1)) = (self.bracket.lo, self.bracket.hi);
        let guess = (t0 * f1 - t1 * f0) / (f1 - f0);
        self.t = if guess.is_finite() && guess > t0 && guess < t1 {
            guess
        } else {
            0.5 * (t0 + t1)
        };
    }
}

impl Search for Root {
    fn ask(&self, points: &mut Vec<DVec3>) {
        match self.stage {
            Stage::Root => points.push(self.a + self.along * self.t),
            Stage::Normal(p) => search::gradient_points(p, self.step, points),
            Stage::Done(..) => {}
        }
    }

    fn tell(&mut self, values: &[f64]) {
        match self.stage {
            Stage::Root => self.step(values[0]),
            Stage::Normal(p) => self.stage = Stage::Done(p, search::unit_gradient(values)),
            Stage::Done(..) => {}
        }
    }
}
