//! The catalog: one entry per primitive, operator and math function — parameters, Lipschitz rule, CPU evaluation.
//!
//! The checker, the evaluator, the docs table and the tests all loop over these tables; adding a
//! primitive means adding one entry (and its formula) in `primitives.rs`.

pub mod absorb;
mod baked;
mod bound;
pub mod domain;
pub mod field;
pub mod geometry;
pub mod gpu;
mod math;
pub mod operators;
pub mod planar;
pub mod polar;
pub mod primitives;
pub mod prune;
pub mod repeat;
mod rules;
pub mod shapes;
mod symmetry;
pub mod traits;
mod value;
mod warp;

pub use bound::Bound;
pub use field::{Field, ParamRef};
pub use math::{DERIVED_FUNCTIONS, DerivedFn, MATH_FUNCTIONS, MathFn, Units};
pub use operators::OPERATORS;
pub use primitives::PRIMITIVES;
pub(crate) use symmetry::{NO_SWAP, equal_pairs};
pub use value::{GPU_RANGE, Param, Ty, Val, fits_gpu, opt, req};

use glam::DVec3;

/// The result of evaluating a node at a point: the field value and the material of the surface
/// that value belongs to (`None`: the default material).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Sample {
    /// Field value (a signed distance bound once divided by the node's λ).
    pub d: f64,
    /// Material index into the scene's materials.
    pub mat: Option<u32>,
}

/// What an operator knows when it evaluates or computes its bound: its checked arguments and its
/// children's Lipschitz bounds and bounds and symmetries.
#[derive(Clone, Debug, PartialEq)]
pub struct Ctx {
    /// Arguments in parameter order, defaults filled in.
    pub args: Vec<Val>,
    /// λ of each child (annotations applied).
    pub child_lambda: Vec<f64>,
    /// Where each child's surface lies.
    pub child_bound: Vec<Bound>,
    /// Each child's reflection symmetry per axis (see [`Primitive::mirror`]).
    pub child_mirror: Vec<[bool; 3]>,
    /// Each child's exchange symmetry per axis (see [`Primitive::swap`]).
    pub child_swap: Vec<[bool; 3]>,
    /// Whether each child's field, divided by its λ, is the distance to its surface outside it
    /// (see [`Operator::keeps_exact`]).
    pub child_exact: Vec<bool>,
    /// A union's bounding-volume tree (see [`prune`]), built once at check time; `None`
    /// evaluates every child.
    pub prune: Option<std::sync::Arc<prune::Tree>>,
    /// `bake`'s distance map of its child, made when the scene is checked (`crate::bake`).
    pub baked: Option<std::sync::Arc<crate::bake::Volume>>,
    /// Per argument, its components as expressions of parameters when it reads any (the
    /// shader computes it at run time; `args` holds its value where the scene was checked);
    /// empty when no argument does.
    pub sym: ArgSyms,
}

/// Per argument, its components as expressions of parameters if it reads any.
pub type ArgSyms = Vec<Option<Vec<Field>>>;

/// `syms` in the form every checked node holds: the empty list where no argument reads a
/// parameter.
pub fn arg_syms(mut syms: ArgSyms) -> ArgSyms {
    if syms.iter().all(Option::is_none) {
        syms.clear();
    }
    syms
}

impl Ctx {
    /// A primitive's context from its arguments alone (no children, nothing read at run time):
    /// what the scene as data carries for a leaf (`crate::tape::program`).
    pub fn of_args(args: Vec<Val>) -> Ctx {
        Ctx {
            args,
            child_lambda: Vec::new(),
            child_bound: Vec::new(),
            child_mirror: Vec::new(),
            child_swap: Vec::new(),
            child_exact: Vec::new(),
            prune: None,
            baked: None,
            sym: Vec::new(),
        }
    }

    /// The bound of the children's surfaces grown by `by`, where the part that grows is
    /// {f/λ < by}: that lies within `by` of a child's surface only where the child's f/λ is its
    /// distance; otherwise it is not known (a loose field is small far from its surface).
    pub fn grown_if_exact(&self, b: Bound, by: f64) -> Bound {
        if self.child_exact.iter().all(|&e| e) {
            b.grown(by)
        } else {
            Bound::INFINITE
        }
    }
}

