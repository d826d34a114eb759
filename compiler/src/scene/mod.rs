//! The checked scene graph: shape nodes with their Lipschitz bounds, materials, camera, lights and
//! tracer settings. Both the CPU evaluator and the lowering read this, so they cannot drift apart.

mod params;
mod settings;

pub use crate::catalog::field::{Field, ParamRef, binary};
pub use params::{ParamDecl, ParamKind};
pub use settings::{
    EPSILON_FLOOR, Epsilon, Fog, Light, LightKind, Method, Occlusion, Shadow, Trace,
};

use crate::catalog::{Bound, Ctx, Operator, Primitive};
use crate::diag::Span;
use glam::DVec3;

/// Index of a node in [`Scene::nodes`].
pub type NodeId = usize;

/// A checked scene.
#[derive(Clone, Debug)]
pub struct Scene {
    /// All shape nodes; children come before their parents. Nodes may be shared (`let`).
    pub nodes: Vec<Node>,
    /// The node whose field is the scene.
    pub root: NodeId,
    /// Materials in declaration order; a node's material is an index here.
    pub materials: Vec<Material>,
    /// The camera.
    pub camera: Camera,
    /// Lights (a default light when the file declares none).
    pub lights: Vec<Light>,
    /// Background colour (sRGB, 0..1).
    pub background: DVec3,
    /// Tracer choice and parameters.
    pub trace: Trace,
    /// A convex volume enclosing every surface, if the file declares one (`bound`).
    pub bound: Option<Convex>,
    /// Ambient occlusion, if the file asks for it (`occlusion { .. }`).
    pub occlusion: Option<Occlusion>,
    /// Distance fog, if the file asks for it (`fog { .. }`).
    pub fog: Option<Fog>,
    /// The parameters the scene reads at run time (`param`, and `time` if used), in the order
    /// of the shader's `Params` uniform.
    pub params: Vec<ParamDecl>,
}

impl Scene {
    /// The same scene with every union's bounding-volume tree dropped (each child evaluated
    /// every time): the plain field the trees are measured and tested against. (The lowering
    /// drops each tree itself unless `Options::bounding_volumes` uses it.)
    pub fn without_bounding_volumes(&self) -> Scene {
        let mut s = self.clone();
        for n in &mut s.nodes {
            if let NodeKind::Operator { ctx, .. } = &mut n.kind {
                ctx.prune = None;
            }
        }
        s
    }

    /// The scene as the shader draws it when the host sets parameters to `values` (name →
    /// components; others keep theirs): every argument and field that reads a parameter
    /// recomputed, everything decided when the scene was checked (λ, bounds, `repeat`'s copies,
    /// bounding volumes) kept. Values are not checked against ranges here
    /// (`check::compile_with` does).
    pub fn with_values(&self, values: &std::collections::HashMap<String, Vec<f64>>) -> Scene {
        let mut s = self.clone();
        for p in &mut s.params {
            if let Some(v) = values.get(&p.name) {
                for (i, x) in v.iter().take(p.kind.components()).enumerate() {
                    p.value[i] = *x;
                }
            }
        }
        let params = s.params.clone();
        let value = |r: &ParamRef| params[r.index].value[r.comp];
        let at = |sym: &crate::catalog::ArgSyms, i: usize| -> Option<DVec3> {
            let comps = sym.get(i)?.as_ref()?;
            let v: Vec<f64> = comps
                .iter()
                .map(|f| f.with_values(&value).eval(DVec3::ZERO))
                .collect();
            Some(DVec3::new(v[0], v[v.len().min(2) - 1], v[v.len() - 1]))
        };
        for m in &mut s.materials {
            if let Some(c) = at(&m.sym, 0) {
                m.color = c;
            }
            if let Some(x) = at(&m.sym, 1) {
                m.specular = x.x;
            }
        }
        for l in &mut s.lights {
            if let Some(v) = at(&l.sym, 0) {
                l.kind = match l.kind {
                    LightKind::Directional(_) => LightKind::Directional(v),
                    LightKind::Point(_) => LightKind::Point(v),
                };
            }
            if let Some(c) = at(&l.sym, 1) {
                l.color = c;
            }
            if let Some(x) = at(&l.sym, 2) {
                l.intensity = x.x;
            }
        }
        for n in &mut s.nodes {
            match &mut n.kind {
                NodeKind::Primitive { ctx, .. } | NodeKind::Operator { ctx, .. } => {
                    if !ctx.sym.is_empty() {
                        *ctx = ctx.at_values(&value);
                    }
                }
                NodeKind::Implicit { field } => *field = field.with_values(&value),
            }
        }
        s
    }

    /// The root node.
    pub fn root_node(&self) -> &Node {
        &self.nodes[self.root]
    }

