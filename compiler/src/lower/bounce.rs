//! Reflected and refracted rays in IR: `march` (basic sphere tracing of ±f for secondary rays)
//! and `path`, one pixel's path through mirrors and transparent solids, a loop without
//! recursion (the f64 reference it mirrors: `crate::shading::path`).

use super::builder::{Ex, FnBuilder, ModuleBuilder};
use super::probes::lift;
use crate::scene::Scene;
use crate::shading::{MIN_WEIGHT, REFLECTIONS, REFRACTIONS, SECONDARY_STEPS};
use naga::{BinaryOperator as Op, Function, Handle, MathFunction as M, VectorSize};

/// `march(ro, rd, sign, h, far)`: basic sphere tracing of sign·f from `ro` along `rd` (sign −1
/// inside a solid): the t where sign·f < h, or −1 past `far` or after [`SECONDARY_STEPS`]
/// evaluations (`crate::shading::march`).
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

/// Schlick's reflectance at cosine `c` for index `ior` (`crate::shading::schlick`), with the
/// fifth power as products.
fn schlick(b: &mut FnBuilder, c: Ex, ior: Ex) -> Ex {
    let one = b.f(1.0);
    let num = b.sub(ior, one);
    let den = b.add(ior, one);
    let r = b.div(num, den);
    let f0 = b.mul(r, r);
    let zero = b.f(0.0);
    let c = b.clamp(c, zero, one);
    let x = b.sub(one, c);
    let x2 = b.mul(x, x);
    let x4 = b.mul(x2, x2);
    let x5 = b.mul(x4, x);
    let rest = b.sub(one, f0);
    let rest = b.mul(rest, x5);
    b.add(f0, rest)
}