impl Ctx {
    /// Argument `i` as a number.
    pub fn num(&self, i: usize) -> f64 {
        self.args[i].num()
    }

    /// Argument `i` as a vector.
    pub fn vec(&self, i: usize) -> DVec3 {
        self.args[i].vec()
    }

    /// The context with every parameter use valued by `value` (the arguments that read
    /// parameters recomputed).
    pub fn at_values(&self, value: &dyn Fn(&ParamRef) -> f64) -> Ctx {
        let mut c = self.clone();
        for (i, sym) in self.sym.iter().enumerate() {
            let Some(comps) = sym else { continue };
            let v: Vec<f64> = comps
                .iter()
                .map(|f| f.with_values(value).eval(DVec3::ZERO))
                .collect();
            c.args[i] = match c.args[i] {
                Val::Vec3(_) => Val::Vec3(DVec3::new(v[0], v[1], v[2])),
                _ => Val::Num(v[0]),
            };
            c.sym[i] = Some(comps.iter().map(|f| f.with_values(value)).collect());
        }
        c
    }

    /// Argument `i`'s components as expressions of parameters, if it reads any.
    pub fn sym(&self, i: usize) -> Option<&[Field]> {
        self.sym.get(i).and_then(|s| s.as_deref())
    }
}

/// How many children an operator takes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Arity {
    /// Exactly this many.
    Exactly(usize),
    /// At least this many.
    AtLeast(usize),
}

impl Arity {
    /// Whether `n` children are accepted.
    pub fn accepts(self, n: usize) -> bool {
        match self {
            Arity::Exactly(k) => n == k,
            Arity::AtLeast(k) => n >= k,
        }
    }
}

/// Evaluates one child of an operator at a point: its raw field (not divided by its λ).
pub type ChildEval<'a> = &'a mut dyn FnMut(usize, DVec3) -> f64;

/// Which child's material the result takes. Comparisons use the children's fields divided by
/// their λ and a sharp fold even for smooth blends, identically on the CPU and in shaders.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum MatRule {
    /// The smallest field wins (union, smooth union, blob).
    Nearest,
    /// The largest field wins (intersection).
    Farthest,
    /// The first child, unless a later one's negated field is larger (subtraction: cut faces
    /// take the cutter's material).
    Cut,
    /// The first child up to weight 0.5, else the second (`mix`; the weight is argument 0);
    /// shading blends the two by the weight.
    Weighted,
    /// The only child's.
    Pass,
    /// As `Nearest`; shading blends the children's materials over the smooth minimum's radius
    /// (argument 0) by its mix factor (`crate::reference::blend`).
    SmoothNearest,
    /// As `Farthest`, blended over the smooth maximum's radius.
    SmoothFarthest,
    /// As `Cut`, blended over the smooth maximum's radius.
    SmoothCut,
}

impl MatRule {
    /// The material (or any tag) of an operator's result from its children's raw fields and
    /// tags, in child order.
    pub fn pick<T: Copy>(self, ctx: &Ctx, children: &[(f64, Option<T>)]) -> Option<T> {
        let rule = self.sharp();
        let norm = |i: usize| children[i].0 / ctx.child_lambda[i];
        let fold = |better: &dyn Fn(f64, f64) -> bool, sign: f64| {
            let (mut d, mut m) = (norm(0), children[0].1);
            for (i, child) in children.iter().enumerate().skip(1) {
                let di = sign * norm(i);
                if better(di, d) {
                    (d, m) = (di, child.1);
                }
            }
            m
        };
        match rule {
            MatRule::Pass => children[0].1,
            MatRule::Weighted => children[usize::from(ctx.num(0) > 0.5)].1,
            MatRule::Nearest => fold(&|a, b| a < b, 1.0),
            MatRule::Farthest => fold(&|a, b| a > b, 1.0),
            MatRule::Cut => fold(&|a, b| a > b, -1.0),
            _ => unreachable!("sharp rules only"),
        }
    }

