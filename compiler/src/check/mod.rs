//! Checking: AST → scene graph. Names resolved, arguments typed and ranged, units converted,
//! materials resolved, a Lipschitz bound for every node; all errors of a file reported at once.

mod absorb;
mod args;
mod arith;
mod bake;
mod call;
mod convert;
mod derived;
mod expr;
mod file;
mod fn_args;
mod functions;
mod implicit;
mod lattice;
mod look;
mod names;
mod nodes;
mod overflow;
mod param_args;
mod param_decl;
mod params;
mod planar;
mod ranges;
pub mod sampler;
mod settings;
pub mod tracer;
mod whole;

pub use args::signature;
pub use look::LIGHT_KINDS;
pub use params::TIME;
pub use tracer::TRACE_METHODS;

use crate::diag::{Diagnostic, Span};
use crate::scene::{Field, Material, Node, NodeId, Scene};
use crate::source::Sources;
use crate::syntax::{self, Expr, Item};
use glam::DVec3;
use std::collections::HashMap;

/// Most shape nodes a scene may have.
pub const MAX_NODES: usize = 100_000;
/// Most materials a scene may declare: each is a branch of the shading's material table.
/// On lavapipe, 1 000 shapes each with its own material rendered (the driver's compile
/// dominating) in 8.3 s at 32×18, 2 000 in 31 s.
pub const MAX_MATERIALS: usize = 1024;
/// Most lights a scene may have: each is a term of the shading. On lavapipe 1 000 lights
/// rendered in 0.8 s, 4 000 in 8.6 s, 10 000 in 39 s.
pub const MAX_LIGHTS: usize = 4096;
/// Most primitive evaluations one evaluation of the scene's field may cost (`Node::evaluations`):
/// shared `let`s and `repeat` copies multiply work without adding nodes (16 levels of a `let`
/// used twice are 65 536 evaluations: the render grew to 7 GB and died). On lavapipe, 4 096
/// cost 2.4 s and 600 MB to render at 32×18, 1 024 cost 0.6 s.
pub const MAX_EVALUATIONS: f64 = 10_000.0;
/// Smallest Lipschitz bound a node gets (a constant field has slope 0, and the tracer divides by λ).
pub const MIN_LAMBDA: f64 = 1e-9;
/// Deepest expression nesting the checker follows.
pub const MAX_DEPTH: usize = 256;

/// The result of checking: a scene (if there were no errors) and all diagnostics, warnings
/// included.
pub struct Checked {
    /// The scene, when no error was found.
    pub scene: Option<Scene>,
    /// Errors and warnings in source order.
    pub diagnostics: Vec<Diagnostic>,
    /// The files read (the main one and its imports), for showing the diagnostics.
    pub sources: Sources,
}

/// The key of `values` (for [`compile_with`] and the others) that sets the `res` of every
/// `bake` in the scene, as `sdfc --bake-res N` does: one number within `bake`'s range. Not a
/// name a parameter can have.
pub const BAKE_RES: &str = "bake.res";

/// Parses and checks source text (its imports may name the standard library only: a file's
/// imports are relative to it, see [`compile_file`]).
pub fn compile(source: &str) -> Checked {
    compile_with(source, &HashMap::new())
}

/// Parses and checks source text with parameters set to other values than their defaults
/// (`name` → components; `time` included): the scene the shader draws when the host sets
/// them, for the CPU reference. A value outside a parameter's range is an error; names the
/// scene does not declare are ignored (see [`unknown_params`]).
pub fn compile_with(source: &str, values: &HashMap<String, Vec<f64>>) -> Checked {
    compile_file("<input>", source, values, &syntax::NoFiles)
}

/// Parses and checks the file `name` (its imports read by `loader`, relative to `name`'s
/// directory) with parameters at `values` (see [`compile_with`]).
pub fn compile_file(
    name: &str,
    source: &str,
    values: &HashMap<String, Vec<f64>>,
    loader: &dyn syntax::Loader,
) -> Checked {
    compile_file_at(name, std::path::Path::new(name), source, values, loader)
}

/// [`compile_file`] for the file at `path`, shown as `name` (its imports found beside `path`
/// itself, whatever its bytes: see [`syntax::load_at`]).
pub fn compile_file_at(
    name: &str,
    path: &std::path::Path,
    source: &str,
    values: &HashMap<String, Vec<f64>>,
    loader: &dyn syntax::Loader,
) -> Checked {
    let loaded = syntax::load_at(name, path, source, loader);
    match loaded.file {
        Some(file) => {
            let mut checked = file::check_with_lines(&file, &loaded.sources, values);
            checked.sources = loaded.sources;
            checked
        }
        None => Checked {
            scene: None,
            diagnostics: loaded.diagnostics,
            sources: loaded.sources,
        },
    }
}

