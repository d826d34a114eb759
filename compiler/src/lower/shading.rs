//! Shading in IR: `normal` from a tetrahedron of samples, `shade` with only the lights,
//! material terms, shadows and occlusion the scene has, and `fog` if it has fog (the f64
//! reference they mirror: `crate::reference::shading`).

use super::params;
use super::probes::{add_occlusion, add_shadow};
use super::vector::unit_or_zero;
use crate::catalog::gpu::args;
use crate::catalog::{Ty, Val};
use crate::ir::builder::{Ex, FnBuilder, ModuleBuilder};
use crate::reference::shading::{AMBIENT, DEFAULT_COLOR, SHININESS, has_shadows};
use crate::scene::{Light, LightKind, Scene, Shadow};
use naga::{Function, Handle, MathFunction as M, ScalarKind};

/// `normal(p, h)`: the field's gradient from four samples at the corners of a tetrahedron
/// around `p`, each at distance `h` (see [`crate::reference::eval::TETRAHEDRON`]), normalised: four
/// evaluations instead of central differences' six (Munini §2.3), at the price of an O(h)
/// error from the mixed second derivatives where central differences have O(h²); a zero
/// gradient gives zero, not NaN.
pub(super) fn add_normal(mb: &mut ModuleBuilder, map: Handle<Function>) -> Handle<Function> {
    let v3 = mb.vec3();
    let f32t = mb.f32();
    let mut b = FnBuilder::new(mb, "normal", &[("p", v3), ("h", f32t)], Some(v3));
    let (p, h) = (b.arg(0), b.arg(1));
    super::count::count(&mut b, crate::reference::eval::TETRAHEDRON.len() as u32);
    let third = b.f(1.0 / 3f64.sqrt());
    let e = b.mul(h, third);
    // One call of `map` in a loop over the corners rather than four: the driver inlines every
    // call, so four calls compile `map` four times (docs/stability.md, the compile cost). The
    // corner of index i is (((i + 3) >> 1) & 1, (i >> 1) & 1, i & 1) · 2 − 1, TETRAHEDRON's order;
    // the sum runs in the same order from zero, so the result is the same to the bit.
    let zero = b.splat3(0.0);
    let sum = b.local("gradient", v3, Some(zero));
    let four = b.u(crate::reference::eval::TETRAHEDRON.len() as u32);
    b.repeat("corner", four, |b, i| {
        let bit = |b: &mut FnBuilder, shift: u32, plus: u32| {
            let mut j = i;
            if plus > 0 {
                let add = b.u(plus);
                j = b.add(j, add);
            }
            if shift > 0 {
                let sh = b.u(shift);
                j = b.bin(naga::BinaryOperator::ShiftRight, j, sh);
            }
            let one = b.u(1);
            let j = b.bin(naga::BinaryOperator::And, j, one);
            b.cast(j, ScalarKind::Float)
        };
        let c = [bit(b, 1, 3), bit(b, 1, 0), bit(b, 0, 0)];
        let unit = b.compose_vec3(c);
        let two = b.f(2.0);
        let one = b.splat3(1.0);
        let twice = b.mul(unit, two);
        let corner = b.sub(twice, one);
        let off = b.mul(corner, e);
        let q = b.add(p, off);
        let d = b.call(map, vec![q]);
        let term = b.mul(corner, d);
        let was = b.load(sum);
        let now = b.add(was, term);
        b.store(sum, now);
    });
    let g = b.load(sum);
    let l = b.length(g);
    let one = b.f(1.0);
    let inv = b.div(one, l);
    let n = b.mul(g, inv);
    let zv = b.splat3(0.0);
    // (Below 1e-30 the reciprocal would overflow f32: no direction, zero.)
    let tiny = b.f(1e-30);
    let ok = b.gt(l, tiny);
    let n = b.select(ok, n, zv);
    b.ret(Some(n));
    let f = b.finish();
    mb.add_function(f)
}