/// `path(p, n, rd, material, h, local) -> vec3`: the colour of a camera ray's hit at `p`
/// (normal `n`, own shading `local`) following one path of reflected and refracted rays —
/// the rule, budgets and offsets of `crate::shading::path`, step for step.
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
    let h = b.arg(4);
    let vars: Vec<Ex> = [("p_", 0), ("n_", 1), ("rd_", 2), ("m", 3), ("local_", 5)]
        .iter()
        .map(|&(name, i)| {
            let init = b.arg(i);
            let ty = if i == 3 { u32t } else { v3 };
            b.local(name, ty, Some(init))
        })
        .collect();
    let [p_v, n_v, rd_v, m_v, local_v] = vars[..] else {
        unreachable!()
    };
    let zero3 = b.splat3(0.0);
    let acc_v = b.local("acc", v3, Some(zero3));
    let one3 = b.splat3(1.0);
    let w_v = b.local("w", v3, Some(one3));
    let no = b.boolean(false);
    let inside_v = b.local("inside", boolt, Some(no));
    let one = b.f(1.0);
    let ior_v = b.local("solid_ior", f32t, Some(one));
    let zero_u = b.u(0);
    let reflections_v = b.local("reflections", u32t, Some(zero_u));
    let refractions_v = b.local("refractions", u32t, Some(zero_u));
    let bg = b.vec3_lit(crate::color::linear(scene.background));
    let far = b.f(scene.trace.max_distance);
    // Ends the path: the colour so far plus the weight (times `rest`, if given) in the
    // background's colour.
    let finish = |b: &mut FnBuilder, rest: Option<Ex>| {
        let acc = b.load(acc_v);
        let w = b.load(w_v);
        let wr = match rest {
            Some(r) => b.mul(w, r),
            None => w,
        };
        let add = b.mul(wr, bg);
        let out = b.add(acc, add);
        b.ret(Some(out));
    };
    b.loop_(|b| {
        let (p, n, rd, m) = (b.load(p_v), b.load(n_v), b.load(rd_v), b.load(m_v));
        let inside = b.load(inside_v);
        // The material seen from outside: reflect, transparent, ior, tint (linear colour).
        let (mut r, mut t, mut ior, mut tint) = (b.f(0.0), b.f(0.0), b.f(1.0), b.splat3(1.0));
        for (i, mat) in scene.materials.iter().enumerate() {
            if !mat.continues() {
                continue;
            }
            let id = b.u(i as u32 + 1);
            let is = b.bin(Op::Equal, m, id);
            let (mr, mt, mi) = (b.f(mat.reflect), b.f(mat.transparent), b.f(mat.ior));
            let mc =
                super::params::linear_color(b, mat.color, super::params::setting(&mat.sym, 0), m);
            r = b.select(is, mr, r);
            t = b.select(is, mt, t);
            ior = b.select(is, mi, ior);
            tint = b.select(is, mc, tint);
        }
        // Outside: the surface's own share, 1 − R − T of its shading.
        let one = b.f(1.0);
        let rt = b.add(r, t);
        let own = b.sub(one, rt);
        let zero = b.f(0.0);
        let own = b.select(inside, zero, own);
        let local = b.load(local_v);
        let w = b.load(w_v);
        let wl = b.mul(w, local);
        let gain = b.mul(wl, own);
        let acc = b.load(acc_v);
        let acc = b.add(acc, gain);
        b.store(acc_v, acc);
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
                finish(b, Some(rest));
            },
            |_| {},
        );
        // The lobes: refracted (leaving, or entering tinted) and reflected, about the normal
        // on the ray's side (`faceForward`: a silhouette's normal may face away from it).
        let solid_ior = b.load(ior_v);
        let s_ior = b.select(inside, solid_ior, ior);
        let facing = b.math(M::FaceForward, &[n, rd, n]);
        let inv = b.div(one, ior);
        let eta = b.select(inside, s_ior, inv);
        let dir_t = b.math(M::Refract, &[rd, facing, eta]);
        let len2 = b.dot(dir_t, dir_t);
        let tir = b.bin(Op::Equal, len2, zero);
        let c_in = b.dot(dir_t, facing);
        let c_in = b.neg(c_in);
        let c_out = b.dot(rd, facing);
        let c_out = b.neg(c_out);
        let cos = b.select(inside, c_in, c_out);
        let f = schlick(b, cos, s_ior);
        let f_in = b.select(tir, one, f);
        let has_t = b.gt(t, zero);
        let f_out = b.select(has_t, f, zero);
        let tf = b.mul(t, f_out);
        let refl_out = b.add(r, tf);
        let reflected = b.select(inside, f_in, refl_out);
        let keep = b.sub(one, f_out);
        let keep = b.mul(t, keep);
        let refr_out = b.mul(tint, keep);
        let keep_in = b.sub(one, f_in);
        let refr_in = b.splat(keep_in, VectorSize::Tri);
        let refracted = b.select(inside, refr_in, refr_out);
        let zero3 = b.splat3(0.0);
        let refracted = b.select(tir, zero3, refracted);
        let [x, y, z] = b.xyz(refracted);
        let sum = b.add(x, y);
        let sum = b.add(sum, z);
        let third = b.f(1.0 / 3.0);
        let mean = b.mul(sum, third);
        let heavier = b.ge(mean, reflected);
        let some = b.gt(mean, zero);
        let through = b.bin(Op::LogicalAnd, heavier, some);
        // The bounce's budget: refractions for a way through or within a solid, else
        // reflections.
        let uses_refr = b.bin(Op::LogicalOr, through, inside);
        let (nr, nf) = (b.load(refractions_v), b.load(reflections_v));
        let used = b.select(uses_refr, nr, nf);
        let (lr, lf) = (b.u(REFRACTIONS), b.u(REFLECTIONS));
        let limit = b.select(uses_refr, lr, lf);
        let spent = b.ge(used, limit);
        let reflected3 = b.splat(reflected, VectorSize::Tri);
        b.if_(
            spent,
            |b| {
                let both = b.add(refracted, reflected3);
                finish(b, Some(both));
            },
            |_| {},
        );
        let (one_u, zero_u) = (b.u(1), b.u(0));
        let dr = b.select(uses_refr, one_u, zero_u);
        let df = b.select(uses_refr, zero_u, one_u);
        let nr = b.add(nr, dr);
        b.store(refractions_v, nr);
        let nf = b.add(nf, df);
        b.store(reflections_v, nf);
        let other = b.select(through, reflected3, refracted);
        let wo = b.mul(w, other);
        let lost = b.mul(wo, bg);
        let acc = b.add(acc, lost);
        b.store(acc_v, acc);
        let gain = b.select(through, refracted, reflected3);
        let w = b.mul(w, gain);
        b.store(w_v, w);
        let mirror = b.math(M::Reflect, &[rd, facing]);
        let dir = b.select(through, dir_t, mirror);
        let wmax = b.max3(w);
        let least = b.f(MIN_WEIGHT);
        let faint = b.lt(wmax, least);
        b.if_(faint, |b| finish(b, None), |_| {});
        // The next ray: from p moved by ε_dynamic = 2·max(h, |f(p)|) to the side it goes to —
        // a reflection stays on the ray's side, a refraction crosses into or out of the solid.
        let minus_one = b.f(-1.0);
        let side = b.select(through, minus_one, one);
        let lift = lift(b, c.map, p, h, fixed_offset);
        let off = b.mul(side, lift);
        let off = b.mul(facing, off);
        let ro = b.add(p, off);
        let now_inside = b.select(through, outside, inside);
        let sign = b.select(now_inside, minus_one, one);
        let tt = b.call(c.march, vec![ro, dir, sign, h, far]);
        let missed = b.lt(tt, zero);
        b.if_(missed, |b| finish(b, None), |_| {});
        let step = b.mul(dir, tt);
        let np = b.add(ro, step);
        let nn = b.call(c.normal, vec![np, h]);
        b.store(p_v, np);
        b.store(n_v, nn);
        b.store(rd_v, dir);
        b.store(inside_v, now_inside);
        b.store(ior_v, s_ior);
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
                b.store(m_v, nm);
                b.store(local_v, nl);
            },
            |_| {},
        );
    });
    // (Every turn of the loop spends a bounce or returns, so the loop ends above.)
    let acc = b.load(acc_v);
    b.ret(Some(acc));
    let f = b.finish();
    mb.add_function(f)
}
