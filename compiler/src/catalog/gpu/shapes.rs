//! IR bodies of the primitives in `catalog/shapes.rs`, each mirroring its f64 formula
//! operation for operation (GLSL's `sign`, 0 at 0, is the CPU's `sign0`).

use crate::catalog::geometry::HEX_FOLD;
use crate::ir::{Ex, FnBuilder};
use naga::MathFunction as M;

/// The extrusion of a 2D distance `d` to `half` along the coordinate `w`.
pub(super) fn extrude(b: &mut FnBuilder, d: Ex, w: Ex, half: Ex) -> Ex {
    let aw = b.abs(w);
    let e1 = b.sub(aw, half);
    let m = b.max(d, e1);
    let zero = b.f(0.0);
    let inside = b.min(m, zero);
    let (ox, oy) = (b.max(d, zero), b.max(e1, zero));
    let o = b.vec2(ox, oy);
    let o = b.length(o);
    b.add(inside, o)
}

fn half(b: &mut FnBuilder, x: Ex) -> Ex {
    let h = b.f(0.5);
    b.mul(x, h)
}

/// `catalog::shapes::sd_hex_prism`
pub fn hex_prism(b: &mut FnBuilder, p: Ex, a: &[Ex]) -> Ex {
    let (kx, kz, t) = HEX_FOLD;
    let [px, py, pz] = b.xyz(p);
    let (x, z) = (b.abs(px), b.abs(pz));
    let (ckx, ckz) = (b.f(kx), b.f(kz));
    let (xk, zk) = (b.mul(ckx, x), b.mul(ckz, z));
    let dot = b.add(xk, zk);
    let zero = b.f(0.0);
    let m = b.min(dot, zero);
    let two = b.f(2.0);
    let fold = b.mul(two, m);
    let (fx, fz) = (b.mul(fold, ckx), b.mul(fold, ckz));
    let (x, z) = (b.sub(x, fx), b.sub(z, fz));
    let ct = b.f(t);
    let hi = b.mul(ct, a[0]);
    let lo = b.neg(hi);
    let c = b.clamp(x, lo, hi);
    let dx = b.sub(x, c);
    let dz = b.sub(z, a[0]);
    let v = b.vec2(dx, dz);
    let l = b.length(v);
    let s = b.math(M::Sign, &[dz]);
    let d = b.mul(l, s);
    let h = half(b, a[1]);
    extrude(b, d, py, h)
}

/// `catalog::shapes::sd_round_cone`
pub fn round_cone(b: &mut FnBuilder, p: Ex, a: &[Ex]) -> Ex {
    let (r1, r2, h) = (a[0], a[1], a[2]);
    let xz = b.swizzle(p, &[0, 2]);
    let qx = b.length(xz);
    let y = b.at(p, 1);
    let hh = half(b, h);
    let qy = b.add(y, hh);
    let q = b.vec2(qx, qy);
    let zero = b.f(0.0);
    let top = b.vec2(zero, h);
    let qt = b.sub(q, top);
    let lb = b.length(q);
    let lt = b.length(qt);
    let bottom_ball = b.sub(lb, r1);
    let top_ball = b.sub(lt, r2);
    // One ball holds the other (h ≤ |r1 − r2|): the larger alone.
    let dr = b.sub(r1, r2);
    let adr = b.abs(dr);
    let nested = b.ge(adr, h);
    let bottom_larger = b.ge(r1, r2);
    let larger = b.select(bottom_larger, bottom_ball, top_ball);
    // Otherwise the hull: the side's slope b and a = √(1 − b²) (h kept from 0 for the division
    // the nested case does not use).
    let tiny = b.f(1e-30);
    let hs = b.max(h, tiny);
    let sb = b.div(dr, hs);
    let one = b.f(1.0);
    let bb = b.mul(sb, sb);
    let ab = b.sub(one, bb);
    let ab = b.max(ab, zero);
    let sa = b.sqrt(ab);
    let nb = b.neg(sb);
    let axis = b.vec2(nb, sa);
    let k = b.dot(q, axis);
    let side_dir = b.vec2(sa, sb);
    let side = b.dot(q, side_dir);
    let side = b.sub(side, r1);
    let below = b.lt(k, zero);
    let ah = b.mul(sa, h);
    let above = b.gt(k, ah);
    let upper = b.select(above, top_ball, side);
    let hull = b.select(below, bottom_ball, upper);
    b.select(nested, larger, hull)
}

/// `catalog::shapes::sd_link`
pub fn link(b: &mut FnBuilder, p: Ex, a: &[Ex]) -> Ex {
    let [x, y, z] = b.xyz(p);
    let ay = b.abs(y);
    let l = half(b, a[0]);
    let y = b.sub(ay, l);
    let zero = b.f(0.0);
    let y = b.max(y, zero);
    let xy = b.vec2(x, y);
    let r = b.length(xy);
    let r = b.sub(r, a[1]);
    let v = b.vec2(r, z);
    let d = b.length(v);
    b.sub(d, a[2])
}

