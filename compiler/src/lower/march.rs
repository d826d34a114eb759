//! The frame every tracing variant is lowered into: `trace_<method>(ro, rd[, pixel][, start,
//! end][, budget, cone])` with its result type, ε(t), counting and stopping; the variants' bodies
//! live in `variants.rs` (the caller passes `variants::body`), step for step the same as the
//! CPU reference in `crate::reference::trace`.

use super::globals::struct_ty;
use crate::ir::builder::{Ex, FnBuilder, ModuleBuilder};
use crate::reference::trace::TOUCH;
use crate::scene::{Epsilon, Method, Trace};
use naga::{Function, Handle, Type};

/// Bit of `TraceResult.flags`: the ray hit (or, for `relaxed`, its candidate is taken).
pub const HIT: u32 = 1;
/// Bit of `TraceResult.flags`: the step budget ran out.
pub const EXHAUSTED: u32 = 2;

/// Whether `flags` (a `TraceResult`'s) have the [`HIT`] bit.
pub fn is_hit(b: &mut FnBuilder, flags: Ex) -> Ex {
    let bit = b.u(HIT);
    let masked = b.bin(naga::BinaryOperator::And, flags, bit);
    let zero = b.u(0);
    b.bin(naga::BinaryOperator::NotEqual, masked, zero)
}

/// `struct TraceResult { t: f32, steps: u32, flags: u32 }` (flags: [`HIT`] | [`EXHAUSTED`]),
/// with cone anti-aliasing also `cover_t: f32, cover: f32` (see `crate::reference::trace::Traced`).
pub fn trace_result_type(mb: &mut ModuleBuilder, antialias: bool) -> Handle<Type> {
    let (f, u) = (mb.f32(), mb.u32());
    let mut members = vec![("t", f, 0), ("steps", u, 4), ("flags", u, 8)];
    if antialias {
        members.extend([("cover_t", f, 12), ("cover", f, 16)]);
    }
    let span = 4 * members.len() as u32;
    struct_ty(mb, "TraceResult", &members, span)
}

/// The hit threshold ε(t): absolute, or `pixel·t` kept above `floor`.
pub fn epsilon(b: &mut FnBuilder, trace: &Trace, t: Ex, pixel: Option<Ex>, floor: f64) -> Ex {
    match (trace.epsilon, pixel) {
        (Epsilon::Pixel, Some(px)) => {
            let e = b.mul(px, t);
            let fl = b.f(floor);
            b.max(e, fl)
        }
        // Below the floor f32 positions cannot resolve the surface (the check warns).
        (Epsilon::Absolute(e), _) => b.f(e.max(floor).max(f64::MIN_POSITIVE)),
        (Epsilon::Pixel, None) => b.f(floor),
    }
}

/// The name of a variant's function.
pub fn function_name(method: Method) -> String {
    format!("trace_{}", crate::check::tracer::method_entry(method).0)
}

/// Which inputs `trace_<method>` takes besides `ro` and `rd`, each only when something needs it
/// (mirrors `crate::reference::trace::Segment`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Inputs {
    /// `pixel`: the footprint of a pixel per unit distance, for the pixel ε.
    pub pixel: bool,
    /// `start, end`: the part of the ray to search (a convex bound, a multi-resolution pass).
    pub segment: bool,
    /// `budget, cone`: the step budget and the cone slope α of a multi-resolution pass
    /// (Bálint §4: the field is traced as F = (f − α·t)/(1 + α)).
    pub pass: bool,
}

impl Inputs {
    /// The arguments in order, with their types.
    pub fn arguments(self, mb: &mut ModuleBuilder) -> Vec<(&'static str, Handle<Type>)> {
        let (v3, f, u) = (mb.vec3(), mb.f32(), mb.u32());
        let mut args = vec![("ro", v3), ("rd", v3)];
        if self.pixel {
            args.push(("pixel", f));
        }
        if self.segment {
            args.extend([("start", f), ("end", f)]);
        }
        if self.pass {
            args.extend([("budget", u), ("cone", f)]);
        }
        args
    }
}

