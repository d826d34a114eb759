//! Reflected and refracted rays in IR: `march` (basic sphere tracing of ±f for secondary rays)
//! and `path`, one pixel's path through mirrors and transparent solids, a loop without
//! recursion (the f64 reference it mirrors: `crate::reference::pixel::path`).

use super::lobes::{Continuing, Lobes, continuing};
use super::probes::lift;
use crate::ir::builder::{Ex, FnBuilder, ModuleBuilder};
use crate::reference::pixel::{MIN_WEIGHT, REFLECTIONS, REFRACTIONS, SECONDARY_STEPS};
use crate::scene::Scene;
use naga::{BinaryOperator as Op, Function, Handle, MathFunction as M, Type, VectorSize};

/// `march(ro, rd, sign, h, far)`: basic sphere tracing of sign·f from `ro` along `rd` (sign −1
/// inside a solid): the t where sign·f < h, or −1 past `far` or after [`SECONDARY_STEPS`]
/// evaluations (`crate::reference::pixel::march`).
pub(super) fn add_march(mb: &mut ModuleBuilder, map: Handle<Function>) -> Handle<Function> {
    let v3 = mb.vec3();
    let f32t = mb.f32();
    let u32t = mb.u32();
    let args = [
        ("ro", v3),
        ("rd", v3),
        ("sign", f32t),
        ("h", f32t),
        ("far", f32t),
    ];
    let mut b = FnBuilder::new(mb, "march", &args, Some(f32t));
    let (ro, rd, sign, h, far) = (b.arg(0), b.arg(1), b.arg(2), b.arg(3), b.arg(4));
    let zero = b.f(0.0);
    let t = b.local("t", f32t, Some(zero));
    let zero_u = b.u(0);
    let i = b.local("i", u32t, Some(zero_u));
    b.loop_(|b| {
        let iv = b.load(i);
        let limit = b.u(SECONDARY_STEPS);
        let out = b.ge(iv, limit);
        b.break_if(out);
        b.increment(i);
        let tv = b.load(t);
        let s = b.mul(rd, tv);
        let q = b.add(ro, s);
        super::count::count(b, 1);
        let d = b.call(map, vec![q]);
        let d = b.mul(sign, d);
        let hit = b.lt(d, h);
        b.if_(hit, |b| b.ret(Some(tv)), |_| {});
        let nt = b.add(tv, d);
        b.store(t, nt);
        let gone = b.ge(nt, far);
        b.break_if(gone);
    });
    let miss = b.f(-1.0);
    b.ret(Some(miss));
    let f = b.finish();
    mb.add_function(f)
}

/// The functions `path` calls.
pub(super) struct Calls {
    pub map: Handle<Function>,
    pub normal: Handle<Function>,
    pub material: Handle<Function>,
    pub shade: Handle<Function>,
    pub march: Handle<Function>,
}

/// `path(p, n, rd, material, h, local) -> vec3`: the colour of a camera ray's hit at `p`
/// (normal `n`, own shading `local`) following one path of reflected and refracted rays —
/// the rule, budgets and offsets of `crate::reference::pixel::path`, step for step.
pub(super) fn add_path(
    mb: &mut ModuleBuilder,
    scene: &Scene,
    c: &Calls,
    fixed_offset: Option<f64>,
) -> Handle<Function> {
    let v3 = mb.vec3();
    let f32t = mb.f32();
    let u32t = mb.u32();
    let boolt = mb.bool();
    let args = [
        ("p", v3),
        ("n", v3),
        ("rd", v3),
        ("material", u32t),
        ("h", f32t),
        ("local", v3),
    ];
    let mut b = FnBuilder::new(mb, "path", &args, Some(v3));
    let v = Path::declare(&mut b, scene, [v3, f32t, u32t, boolt]);
    b.loop_(|b| {
        let (p, n, rd, m) = (b.load(v.p), b.load(v.n), b.load(v.rd), b.load(v.m));
        let inside = b.load(v.inside);
        let material = continuing(b, scene, m);
        let own = v.own_share(b, inside, &material, n);
        let lobes = Lobes::new(b, (inside, v.ior), &material, (n, rd), (own.one, own.zero));
        let reflected3 = v.spend(b, inside, &lobes);
        let other = b.select(lobes.through, reflected3, lobes.refracted);
        let wo = b.mul(own.w, other);
        let lost = b.mul(wo, v.bg);
        let acc = b.add(own.acc, lost);
        b.store(v.acc, acc);
        let gain = b.select(lobes.through, lobes.refracted, reflected3);
        let w = b.mul(own.w, gain);
        b.store(v.w, w);
        let mirror = b.math(M::Reflect, &[rd, lobes.facing]);
        let dir = b.select(lobes.through, lobes.dir_t, mirror);
        let wmax = b.max3(w);
        let least = b.f(MIN_WEIGHT);
        let faint = b.lt(wmax, least);
        b.if_(faint, |b| v.finish(b, None), |_| {});
        v.next(b, c, fixed_offset, (p, dir, inside), (&own, &lobes));
    });
    // (Every turn of the loop spends a bounce or returns, so the loop ends above.)
    let acc = b.load(v.acc);
    b.ret(Some(acc));
    let f = b.finish();
    mb.add_function(f)
}

