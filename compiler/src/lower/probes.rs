//! Samples of the field away from the camera ray, for shading: shadow rays towards lights,
//! ambient occlusion along the normal, and how far secondary rays start off the surface (the
//! f64 formulas they mirror: `crate::reference::shading`).

use crate::ir::builder::{Ex, FnBuilder, ModuleBuilder};
use crate::reference::shading::SHADOW_STEPS;
use crate::scene::Occlusion;
use naga::{Function, Handle};

/// `shadow(p, n, l, far, h, k)`: how much of the light in direction `l` reaches the surface
/// point `p` of normal `n` — sphere tracing towards it from `p` moved along `n` by Keinert's
/// ε_dynamic = 2·max(h, |f(p)|) (§3.3: the ray neither finds the surface it leaves nor starts
/// inside another), up to `far`: 0 when some step comes within `h` of a surface; with `k` > 0
/// the penumbra min(k·f/t) of the closest approach (soft), else 1 (hard). At most
/// [`SHADOW_STEPS`] evaluations; a ray that runs out counts as lit.
pub(super) fn add_shadow(
    mb: &mut ModuleBuilder,
    map: Handle<Function>,
    fixed_offset: Option<f64>,
) -> Handle<Function> {
    let v3 = mb.vec3();
    let f32t = mb.f32();
    let args = [
        ("p", v3),
        ("n", v3),
        ("l", v3),
        ("far", f32t),
        ("h", f32t),
        ("k", f32t),
    ];
    let mut b = FnBuilder::new(mb, "shadow", &args, Some(f32t));
    let (p, n, l, far, h, k) = (b.arg(0), b.arg(1), b.arg(2), b.arg(3), b.arg(4), b.arg(5));
    let lift = lift(&mut b, map, p, h, fixed_offset);
    let up = b.mul(n, lift);
    let p = b.add(p, up);
    let zero = b.f(0.0);
    let t = b.local("t", f32t, Some(zero));
    let one = b.f(1.0);
    let lit = b.local("lit", f32t, Some(one));
    let u32t = b.m.u32();
    let zero_u = b.u(0);
    let i = b.local("i", u32t, Some(zero_u));
    b.loop_(|b| {
        let (tv, iv) = (b.load(t), b.load(i));
        let limit = b.u(SHADOW_STEPS);
        let out = b.ge(iv, limit);
        let gone = b.ge(tv, far);
        let stop = b.bin(naga::BinaryOperator::LogicalOr, out, gone);
        b.break_if(stop);
        b.increment(i);
        let s = b.mul(l, tv);
        let q = b.add(p, s);
        super::count::count(b, 1);
        let d = b.call(map, vec![q]);
        let blocked = b.lt(d, h);
        b.if_(
            blocked,
            |b| {
                let zero = b.f(0.0);
                b.store(lit, zero);
                b.brk();
            },
            |_| {},
        );
        // Soft: the closest approach relative to the distance travelled (k = 0: hard, 1).
        let kd = b.mul(k, d);
        let tiny = b.f(1e-6);
        let tt = b.max(tv, tiny);
        let kd = b.div(kd, tt);
        let zero = b.f(0.0);
        let soft = b.gt(k, zero);
        let cur = b.load(lit);
        let m = b.min(cur, kd);
        let m = b.select(soft, m, cur);
        b.store(lit, m);
        let nt = b.add(tv, d);
        b.store(t, nt);
    });
    let v = b.load(lit);
    let zero = b.f(0.0);
    let one = b.f(1.0);
    let v = b.clamp(v, zero, one);
    b.ret(Some(v));
    let f = b.finish();
    mb.add_function(f)
}

/// `occlusion(p, n)`: ambient occlusion at the surface point `p` of normal `n` (Evans 2006, as
/// `crate::reference::shading::occlusion`): `samples` evaluations at i·δ along `n` in one loop (one call
/// site of `map`), the missing clearance iδ − f weighted by 2⁻ⁱ; returns
/// clamp(1 − strength·Σ/δ, 0, 1).
pub(super) fn add_occlusion(
    mb: &mut ModuleBuilder,
    map: Handle<Function>,
    o: &Occlusion,
) -> Handle<Function> {
    let v3 = mb.vec3();
    let f32t = mb.f32();
    let u32t = mb.u32();
    let mut b = FnBuilder::new(mb, "occlusion", &[("p", v3), ("n", v3)], Some(f32t));
    let (p, n) = (b.arg(0), b.arg(1));
    let delta = o.distance / o.samples as f64;
    let zero = b.f(0.0);
    let missing = b.local("missing", f32t, Some(zero));
    let half = b.f(0.5);
    let w = b.local("w", f32t, Some(half));
    let one_u = b.u(1);
    let i = b.local("i", u32t, Some(one_u));
    b.loop_(|b| {
        let iv = b.load(i);
        let last = b.u(o.samples);
        let done = b.gt(iv, last);
        b.break_if(done);
        let fi = b.cast(iv, naga::ScalarKind::Float);
        let d = b.f(delta);
        let s = b.mul(d, fi);
        let off = b.mul(n, s);
        let q = b.add(p, off);
        super::count::count(b, 1);
        let f = b.call(map, vec![q]);
        let gap = b.sub(s, f);
        let wv = b.load(w);
        let term = b.mul(wv, gap);
        let m = b.load(missing);
        let m = b.add(m, term);
        b.store(missing, m);
        let half = b.f(0.5);
        let wn = b.mul(wv, half);
        b.store(w, wn);
        b.increment(i);
    });
    let m = b.load(missing);
    let k = b.f(o.strength / delta);
    let km = b.mul(k, m);
    let one = b.f(1.0);
    let ao = b.sub(one, km);
    let zero = b.f(0.0);
    let one = b.f(1.0);
    let ao = b.clamp(ao, zero, one);
    b.ret(Some(ao));
    let f = b.finish();
    mb.add_function(f)
}

/// How far a secondary ray's origin moves off the surface point `p`: Keinert's ε_dynamic =
/// 2·max(h, |f(p)|) (§3.3), or `fixed` (for comparison, `Options::fixed_offset`).
pub(super) fn lift(
    b: &mut FnBuilder,
    map: Handle<Function>,
    p: Ex,
    h: Ex,
    fixed: Option<f64>,
) -> Ex {
    if let Some(f) = fixed {
        return b.f(f);
    }
    super::count::count(b, 1);
    let here = b.call(map, vec![p]);
    let here = b.abs(here);
    let lift = b.max(here, h);
    let two = b.f(2.0);
    b.mul(lift, two)
}