/// What every variant's body uses: the ray, the field, the result variables. Inside, `t` runs
/// from 0 at `start` (the ray's origin `ro` is moved there), so only ε, the far limit and the
/// cone transform see the offset.
#[derive(Clone, Copy)]
pub(super) struct Cx {
    map: Handle<Function>,
    /// The point where `t` = 0.
    pub ro: Ex,
    pub rd: Ex,
    pixel: Option<Ex>,
    floor: f64,
    pub trace: Trace,
    /// Distance of `ro` from the ray's real origin (`start`), if a segment is traced.
    offset: Option<Ex>,
    /// Length of the segment (`end − start`), if given.
    length: Option<Ex>,
    budget: Option<Ex>,
    cone: Option<Ex>,
    /// Pointers to the result variables; `p` is the current point, advanced with `t` rather
    /// than recomputed as ro + rd·t, which keeps the coordinates near the surface exact to f32
    /// where the ray is long and grazing (the grazing-plane table at 0.1°).
    pub t: Ex,
    pub p: Ex,
    pub steps: Ex,
    pub flags: Ex,
    /// With cone anti-aliasing: the best near miss's t and coverage.
    pub cover: Option<(Ex, Ex)>,
    /// `map_loose`, if hits are confirmed (`careful.rs`): the scene's f/λ is not a distance to
    /// first order everywhere.
    pub loose: Option<Handle<Function>>,
}

impl Cx {
    /// The pixel footprint argument (present in pixel-ε mode and with anti-aliasing).
    pub fn pixel(&self) -> Option<Ex> {
        self.pixel
    }

    /// The cone slope argument of a multi-resolution pass, if the function takes one.
    pub fn cone(&self) -> Option<Ex> {
        self.cone
    }

    /// Distance from the real origin of the point at `t`.
    pub fn absolute(&self, b: &mut FnBuilder, t: Ex) -> Ex {
        match self.offset {
            Some(o) => b.add(t, o),
            None => t,
        }
    }

    /// `map(ro + rd·t)`, counted as a step.
    pub fn field(&self, b: &mut FnBuilder, t: Ex) -> Ex {
        let s = b.mul(self.rd, t);
        let p = b.add(self.ro, s);
        self.field_at(b, p, t)
    }

    /// `map(point)` for the point at `t`, counted as a step; in a cone pass Bálint's transform
    /// F = (f − α·t)/(1 + α) of it.
    pub fn field_at(&self, b: &mut FnBuilder, point: Ex, t: Ex) -> Ex {
        let d = b.call(self.map, vec![point]);
        b.increment(self.steps);
        match self.cone {
            Some(alpha) => {
                let at = self.absolute(b, t);
                let widening = b.mul(alpha, at);
                let d = b.sub(d, widening);
                let one = b.f(1.0);
                let scale = b.add(one, alpha);
                b.div(d, scale)
            }
            None => d,
        }
    }

    /// The field at the current point, counted as a step and named: (t, the field).
    pub fn here(&self, b: &mut FnBuilder, name: &str) -> (Ex, Ex) {
        let t = b.load(self.t);
        let p = b.load(self.p);
        let d = self.field_at(b, p, t);
        b.name(d, name);
        (t, d)
    }

    /// The current point moved by `step` along the ray.
    pub fn ahead(&self, b: &mut FnBuilder, step: Ex) -> Ex {
        let p = b.load(self.p);
        let s = b.mul(self.rd, step);
        b.add(p, s)
    }

    /// Evaluates the field `step` ahead of the current point (at t0 + step) and tests whether
    /// the unbounding spheres there and here (radius `r`) fail to overlap (see [`Cx::apart`]);
    /// `e` is ε at t0 where the caller has it at hand (auto's hit test computed it this
    /// iteration); else it is computed here. Returns (t0 + step, the point, the field there, the
    /// test).
    pub fn probe(
        &self,
        b: &mut FnBuilder,
        t0: Ex,
        (r, step): (Ex, Ex),
        e: Option<Ex>,
    ) -> (Ex, Ex, Ex, Ex) {
        let at = b.add(t0, step);
        let point = self.ahead(b, step);
        let rn = self.field_at(b, point, at);
        b.name(rn, "r_next");
        let e = e.unwrap_or_else(|| self.eps(b, t0));
        let apart = self.apart(b, step, (r, rn), e);
        (at, point, rn, apart)
    }

    /// `crate::reference::trace::apart`: spheres of radii `r.0`, `r.1` a `step` apart fail to overlap by
    /// more than the [`TOUCH`] margin, kept below `e` (ε at the current point).
    pub fn apart(&self, b: &mut FnBuilder, step: Ex, r: (Ex, Ex), e: Ex) -> Ex {
        let (a, c) = (b.abs(r.0), b.abs(r.1));
        let reach = b.add(a, c);
        let touch = b.f(TOUCH);
        let margin = b.mul(reach, touch);
        let margin = b.min(margin, e);
        let reach = b.add(reach, margin);
        b.gt(step, reach)
    }

    /// `t = t0 + step; p = p + rd·step`.
    pub fn advance(&self, b: &mut FnBuilder, t0: Ex, step: Ex) -> Ex {
        let nt = b.add(t0, step);
        b.store(self.t, nt);
        let np = self.ahead(b, step);
        b.store(self.p, np);
        nt
    }