    /// Whether node `id` is where f/λ stops being a distance to first order: its gradient is
    /// not of length λ almost everywhere while its children's are, or it is an operator that
    /// does not keep that, or an annotation. Below such a node everything is loose; above it,
    /// the loose part is the one the materials' rule picks.
    pub fn breaks_unit_gradient(&self, id: NodeId) -> bool {
        let n = &self.nodes[id];
        if n.unit_gradient {
            return false;
        }
        let annotated = n.lambda != n.inferred_lambda;
        match &n.kind {
            NodeKind::Operator { op, ctx, children } => {
                annotated
                    || !(op.unit_gradient)(ctx)
                    || children.iter().all(|&c| self.nodes[c].unit_gradient)
            }
            _ => true,
        }
    }

    /// The baked volumes of reachable `bake` nodes, each once, in node order: the order of
    /// their bindings (`layout::VOLUME_BINDING`) and of `emit`'s volume files.
    pub fn volumes(&self) -> Vec<std::sync::Arc<crate::bake::Volume>> {
        let mut out: Vec<std::sync::Arc<crate::bake::Volume>> = Vec::new();
        for id in self.reachable() {
            if let NodeKind::Operator { ctx, .. } = &self.nodes[id].kind
                && let Some(v) = &ctx.baked
                && !out.iter().any(|o| std::sync::Arc::ptr_eq(o, v))
            {
                out.push(v.clone());
            }
        }
        out
    }

    /// Nodes reachable from the root, children before parents, each once.
    pub fn reachable(&self) -> Vec<NodeId> {
        let mut seen = vec![false; self.nodes.len()];
        let mut stack = vec![self.root];
        while let Some(n) = stack.pop() {
            if !std::mem::replace(&mut seen[n], true) {
                stack.extend(self.nodes[n].children());
            }
        }
        (0..self.nodes.len()).filter(|&n| seen[n]).collect()
    }
}

/// A shape node.
#[derive(Clone, Debug)]
pub struct Node {
    /// What it computes.
    pub kind: NodeKind,
    /// Where it was written.
    pub span: Span,
    /// The outermost call of a function whose body built it, if one did: what a message about
    /// it names besides `span` (which points into the body, shared by every call).
    pub call_site: Option<Span>,
    /// Lipschitz bound of the node's field (annotation applied).
    pub lambda: f64,
    /// The bound the catalog's rules give, before any annotation.
    pub inferred_lambda: f64,
    /// Where its surface lies.
    pub bound: Bound,
    /// Per axis, whether its field is symmetric under reflection of that coordinate.
    pub mirror: [bool; 3],
    /// Per axis k, whether its field is symmetric under exchanging the other two coordinates.
    pub swap: [bool; 3],
    /// Whether |∇f| = λ almost everywhere (exact primitives under operators that keep it, no
    /// annotation): then f/λ < ε means the surface is within ε, to first order.
    pub unit_gradient: bool,
    /// Whether f/λ is the distance to its surface outside it (see `Operator::keeps_exact`).
    pub exact: bool,
    /// Primitive (and `implicit`) evaluations one evaluation of this node costs, counting every
    /// use of a shared `let` and every copy a `repeat` looks at.
    pub evaluations: f64,
    /// Material for surfaces of this subtree that have none of their own.
    pub material: Option<u32>,
    /// The `let` name it was bound to, if any.
    pub name: Option<String>,
}

impl Node {
    /// Child node ids (empty for primitives).
    pub fn children(&self) -> &[NodeId] {
        match &self.kind {
            NodeKind::Operator { children, .. } => children,
            _ => &[],
        }
    }

    /// The catalog name of what this node is (`sphere`, `union`, `implicit`).
    pub fn kind_name(&self) -> &'static str {
        match &self.kind {
            NodeKind::Primitive { prim, .. } => prim.name,
            NodeKind::Operator { op, .. } => op.name,
            NodeKind::Implicit { .. } => "implicit",
        }
    }
}

/// The kinds of node.
#[derive(Clone, Debug)]
pub enum NodeKind {
    /// A catalog primitive with checked arguments.
    Primitive {
        /// The catalog entry.
        prim: &'static Primitive,
        /// Its arguments.
        ctx: Ctx,
    },
    /// A catalog operator applied to children.
    Operator {
        /// The catalog entry.
        op: &'static Operator,
        /// Its arguments and its children's bounds.
        ctx: Ctx,
        /// The children in order.
        children: Vec<NodeId>,
    },
    /// `implicit { expr }`
    Implicit {
        /// The expression of x, y, z.
        field: Field,
    },
}

