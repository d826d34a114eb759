//! The scene as data (issue 33): its field as a tree of leaves (primitives seen through the
//! moves, turns and scales above them) and folds (hard and smooth unions, intersections and
//! subtractions), which a generic evaluator runs and Lipschitz pruning cuts per cell of space.
//!
//! Barbier, Sanchez et al., *Lipschitz Pruning* (Eurographics 2025), §4: a fold's child whose
//! value over a cell cannot change the fold's result there is dropped — for a smooth blend of
//! radius k once it is k beyond the rest, where the blend's kernel is zero. [`cells`] does that
//! pruning; [`eval`] runs a tree. This CPU form is the reference for the shader's (to come).

pub mod cells;
pub mod data;
pub mod eval;
pub mod program;
pub mod seed;

use crate::catalog::traits::{Fold, Motion};
use crate::scene::{NodeId, NodeKind, Scene};
use glam::{DMat3, DVec3};

/// The affine map from world points to a part's own point: `m·p + t`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Frame {
    /// The linear part.
    pub m: DMat3,
    /// The offset.
    pub t: DVec3,
}

impl Frame {
    /// World points as they are.
    pub const IDENTITY: Frame = Frame {
        m: DMat3::IDENTITY,
        t: DVec3::ZERO,
    };

    /// The point `p` in this frame.
    pub fn apply(&self, p: DVec3) -> DVec3 {
        self.m * p + self.t
    }

    /// This frame followed by the local map `q ↦ l·q + o`.
    fn then(&self, l: DMat3, o: DVec3) -> Frame {
        Frame {
            m: l * self.m,
            t: l * self.t + o,
        }
    }
}

/// How a fold combines its children's values.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Way {
    /// The smallest (a union), smoothly over `k` when k > 0 (IQ's quadratic smooth minimum).
    Min,
    /// The largest (an intersection; a subtraction with its later children negated).
    Max,
}

/// A part of the tree: what it computes, where its point is, and how its parent sees it.
#[derive(Clone, Debug)]
pub struct Part {
    /// A leaf or a fold.
    pub kind: PartKind,
    /// The scene node it stands for (the primitive, or the fold's operator).
    pub node: NodeId,
    /// Its place in the whole tree, in pre-order (a pruned tree keeps its parts' numbers: they
    /// name their entries in the program's table, `program::Table`).
    pub id: usize,
    /// World points to the node's own point.
    pub frame: Frame,
    /// How far the node's point moves when the world point moves by 1 (the frame's scales).
    pub zoom: f64,
    /// The node's raw field times this is its value as its parent fold sees it: the scales'
    /// factors between them, divided by the λ the fold normalises this child by (for the root,
    /// its own λ: the value is then the scene's distance bound).
    pub factor: f64,
    /// The material given to surfaces of this part that have none of their own: the node's,
    /// else that of the nearest move, turn or scale above it below the parent fold.
    pub material: Option<u32>,
    /// Whether the part's value is proven 1-Lipschitz in its parent fold's point: every λ in
    /// it is the catalog's bound or above (no annotation below it). Only such parts are pruned.
    pub proven: bool,
    /// Whether the node or a move, turn or scale above it below the parent fold is where f/λ
    /// stops being a distance to first order (`Scene::breaks_unit_gradient`): a hit on it needs
    /// confirming (`eval::loose`).
    pub loose: bool,
}

/// What a part computes.
#[derive(Clone, Debug)]
pub enum PartKind {
    /// The primitive at the part's node, at the frame's point.
    Leaf,
    /// Children combined in order.
    Fold {
        /// Smallest or largest.
        way: Way,
        /// The smooth blend's radius (0: sharp).
        k: f64,
        /// The children; each with whether the fold negates it (a subtraction's cutters).
        children: Vec<(Part, bool)>,
    },
}

impl Part {
    /// The number of parts in it, itself included (its ids run from its own to its own + this).
    pub fn size(&self) -> usize {
        match &self.kind {
            PartKind::Leaf => 1,
            PartKind::Fold { children, .. } => {
                1 + children.iter().map(|(c, _)| c.size()).sum::<usize>()
            }
        }
    }

    /// The number of leaves (primitive evaluations) the part makes.
    pub fn leaves(&self) -> usize {
        match &self.kind {
            PartKind::Leaf => 1,
            PartKind::Fold { children, .. } => children.iter().map(|(c, _)| c.leaves()).sum(),
        }
    }
}

/// Why a scene has no data form (yet).
#[derive(Clone, Debug, PartialEq)]
pub struct Unsupported {
    /// The node that is not a primitive, move, turn, scale or fold of those.
    pub node: NodeId,
    /// What it is.
    pub what: &'static str,
}

