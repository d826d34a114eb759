//! Checking `bake`: its shape reads no parameters, has a box to bake over and fits in memory
//! (estimated and refused before any work); then the bake itself, reused from the cache while
//! the shape and the grid do not change (`crate::bake::cache`).

use super::Checker;
use crate::bake::{self, Grid, Volume};
use crate::catalog::Ctx;
use crate::diag::{Diagnostic, Span};
use crate::scene::{NodeId, NodeKind};
use glam::DVec3;
use std::collections::HashMap;
use std::hash::{Hash, Hasher};
use std::sync::Arc;

impl Checker<'_> {
    /// The distance map of `bake`'s shape `child` (`ctx`: the operator's arguments), or `None`
    /// with an error.
    pub(super) fn bake(&mut self, ctx: &Ctx, child: NodeId, span: Span) -> Option<Arc<Volume>> {
        let subtree = self.subtree(child);
        if let Some(name) = self.param_read_in(&subtree) {
            self.diags.push(
                Diagnostic::error(span, "a baked shape cannot read parameters")
                    .label(format!("its shape reads `{name}`"))
                    .note(format!("the map is baked once, when the scene is compiled: a host setting `{name}` would not change it"))
                    .help("use a constant there, or leave this part unbaked"),
            );
            return None;
        }
        let res = self.bake_res(ctx, span)?;
        let size = ctx.vec(1);
        let (lo, hi) = if size != DVec3::ZERO {
            (-size, size)
        } else {
            let b = self.nodes[child].bound;
            (b.lo, b.hi)
        };
        if !(lo.is_finite() && hi.is_finite()) {
            self.diags.push(
                Diagnostic::error(span, "cannot bake a shape without a bound")
                    .label("its surface may reach infinity, and a map covers a box")
                    .help("give `bake` a box by its half extents, e.g. `bake(res = 64, size = (2, 2, 2)) { … }`, or intersect the shape with a bounded one"),
            );
            return None;
        }
        let grid = Grid::around(lo, hi, res);
        let bytes = bake::bytes_to_bake(&grid);
        if bytes > bake::MAX_BYTES {
            let fits = (bake::MIN_RES..res)
                .rev()
                .find(|&r| bake::bytes_to_bake(&Grid::around(lo, hi, r)) <= bake::MAX_BYTES)
                .unwrap_or(bake::MIN_RES);
            self.diags.push(
                Diagnostic::error(span, format!("`bake(res = {res})` needs too much memory"))
                    .label(format!(
                        "{} × {} × {} points: about {:.1} GiB while baking",
                        grid.n[0],
                        grid.n[1],
                        grid.n[2],
                        bytes as f64 / f64::from(1u32 << 30)
                    ))
                    .note(format!(
                        "baking holds {} bytes per point; the limit is {} GiB",
                        bake::BYTES_PER_POINT,
                        bake::MAX_BYTES >> 30
                    ))
                    .help(format!("use `res = {fits}` or less")),
            );
            return None;
        }
        let work = grid.len() as f64 * self.nodes[child].evaluations;
        if work > bake::MAX_WORK {
            self.diags.push(
                Diagnostic::error(span, format!("`bake(res = {res})` would take too long"))
                    .label(format!(
                        "{} points × {:.0} primitive evaluations each",
                        grid.len(),
                        self.nodes[child].evaluations
                    ))
                    .note(format!(
                        "the limit is {:.0e} evaluations per bake (about a minute on two cores)",
                        bake::MAX_WORK
                    ))
                    .help("use a smaller `res`, or bake the parts of the shape separately"),
            );
            return None;
        }
        let key = self.bake_key(child, &grid);
        self.count_map(key, span)?;
        // No scene comes of it after an error, and the shape may be one the limits refused.
        if self.diags.iter().any(Diagnostic::is_error) {
            return None;
        }
        let nodes = self.nodes_for_baking(&subtree);
        let field = |p: DVec3| crate::reference::eval::raw(&nodes, child, p);
        let lambda = match self.proven_bound(&subtree) {
            true => self.nodes[child].lambda,
            false => f64::INFINITY,
        };
        // On the host's sampler (the GPU) when the work is worth it, else on the CPU.
        let part = super::settings::Settings::default().finish(
            nodes.clone(),
            child,
            self.materials.clone(),
        );
        let make = || {
            if let Some(samples) = super::sampler::sample(&part, &grid, work) {
                return Volume::from_samples(grid, &samples, &field);
            }
            match lambda.is_finite() {
                true => Volume::bake_lipschitz(&field, lambda, lo, hi, res),
                false => Volume::bake(&field, lo, hi, res),
            }
        };
        // (A stored volume on another grid is not this one, whatever its key.)
        let (volume, _) = bake::cache::get_or_bake(key, |v| v.grid == grid, make);
        Some(volume)
    }

    /// Whether a shape of these nodes has a proven bound, so that it is evaluated only near
    /// its surface: one node without, combined as if it had λ 1, leaves the whole with none (a
    /// union's λ of 1 assumes its children's), and an estimate's λ is not a bound.
    fn proven_bound(&self, subtree: &[NodeId]) -> bool {
        subtree.iter().all(|&n| {
            let node = &self.nodes[n];
            let estimate = matches!(&node.kind, NodeKind::Primitive { prim, .. } if prim.estimate);
            node.lambda.is_finite() && !estimate
        })
    }

    /// The `res` to bake at: `--bake-res` when given (and valid), else the operator's.
    fn bake_res(&mut self, ctx: &Ctx, span: Span) -> Option<usize> {
        match self.overrides.get(super::BAKE_RES).and_then(|v| v.first()) {
            Some(&n)
                if n.fract() == 0.0 && (bake::MIN_RES..=bake::MAX_RES).contains(&(n as usize)) =>
            {
                Some(n as usize)
            }
            Some(&n) => {
                self.diags.push(
                    Diagnostic::error(span, format!("cannot bake at the resolution {n} asked for"))
                        .label("this `bake`'s `res` was set from outside (`--bake-res`)")
                        .note(format!(
                            "`res` is a whole number from {} to {}",
                            bake::MIN_RES,
                            bake::MAX_RES
                        )),
                );
                None
            }
            None => Some(ctx.num(0) as usize),
        }
    }

    /// Counts the map `key` among the scene's distinct ones; `None` with an error past
    /// `layout::MAX_VOLUMES`.
    fn count_map(&mut self, key: u64, span: Span) -> Option<()> {
        if self.bakes.contains(&key) {
            return Some(());
        }
        if self.bakes.len() == crate::layout::MAX_VOLUMES {
            self.diags.push(
                Diagnostic::error(span, "too many baked maps")
                    .label(format!(
                        "the {}th distinct map of this scene",
                        crate::layout::MAX_VOLUMES + 1
                    ))
                    .note(format!(
                        "a shader binds at most {} volumes (bindings {}…{} of group {})",
                        crate::layout::MAX_VOLUMES,
                        crate::layout::VOLUME_BINDING,
                        crate::layout::VOLUME_BINDING as usize + crate::layout::MAX_VOLUMES - 1,
                        crate::layout::GROUP
                    ))
                    .help("bake a union of several parts as one shape"),
            );
            return None;
        }
        self.bakes.push(key);
        Some(())
    }

    /// Every node below `id` (itself included), each once.
    fn subtree(&self, id: NodeId) -> Vec<NodeId> {
        let mut seen = vec![false; self.nodes.len()];
        let mut stack = vec![id];
        let mut out = Vec::new();
        while let Some(n) = stack.pop() {
            if !std::mem::replace(&mut seen[n], true) {
                out.push(n);
                stack.extend(self.nodes[n].children());
            }
        }
        out
    }

    /// The name of a parameter some node of `subtree` reads, if one does.
    fn param_read_in(&self, subtree: &[NodeId]) -> Option<String> {
        let mut read = None;
        for &n in subtree {
            match &self.nodes[n].kind {
                NodeKind::Primitive { ctx, .. } | NodeKind::Operator { ctx, .. } => {
                    for comps in ctx.sym.iter().flatten() {
                        comps
                            .iter()
                            .for_each(|f| f.params(&mut |r| read = Some(r.index)));
                    }
                }
                NodeKind::Implicit { field } => field.params(&mut |r| read = Some(r.index)),
            }
        }
        read.map(|i| self.params[i].name.clone())
    }

    /// The nodes up to the baked shape's, those of its subtree with an unknown slope combined
    /// as if it were 1 (hard CSG keeps their surface whatever positive λ divides them; a
    /// smooth blend's radius is then in their own units): the field that is baked.
    fn nodes_for_baking(&self, subtree: &[NodeId]) -> Vec<crate::scene::Node> {
        let last = subtree.iter().copied().max().unwrap_or(0);
        let mut nodes = self.nodes[..=last].to_vec();
        for &n in subtree {
            let node = &mut nodes[n];
            if !node.lambda.is_finite() {
                node.lambda = 1.0;
            }
            if let NodeKind::Operator { ctx, .. } = &mut node.kind {
                for l in &mut ctx.child_lambda {
                    if !l.is_finite() {
                        *l = 1.0;
                    }
                }
            }
        }
        nodes
    }

    /// What the volume of `id` on `grid` depends on, hashed: every node's kind and arguments
    /// below it (an `implicit`'s expression), and the grid.
    fn bake_key(&self, id: NodeId, grid: &Grid) -> u64 {
        let mut memo = HashMap::new();
        let mut h = std::hash::DefaultHasher::new();
        self.content_hash(id, &mut memo).hash(&mut h);
        format!("{grid:?}").hash(&mut h);
        bake::VERSION.hash(&mut h);
        h.finish()
    }

    fn content_hash(&self, id: NodeId, memo: &mut HashMap<NodeId, u64>) -> u64 {
        if let Some(&k) = memo.get(&id) {
            return k;
        }
        let node = &self.nodes[id];
        let mut h = std::hash::DefaultHasher::new();
        node.kind_name().hash(&mut h);
        node.lambda.to_bits().hash(&mut h);
        match &node.kind {
            NodeKind::Primitive { ctx, .. } | NodeKind::Operator { ctx, .. } => {
                format!("{:?}", ctx.args).hash(&mut h);
                // (A blend divides by its children's λ: an annotation changes the surface.)
                for l in &ctx.child_lambda {
                    l.to_bits().hash(&mut h);
                }
            }
            NodeKind::Implicit { field } => format!("{field:?}").hash(&mut h),
        }
        for &c in node.children() {
            self.content_hash(c, memo).hash(&mut h);
        }
        let k = h.finish();
        memo.insert(id, k);
        k
    }
}
