//! Lowering: the checked scene graph becomes a naga module — `sd_*` functions for the primitives
//! used, `op_*` helpers for the blends used, a function `let_<name>` per surviving `let` shape,
//! `map`, (only when the scene has materials) `map_material`, (only when a material has a
//! pattern) `map_texture` and (only when it has a loose part) `map_loose` (the tag walks:
//! `tags.rs`, which return a constant where the scene leaves no choice); the tracer and entry
//! points come from `assemble.rs`.

mod assemble;
mod bounce;
mod bound;
mod camera;
mod careful;
mod constant;
mod count;
mod data;
mod entry;
mod fns;
mod globals;
mod handoff;
mod hybrid;
pub mod interface;
mod lobes;
pub mod march;
pub mod params;
mod pick;
mod probes;
mod rays;
mod shading;
mod tags;
mod texture;
pub mod tracer;
mod variants;
mod vector;
mod volumes;

use crate::catalog::gpu::{args, field};
use crate::catalog::traits::Helper;
use crate::catalog::{Ctx, Ty, Val};
use crate::ir::{Ex, FnBuilder, ModuleBuilder};
use crate::scene::{NodeId, NodeKind, Scene};
use naga::{Function, Handle, Type};
use std::borrow::Cow;
use std::collections::HashMap;
use tracer::BoundingVolumes;

pub use constant::{constant_looseness, constant_materials};
pub use tracer::Entry;

/// Builds the module for a scene and an entry kind. Validation happens in `emit`.
pub fn lower(scene: &Scene, entry: Entry, options: &tracer::Options) -> naga::Module {
    let mut mb = ModuleBuilder::default();
    mb.params = params::add(
        &mut mb,
        scene,
        (options.private_params, options.params_binding),
    );
    let reachable = scene.reachable();
    volumes::add(&mut mb, scene);
    if options.count_primitives && matches!(entry, Entry::Compute | Entry::Trace) {
        count::add_counter(&mut mb);
        mb.primitives = true;
    }
    add_primitive_functions(&mut mb, scene, &reachable);
    add_operator_helpers(&mut mb, scene, &reachable);
    let trees = options.bounding_volumes;
    let any_tree = scene.nodes.iter().any(|n| match &n.kind {
        NodeKind::Operator { ctx, .. } => ctx.prune.as_deref().is_some_and(|t| trees.uses(t)),
        _ => false,
    });
    let named = add_let_functions(&mut mb, scene, &reachable, trees, any_tree);
    let walk = Walk {
        scene,
        named: &named,
        root_fn: None,
        trees,
        any_tree,
    };
    let f32t = mb.f32();
    // The data form's evaluator, where asked for and the scene has one.
    let blends = crate::reference::blend::has_blends(scene);
    let evaluators = (options.form == tracer::Form::Data)
        .then(|| crate::tape::data::layout(scene, None).ok())
        .flatten()
        .map(|(_, layout)| data::add(&mut mb, &layout, blends));
    let data = evaluators.as_ref().map(|e| e.eval);
    let data_blend = evaluators.as_ref().and_then(|e| e.blend);
    let map = point_function(&mut mb, "map", f32t, |b, p| match data {
        Some(eval) => data::value(b, eval, p),
        None => {
            let d = walk.distance(b, scene.root, p);
            crate::catalog::gpu::scale_by(b, d, 1.0 / scene.root_node().lambda)
        }
    });
    let u32t = mb.u32();
    // (The library always has `map_material`: its interface does not depend on the scene.)
    let material = (has_materials(scene, &reachable) || entry == Entry::Library).then(|| {
        point_function(&mut mb, "map_material", u32t, |b, p| match data {
            Some(eval) => data::material(b, eval, p),
            None => {
                let m = walk.with_material(b, scene.root, p);
                m.unwrap_or_else(|| b.u(0))
            }
        })
    });
    // Where the scene's f/λ is not a distance to first order everywhere: `map_loose(p)`, 1 where
    // the nearest part is loose (`eval::loose`), for the tracer's hit confirmation.
    let loose = (!scene.root_node().unit_gradient).then(|| {
        point_function(&mut mb, "map_loose", u32t, |b, p| match data {
            // The data form's looseness: the tag's bit (`lower/data.rs`).
            Some(eval) => data::loose(b, eval, p),
            None => {
                let l = walk.with_loose(b, scene.root, p);
                l.unwrap_or_else(|| b.u(0))
            }
        })
    });
    let [texture, blend] = add_surface_maps(&mut mb, &walk, scene, data_blend);
    // The camera's trace steps by a far cell's clearance (`data/far.rs`); all else by `map`.
    let trace_map = evaluators.and_then(|e| e.trace).unwrap_or(map);
    assemble::add(
        &mut mb,
        scene,
        (map, trace_map),
        [material, texture, blend],
        loose,
        entry,
        options,
    );
    mb.module
}

