//! Checking calls: math functions, `implicit`, primitives and operators with their children,
//! material tags, and the copy a tag or annotation makes of a shared shape.

use super::args::RunTime;
use super::{Binding, Checker, Value};
use crate::catalog::{self, Arity};
use crate::diag::Diagnostic;
use crate::scene::{NodeId, NodeKind};
use crate::syntax::{Call, Ident};

impl Checker<'_> {
    /// The node of a primitive with checked arguments.
    pub(super) fn primitive_node(
        &mut self,
        prim: &'static catalog::Primitive,
        args: (Vec<catalog::Val>, catalog::ArgSyms),
        span: crate::diag::Span,
    ) -> Option<NodeId> {
        let ctx = self.ctx_over(args, &[]);
        let rules = self.rules_over_ranges(&ctx, span, prim.name, &|c| {
            super::ranges::Rules::primitive(prim, c)
        })?;
        let id = self.push_node(
            NodeKind::Primitive { prim, ctx },
            rules.lambda,
            rules.bound,
            span,
        )?;
        self.narrow_rules(id, &rules);
        Some(id)
    }

    /// A call: a math function, `implicit`, a primitive or an operator. `piped` is the child
    /// given by `lhs |> call`.
    pub(super) fn call(&mut self, call: &Call, piped: Option<NodeId>) -> Option<Value> {
        let name = call.name.name.as_str();
        // `mix` is both: the operator when it has shapes (a block or `|>`), else the number.
        let shapes = call.block.is_some() || piped.is_some();
        if let Some(f) = catalog::math_fn(name)
            && !(shapes && catalog::operator(name).is_some())
        {
            return self.math_call(f, call);
        }
        if name == "implicit" {
            return self.implicit(call, piped);
        }
        if let Some(f) = catalog::derived_fn(name) {
            return self.derived_call(f, call);
        }
        if self.fns.contains_key(name) && (self.visible(name) || self.in_frame(name)) {
            return self.fn_call(call, piped);
        }
        if let Some(prim) = catalog::primitive(name) {
            return self.primitive_call(prim, call, piped);
        }
        if let Some(op) = catalog::operator(name) {
            return self.operator_call(op, call, piped);
        }
        self.not_callable(call)
    }

    /// A primitive's call: no shape piped in, no block, its arguments bound.
    fn primitive_call(
        &mut self,
        prim: &'static catalog::Primitive,
        call: &Call,
        piped: Option<NodeId>,
    ) -> Option<Value> {
        let name = call.name.name.as_str();
        if piped.is_some() {
            self.diags.push(
                Diagnostic::error(
                    call.name.span,
                    format!("`{name}` is a primitive and takes no shape"),
                )
                .label("only operators can follow `|>`"),
            );
            return None;
        }
        if let Some(block) = &call.block {
            let span = block.first().map_or(call.span, |e| e.span);
            self.diags.push(
                Diagnostic::error(span, format!("`{name}` is a primitive and takes no block"))
                    .label("unexpected block")
                    .help(format!("write `{}`", signature_of_prim(prim))),
            );
            return None;
        }
        let args = self.bind_args(name, prim.params, &call.args, call.span, RunTime::All)?;
        self.primitive_node(prim, args, call.span).map(Value::Shape)
    }

    /// An operator's call: its arguments and children (a warning for a combination of one).
    fn operator_call(
        &mut self,
        op: &'static catalog::Operator,
        call: &Call,
        piped: Option<NodeId>,
    ) -> Option<Value> {
        let name = call.name.name.as_str();
        let args = self.bind_args(name, op.params, &call.args, call.span, RunTime::All);
        let children = self.children(call, piped, op.arity)?;
        if children.len() == 1 && matches!(op.arity, Arity::AtLeast(_)) {
            self.diags.push(
                Diagnostic::warning(call.span, format!("`{name}` of one shape is that shape"))
                    .label("only one shape")
                    .note(format!(
                        "`{name}` combines the shapes in its block; `a |> {name}(…)` gives it only `a`"
                    ))
                    .help(format!("give it the others: `{name}(…) {{ a b }}`")),
            );
        }
        self.operator_node(name, args?, children, call.span)
            .map(Value::Shape)
    }

    /// A call of a name that is no function: a value, a pattern, something defined further
    /// down, or an unknown name; each reported.
    fn not_callable(&mut self, call: &Call) -> Option<Value> {
        let name = call.name.name.as_str();
        if let Some((binding, def)) = self.lets.get(name) {
            let what = match binding {
                Binding::Value(v) => v.describe(),
                Binding::Failed => "a failed definition".into(),
            };
            let d = Diagnostic::error(call.name.span, format!("`{name}` cannot be called"))
                .label(format!("`{name}` is {what}"))
                .also(*def, "defined here");
            self.diags.push(d);
            return None;
        }
        if crate::reference::texture::PATTERNS
            .iter()
            .any(|p| p.0 == name)
        {
            self.diags.push(
                Diagnostic::error(
                    call.name.span,
                    format!("`{name}` is a pattern, not a value"),
                )
                .label("a pattern is only a material's colour")
                .help(format!(
                    "give it directly as a colour: `material m {{ color {name}(#fff, #000) }}`"
                )),
            );
            return None;
        }
        if !self.frames.is_empty() && self.fns.contains_key(name) {
            // A function defined below the one whose body calls it.
            return self.defined_after_fn(&call.name);
        }
        if let Some(def) = self.declared.get(name).copied() {
            self.used_before_definition(call, def);
            return None;
        }
        if self.keyword_typo_line == Some(self.line_of(call.span.start)) && call.block.is_some() {
            // The rest of a misspelt block statement (reported at its keyword).
            return None;
        }
        self.unknown_call(call);
        None
    }

    /// A function (or other definition) written further down, at `def`: reported unless its
    /// definition failed; its arguments checked anyway.
    fn used_before_definition(&mut self, call: &Call, def: crate::diag::Span) {
        let name = call.name.name.as_str();
        let what = if self.fns.contains_key(name) || self.failed.contains(name) {
            "a function defined later in the file"
        } else {
            "defined later in the file"
        };
        let d = if self.failed.contains(name) {
            None
        } else {
            Some(
                Diagnostic::error(
                    call.name.span,
                    format!("`{name}` is used before its definition"),
                )
                .label(what)
                .also(def, "defined here")
                .help("move the definition above its first use"),
            )
        };
        self.diags.extend(d);
        for a in &call.args {
            self.value(&a.value);
        }
    }

    /// A name neither in the catalog nor defined: reported with the nearest name, its
    /// arguments checked anyway so their errors are reported too.
    fn unknown_call(&mut self, call: &Call) {
        let name = call.name.name.as_str();
        let mut d = Diagnostic::error(
            call.name.span,
            format!("unknown function or shape `{name}`"),
        )
        .label("not in the catalog");
        let candidates: Vec<String> = catalog::all_names()
            .chain(["implicit"])
            .map(str::to_string)
            .chain(self.fns.keys().cloned())
            .collect();
        d = match self.did_you_mean(name, candidates.iter().map(String::as_str)) {
            Some(s) => d.help(format!("did you mean `{s}`?")),
            None => d.note("`sdfc check --list` prints the primitives and operators"),
        };
        self.diags.push(d);
        for a in &call.args {
            self.value(&a.value);
        }
    }

    pub(super) fn children(
        &mut self,
        call: &Call,
        piped: Option<NodeId>,
        arity: Arity,
    ) -> Option<Vec<NodeId>> {
        let name = &call.name.name;
        let mut children = Vec::new();
        let mut ok = true;
        match (&call.block, piped) {
            (Some(_), Some(_)) => {
                self.diags.push(
                    Diagnostic::error(
                        call.span,
                        format!("`{name}` gets its shape from `|>` and a block"),
                    )
                    .label("give it one or the other"),
                );
                return None;
            }
            (Some(block), None) => {
                for e in block {
                    match self.shape(e) {
                        Some(n) => children.push(n),
                        None => ok = false,
                    }
                }
            }
            (None, Some(n)) => children.push(n),
            (None, None) => {
                self.diags.push(
                    Diagnostic::error(call.span, format!("`{name}` needs shapes to work on"))
                        .label("no block")
                        .help(format!(
                            "write `{name}(...) {{ shape ... }}` or `shape |> {name}(...)`"
                        )),
                );
                return None;
            }
        }
        if !ok {
            return None;
        }
        if !arity.accepts(children.len()) {
            let want = match arity {
                Arity::Exactly(1) => "exactly one shape".to_string(),
                Arity::Exactly(n) => format!("exactly {n} shapes"),
                Arity::AtLeast(1) => "at least one shape".to_string(),
                Arity::AtLeast(n) => format!("at least {n} shapes"),
            };
            let msg = if children.is_empty() {
                format!("empty `{name}` block")
            } else {
                format!("`{name}` takes {want}, found {}", children.len())
            };
            self.diags
                .push(Diagnostic::error(call.span, msg).label(format!("`{name}` takes {want}")));
            return None;
        }
        Some(children)
    }

    pub(super) fn material_ref(&mut self, id: &Ident) -> Option<u32> {
        if !self.material_visible(&id.name) {
            let at = self
                .material_spans
                .iter()
                .zip(&self.material_names)
                .find(|(_, n)| **n == id.name)
                .map(|(s, _)| *s);
            self.defined_after_fn_at(id, at);
            return None;
        }
        if let Some(i) = self.materials.iter().position(|m| m.name == id.name) {
            return Some(i as u32);
        }
        if self.failed.contains(&id.name) {
            return None;
        }
        let d = match self.declared.get(&id.name) {
            Some(def) if self.material_spans.contains(def) => Diagnostic::error(
                id.span,
                format!("material `{}` is used before its definition", id.name),
            )
            .label("defined later")
            .also(*def, "defined here")
            .help("move the material above its first use"),
            _ => {
                let mut d = Diagnostic::error(id.span, format!("unknown material `{}`", id.name))
                    .label("no such material");
                let names: Vec<&str> = self.materials.iter().map(|m| m.name.as_str()).collect();
                d = match self.did_you_mean(&id.name, names) {
                    Some(s) => d.help(format!("did you mean `{s}`?")),
                    None => d.help(format!(
                        "declare it: `material {} {{ color #d4af37 }}`",
                        id.name
                    )),
                };
                d
            }
        };
        self.diags.push(d);
        None
    }

    /// A copy of a node, so that tagging or annotating a shared (`let`) shape changes only this
    /// use of it.
    pub(super) fn copy_node(&mut self, n: NodeId) -> Option<NodeId> {
        let node = self.nodes[n].clone();
        let id = self.push_node(node.kind.clone(), node.lambda, node.bound, node.span)?;
        self.nodes[id] = node;
        Some(id)
    }
}

fn signature_of_prim(p: &catalog::Primitive) -> String {
    super::signature(p.name, p.params)
}