/// `shade(p, n, rd, material, h)`: Lambert with an ambient term (Munini §2.3), a Blinn–Phong
/// highlight only if some material is specular, the scene's lights folded in as constants;
/// with shadows, each shadowing light's terms scaled by `shadow` (`h`: the hit threshold);
/// with occlusion, the ambient and diffuse terms scaled by `occlusion(p, n)`.
pub(super) fn add_shade(
    mb: &mut ModuleBuilder,
    scene: &Scene,
    (map, texture, blend): (
        Handle<Function>,
        Option<Handle<Function>>,
        Option<Handle<Function>>,
    ),
    fixed_offset: Option<f64>,
) -> Handle<Function> {
    let textures = texture.map(|t| super::texture::Textures::new(mb, scene, t));
    let shadow = has_shadows(scene).then(|| add_shadow(mb, map, fixed_offset));
    let occlusion = scene.occlusion.map(|o| add_occlusion(mb, map, &o));
    let v3 = mb.vec3();
    let u32t = mb.u32();
    let f32t = mb.f32();
    // `h` whether or not a light casts shadows: the library's signature does not depend on the
    // scene (docs/interface.md).
    let args = [
        ("p", v3),
        ("n", v3),
        ("rd", v3),
        ("material", u32t),
        ("h", f32t),
    ];
    let mut b = FnBuilder::new(mb, "shade", &args, Some(v3));
    let (p, n, rd, mat) = (b.arg(0), b.arg(1), b.arg(2), b.arg(3));
    // Scene colours are sRGB; lighting is linear (the conversion folds at compile time).
    // Patterned materials' colours at this point (procedural textures, Liktor §4).
    let patterned = match &textures {
        Some(t) => t.colors(&mut b, scene, p, n),
        None => Vec::new(),
    };
    let (base, spec) = base_and_specular(&mut b, scene, (mat, p), blend, &patterned);
    // Occlusion darkens the light that reaches the surface from all around, and the diffuse.
    let lit_base = match occlusion {
        Some(f) => {
            let ao = b.call(f, vec![p, n]);
            b.mul(base, ao)
        }
        None => base,
    };
    let amb = b.f(AMBIENT);
    let mut color = b.mul(lit_base, amb);
    for light in &scene.lights {
        color = add_light(
            &mut b,
            (scene, light),
            [p, n, rd],
            (lit_base, spec),
            shadow,
            color,
        );
    }
    b.ret(Some(color));
    let f = b.finish();
    mb.add_function(f)
}

/// The surface's linear base colour and specular strength (if some material is specular): of
/// material `mat`, or across a smooth operator's seam two materials mixed by its weight
/// (`blend`: `map_blend`, see `crate::reference::blend`).
fn base_and_specular(
    b: &mut FnBuilder,
    scene: &Scene,
    (mat, p): (Ex, Ex),
    blend: Option<Handle<Function>>,
    patterned: &[(usize, Ex)],
) -> (Ex, Option<Ex>) {
    let Some(f) = blend else {
        return material_props(b, scene, mat, patterned);
    };
    super::count::count(b, 1);
    let bl = b.call(f, vec![p]);
    let [x, y, t] = b.xyz(bl);
    let (ia, ib) = (b.cast(x, ScalarKind::Uint), b.cast(y, ScalarKind::Uint));
    let (ca, sa) = material_props(b, scene, ia, patterned);
    let (cb, sb) = material_props(b, scene, ib, patterned);
    let t3 = b.splat(t, naga::VectorSize::Tri);
    let base = b.math(M::Mix, &[ca, cb, t3]);
    let spec = match (sa, sb) {
        (Some(sa), Some(sb)) => Some(b.math(M::Mix, &[sa, sb, t])),
        _ => None,
    };
    (base, spec)
}

/// `color` plus one light's terms at the surface point `p` of normal `n` seen along `rd`: the
/// diffuse (Lambert, on `lit_base`) and, if `spec` is given, the Blinn–Phong highlight, both
/// scaled by `shadow(…)` where the light casts shadows.
fn add_light(
    b: &mut FnBuilder,
    (scene, light): (&Scene, &Light),
    [p, n, rd]: [Ex; 3],
    (lit_base, spec): (Ex, Option<Ex>),
    shadow: Option<Handle<Function>>,
    color: Ex,
) -> Ex {
    let (l, far) = light_direction(b, scene, light, p);
    let ndl = b.dot(n, l);
    let zero = b.f(0.0);
    let diff = b.max(ndl, zero);
    let lc = light_color(b, light, p);
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
    let lit = b.mul(lit_base, lit);
    let color = b.add(color, lit);
    let Some(s) = spec else {
        return color;
    };
    let hv = b.sub(l, rd);
    let hv = unit_or_zero(b, hv);
    let ndh = b.dot(n, hv);
    let ndh = b.max(ndh, zero);
    let e = b.f(SHININESS);
    let hl = b.math(M::Pow, &[ndh, e]);
    let hl = b.mul(hl, s);
    let hl = b.mul(lc, hl);
    b.add(color, hl)
}