/// The names in `values` that are not parameters of `scene` (`time` is one whenever asked
/// for: a scene that does not read it ignores it), with the closest parameter's name.
pub fn unknown_params<'v>(
    scene: &Scene,
    values: &'v HashMap<String, Vec<f64>>,
) -> Vec<(&'v str, Option<String>)> {
    let mut out: Vec<(&str, Option<String>)> = values
        .keys()
        .filter(|n| *n != TIME && *n != BAKE_RES && !scene.params.iter().any(|p| &p.name == *n))
        .map(|n| {
            let near = crate::diag::did_you_mean(n, scene.params.iter().map(|p| p.name.as_str()));
            (n.as_str(), near.map(str::to_string))
        })
        .collect();
    out.sort();
    out
}

/// Checks a parsed file.
pub fn check(file: &syntax::File) -> Checked {
    file::check_with_lines(file, &Sources::default(), &HashMap::new())
}

/// The dimension of a number: plain, or an angle (from a `deg`/`rad` unit).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Dim {
    None,
    Angle,
}

/// A value during checking.
#[derive(Clone, Debug)]
pub(crate) enum Value {
    Num(f64, Dim),
    Vec3(DVec3),
    Color(DVec3),
    Shape(NodeId),
    /// An expression of x, y, z (inside `implicit`).
    Field(Field),
    /// A number, vector or colour computed from parameters at run time.
    Param(params::Sym),
}

impl Value {
    fn describe(&self) -> String {
        match self {
            Value::Num(x, Dim::None) => format!("the number {x}"),
            Value::Num(x, Dim::Angle) => format!("the angle {x}rad"),
            Value::Vec3(v) => format!("the vector ({}, {}, {})", v.x, v.y, v.z),
            Value::Color(_) => "a colour".into(),
            Value::Shape(_) => "a shape".into(),
            Value::Field(_) => "an expression of x, y, z".into(),
            Value::Param(s) => format!(
                "a value computed from parameters ({})",
                s.value().describe()
            ),
        }
    }
}

/// What a `let` name stands for.
#[derive(Clone, Debug)]
enum Binding {
    /// A checked value.
    Value(Value),
    /// The definition had errors (already reported); uses stay quiet.
    Failed,
}

pub(crate) struct Checker<'a> {
    nodes: Vec<Node>,
    diags: Vec<Diagnostic>,
    lets: HashMap<String, (Binding, Span)>,
    /// Every `let` and `material` name in the file with its definition, for "used before
    /// definition" messages.
    declared: HashMap<String, Span>,
    /// Definition spans of the file's material names.
    material_spans: Vec<Span>,
    /// Those names, in the same order.
    material_names: Vec<String>,
    materials: Vec<Material>,
    /// The `let` being checked and where its name is, to catch self-reference.
    defining: Option<(&'a str, Span)>,
    /// Names whose definitions failed (errors already reported): uses stay quiet.
    failed: std::collections::HashSet<String>,
    /// Whether "nested too deeply" was reported for the current statement.
    depth_reported: bool,
    /// Byte offsets of line starts, for messages that compare lines.
    line_starts: Vec<usize>,
    /// Inside an `implicit` body: x, y and z are coordinates.
    in_implicit: bool,
    depth: usize,
    settings: settings::Settings,
    /// Declared parameters (and `time` once used), in order.
    params: Vec<crate::scene::ParamDecl>,
    /// Their indices by name.
    param_index: HashMap<String, usize>,
    /// Whether each is read somewhere.
    param_used: Vec<bool>,
    /// Values asked for parameters instead of their defaults (`compile_with`).
    overrides: HashMap<String, Vec<f64>>,
    /// Declared functions by name.
    fns: HashMap<String, functions::FnEntry<'a>>,
    /// The calls being checked, innermost last.
    frames: Vec<functions::Frame>,
    /// The statement index of each `let`, parameter, function and material: a body sees only
    /// those before its function.
    item_of: HashMap<String, usize>,
    /// The statement index of each material (a name space of its own).
    material_item: HashMap<String, usize>,
    /// The statement being checked.
    item: usize,
    /// Calls expanded so far.
    calls: usize,
    /// Per node, whether it is a 2D shape.
    planar: Vec<bool>,
    /// Per node, the outermost call of a function whose body built it.
    call_site: Vec<Option<Span>>,
    /// The line of a name that looked like a misspelt block keyword (`matrial`).
    keyword_typo_line: Option<usize>,
    /// How nodes are written, for grouping copies (see `lattice`).
    forms: lattice::Forms,
    /// "Did you mean" suggestions left to compute: a report shows only the first
    /// `diag::MAX_SHOWN` diagnostics, and 10 000 misspelt names against 10 000 took 35 s.
    suggestions_left: std::cell::Cell<usize>,
    /// The cache keys of the distinct maps baked so far (at most `layout::MAX_VOLUMES`).
    bakes: Vec<u64>,
}