    /// Whether a hit needs confirming at an operator's result (`eval::loose`, `map_loose`),
    /// from the children's raw fields and looseness (`Some`: loose): as [`MatRule::pick`] picks,
    /// except where the largest operand decides (an intersection, a cut, sharp or smooth).
    /// There a point is near the result's surface only if it is near or inside every operand,
    /// and a loose operand's small positive field does not say it is near: so the result is
    /// loose where some loose operand is positive (the cut's later operands negated), or where
    /// every operand is loose. (Before, the largest operand alone decided, and an exact cutter
    /// trusted at the rim of a loose shell fattened it: `docs/lipschitz.md` §5.)
    pub fn pick_loose<T: Copy>(self, ctx: &Ctx, children: &[(f64, Option<T>)]) -> Option<T> {
        let rule = self.sharp();
        if !matches!(rule, MatRule::Farthest | MatRule::Cut) {
            return self.pick(ctx, children);
        }
        let sign = |i: usize| {
            if rule == MatRule::Cut && i > 0 {
                -1.0
            } else {
                1.0
            }
        };
        if children.iter().all(|c| c.1.is_some()) {
            return children[0].1;
        }
        children
            .iter()
            .enumerate()
            .find(|(i, c)| c.1.is_some() && sign(*i) * c.0 > 0.0)
            .and_then(|(_, c)| c.1)
    }

    /// The rule that picks one material (the smooth rules' sharp ones).
    pub fn sharp(self) -> MatRule {
        match self {
            MatRule::SmoothNearest => MatRule::Nearest,
            MatRule::SmoothFarthest => MatRule::Farthest,
            MatRule::SmoothCut => MatRule::Cut,
            r => r,
        }
    }

    /// Whether shading blends the children's materials.
    pub fn blends(self) -> bool {
        self.sharp() != self || self == MatRule::Weighted
    }
}

/// A primitive shape.
pub struct Primitive {
    /// Name in the language.
    pub name: &'static str,
    /// One line for the docs.
    pub doc: &'static str,
    /// Parameters in positional order.
    pub params: &'static [Param],
    /// Whether the field is an exact Euclidean distance (else a bound).
    pub exact: bool,
    /// Whether its λ is its distance estimator's, not a proven bound (the Mandelbulb's,
    /// docs/lipschitz.md): tracing by it is as good as the estimate, but nothing whose
    /// correctness rests on the bound (a bake's near-surface sampling, a cell's pruning) trusts
    /// it.
    pub estimate: bool,
    /// Whether its function takes the arguments every use in a scene shares as constants
    /// rather than as parameters: its lowering makes faster code from known values (the
    /// Mandelbulb's whole powers multiplied out).
    pub bake: bool,
    /// Whether it is a 2D shape: in the xy plane, the same at every z (`catalog/planar.rs`).
    pub planar: bool,
    /// Whether |∇f| = λ almost everywhere (exact fields, and estimates built to be distances):
    /// then f/λ < ε means the surface is within ε to first order (see
    /// [`Operator::unit_gradient`]).
    pub unit_gradient: fn(&Ctx) -> bool,
    /// Lipschitz bound λ of the field.
    pub lipschitz: fn(&Ctx) -> f64,
    /// Where the surface lies.
    pub bound: fn(&Ctx) -> Bound,
    /// Per axis, whether the field is symmetric under reflection of that coordinate
    /// (f(…, −x, …) = f(…, x, …)); `repeat` then needs no neighbouring cells.
    pub mirror: fn(&Ctx) -> [bool; 3],
    /// Per axis k, whether the field is symmetric under exchanging the other two coordinates
    /// (for k = z: f(y, x, z) = f(x, y, z)). With the reflections of those two it gives the
    /// field a square's symmetries about k, which an eighth turn about k maps onto themselves:
    /// `rotate` keeps the reflections then (a square prism turned 45° is still symmetric about
    /// its cell, so `repeat` evaluates one copy of it).
    pub swap: fn(&Ctx) -> [bool; 3],
    /// The field in f64.
    pub eval: fn(&Ctx, DVec3) -> f64,
    /// The same field as the body of `sd_<name>(p, params...)` in naga IR.
    pub lower: gpu::PrimLower,
}