/// A declared material.
#[derive(Clone, Debug, PartialEq)]
pub struct Material {
    /// Its name.
    pub name: String,
    /// Base colour (sRGB, 0..1).
    pub color: DVec3,
    /// Strength of the specular highlight, 0..1.
    pub specular: f64,
    /// Share of the light a mirror reflects (Keinert §3.3's reflection rays), 0..1.
    pub reflect: f64,
    /// Share of the light that passes into the solid and through it (refraction rays),
    /// 0..1; `reflect + transparent` ≤ 1, the rest is the surface's own shading.
    pub transparent: f64,
    /// Index of refraction of a transparent solid (1.5 glass, 2.42 diamond).
    pub ior: f64,
    /// A procedural pattern mixing `color` with a second colour (`crate::reference::texture`).
    pub pattern: Option<Pattern>,
    /// Settings computed from parameters (indexed as `check::look::MATERIAL`: `color`,
    /// `specular`), as expressions per component; empty when none is.
    pub sym: crate::catalog::ArgSyms,
    /// Where it was declared.
    pub span: Span,
}

/// A procedural texture (Liktor §4): `color KIND(first, second, scale, octaves)`, the surface
/// colour mix(first, second, w) with w ∈ [0, 1] the pattern's weight at the point in the
/// tagged shape's own coordinates.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Pattern {
    /// Which pattern.
    pub kind: PatternKind,
    /// The second colour (sRGB, 0..1); the first is the material's `color`.
    pub other: DVec3,
    /// The pattern's size: a checker's cell, noise's feature, marble's band, wood's ring.
    pub scale: f64,
    /// Octaves of noise summed (noise, turbulence, marble, wood).
    pub octaves: u32,
}

/// The patterns (`crate::reference::texture::PATTERNS` says what each is).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[allow(missing_docs)]
pub enum PatternKind {
    Checker,
    Tiles,
    Noise,
    Turbulence,
    Marble,
    Wood,
}

impl PatternKind {
    /// Whether the pattern sums octaves of noise.
    pub fn uses_noise(self) -> bool {
        !matches!(self, PatternKind::Checker | PatternKind::Tiles)
    }
}

impl Material {
    /// Whether rays go on from a surface of this material (it reflects or lets light through).
    pub fn continues(&self) -> bool {
        self.reflect > 0.0 || self.transparent > 0.0
    }
}

/// A pinhole camera (Munini §2.1).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Camera {
    /// Eye position.
    pub eye: DVec3,
    /// Point looked at.
    pub target: DVec3,
    /// Up direction (unit).
    pub up: DVec3,
    /// Vertical field of view, radians.
    pub fov: f64,
}

impl Camera {
    /// The smallest hit threshold the tracers use with this camera: `EPSILON_FLOOR` times its
    /// distance from its target, above f32's resolution of positions there.
    pub fn epsilon_floor(&self) -> f64 {
        EPSILON_FLOOR * (self.eye - self.target).length()
    }
}

/// A convex volume declared to enclose the scene's surfaces (Keinert §3.5): rays start where
/// they enter it and are culled if they miss it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Convex {
    /// The volume.
    pub shape: BoundShape,
    /// Whether the file declares the enclosed object itself convex, so a ray starting inside it
    /// is traced backwards from where it leaves the volume (Keinert §3.5, case 3).
    pub convex: bool,
}

/// The shape of a [`Convex`] bound.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum BoundShape {
    /// A sphere.
    Sphere {
        /// Centre.
        center: DVec3,
        /// Radius (> 0).
        radius: f64,
    },
    /// An axis-aligned box.
    Box {
        /// Centre.
        center: DVec3,
        /// Half the edge lengths (each > 0).
        half: DVec3,
    },
}

impl BoundShape {
    /// Where the line `ro + t·rd` (unit `rd`) enters and leaves the volume, if it meets it
    /// (the entry may be negative: the origin is inside).
    pub fn interval(&self, ro: DVec3, rd: DVec3) -> Option<(f64, f64)> {
        match *self {
            BoundShape::Sphere { center, radius } => {
                let oc = ro - center;
                let b = oc.dot(rd);
                let c = oc.dot(oc) - radius * radius;
                let disc = b * b - c;
                (disc >= 0.0).then(|| (-b - disc.sqrt(), -b + disc.sqrt()))
            }
            BoundShape::Box { center, half } => {
                let inv = rd.map(|x| 1.0 / guard_axis(x));
                let a = (center - half - ro) * inv;
                let c = (center + half - ro) * inv;
                let near = a.min(c).max_element();
                let far = a.max(c).min_element();
                (near <= far).then_some((near, far))
            }
        }
    }
}

/// A direction component kept away from zero (its sign kept) so the slab test's 1/x stays finite.
pub fn guard_axis(x: f64) -> f64 {
    if x.abs() < AXIS_GUARD {
        AXIS_GUARD.copysign(x)
    } else {
        x
    }
}

/// Smallest magnitude of a ray direction component in the box test.
pub const AXIS_GUARD: f64 = 1e-20;