/// The data form's pre-pass on the GPU for `scene` (`data/prune.rs`): `main` prunes one grid's
/// cells from the coarser grid's programs; with how many folds deep its arrays hold (the
/// scene's tree's nesting at its defaults). None where the scene has no data form.
pub fn prune(scene: &Scene) -> Option<(naga::Module, usize)> {
    let (tree, layout) = crate::tape::data::layout(scene, None).ok()?;
    let height = crate::tape::program::height(&tree);
    let mut mb = ModuleBuilder::default();
    add_primitive_functions(&mut mb, scene, &scene.reachable());
    data::prune::add(&mut mb, &layout.kinds, height);
    Some((mb.module, height))
}

/// `map_texture` where a material has a pattern and `map_blend` where an operator blends
/// materials (each `None` where the scene has none).
fn add_surface_maps(
    mb: &mut ModuleBuilder,
    walk: &Walk,
    scene: &Scene,
    data_blend: Option<Handle<Function>>,
) -> [Option<Handle<Function>>; 2] {
    let v3 = mb.vec3();
    // Where a material has a pattern: `map_texture(p)`, the point in the own coordinates of
    // the shape whose material the surface takes (`eval::surface`).
    let texture = (!used_patterns(scene).is_empty()).then(|| {
        point_function(mb, "map_texture", v3, |b, p| {
            let q = walk.with_texture(b, scene.root, p);
            // The point itself where no material was given (as `eval::surface`).
            match q {
                Some(q) => {
                    let xyz = b.swizzle(q, &[0, 1, 2]);
                    let w = b.at(q, 3);
                    let zero = b.f(0.0);
                    let given = b.gt(w, zero);
                    b.select(given, xyz, p)
                }
                None => p,
            }
        })
    });
    // Where a smooth operator or `mix` blends materials: `map_blend(p)`, vec3(first id, second
    // id, weight of the second) (`crate::reference::blend`, `eval::blend`); in the data form,
    // the evaluator's `tape_blend`.
    let blend = crate::reference::blend::has_blends(scene).then(|| {
        point_function(mb, "map_blend", v3, |b, p| match data_blend {
            Some(f) => data::blend_at(b, f, p),
            None => {
                let bl = walk.with_blend(b, scene.root, p);
                bl.unwrap_or_else(|| b.splat3(0.0))
            }
        })
    });
    [texture, blend]
}

/// Adds the helper `name(p: vec3<f32>) -> ret` returning `body(p)`.
fn point_function(
    mb: &mut ModuleBuilder,
    name: &str,
    ret: Handle<Type>,
    body: impl FnOnce(&mut FnBuilder, Ex) -> Ex,
) -> Handle<Function> {
    let v3 = mb.vec3();
    let mut b = FnBuilder::new(mb, name, &[("p", v3)], Some(ret));
    let p = b.arg(0);
    let value = body(&mut b, p);
    b.ret(Some(value));
    let f = b.finish();
    mb.add_helper(name, f)
}