/// An operator on child shapes (CSG, blend, transform, domain operation).
pub struct Operator {
    /// Name in the language.
    pub name: &'static str,
    /// One line for the docs (including its Lipschitz rule).
    pub doc: &'static str,
    /// Parameters in positional order.
    pub params: &'static [Param],
    /// How many children.
    pub arity: Arity,
    /// Lipschitz bound λ of the result (infinite: cannot be bounded; the checker asks for an
    /// annotation).
    pub lipschitz: fn(&Ctx) -> f64,
    /// Where the result's surface lies.
    pub bound: fn(&Ctx) -> Bound,
    /// Per axis, whether the result is symmetric under reflection of that coordinate, given
    /// its arguments and its children's symmetries (`Ctx::child_mirror`).
    pub mirror: fn(&Ctx) -> [bool; 3],
    /// Per axis, whether the result is symmetric under exchanging the other two coordinates
    /// (see [`Primitive::swap`]), given its arguments and its children's (`Ctx::child_swap`).
    pub swap: fn(&Ctx) -> [bool; 3],
    /// The field in f64, given a way to evaluate the children.
    pub eval: fn(&Ctx, DVec3, ChildEval) -> f64,
    /// Whether the result's gradient has length λ almost everywhere when every child's has
    /// (its own λ then: f/λ is a distance to first order, so the tracer's hit test f/λ < ε
    /// needs no confirmation; see `crate::reference::trace::careful`).
    pub unit_gradient: fn(&Ctx) -> bool,
    /// Whether the result's f/λ is the distance to its surface outside it when every child's
    /// is (union, moves, uniform scale, `repeat`, `round`, `onion`).
    pub keeps_exact: fn(&Ctx) -> bool,
    /// How materials propagate.
    pub materials: MatRule,
    /// Whether its arguments must be constants: its lowering shapes the code by their values
    /// (`repeat`'s copies, a warp's stretch), so they cannot be parameters.
    pub fixed_args: bool,
    /// The same field in naga IR.
    pub lower: gpu::OpLower,
    /// What the checker and the lowering do with it besides its field.
    pub traits: traits::Traits,
}

/// Looks up a primitive by name.
pub fn primitive(name: &str) -> Option<&'static Primitive> {
    PRIMITIVES.iter().find(|p| p.name == name)
}

/// Looks up an operator by name: the language's own, then those [`register_operator`] added.
pub fn operator(name: &str) -> Option<&'static Operator> {
    OPERATORS.iter().find(|p| p.name == name).or_else(|| {
        let added = ADDED_OPERATORS.read().unwrap_or_else(|e| e.into_inner());
        added.iter().copied().find(|p| p.name == name)
    })
}

/// Operators defined outside this crate, after the language's own.
static ADDED_OPERATORS: std::sync::RwLock<Vec<&'static Operator>> =
    std::sync::RwLock::new(Vec::new());

/// Adds an operator defined outside this crate (an embedder's, or a test's) to the table names
/// are looked up in, for every scene checked after: its entry is all the checker, the CPU
/// evaluator, the Lipschitz rules and the lowering need. `Err` (and nothing added) when a
/// primitive, operator or math function already has its name.
pub fn register_operator(op: &'static Operator) -> Result<(), String> {
    let mut added = ADDED_OPERATORS.write().unwrap_or_else(|e| e.into_inner());
    if all_names().any(|n| n == op.name) || added.iter().any(|o| o.name == op.name) {
        return Err(format!("`{}` is taken", op.name));
    }
    added.push(op);
    Ok(())
}

/// Looks up a math function by name.
pub fn math_fn(name: &str) -> Option<&'static MathFn> {
    MATH_FUNCTIONS.iter().find(|p| p.name == name)
}

/// Looks up a derived math function by name.
pub fn derived_fn(name: &str) -> Option<&'static DerivedFn> {
    math::DERIVED_FUNCTIONS.iter().find(|p| p.name == name)
}

/// Every name a call may use: primitives, operators and math functions.
pub fn all_names() -> impl Iterator<Item = &'static str> {
    PRIMITIVES
        .iter()
        .map(|p| p.name)
        .chain(OPERATORS.iter().map(|o| o.name))
        .chain(MATH_FUNCTIONS.iter().map(|m| m.name))
        .chain(math::DERIVED_FUNCTIONS.iter().map(|m| m.name))
}

macro_rules! by_name {
    ($($t:ty),*) => {$(
        impl std::fmt::Debug for $t {
            fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
                f.write_str(self.name)
            }
        }
        impl PartialEq for $t {
            fn eq(&self, other: &Self) -> bool {
                std::ptr::eq(self, other)
            }
        }
    )*};
}
by_name!(Primitive, Operator, MathFn);
