//! What an operator is to the checker's rewrites and checks and to the lowering, besides its
//! field: each stage reads these from the entry, so none matches on an operator's name.

use super::Ctx;
use crate::diag::{Diagnostic, Span};
use crate::ir::{Ex, FnBuilder};
use glam::DVec3;

/// An operator's traits; [`PLAIN`] for one with none.
#[derive(Clone, Copy)]
pub struct Traits {
    /// The motion of space it is, if any: the scale rewrite (`check/absorb.rs`) and lattice
    /// grouping (`check/lattice.rs`) reason about moves, turns and scales.
    pub motion: Motion,
    /// A union: copies of one shape on a lattice among its children are grouped into a
    /// `repeat` (`check/lattice.rs`), and its children get a bounding-volume tree (`prune`).
    pub groups: bool,
    /// What it does with 2D shapes.
    pub plane: Plane,
    /// For a repetition: how many copies of its shape one evaluation looks at.
    pub copies: Option<Copies>,
    /// A note for the error when its λ is unknown because its shape is not bounded.
    pub unbounded: Option<&'static str>,
    /// A function of the module its IR body calls, added once (`op_smooth_union(a, b, k)`).
    pub helper: Option<Helper>,
    /// Its shape is baked into a distance map when checked (`bake`): the shape may have no
    /// Lipschitz bound, must not read parameters, and is not evaluated by the field.
    pub bakes: bool,
    /// For a union, intersection or subtraction, hard or smooth: how it folds its children,
    /// which the scene as data (`crate::tape`) runs and prunes.
    pub fold: Option<Fold>,
}

/// How an operator folds its (normalised) children in order.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Fold {
    /// The largest value wins (an intersection, a subtraction), else the smallest.
    pub largest: bool,
    /// Smoothly, over the radius of its first argument.
    pub smooth: bool,
    /// The children after the first are negated (a subtraction).
    pub negates_later: bool,
}

/// The traits of an operator that is none of these things.
pub const PLAIN: Traits = Traits {
    motion: Motion::None,
    groups: false,
    plane: Plane::Solids,
    copies: None,
    unbounded: None,
    helper: None,
    bakes: false,
    fold: None,
};

/// A motion of space an operator is.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Motion {
    /// None of these.
    None,
    /// A move by its first argument (a vector).
    Move,
    /// A turn about its first argument (an axis) by its second (an angle).
    Turn,
    /// A scale by its first argument (a factor or a factor per axis).
    Scale,
}

/// What an operator does with 2D shapes (shapes in the xy plane, the same at every z).
#[derive(Clone, Copy)]
pub enum Plane {
    /// It works on solids only: a 2D child is an error.
    Solids,
    /// Its children are all 2D or all solids, and so is its result.
    Keeps,
    /// As `Keeps`, when its first argument keeps the shape in its plane.
    KeepsIf(PlaneRule),
    /// It takes 2D shapes only and makes a solid of them (`extrude`, `revolve`).
    Makes,
}

/// The test an operator's first argument passes to keep a 2D shape in its plane, and what is
/// said when it does not.
#[derive(Clone, Copy)]
pub struct PlaneRule {
    /// Whether the first argument (an axis, a normal, a spacing) keeps the shape in the plane.
    pub keeps: fn(DVec3) -> bool,
    /// The error's message.
    pub message: &'static str,
    /// The error's help.
    pub help: &'static str,
}

/// How many copies of its shape a repetition looks at per evaluation.
#[derive(Clone, Copy)]
pub struct Copies {
    /// The number of copies one evaluation looks at.
    pub count: fn(&Ctx) -> f64,
    /// What is wrong with that many (an error past the limit, a warning where every copy is
    /// evaluated), at the operator's span.
    pub diagnose: fn(&Ctx, f64, Span) -> Vec<Diagnostic>,
}

/// A function of the module an operator's IR body calls by name.
#[derive(Clone, Copy)]
pub struct Helper {
    /// Its name in the module.
    pub name: &'static str,
    /// Its body, of `(a: f32, b: f32, k: f32) -> f32`.
    pub body: fn(&mut FnBuilder) -> Ex,
}