/// The materials given to some reachable shape that have a pattern, by index.
pub(crate) fn used_patterns(scene: &Scene) -> Vec<usize> {
    let mut used: Vec<usize> = scene
        .reachable()
        .iter()
        .filter_map(|&n| scene.nodes[n].material)
        .map(|m| m as usize)
        .filter(|&m| scene.materials[m].pattern.is_some())
        .collect();
    used.sort_unstable();
    used.dedup();
    used
}

fn has_materials(scene: &Scene, reachable: &[NodeId]) -> bool {
    reachable.iter().any(|&n| scene.nodes[n].material.is_some())
}

/// The IR type of a parameter of type `ty`.
fn param_type(mb: &mut ModuleBuilder, ty: Ty) -> Handle<Type> {
    match ty {
        Ty::Count | Ty::CountTo(_) | Ty::WholeIn(..) => mb.u32(),
        Ty::Vec3 | Ty::Size | Ty::Scale | Ty::Axis | Ty::Color | Ty::Counts => mb.vec3(),
        _ => mb.f32(),
    }
}

/// `sd_<name>(p, params...)` for each primitive kind the scene uses, in order of first use.
fn add_primitive_functions(mb: &mut ModuleBuilder, scene: &Scene, reachable: &[NodeId]) {
    for &n in reachable {
        let NodeKind::Primitive { prim, .. } = &scene.nodes[n].kind else {
            continue;
        };
        let name = format!("sd_{}", prim.name);
        if mb.has_helper(&name) {
            continue;
        }
        let shared = if prim.bake {
            shared_args(scene, reachable, prim.name)
        } else {
            vec![None; prim.params.len()]
        };
        let v3 = mb.vec3();
        let f32t = mb.f32();
        let mut args = vec![("p", v3)];
        for (param, _) in prim.params.iter().zip(&shared).filter(|(_, s)| s.is_none()) {
            let ty = param_type(mb, param.ty);
            // Keep the module's own function names (`normal`) free for those functions.
            let name = if param.name == "normal" {
                "n"
            } else {
                param.name
            };
            args.push((name, ty));
        }
        let mut b = FnBuilder::new(mb, &name, &args, Some(f32t));
        count::primitive(&mut b);
        let p = b.arg(0);
        let mut next = 1;
        let params: Vec<Ex> = prim
            .params
            .iter()
            .zip(&shared)
            .map(|(param, s)| match s {
                Some(v) => args::arg(&mut b, param.ty, *v, None, p),
                None => {
                    next += 1;
                    b.arg(next - 1)
                }
            })
            .collect();
        let d = (prim.lower)(&mut b, p, &params);
        b.ret(Some(d));
        let f = b.finish();
        mb.baked
            .insert(name.clone(), shared.iter().map(Option::is_some).collect());
        mb.add_helper(&name, f);
    }
}

/// Per parameter of primitive `name`, its value where every reachable use of it gives the same
/// constant (not read from a parameter), else `None`.
fn shared_args(scene: &Scene, reachable: &[NodeId], name: &str) -> Vec<Option<Val>> {
    let mut shared: Option<Vec<Option<Val>>> = None;
    for &n in reachable {
        let NodeKind::Primitive { prim, ctx } = &scene.nodes[n].kind else {
            continue;
        };
        if prim.name != name {
            continue;
        }
        let here: Vec<Option<Val>> = (0..prim.params.len())
            .map(|i| ctx.sym(i).is_none().then_some(ctx.args[i]))
            .collect();
        shared = Some(match shared {
            None => here,
            Some(s) => s
                .into_iter()
                .zip(here)
                .map(|(a, b)| if a == b { a } else { None })
                .collect(),
        });
    }
    shared.unwrap_or_default()
}