    /// ε at the point `t`.
    pub fn eps(&self, b: &mut FnBuilder, t: Ex) -> Ex {
        let at = self.absolute(b, t);
        epsilon(b, &self.trace, at, self.pixel, self.floor)
    }

    /// Where the search ends (in the variant's `t`).
    pub fn far(&self, b: &mut FnBuilder) -> Ex {
        match self.length {
            Some(l) => l,
            None => b.f(self.trace.max_distance),
        }
    }

    /// `if steps >= budget { on_exhausted; flags = value; break; }`
    pub fn budget(&self, b: &mut FnBuilder, value: u32, on_exhausted: impl FnOnce(&mut FnBuilder)) {
        let n = b.load(self.steps);
        let budget = match self.budget {
            Some(budget) => budget,
            None => b.u(self.trace.steps),
        };
        let out = b.ge(n, budget);
        let flags = self.flags;
        b.if_(
            out,
            |b| {
                on_exhausted(b);
                let e = b.u(value);
                b.store(flags, e);
                b.brk();
            },
            |_| {},
        );
    }

    /// `if condition { flags = value; break; }`
    pub fn stop_if(&self, b: &mut FnBuilder, condition: Ex, flags: u32) {
        let ptr = self.flags;
        b.if_(
            condition,
            |b| {
                if flags != 0 {
                    let v = b.u(flags);
                    b.store(ptr, v);
                }
                b.brk();
            },
            |_| {},
        );
    }
}

/// A local f32 variable.
pub(super) fn var(b: &mut FnBuilder, name: &str, init: f64) -> Ex {
    let ty = b.m.f32();
    let v = b.f(init);
    b.local(name, ty, Some(v))
}

/// The loop of a variant, emitted into the frame [`Cx`] (`variants::body`).
pub(super) type Body = fn(&mut FnBuilder, &Cx);

/// Adds `trace_<method>` for the settings' variant, taking `inputs`; `body` emits its loop.
pub(super) fn add_trace(
    mb: &mut ModuleBuilder,
    (map, loose): (Handle<Function>, Option<Handle<Function>>),
    result_ty: Handle<Type>,
    trace: &Trace,
    (inputs, floor): (Inputs, f64),
    body: Body,
) -> Handle<Function> {
    let f32t = mb.f32();
    let u32t = mb.u32();
    let v3 = mb.vec3();
    let args = inputs.arguments(mb);
    let mut b = FnBuilder::new(mb, &function_name(trace.method), &args, Some(result_ty));
    let mut next = 2;
    let mut arg = |b: &mut FnBuilder, on: bool| {
        on.then(|| {
            next += 1;
            b.arg(next - 1)
        })
    };
    let (origin, rd) = (b.arg(0), b.arg(1));
    let pixel = arg(&mut b, inputs.pixel);
    let start = arg(&mut b, inputs.segment);
    let end = arg(&mut b, inputs.segment);
    let budget = arg(&mut b, inputs.pass);
    let cone = arg(&mut b, inputs.pass);
    let (ro, length) = match (start, end) {
        (Some(s), Some(e)) => {
            let along = b.mul(rd, s);
            let ro = b.add(origin, along);
            b.name(ro, "from");
            (ro, Some(b.sub(e, s)))
        }
        _ => (origin, None),
    };
    let zero = b.f(0.0);
    let t = b.local("t", f32t, Some(zero));
    let zero_u = b.u(0);
    let steps = b.local("steps", u32t, Some(zero_u));
    let flags = b.local("flags", u32t, Some(zero_u));
    let p = b.local("position", v3, Some(ro));
    let cover = trace.antialias.then(|| {
        let zero = b.f(0.0);
        (
            b.local("cover_t", f32t, Some(zero)),
            b.local("cover", f32t, Some(zero)),
        )
    });
    let cx = Cx {
        map,
        ro,
        rd,
        pixel,
        floor,
        trace: *trace,
        offset: start,
        length,
        budget,
        cone,
        t,
        p,
        steps,
        flags,
        cover,
        loose,
    };
    body(&mut b, &cx);
    let tv = b.load(t);
    let tv = cx.absolute(&mut b, tv);
    let (s, h) = (b.load(steps), b.load(flags));
    let mut fields = vec![tv, s, h];
    if let Some((ct, c)) = cover {
        fields.extend([b.load(ct), b.load(c)]);
    }
    let r = b.compose(result_ty, fields);
    b.ret(Some(r));
    let f = b.finish();
    mb.add_function(f)
}