/// The scene's field as a tree of parts, or the first node the data form cannot hold: nodes
/// other than primitives (not those whose code is made from their arguments' values, the
/// Mandelbulb's), moves, turns, scales and the catalog's folds (`Traits::fold`: the hard and
/// smooth unions, intersections and subtractions).
pub fn build(scene: &Scene) -> Result<Part, Unsupported> {
    let root = scene.root_node();
    let at = At {
        frame: Frame::IDENTITY,
        zoom: 1.0,
        factor: 1.0 / root.lambda,
        material: None,
        proven: true,
        loose: false,
    };
    let mut tree = part(scene, scene.root, at)?;
    number(&mut tree, &mut 0);
    Ok(tree)
}

/// Numbers `part` and everything in it in pre-order from `next`.
fn number(part: &mut Part, next: &mut usize) {
    part.id = *next;
    *next += 1;
    if let PartKind::Fold { children, .. } = &mut part.kind {
        for (c, _) in children {
            number(c, next);
        }
    }
}

/// Where a part is and how its parent sees it (the fields of [`Part`] of those names), as the
/// walk down from its parent fold has found so far.
#[derive(Clone, Copy)]
struct At {
    frame: Frame,
    zoom: f64,
    factor: f64,
    material: Option<u32>,
    proven: bool,
    loose: bool,
}

/// The part for `id` where `at` says.
fn part(scene: &Scene, id: NodeId, at: At) -> Result<Part, Unsupported> {
    let node = &scene.nodes[id];
    let at = At {
        material: node.material.or(at.material),
        proven: at.proven && node.lambda.is_finite() && node.lambda >= node.inferred_lambda,
        loose: at.loose || scene.breaks_unit_gradient(id),
        ..at
    };
    let unsupported = Unsupported {
        node: id,
        what: node.kind_name(),
    };
    match &node.kind {
        NodeKind::Implicit { .. } => Err(unsupported),
        // (A primitive whose code is made from its arguments' values cannot take them as data.)
        NodeKind::Primitive { prim, .. } if prim.bake => Err(unsupported),
        NodeKind::Primitive { prim, .. } => Ok(Part {
            kind: PartKind::Leaf,
            node: id,
            id: 0,
            frame: at.frame,
            zoom: at.zoom,
            factor: at.factor,
            material: at.material,
            proven: at.proven && !prim.estimate,
            loose: at.loose,
        }),
        NodeKind::Operator { op, ctx, children } => {
            let moved = |l: DMat3, o: DVec3| At {
                frame: at.frame.then(l, o),
                ..at
            };
            match (op.traits.motion, op.traits.fold) {
                (Motion::Move, _) => part(scene, children[0], moved(DMat3::IDENTITY, -ctx.vec(0))),
                (Motion::Turn, _) => {
                    let (axis, angle) = (ctx.vec(0), -ctx.num(1));
                    let turn = |v| crate::catalog::geometry::rotate(v, axis, angle);
                    let l = DMat3::from_cols(turn(DVec3::X), turn(DVec3::Y), turn(DVec3::Z));
                    part(scene, children[0], moved(l, DVec3::ZERO))
                }
                (Motion::Scale, _) => {
                    let s = ctx.vec(0);
                    let inner = At {
                        zoom: at.zoom / s.min_element(),
                        factor: at.factor * s.min_element(),
                        ..moved(DMat3::from_diagonal(DVec3::ONE / s), DVec3::ZERO)
                    };
                    part(scene, children[0], inner)
                }
                (Motion::None, Some(how)) => fold(scene, (id, ctx, children), at, how),
                (Motion::None, None) => Err(unsupported),
            }
        }
    }
}

/// The fold at operator node `id` (with its arguments and children), folding as `way` says.
fn fold(
    scene: &Scene,
    (id, ctx, children): (NodeId, &crate::catalog::Ctx, &[NodeId]),
    at: At,
    how: Fold,
) -> Result<Part, Unsupported> {
    let k = if how.smooth { ctx.num(0) } else { 0.0 };
    let way = if how.largest { Way::Max } else { Way::Min };
    let mut parts = Vec::with_capacity(children.len());
    for (i, &c) in children.iter().enumerate() {
        let child = At {
            factor: 1.0 / ctx.child_lambda[i],
            material: None,
            proven: true,
            loose: false,
            ..at
        };
        parts.push((part(scene, c, child)?, how.negates_later && i > 0));
    }
    Ok(Part {
        proven: at.proven && parts.iter().all(|(p, _)| p.proven),
        kind: PartKind::Fold {
            way,
            k,
            children: parts,
        },
        node: id,
        id: 0,
        frame: at.frame,
        zoom: at.zoom,
        factor: at.factor,
        material: at.material,
        loose: at.loose,
    })
}
