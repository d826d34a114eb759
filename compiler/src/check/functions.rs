//! User-defined functions: `fn name(params) = body`. A call binds its arguments (positional,
//! named, defaults; typed by annotation or default) and checks the body in a scope that sees
//! the arguments and what was defined before the `fn` — an expansion, so λ, bounds and
//! materials flow through a call exactly as through `let`. Errors in a body are shown at the
//! body with the call beside them; recursion is refused.

use super::fn_args::TYPES;
use super::{Checker, Value};
use crate::diag::{Diagnostic, Span};
use crate::scene::NodeId;
use crate::syntax::{Call, FnDef};
use std::collections::HashMap;

/// Most function calls one file's check may expand (a chain of functions each calling the
/// next twice doubles the work per level).
pub const MAX_CALLS: usize = 100_000;

/// Most calls of a chain a diagnostic in a body shows.
const MAX_CALL_LABELS: usize = 3;

/// A declared function.
pub(super) struct FnEntry<'a> {
    pub def: &'a FnDef,
    /// The index of its statement: its body sees what was defined before it.
    pub item: usize,
    pub used: bool,
}

/// A call being checked: its arguments by name and what its body may see.
pub(super) struct Frame {
    pub args: HashMap<String, Value>,
    /// Statements before this index are visible.
    pub horizon: usize,
    pub name: String,
    /// The call.
    pub call_span: Span,
}

impl<'a> Checker<'a> {
    /// `fn name(params) = body`: recorded; the body is checked at each call.
    pub(super) fn fn_definition(&mut self, def: &'a FnDef, item: usize) {
        if let Some(d) = self.reserved_name(&def.name) {
            self.diags.push(d);
            self.failed.insert(def.name.name.clone());
            return;
        }
        if self.defined_twice(&def.name) {
            return;
        }
        let mut ok = true;
        // Each name's first parameter (a search of the ones before made 100 000 parameters
        // take 26 s).
        let mut first_of: std::collections::HashMap<&str, &crate::syntax::Ident> =
            std::collections::HashMap::new();
        for p in &def.params {
            if let Some(d) = self.reserved_name(&p.name) {
                self.diags.push(d);
                ok = false;
            }
            if let Some(first) = first_of.get(p.name.name.as_str()) {
                self.diags.push(
                    Diagnostic::error(
                        p.name.span,
                        format!(
                            "`{}` has two parameters named `{}`",
                            def.name.name, p.name.name
                        ),
                    )
                    .label("second parameter")
                    .also(first.span, "first parameter"),
                );
                ok = false;
            } else {
                first_of.insert(&p.name.name, &p.name);
            }
            if let Some(t) = &p.ty
                && !TYPES.contains(&t.name.as_str())
                && t.name != "colour"
            {
                let mut d = Diagnostic::error(t.span, format!("unknown type `{}`", t.name))
                    .label("not a type");
                d = match self.did_you_mean(&t.name, TYPES.iter().copied()) {
                    Some(s) => d.help(format!("did you mean `{s}`?")),
                    None => d.note("the types are number, angle, vector, color and shape"),
                };
                self.diags.push(d);
                ok = false;
            }
        }
        if !ok {
            self.failed.insert(def.name.name.clone());
            return;
        }
        self.item_of.insert(def.name.name.clone(), item);
        self.fns.insert(
            def.name.name.clone(),
            FnEntry {
                def,
                item,
                used: false,
            },
        );
    }

    /// A call of a user-defined function; `piped` is its first argument (`s |> f(…)`).
    pub(super) fn fn_call(&mut self, call: &Call, piped: Option<NodeId>) -> Option<Value> {
        let name = call.name.name.as_str();
        let (def, item) = {
            let entry = self.fns.get_mut(name)?;
            entry.used = true;
            (entry.def, entry.item)
        };
        if !self.may_expand(call, def) {
            return None;
        }
        let given = self.fn_args(def, call, piped)?;
        // The body's scope: the arguments, then defaults in order (each sees the earlier ones).
        let saved_defining = self.defining.take();
        self.frames.push(Frame {
            args: HashMap::new(),
            horizon: item,
            name: name.to_string(),
            call_span: call.span,
        });
        let ok = self.bind_params(call, def, given);
        let out = if ok {
            self.in_body(call, |c| c.value(&def.body))
        } else {
            None
        };
        self.frames.pop();
        self.defining = saved_defining;
        if let Some(Value::Shape(n)) = out {
            self.nodes[n].name.get_or_insert_with(|| name.to_string());
        }
        out
    }

    /// Whether the call of `def` may be expanded: not a recursive call, no block, and not one
    /// call past [`MAX_CALLS`] (counted here); each refusal reported.
    fn may_expand(&mut self, call: &Call, def: &FnDef) -> bool {
        let name = call.name.name.as_str();
        if self.frames.iter().any(|f| f.name == name) {
            let chain: Vec<&str> = self
                .frames
                .iter()
                .map(|f| f.name.as_str())
                .skip_while(|n| *n != name)
                .chain([name])
                .collect();
            self.diags.push(
                Diagnostic::error(call.name.span, format!("`{name}` calls itself"))
                    .label("a recursive call")
                    .also(def.name.span, "defined here")
                    .note(format!("the chain: {}", chain.join(" → ")))
                    .note("a call is expanded where it is written, so a function cannot recurse; write the levels out, or use `repeat`"),
            );
            return false;
        }
        if let Some(block) = &call.block {
            let span = block.first().map_or(call.span, |e| e.span);
            self.diags.push(
                Diagnostic::error(span, format!("`{name}` is a function and takes no block"))
                    .label("unexpected block")
                    .also(def.name.span, "defined here")
                    .help("pass shapes as arguments: `fn f(s: shape) = …` and `f(sphere(1))`"),
            );
            return false;
        }
        self.calls += 1;
        if self.calls > MAX_CALLS {
            if self.calls == MAX_CALLS + 1 {
                self.diags.push(
                    Diagnostic::error(call.span, "too many function calls")
                        .label(format!("more than {MAX_CALLS} calls expanded"))
                        .note("each call is expanded where it is written; functions that call others several times grow exponentially"),
                );
            }
            return false;
        }
        true
    }

