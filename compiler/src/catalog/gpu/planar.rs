//! IR of the 2D shapes and of `extrude` and `revolve` (`catalog/planar.rs`), operation for
//! operation as their f64 formulas.

use super::args as params;
use super::shapes::{extrude as extruded, triangle as triangle_2d};
use super::{ChildLower, norm};
use crate::catalog::Ctx;
use crate::ir::{Ex, FnBuilder};
use naga::{MathFunction as M, ScalarKind, VectorSize};

/// |p.xy| − r
pub fn circle(b: &mut FnBuilder, p: Ex, a: &[Ex]) -> Ex {
    let xy = b.swizzle(p, &[0, 1]);
    let l = b.length(xy);
    b.sub(l, a[0])
}

/// `catalog::planar::sd_rectangle` of `width`, `height`.
pub fn rectangle(b: &mut FnBuilder, p: Ex, a: &[Ex]) -> Ex {
    let xy = b.swizzle(p, &[0, 1]);
    let h = b.f(0.5);
    let w = b.mul(a[0], h);
    let t = b.mul(a[1], h);
    let half = b.vec2(w, t);
    let ap = b.abs(xy);
    let q = b.sub(ap, half);
    let zero = b.f(0.0);
    let z2 = b.splat(zero, VectorSize::Bi);
    let o = b.max(q, z2);
    let o = b.length(o);
    let (qx, qy) = (b.at(q, 0), b.at(q, 1));
    let m = b.max(qx, qy);
    let i = b.min(m, zero);
    b.add(o, i)
}

/// `catalog::planar::sd_polygon` of `sides` (an integer argument) and `radius`.
pub fn polygon(b: &mut FnBuilder, p: Ex, a: &[Ex]) -> Ex {
    let n = b.cast(a[0], ScalarKind::Float);
    let r = a[1];
    let [x, y, _] = b.xyz(p);
    let pi = b.f(std::f64::consts::PI);
    let an = b.div(pi, n);
    let (s, c) = (b.math(M::Sin, &[an]), b.math(M::Cos, &[an]));
    let ang = b.math(M::Atan2, &[x, y]);
    let two = b.f(2.0);
    let width = b.mul(two, an);
    let k = b.div(ang, width);
    let k = b.math(M::Floor, &[k]);
    let kw = b.mul(width, k);
    let bn = b.sub(ang, kw);
    let bn = b.sub(bn, an);
    let xy = b.vec2(x, y);
    let l = b.length(xy);
    let (bc, bs) = (b.math(M::Cos, &[bn]), b.math(M::Sin, &[bn]));
    let bs = b.abs(bs);
    let (rc, rs) = (b.mul(r, c), b.mul(r, s));
    let qx = b.mul(l, bc);
    let qx = b.sub(qx, rc);
    let qy = b.mul(l, bs);
    let qy = b.sub(qy, rs);
    let nqy = b.neg(qy);
    let zero = b.f(0.0);
    let lift = b.clamp(nqy, zero, rs);
    let qy = b.add(qy, lift);
    let q = b.vec2(qx, qy);
    let d = b.length(q);
    let sg = b.math(M::Sign, &[qx]);
    b.mul(d, sg)
}

/// The equilateral triangle of side `size` in the xy plane.
pub fn triangle(b: &mut FnBuilder, p: Ex, a: &[Ex]) -> Ex {
    let [x, y, _] = b.xyz(p);
    triangle_2d(b, x, y, a[0])
}

/// The shape's d/λ (it is the same at every z) and |z| − height/2, combined.
pub fn extrude(b: &mut FnBuilder, c: &Ctx, p: Ex, child: ChildLower) -> Ex {
    let d = norm(b, c, child, 0, p);
    let z = b.at(p, 2);
    let h = params::num(b, c, 0, p);
    let half = b.f(0.5);
    let h = b.mul(h, half);
    extruded(b, d, z, h)
}

/// The shape at (|p.xz| − radius, p.y, 0).
pub fn revolve(b: &mut FnBuilder, c: &Ctx, p: Ex, child: ChildLower) -> Ex {
    let xz = b.swizzle(p, &[0, 2]);
    let l = b.length(xz);
    let r = params::num(b, c, 0, p);
    let x = b.sub(l, r);
    let y = b.at(p, 1);
    let zero = b.f(0.0);
    let q = b.compose_vec3([x, y, zero]);
    child(b, 0, q)
}