/// The variables of `path`'s loop — the current hit (point, normal, ray direction, material,
/// its own shading), the colour gathered, the weight the rest of the path carries, whether the
/// ray is inside a solid and the solid's index, the bounces spent — and its constants.
struct Path {
    p: Ex,
    n: Ex,
    rd: Ex,
    m: Ex,
    local: Ex,
    acc: Ex,
    w: Ex,
    inside: Ex,
    ior: Ex,
    reflections: Ex,
    refractions: Ex,
    /// The background's linear colour.
    bg: Ex,
    far: Ex,
    h: Ex,
}

/// The hit's own share of the colour gathered: the weight and colour after it, with the
/// constants and the outside flag the rest of the turn uses.
struct Own {
    one: Ex,
    zero: Ex,
    w: Ex,
    acc: Ex,
    outside: Ex,
}

impl Path {
    /// Declares the loop's variables from the arguments (`types`: vec3, f32, u32, bool).
    fn declare(b: &mut FnBuilder, scene: &Scene, types: [Handle<Type>; 4]) -> Path {
        let [v3, f32t, u32t, boolt] = types;
        let h = b.arg(4);
        let vars: Vec<Ex> = [("p_", 0), ("n_", 1), ("rd_", 2), ("m", 3), ("local_", 5)]
            .iter()
            .map(|&(name, i)| {
                let init = b.arg(i);
                let ty = if i == 3 { u32t } else { v3 };
                b.local(name, ty, Some(init))
            })
            .collect();
        let [p, n, rd, m, local] = vars[..] else {
            unreachable!()
        };
        let zero3 = b.splat3(0.0);
        let acc = b.local("acc", v3, Some(zero3));
        let one3 = b.splat3(1.0);
        let w = b.local("w", v3, Some(one3));
        let no = b.boolean(false);
        let inside = b.local("inside", boolt, Some(no));
        let one = b.f(1.0);
        let ior = b.local("solid_ior", f32t, Some(one));
        let zero_u = b.u(0);
        let reflections = b.local("reflections", u32t, Some(zero_u));
        let refractions = b.local("refractions", u32t, Some(zero_u));
        let bg = b.vec3_lit(crate::color::linear(scene.background));
        let far = b.f(scene.trace.max_distance);
        Path {
            p,
            n,
            rd,
            m,
            local,
            acc,
            w,
            inside,
            ior,
            reflections,
            refractions,
            bg,
            far,
            h,
        }
    }

    /// Ends the path: the colour so far plus the weight (times `rest`, if given) in the
    /// background's colour.
    fn finish(&self, b: &mut FnBuilder, rest: Option<Ex>) {
        let acc = b.load(self.acc);
        let w = b.load(self.w);
        let wr = match rest {
            Some(r) => b.mul(w, r),
            None => w,
        };
        let add = b.mul(wr, self.bg);
        let out = b.add(acc, add);
        b.ret(Some(out));
    }