/// The smooth-blend helpers the scene uses.
fn add_operator_helpers(mb: &mut ModuleBuilder, scene: &Scene, reachable: &[NodeId]) {
    for &n in reachable {
        let NodeKind::Operator { op, .. } = &scene.nodes[n].kind else {
            continue;
        };
        let Some(Helper { name, body }) = op.traits.helper else {
            continue;
        };
        if mb.has_helper(name) {
            continue;
        }
        let f32t = mb.f32();
        let mut b = FnBuilder::new(
            mb,
            name,
            &[("a", f32t), ("b", f32t), ("k", f32t)],
            Some(f32t),
        );
        let d = body(&mut b);
        b.ret(Some(d));
        let f = b.finish();
        mb.add_helper(name, f);
    }
}

/// A function per reachable `let` shape (children first), so a shape used twice is code once.
fn add_let_functions(
    mb: &mut ModuleBuilder,
    scene: &Scene,
    reachable: &[NodeId],
    trees: BoundingVolumes,
    any_tree: bool,
) -> HashMap<NodeId, Handle<Function>> {
    let mut named = HashMap::new();
    for &n in reachable {
        let Some(name) = &scene.nodes[n].name else {
            continue;
        };
        // Tagged or annotated copies share the name; the first keeps it plain. The `let_`
        // prefix keeps user names clear of every target's reserved words (`sampler2D` made
        // HLSL that did not compile) and of the module's own functions.
        let v3 = mb.vec3();
        let f32t = mb.f32();
        let mut b = FnBuilder::new(mb, &format!("let_{name}"), &[("p", v3)], Some(f32t));
        let p = b.arg(0);
        let d = Walk {
            scene,
            named: &named,
            root_fn: Some(n),
            trees,
            any_tree,
        }
        .distance(&mut b, n, p);
        b.ret(Some(d));
        let f = b.finish();
        named.insert(n, mb.add_function(f));
    }
    named
}

/// A walk over the scene graph emitting IR.
struct Walk<'s> {
    scene: &'s Scene,
    named: &'s HashMap<NodeId, Handle<Function>>,
    /// The `let` function being built (which must not call itself).
    root_fn: Option<NodeId>,
    /// Which unions' fields test their bounding-volume tree (`Options::bounding_volumes`).
    trees: BoundingVolumes,
    /// Whether any union of the scene tests its tree.
    any_tree: bool,
}

impl Walk<'_> {
    /// An operator's context as this walk lowers it: a union's bounding-volume tree dropped
    /// unless the field tests it; always for `tags`, which need every child's value.
    fn ctx_for<'c>(&self, ctx: &'c Ctx, tags: bool) -> Cow<'c, Ctx> {
        match &ctx.prune {
            Some(t) if tags || !self.trees.uses(t) => Cow::Owned(Ctx {
                prune: None,
                ..ctx.clone()
            }),
            _ => Cow::Borrowed(ctx),
        }
    }

    /// The raw field of node `id` at `p`.
    fn distance(&self, b: &mut FnBuilder, id: NodeId, p: Ex) -> Ex {
        if self.root_fn != Some(id)
            && let Some(&f) = self.named.get(&id)
        {
            return b.call(f, vec![p]);
        }
        let node = &self.scene.nodes[id];
        match &node.kind {
            NodeKind::Primitive { prim, ctx } => {
                let name = format!("sd_{}", prim.name);
                let f = b.m.helper(&name);
                let mut args = vec![p];
                for (i, (param, v)) in prim.params.iter().zip(&ctx.args).enumerate() {
                    if !b.m.baked.get(&name).is_some_and(|m| m[i]) {
                        args.push(args::arg(b, param.ty, *v, ctx.sym(i), p));
                    }
                }
                b.call(f, args)
            }
            NodeKind::Implicit { field: f } => field::lower(b, f, p),
            NodeKind::Operator { op, ctx, children } => {
                let inner = Walk {
                    root_fn: None,
                    ..*self
                };
                let mut child =
                    |b: &mut FnBuilder, i: usize, q: Ex| inner.distance(b, children[i], q);
                (op.lower)(b, &self.ctx_for(ctx, false), p, &mut child)
            }
        }
    }
}