/// The direction towards `light` from `p` and how far the light is (the scene's far limit for
/// a directional one).
fn light_direction(b: &mut FnBuilder, scene: &Scene, light: &Light, p: Ex) -> (Ex, Ex) {
    let place = params::setting(&light.sym, 0);
    match light.kind {
        LightKind::Directional(d) => {
            let l = match place {
                Some(_) => args::arg(b, Ty::Axis, Val::Vec3(d), place, p),
                None => b.vec3_lit(d.normalize()),
            };
            (l, b.f(scene.trace.max_distance))
        }
        LightKind::Point(pos) => {
            let pv = args::arg(b, Ty::Vec3, Val::Vec3(pos), place, p);
            let d = b.sub(pv, p);
            (unit_or_zero(b, d), b.length(d))
        }
    }
}

/// The light's linear colour times its intensity: a constant unless a parameter sets them.
fn light_color(b: &mut FnBuilder, light: &Light, p: Ex) -> Ex {
    let (tint, intensity) = (
        params::setting(&light.sym, 1),
        params::setting(&light.sym, 2),
    );
    if tint.is_none() && intensity.is_none() {
        b.vec3_lit(crate::color::linear(light.color) * light.intensity)
    } else {
        let c = params::linear_color(b, light.color, tint, p);
        let k = args::arg(b, Ty::Number, Val::Num(light.intensity), intensity, p);
        b.mul(c, k)
    }
}

/// The linear base colour of material `id` (patterned ones from `patterned`) and its specular
/// strength, if some material is specular: select chains over the declared materials.
fn material_props(
    b: &mut FnBuilder,
    scene: &Scene,
    id: Ex,
    patterned: &[(usize, Ex)],
) -> (Ex, Option<Ex>) {
    let mut base = b.vec3_lit(crate::color::linear(DEFAULT_COLOR));
    let mut spec = None;
    for (i, m) in scene.materials.iter().enumerate() {
        let k = b.u(i as u32 + 1);
        let is = b.bin(naga::BinaryOperator::Equal, id, k);
        let c = match patterned.iter().find(|(j, _)| *j == i) {
            Some(&(_, c)) => c,
            None => params::linear_color(b, m.color, params::setting(&m.sym, 0), id),
        };
        base = b.select(is, c, base);
        let specular = params::setting(&m.sym, 1);
        if m.specular > 0.0 || spec.is_some() || specular.is_some() {
            let prev = match spec {
                Some(s) => s,
                None => b.f(0.0),
            };
            let s = args::arg(b, Ty::Number, Val::Num(m.specular), specular, id);
            spec = Some(b.select(is, s, prev));
        }
    }
    (base, spec)
}

/// `shade(p, n, rd, material, h)`.
pub(super) fn call_shade(
    b: &mut FnBuilder,
    shade: Handle<Function>,
    [p, n, rd, m]: [Ex; 4],
    h: Ex,
) -> Ex {
    b.call(shade, vec![p, n, rd, m, h])
}

/// `fog(c, t)`: the linear colour `c` seen through the scene's fog from distance `t`,
/// mix(fog, c, e^(−density·t)) (as `crate::reference::shading::fog`); `None` without fog.
pub(super) fn add_fog(mb: &mut ModuleBuilder, scene: &Scene) -> Option<Handle<Function>> {
    let fog = scene.fog?;
    let v3 = mb.vec3();
    let f32t = mb.f32();
    let mut b = FnBuilder::new(mb, "fog", &[("c", v3), ("t", f32t)], Some(v3));
    let (c, t) = (b.arg(0), b.arg(1));
    let k = b.f(-fog.density);
    let kt = b.mul(k, t);
    let keep = b.math(M::Exp, &[kt]);
    let keep = b.splat(keep, naga::VectorSize::Tri);
    let color = b.vec3_lit(crate::color::linear(fog.color));
    let out = b.math(M::Mix, &[color, c, keep]);
    b.ret(Some(out));
    let f = b.finish();
    Some(mb.add_function(f))
}