/// `catalog::shapes::sd_triangle` of side `size` at (`px`, `py`).
pub(super) fn triangle(b: &mut FnBuilder, px: Ex, py: Ex, size: Ex) -> Ex {
    let k = b.f(3f64.sqrt());
    let r = half(b, size);
    let ax = b.abs(px);
    let x = b.sub(ax, r);
    let rk = b.div(r, k);
    let y = b.add(py, rk);
    let ky = b.mul(k, y);
    let test = b.add(x, ky);
    let zero = b.f(0.0);
    let fold = b.gt(test, zero);
    let h = b.f(0.5);
    let fx = b.sub(x, ky);
    let fx = b.mul(fx, h);
    let kx = b.mul(k, x);
    let nkx = b.neg(kx);
    let fy = b.sub(nkx, y);
    let fy = b.mul(fy, h);
    let x = b.select(fold, fx, x);
    let y = b.select(fold, fy, y);
    let two = b.f(-2.0);
    let lo = b.mul(two, r);
    let c = b.clamp(x, lo, zero);
    let x = b.sub(x, c);
    let v = b.vec2(x, y);
    let l = b.length(v);
    let s = b.math(M::Sign, &[y]);
    let d = b.mul(l, s);
    b.neg(d)
}

/// `catalog::shapes::sd_triangle`, extruded along z.
pub fn tri_prism(b: &mut FnBuilder, p: Ex, a: &[Ex]) -> Ex {
    let [px, py, pz] = b.xyz(p);
    let d = triangle(b, px, py, a[0]);
    let depth = half(b, a[1]);
    extrude(b, d, pz, depth)
}

/// `catalog::shapes::sd_pyramid`
pub fn pyramid(b: &mut FnBuilder, p: Ex, a: &[Ex]) -> Ex {
    let (s, h) = (a[0], a[1]);
    let [px, py, pz] = b.xyz(p);
    let h1 = b.div(h, s);
    let hh = b.mul(h1, h1);
    let quarter = b.f(0.25);
    let m2 = b.add(hh, quarter);
    let (ax, az) = (b.abs(px), b.abs(pz));
    let (ax, az) = (b.div(ax, s), b.div(az, s));
    let hy = half(b, h);
    let y = b.add(py, hy);
    let y = b.div(y, s);
    let swap = b.gt(az, ax);
    let x = b.select(swap, az, ax);
    let z = b.select(swap, ax, az);
    let h5 = b.f(0.5);
    let x = b.sub(x, h5);
    let z = b.sub(z, h5);
    let qx = z;
    let hy1 = b.mul(h1, y);
    let x5 = b.mul(h5, x);
    let qy = b.sub(hy1, x5);
    let hx1 = b.mul(h1, x);
    let y5 = b.mul(h5, y);
    let qz = b.add(hx1, y5);
    let zero = b.f(0.0);
    let nqx = b.neg(qx);
    let k = b.max(nqx, zero);
    let z5 = b.mul(h5, z);
    let num = b.sub(qy, z5);
    let den = b.add(m2, quarter);
    let t = b.div(num, den);
    let one = b.f(1.0);
    let t = b.clamp(t, zero, one);
    let qk = b.add(qx, k);
    let qk2 = b.mul(qk, qk);
    let aa = b.mul(m2, qk2);
    let qyy = b.mul(qy, qy);
    let aa = b.add(aa, qyy);
    let t5 = b.mul(h5, t);
    let qt = b.add(qx, t5);
    let qt2 = b.mul(qt, qt);
    let bb = b.mul(m2, qt2);
    let m2t = b.mul(m2, t);
    let qm = b.sub(qy, m2t);
    let qm2 = b.mul(qm, qm);
    let bb = b.add(bb, qm2);
    let xm = b.mul(nqx, m2);
    let y5q = b.mul(qy, h5);
    let e = b.sub(xm, y5q);
    let e = b.min(qy, e);
    let inside = b.gt(e, zero);
    let ab = b.min(aa, bb);
    let d2 = b.select(inside, zero, ab);
    let qzz = b.mul(qz, qz);
    let n = b.add(d2, qzz);
    let n = b.div(n, m2);
    let l = b.sqrt(n);
    let ny = b.neg(y);
    let m = b.max(qz, ny);
    let sg = b.math(M::Sign, &[m]);
    let d = b.mul(l, sg);
    // Inside: the base's plane too.
    let with_base = b.max(d, ny);
    let neg = b.lt(d, zero);
    let d = b.select(neg, with_base, d);
    // At or below the base: the distance to the base square.
    let bx = b.max(x, zero);
    let bz = b.max(z, zero);
    let bxz = b.select(swap, bz, bx);
    let bzx = b.select(swap, bx, bz);
    let under = b.compose_vec3([bxz, ny, bzx]);
    let base = b.length(under);
    let below = b.le(y, zero);
    let d = b.select(below, base, d);
    b.mul(s, d)
}

/// `catalog::shapes::sd_rounded_cylinder`
pub fn rounded_cylinder(b: &mut FnBuilder, p: Ex, a: &[Ex]) -> Ex {
    let hh = half(b, a[1]);
    let r = b.min(a[2], a[0]);
    let r = b.min(r, hh);
    let xz = b.swizzle(p, &[0, 2]);
    let l = b.length(xz);
    let ir = b.sub(a[0], r);
    let dx = b.sub(l, ir);
    let y = b.at(p, 1);
    let ih = b.sub(hh, r);
    let d = extrude(b, dx, y, ih);
    b.sub(d, r)
}
