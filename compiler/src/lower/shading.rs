//! Shading in IR: `normal` from a tetrahedron of samples and `shade` with only the lights and
//! material terms the scene has.

use super::builder::{FnBuilder, ModuleBuilder};
use super::tracer::{AMBIENT, DEFAULT_COLOR, SHININESS};
use crate::scene::{LightKind, Scene, Shadow};
use naga::{Function, Handle, MathFunction as M};

/// `normal(p, h)`: the field's gradient from four samples at the corners of a tetrahedron
/// around `p`, each at distance `h` (see [`crate::eval::TETRAHEDRON`]), normalised: four
/// evaluations instead of central differences' six (Munini §2.3), at the price of an O(h)
/// error from the mixed second derivatives where central differences have O(h²); a zero
/// gradient gives zero, not NaN.
pub(super) fn add_normal(mb: &mut ModuleBuilder, map: Handle<Function>) -> Handle<Function> {
    let v3 = mb.vec3();
    let f32t = mb.f32();
    let mut b = FnBuilder::new(mb, "normal", &[("p", v3), ("h", f32t)], Some(v3));
    let (p, h) = (b.arg(0), b.arg(1));
    let zero = b.f(0.0);
    let third = b.f(1.0 / 3f64.sqrt());
    let e = b.mul(h, third);
    let mut g = None;
    for k in crate::eval::TETRAHEDRON {
        let corner = b.vec3_lit(k);
        let off = b.mul(corner, e);
        let q = b.add(p, off);
        let d = b.call(map, vec![q]);
        let term = b.mul(corner, d);
        g = Some(match g {
            None => term,
            Some(sum) => b.add(sum, term),
        });
    }
    let g = g.expect("four corners");
    let l = b.length(g);
    let one = b.f(1.0);
    let inv = b.div(one, l);
    let n = b.mul(g, inv);
    let zv = b.splat3(0.0);
    let ok = b.gt(l, zero);
    let n = b.select(ok, n, zv);
    b.ret(Some(n));
    let f = b.finish();
    mb.add_function(f)
}

/// Most steps of a shadow ray.
pub const SHADOW_STEPS: u32 = 64;

/// Whether some light casts shadows (then `shade` takes the hit threshold `h` and calls
/// `shadow`).
pub fn has_shadows(scene: &Scene) -> bool {
    scene.lights.iter().any(|l| l.shadow != Shadow::None)
}

/// `shadow(p, n, l, far, h, k)`: how much of the light in direction `l` reaches the surface
/// point `p` of normal `n` — sphere tracing towards it from `p` moved along `n` by Keinert's
/// ε_dynamic = 2·max(h, |f(p)|) (§3.3: the ray neither finds the surface it leaves nor starts
/// inside another), up to `far`: 0 when some step comes within `h` of a surface; with `k` > 0
/// the penumbra min(k·f/t) of the closest approach (soft), else 1 (hard). At most
/// [`SHADOW_STEPS`] evaluations; a ray that runs out counts as lit.
fn add_shadow(mb: &mut ModuleBuilder, map: Handle<Function>) -> Handle<Function> {
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
    let here = b.call(map, vec![p]);
    let here = b.abs(here);
    let lift = b.max(here, h);
    let two = b.f(2.0);
    let lift = b.mul(lift, two);
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

/// `shade(p, n, rd, material[, h])`: Lambert with an ambient term (Munini §2.3), a Blinn–Phong
/// highlight only if some material is specular, the scene's lights folded in as constants;
/// with shadows, each shadowing light's terms scaled by `shadow` (`h`: the hit threshold).
pub(super) fn add_shade(
    mb: &mut ModuleBuilder,
    scene: &Scene,
    map: Handle<Function>,
) -> Handle<Function> {
    let shadow = has_shadows(scene).then(|| add_shadow(mb, map));
    let v3 = mb.vec3();
    let u32t = mb.u32();
    let f32t = mb.f32();
    let mut args = vec![("p", v3), ("n", v3), ("rd", v3), ("material", u32t)];
    if shadow.is_some() {
        args.push(("h", f32t));
    }
    let mut b = FnBuilder::new(mb, "shade", &args, Some(v3));
    let (p, n, rd, mat) = (b.arg(0), b.arg(1), b.arg(2), b.arg(3));
    // Scene colours are sRGB; lighting is linear (the conversion folds at compile time).
    let mut base = b.vec3_lit(crate::color::linear(DEFAULT_COLOR));
    let mut spec = None;
    for (i, m) in scene.materials.iter().enumerate() {
        let id = b.u(i as u32 + 1);
        let is = b.bin(naga::BinaryOperator::Equal, mat, id);
        let c = b.vec3_lit(crate::color::linear(m.color));
        base = b.select(is, c, base);
        if m.specular > 0.0 || spec.is_some() {
            let prev = match spec {
                Some(s) => s,
                None => b.f(0.0),
            };
            let s = b.f(m.specular);
            spec = Some(b.select(is, s, prev));
        }
    }
    let amb = b.f(AMBIENT);
    let mut color = b.mul(base, amb);
    for light in &scene.lights {
        let (l, far) = match light.kind {
            LightKind::Directional(d) => (b.vec3_lit(d.normalize()), b.f(scene.trace.max_distance)),
            LightKind::Point(pos) => {
                let pv = b.vec3_lit(pos);
                let d = b.sub(pv, p);
                (b.math(M::Normalize, &[d]), b.length(d))
            }
        };
        let ndl = b.dot(n, l);
        let zero = b.f(0.0);
        let diff = b.max(ndl, zero);
        let lc = b.vec3_lit(crate::color::linear(light.color) * light.intensity);
        let lc = match (shadow, light.shadow) {
            (Some(f), Shadow::Hard | Shadow::Soft(_)) => {
                let k = match light.shadow {
                    Shadow::Soft(k) => b.f(k),
                    _ => b.f(0.0),
                };
                let h = b.arg(4);
                let seen = b.call(f, vec![p, n, l, far, h, k]);
                b.mul(lc, seen)
            }
            _ => lc,
        };
        let lit = b.mul(lc, diff);
        let lit = b.mul(base, lit);
        color = b.add(color, lit);
        if let Some(s) = spec {
            let hv = b.sub(l, rd);
            let hv = b.math(M::Normalize, &[hv]);
            let ndh = b.dot(n, hv);
            let ndh = b.max(ndh, zero);
            let e = b.f(SHININESS);
            let hl = b.math(M::Pow, &[ndh, e]);
            let hl = b.mul(hl, s);
            let hl = b.mul(lc, hl);
            color = b.add(color, hl);
        }
    }
    b.ret(Some(color));
    let f = b.finish();
    mb.add_function(f)
}