impl<'a> Checker<'a> {
    /// [`crate::diag::did_you_mean`] for the first `diag::MAX_SHOWN` questions of the file
    /// (the ones a report can show); `None` after them.
    fn did_you_mean<'c>(
        &self,
        name: &str,
        candidates: impl IntoIterator<Item = &'c str>,
    ) -> Option<&'c str> {
        let left = self.suggestions_left.get();
        if left == 0 {
            return None;
        }
        self.suggestions_left.set(left - 1);
        crate::diag::did_you_mean(name, candidates)
    }

    fn new(file: &'a syntax::File) -> Checker<'a> {
        let mut declared = HashMap::new();
        let mut material_spans = Vec::new();
        let mut material_names = Vec::new();
        for item in &file.items {
            match item {
                Item::Let { name, .. } | Item::Param { name, .. } => {
                    declared.entry(name.name.clone()).or_insert(name.span);
                }
                Item::Fn(def) => {
                    declared
                        .entry(def.name.name.clone())
                        .or_insert(def.name.span);
                }
                Item::Block {
                    keyword,
                    kind: Some(kind),
                    ..
                } if keyword.name == "material" => {
                    declared.entry(kind.name.clone()).or_insert(kind.span);
                    material_spans.push(kind.span);
                    material_names.push(kind.name.clone());
                }
                _ => {}
            }
        }
        Checker {
            suggestions_left: std::cell::Cell::new(crate::diag::MAX_SHOWN),
            nodes: Vec::new(),
            diags: Vec::new(),
            lets: HashMap::new(),
            declared,
            material_spans,
            material_names,
            materials: Vec::new(),
            defining: None,
            failed: Default::default(),
            depth_reported: false,
            line_starts: Vec::new(),
            in_implicit: false,
            depth: 0,
            settings: settings::Settings::default(),
            params: Vec::new(),
            param_index: HashMap::new(),
            param_used: Vec::new(),
            overrides: HashMap::new(),
            fns: HashMap::new(),
            frames: Vec::new(),
            item_of: HashMap::new(),
            material_item: HashMap::new(),
            item: 0,
            calls: 0,
            planar: Vec::new(),
            call_site: Vec::new(),
            keyword_typo_line: None,
            forms: lattice::Forms::default(),
            bakes: Vec::new(),
        }
    }

    fn let_binding(&mut self, name: &'a syntax::Ident, value: &'a Expr) {
        if let Some(d) = self.reserved_name(name) {
            self.diags.push(d);
            self.failed.insert(name.name.clone());
            return;
        }
        if self.defined_twice(name) {
            // Uses of the name find the first definition, or stay quiet.
            self.failed.insert(name.name.clone());
            return;
        }
        self.defining = Some((&name.name, name.span));
        let binding = match self.value(value) {
            Some(Value::Shape(n)) => {
                self.nodes[n].name.get_or_insert_with(|| name.name.clone());
                Binding::Value(Value::Shape(n))
            }
            Some(v) => Binding::Value(v),
            None => Binding::Failed,
        };
        self.defining = None;
        self.lets.insert(name.name.clone(), (binding, name.span));
        self.item_of.insert(name.name.clone(), self.item);
    }

    /// Whether `name` was already defined by a `let` or `param` (reported if so).
    fn defined_twice(&mut self, name: &syntax::Ident) -> bool {
        let first = self
            .lets
            .get(&name.name)
            .map(|(_, s)| *s)
            .or_else(|| {
                self.param_index
                    .get(&name.name)
                    .map(|&i| self.params[i].span)
            })
            .or_else(|| self.fns.get(&name.name).map(|e| e.def.name.span));
        if let Some(first) = first {
            self.diags.push(
                Diagnostic::error(name.span, format!("`{}` is defined twice", name.name))
                    .label("second definition")
                    .also(first, "first definition"),
            );
        }
        first.is_some()
    }

    /// Names that would be confusing or ambiguous as `let` or material names.
    fn reserved_name(&self, name: &syntax::Ident) -> Option<Diagnostic> {
        let n = name.name.as_str();
        if n == params::TIME {
            return Some(
                Diagnostic::error(name.span, "`time` is reserved")
                    .label("the built-in parameter: seconds, set by the host"),
            );
        }
        if ["x", "y", "z"].contains(&n) {
            return Some(
                Diagnostic::error(name.span, format!("`{n}` is reserved"))
                    .label("x, y and z name the coordinates inside `implicit` and the axes"),
            );
        }
        if crate::catalog::all_names().any(|c| c == n) || n == "implicit" {
            return Some(
                Diagnostic::error(
                    name.span,
                    format!("`{n}` is already the name of a built-in"),
                )
                .label("choose another name"),
            );
        }
        None
    }

    /// The 0-based line of a byte offset (0 when the source is unknown).
    fn line_of(&self, offset: usize) -> usize {
        self.line_starts
            .partition_point(|&s| s <= offset)
            .saturating_sub(1)
    }

    fn finish(self, root: NodeId) -> Scene {
        let mut scene = self.settings.finish(self.nodes, root, self.materials);
        scene.params = self.params;
        scene
    }
}
