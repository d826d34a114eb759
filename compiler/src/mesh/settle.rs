//! A polygon's vertex settled on the surface: Newton steps from where the QEF put it, kept in
//! its cell, all cells' searches in lockstep batches.

use super::field::Field;
use super::search::{self, Search};
use glam::DVec3;

/// The |d| below which a point is on the surface, in a grid of cells of `h`.
pub fn on_surface(field: &Field, h: f64) -> f64 {
    (1e-7 * h).max(field.resolution())
}

/// The Newton steps a [`Settle`] takes at most.
const PROJECTION_STEPS: usize = 8;

/// Newton steps of the QEF's point onto the surface (p − d·∇d, the nearest surface point for
/// an exact field), kept in the cell: where the sheet in a cell shows only two of a corner's
/// three faces, the QEF puts the point on the crease's line past the corner, and the step
/// brings it back to the corner. A point the QEF put outside the cell is clamped to the cell's
/// side and moves within that side (the surface's point there nearest a corner just outside).
/// A point already on the surface does not move; a step that does not bring it nearer ends.
pub struct Settle {
    /// The point and the field there.
    pub p: DVec3,
    d: f64,
    /// The cell.
    lo: DVec3,
    hi: DVec3,
    /// 1 along the axes the point may move on, 0 along those it was clamped on.
    free: DVec3,
    steps: usize,
    /// On the surface below this |d|.
    tol: f64,
    /// The gradient's sample distance.
    step: f64,
    phase: Phase,
    /// Where to start again should this start not reach the surface (the QEF's own point,
    /// where a crease's point was tried first: the crease's line leaves the surface past a
    /// corner).
    or: Option<DVec3>,
    /// The point nearest the surface so far, and the field there.
    best: Option<(DVec3, f64)>,
}

/// What a [`Settle`] asks for next.
#[derive(Clone, Copy)]
enum Phase {
    Value,
    Normal,
    Try(DVec3),
    Done,
}

impl Settle {
    pub fn new(field: &Field, (p, or): (DVec3, Option<DVec3>), lo: DVec3, h: f64) -> Settle {
        let mut settle = Settle {
            free: DVec3::ONE,
            p,
            d: f64::NAN,
            lo,
            hi: lo + h,
            steps: 0,
            tol: on_surface(field, h),
            step: field.gradient_step(h),
            phase: Phase::Value,
            or,
            best: None,
        };
        settle.from(p);
        settle
    }

    /// Starts from `p`, clamped to the cell.
    fn from(&mut self, p: DVec3) {
        let (lo, hi) = (self.lo, self.hi);
        self.free = DVec3::select(p.cmplt(lo) | p.cmpgt(hi), DVec3::ZERO, DVec3::ONE);
        self.p = p.clamp(lo, hi);
        self.steps = 0;
        self.phase = Phase::Value;
    }

    /// Done: or, off the surface with another start left, that start next; the point nearest
    /// the surface is kept.
    fn done(&mut self) -> Phase {
        if self.best.is_none_or(|(_, d)| self.d.abs() < d.abs()) {
            self.best = Some((self.p, self.d));
        }
        // (NaN is off the surface.)
        let on = self.d.abs() <= self.tol;
        match self.or.take() {
            Some(q) if !on => {
                self.from(q);
                Phase::Value
            }
            _ => {
                (self.p, self.d) = self.best.unwrap_or((self.p, self.d));
                Phase::Done
            }
        }
    }

    /// Where steps within the cell's side no longer bring the point nearer the surface (the
    /// surface does not meet that side near it: a crease leaving the cell elsewhere), the steps
    /// go on along every axis; else done.
    fn unfreeze(&mut self) -> Phase {
        match self.free == DVec3::ONE {
            true => self.done(),
            false => {
                self.free = DVec3::ONE;
                Phase::Normal
            }
        }
    }

    /// After a value: done, or the gradient next.
    fn next(&mut self) {
        let stop = self.steps == PROJECTION_STEPS || self.d.is_nan() || self.d.abs() <= self.tol;
        self.phase = if stop { self.done() } else { Phase::Normal };
    }
}

impl Search for Settle {
    fn ask(&self, points: &mut Vec<DVec3>) {
        match self.phase {
            Phase::Value => points.push(self.p),
            Phase::Normal => search::gradient_points(self.p, self.step, points),
            Phase::Try(q) => points.push(q),
            Phase::Done => {}
        }
    }

    fn tell(&mut self, values: &[f64]) {
        match self.phase {
            Phase::Value => {
                self.d = values[0];
                self.next();
            }
            Phase::Normal => {
                let n = search::unit_gradient(values) * self.free;
                let g = n.length_squared();
                self.phase = match g < 1e-6 {
                    true => self.unfreeze(),
                    false => Phase::Try((self.p - n * (self.d / g)).clamp(self.lo, self.hi)),
                };
            }
            Phase::Try(q) => {
                let dq = values[0];
                self.steps += 1;
                if dq.is_nan() || dq.abs() >= self.d.abs() {
                    self.phase = self.unfreeze();
                } else {
                    (self.p, self.d) = (q, dq);
                    self.next();
                }
            }
            Phase::Done => {}
        }
    }
}