    /// Puts each parameter's value in the innermost frame: the argument given, else its
    /// default checked in the body's scope (seeing the earlier ones); whether all have one.
    fn bind_params(&mut self, call: &Call, def: &FnDef, given: Vec<Option<Value>>) -> bool {
        let mut ok = true;
        for (p, g) in def.params.iter().zip(given) {
            let v = match g {
                Some(v) => Some(v),
                None => {
                    let default = p.default.as_ref().expect("checked: missing ones reported");
                    self.in_body(call, |c| c.value(default))
                }
            };
            match v {
                Some(v) => {
                    let frame = self.frames.last_mut().expect("pushed");
                    frame.args.insert(p.name.name.clone(), v);
                }
                None => ok = false,
            }
        }
        ok
    }

    /// Runs `f` (checking part of a body for the call `call`): its diagnostics point into the
    /// body and show the call beside them (the innermost [`MAX_CALL_LABELS`] calls of a
    /// chain). The same message for later calls is dropped at the end of the check.
    fn in_body(
        &mut self,
        call: &Call,
        f: impl FnOnce(&mut Self) -> Option<Value>,
    ) -> Option<Value> {
        let start = self.diags.len();
        let v = f(self);
        let label = format!("in this call of `{}`", call.name.name);
        for d in &mut self.diags[start..] {
            let calls = d
                .secondary
                .iter()
                .filter(|(_, l)| l.starts_with("in this call of"))
                .count();
            if !call.span.contains(d.span) && calls < MAX_CALL_LABELS {
                d.secondary.push((call.span, label.clone()));
            }
        }
        v
    }

    /// Whether `name` (a `let`, parameter, function or material) may be used here: inside a
    /// body, only what was defined before the function.
    pub(super) fn visible(&self, name: &str) -> bool {
        match self.frames.last() {
            None => true,
            Some(f) => self.item_of.get(name).is_none_or(|&i| i < f.horizon),
        }
    }

    /// `d`, about node `n`, with the call that built `n` beside it when a function's body did
    /// (for errors found after the statements, when no call is being checked).
    pub(super) fn with_call_site(&self, d: Diagnostic, n: NodeId) -> Diagnostic {
        match self.call_site.get(n).copied().flatten() {
            Some(call) if !call.contains(d.span) => d.also(call, "built by this call"),
            _ => d,
        }
    }

    /// Whether material `name` may be used here: inside a body, only one declared before the
    /// function.
    pub(super) fn material_visible(&self, name: &str) -> bool {
        match self.frames.last() {
            None => true,
            Some(f) => self.material_item.get(name).is_none_or(|&i| i < f.horizon),
        }
    }

    /// Whether a call of `name` is being checked (a call of it again recurses).
    pub(super) fn in_frame(&self, name: &str) -> bool {
        self.frames.iter().any(|f| f.name == name)
    }

    /// The error for a body's use of a name defined after its function.
    pub(super) fn defined_after_fn(&mut self, id: &crate::syntax::Ident) -> Option<Value> {
        let at = self.declared.get(&id.name).copied();
        self.defined_after_fn_at(id, at)
    }

    /// As [`Self::defined_after_fn`], with the definition at `at`.
    pub(super) fn defined_after_fn_at(
        &mut self,
        id: &crate::syntax::Ident,
        at: Option<Span>,
    ) -> Option<Value> {
        let frame = self
            .frames
            .last()
            .map(|f| f.name.clone())
            .unwrap_or_default();
        let def = self.fns.get(&frame).map(|e| e.def.name.span);
        let mut d = Diagnostic::error(
            id.span,
            format!("`{}` is defined after the function `{frame}`", id.name),
        )
        .label("not visible in this body");
        if let Some(def) = def {
            d = d.also(def, "the function");
        }
        if let Some(at) = at {
            d = d.also(at, "defined here");
        }
        self.diags.push(
            d.help("a body sees its arguments and what is defined above the `fn`; move the definition up or pass it as an argument"),
        );
        None
    }

    /// An argument of the innermost call being checked, by name.
    pub(super) fn fn_arg(&self, name: &str) -> Option<Value> {
        self.frames.last()?.args.get(name).cloned()
    }

    /// Functions of the main file never called: a warning (their bodies were never checked).
    pub(super) fn unused_fns(&mut self, main_len: usize) {
        if self.diags.iter().any(Diagnostic::is_error) {
            // A call with a mistake may be the one meant.
            return;
        }
        let mut unused: Vec<&FnDef> = self
            .fns
            .values()
            .filter(|e| !e.used && e.def.span.start <= main_len)
            .map(|e| e.def)
            .collect();
        unused.sort_by_key(|d| d.span.start);
        for def in unused {
            self.diags.push(
                Diagnostic::warning(
                    def.name.span,
                    format!("`{}` is never called", def.name.name),
                )
                .label("unused function")
                .note("a function's body is checked where it is called"),
            );
        }
    }
}

pub(super) use super::fn_args::signature;
