//! Many small searches run in lockstep, so that every round's field values are asked for in one
//! batch (the GPU evaluates them in one dispatch): a search says which points it needs next
//! and is told their values, until it needs none.

use super::field::{Field, inside};
use crate::reference::eval;
use glam::DVec3;

/// One search as a state machine over batches of points.
pub trait Search: Send {
    /// Appends the points whose values the next step needs; none when the search is done.
    fn ask(&self, points: &mut Vec<DVec3>);
    /// Takes the values of the points the last [`Search::ask`] appended, in order.
    fn tell(&mut self, values: &[f64]);
}

/// Runs every search of `searches` to its end, a round of [`Field::many`] per step; returns
/// the evaluations spent. On the CPU the searches run in chunks of [`CHUNK`], each chunk's
/// rounds on one core and the chunks on all (the values are the same: [`Field::many`] on the
/// CPU is [`Field::at`] at each point), so that their own steps run in parallel too — with a
/// cheap field those cost more than the evaluations.
pub fn run<S: Search>(field: &Field, searches: &mut [S]) -> usize {
    if field.batched() {
        return lockstep(searches, |points| field.many(points));
    }
    let each = |chunk: &mut [S]| {
        lockstep(chunk, |points| {
            points.iter().map(|&p| field.at(p)).collect()
        })
    };
    crate::parallel::par_chunks_mut(searches, CHUNK, each)
        .into_iter()
        .sum()
}

/// The searches one core runs in lockstep on the CPU.
const CHUNK: usize = 64;

/// Runs a search made by `make` from each of `items`, in batches (all of a batch's searches in
/// lockstep, as [`run`]), handing each ended search to `take` in `items`' order; returns the
/// evaluations spent. A fine mesh's searches need not all be in memory at once: the box less a
/// ball at 215 cells made 426 000 of its edge searches (160–184 bytes each, a dip's list of
/// stretches besides) together. The results are those of one batch (every search is its own).
pub fn run_batched<T: Sync, S: Search>(
    field: &Field,
    items: &[T],
    make: impl Fn(&T) -> S,
    mut take: impl FnMut(S),
) -> usize {
    // (The GPU's rounds cost a dispatch each: larger batches there.)
    let batch = if field.batched() { 1 << 18 } else { 1 << 15 };
    let mut evaluations = 0;
    for chunk in items.chunks(batch) {
        let mut searches: Vec<S> = chunk.iter().map(&make).collect();
        evaluations += run(field, &mut searches);
        searches.into_iter().for_each(&mut take);
    }
    evaluations
}

/// Runs `searches` to their end in rounds, each round's points evaluated by `many` at once.
fn lockstep<S: Search>(searches: &mut [S], many: impl Fn(&[DVec3]) -> Vec<f64>) -> usize {
    let mut open: Vec<usize> = (0..searches.len()).collect();
    let mut evaluations = 0;
    let mut points = Vec::new();
    // (search, its points' range) for every search that asked this round
    let mut asked: Vec<(usize, usize, usize)> = Vec::new();
    while !open.is_empty() {
        points.clear();
        asked.clear();
        open.retain(|&i| {
            let start = points.len();
            searches[i].ask(&mut points);
            let more = points.len() > start;
            if more {
                asked.push((i, start, points.len()));
            }
            more
        });
        if points.is_empty() {
            break;
        }
        let values = many(&points);
        evaluations += points.len();
        for &(i, start, end) in &asked {
            searches[i].tell(&values[start..end]);
        }
    }
    evaluations
}

/// Illinois regula falsi's bracket on a side change: its two ends (parameters or points, `P`)
/// with the field there, the value at an end left in place twice running halved, so that the
/// secant's root moves on toward it. [`edge_search::Root`](super::edge_search::Root) and
/// [`trace::Bracket`](super::trace::Bracket) place their next point from it, each by its own
/// secant.
#[derive(Clone, Copy, Debug)]
pub struct Illinois<P> {
    /// The low end (on the side the search started from) and the field there (scaled).
    pub lo: (P, f64),
    /// The high end and the field there (scaled).
    pub hi: (P, f64),
    /// Which end the last step replaced (−1 the low, 1 the high, 0 none yet).
    last: i8,
}

impl<P: Copy> Illinois<P> {
    /// The bracket from `lo` to `hi`, each with the field there.
    pub fn new(lo: (P, f64), hi: (P, f64)) -> Illinois<P> {
        Illinois { lo, hi, last: 0 }
    }

    /// Takes the field `f` at `x`, between the ends: `x` replaces the end on its side.
    pub fn narrow(&mut self, x: P, f: f64) {
        if inside(f) == inside(self.lo.1) {
            self.lo = (x, f);
            if self.last == -1 {
                self.hi.1 *= 0.5;
            }
            self.last = -1;
        } else {
            self.hi = (x, f);
            if self.last == 1 {
                self.lo.1 *= 0.5;
            }
            self.last = 1;
        }
    }
}

/// The four points whose values [`unit_gradient`] takes, at distance `step` around `p`.
pub fn gradient_points(p: DVec3, step: f64, points: &mut Vec<DVec3>) {
    points.extend(eval::gradient_points(p, step));
}

/// The unit gradient from the values at [`gradient_points`] (the reference's formula).
pub use eval::unit_gradient_of as unit_gradient;