    /// Outside: the surface's own share, 1 − R − T of its shading, added to the colour; the
    /// path ends at an opaque surface, or where there is no normal.
    fn own_share(&self, b: &mut FnBuilder, inside: Ex, mat: &Continuing, n: Ex) -> Own {
        let one = b.f(1.0);
        let rt = b.add(mat.r, mat.t);
        let own = b.sub(one, rt);
        let zero = b.f(0.0);
        let own = b.select(inside, zero, own);
        let local = b.load(self.local);
        let w = b.load(self.w);
        let wl = b.mul(w, local);
        let gain = b.mul(wl, own);
        let acc = b.load(self.acc);
        let acc = b.add(acc, gain);
        b.store(self.acc, acc);
        let opaque = b.bin(Op::Equal, rt, zero);
        let outside = b.expr(naga::Expression::Unary {
            op: naga::UnaryOperator::LogicalNot,
            expr: inside,
        });
        let stop = b.bin(Op::LogicalAnd, outside, opaque);
        b.if_(stop, |b| b.ret(Some(acc)), |_| {});
        // No normal (a zero gradient): nowhere to reflect or refract to.
        let n2 = b.dot(n, n);
        let no_normal = b.bin(Op::Equal, n2, zero);
        b.if_(
            no_normal,
            |b| {
                let rest = b.select(inside, one, rt);
                self.finish(b, Some(rest));
            },
            |_| {},
        );
        Own {
            one,
            zero,
            w,
            acc,
            outside,
        }
    }

    /// The bounce's budget: refractions for a way through or within a solid, else
    /// reflections; a path that has spent it ends with both lobes in the background's colour.
    /// Returns the reflected weight as a vec3.
    fn spend(&self, b: &mut FnBuilder, inside: Ex, lobes: &Lobes) -> Ex {
        let uses_refr = b.bin(Op::LogicalOr, lobes.through, inside);
        let (nr, nf) = (b.load(self.refractions), b.load(self.reflections));
        let used = b.select(uses_refr, nr, nf);
        let (lr, lf) = (b.u(REFRACTIONS), b.u(REFLECTIONS));
        let limit = b.select(uses_refr, lr, lf);
        let spent = b.ge(used, limit);
        let reflected3 = b.splat(lobes.reflected, VectorSize::Tri);
        b.if_(
            spent,
            |b| {
                let both = b.add(lobes.refracted, reflected3);
                self.finish(b, Some(both));
            },
            |_| {},
        );
        let (one_u, zero_u) = (b.u(1), b.u(0));
        let dr = b.select(uses_refr, one_u, zero_u);
        let df = b.select(uses_refr, zero_u, one_u);
        let nr = b.add(nr, dr);
        b.store(self.refractions, nr);
        let nf = b.add(nf, df);
        b.store(self.reflections, nf);
        reflected3
    }

    /// The next ray: from p moved by ε_dynamic = 2·max(h, |f(p)|) to the side it goes to — a
    /// reflection stays on the ray's side, a refraction crosses into or out of the solid —
    /// marched to its hit, which becomes the current one (shaded where it is outside).
    fn next(
        &self,
        b: &mut FnBuilder,
        c: &Calls,
        fixed_offset: Option<f64>,
        (p, dir, inside): (Ex, Ex, Ex),
        (own, lobes): (&Own, &Lobes),
    ) {
        let h = self.h;
        let minus_one = b.f(-1.0);
        let side = b.select(lobes.through, minus_one, own.one);
        let lift = lift(b, c.map, p, h, fixed_offset);
        let off = b.mul(side, lift);
        let off = b.mul(lobes.facing, off);
        let ro = b.add(p, off);
        let now_inside = b.select(lobes.through, own.outside, inside);
        let sign = b.select(now_inside, minus_one, own.one);
        let tt = b.call(c.march, vec![ro, dir, sign, h, self.far]);
        let missed = b.lt(tt, own.zero);
        b.if_(missed, |b| self.finish(b, None), |_| {});
        let step = b.mul(dir, tt);
        let np = b.add(ro, step);
        let nn = b.call(c.normal, vec![np, h]);
        b.store(self.p, np);
        b.store(self.n, nn);
        b.store(self.rd, dir);
        b.store(self.inside, now_inside);
        b.store(self.ior, lobes.s_ior);
        let out = b.expr(naga::Expression::Unary {
            op: naga::UnaryOperator::LogicalNot,
            expr: now_inside,
        });
        b.if_(
            out,
            |b| {
                super::count::count(b, 1);
                let nm = b.call(c.material, vec![np]);
                let nl = super::shading::call_shade(b, c.shade, [np, nn, dir, nm], h);
                b.store(self.m, nm);
                b.store(self.local, nl);
            },
            |_| {},
        );
    }
}
