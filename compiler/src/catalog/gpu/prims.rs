//! Primitive bodies in naga IR: each builds `sd_<name>(p, params...)`, mirroring the f64 formula
//! of the same catalog entry in `catalog/primitives.rs`.

use crate::catalog::geometry::dodecahedron_normals;
use crate::ir::{Ex, FnBuilder};
use naga::{MathFunction as M, VectorSize};

/// A primitive's IR body: the builder, the point, the parameters (as function arguments).
pub type PrimLower = fn(&mut FnBuilder, Ex, &[Ex]) -> Ex;

/// |p| − r
pub fn sphere(b: &mut FnBuilder, p: Ex, a: &[Ex]) -> Ex {
    let l = b.length(p);
    b.sub(l, a[0])
}

/// IQ's exact box of half extents `half`.
pub(crate) fn box_half(b: &mut FnBuilder, p: Ex, half: Ex) -> Ex {
    let ap = b.abs(p);
    let q = b.sub(ap, half);
    let zero = b.splat3(0.0);
    let outside = b.max(q, zero);
    let outside = b.length(outside);
    let m = b.max3(q);
    let z = b.f(0.0);
    let inside = b.min(m, z);
    b.add(outside, inside)
}

/// Box of full size `a[0]`.
pub fn cuboid(b: &mut FnBuilder, p: Ex, a: &[Ex]) -> Ex {
    let h = b.f(0.5);
    let half = b.mul(a[0], h);
    box_half(b, p, half)
}

/// Box of full size `a[0]` with edges rounded by `a[1]` (at most the smallest half extent).
pub fn rounded_box(b: &mut FnBuilder, p: Ex, a: &[Ex]) -> Ex {
    let h = b.f(0.5);
    let half = b.mul(a[0], h);
    let smallest = b.min3(half);
    let r = b.min(a[1], smallest);
    let rv = b.splat(r, VectorSize::Tri);
    let inner = b.sub(half, rv);
    let d = box_half(b, p, inner);
    b.sub(d, r)
}

/// p · n − offset
pub fn plane(b: &mut FnBuilder, p: Ex, a: &[Ex]) -> Ex {
    let d = b.dot(p, a[0]);
    b.sub(d, a[1])
}

/// |(|p.xz| − R, p.y)| − r
pub fn torus(b: &mut FnBuilder, p: Ex, a: &[Ex]) -> Ex {
    let xz = b.swizzle(p, &[0, 2]);
    let l = b.length(xz);
    let qx = b.sub(l, a[0]);
    let y = b.at(p, 1);
    let q = b.vec2(qx, y);
    let l = b.length(q);
    b.sub(l, a[1])
}

/// Vertical capsule of segment length `a[0]` and radius `a[1]`.
pub fn capsule(b: &mut FnBuilder, p: Ex, a: &[Ex]) -> Ex {
    let h = b.f(0.5);
    let hh = b.mul(a[0], h);
    let lo = b.neg(hh);
    let [x, y, z] = b.xyz(p);
    let c = b.clamp(y, lo, hh);
    let y = b.sub(y, c);
    let q = b.compose_vec3([x, y, z]);
    let l = b.length(q);
    b.sub(l, a[1])
}

/// Capped vertical cylinder of radius `a[0]` and height `a[1]`.
pub fn cylinder(b: &mut FnBuilder, p: Ex, a: &[Ex]) -> Ex {
    let xz = b.swizzle(p, &[0, 2]);
    let l = b.length(xz);
    let y = b.at(p, 1);
    let q = b.vec2(l, y);
    let q = b.abs(q);
    let h = b.f(0.5);
    let hh = b.mul(a[1], h);
    let size = b.vec2(a[0], hh);
    let d = b.sub(q, size);
    let (dx, dy) = (b.at(d, 0), b.at(d, 1));
    let m = b.max(dx, dy);
    let z = b.f(0.0);
    let inside = b.min(m, z);
    let zero2 = b.splat(z, VectorSize::Bi);
    let out = b.max(d, zero2);
    let out = b.length(out);
    b.add(inside, out)
}

/// IQ's exact capped cone: base radius `a[0]`, height `a[1]`, top radius `a[2]`.
pub fn cone(b: &mut FnBuilder, p: Ex, a: &[Ex]) -> Ex {
    let (r1, r2) = (a[0], a[2]);
    let half = b.f(0.5);
    let h = b.mul(a[1], half);
    let xz = b.swizzle(p, &[0, 2]);
    let qx = b.length(xz);
    let qy = b.at(p, 1);
    let q = b.vec2(qx, qy);
    let k1 = b.vec2(r2, h);
    let dr = b.sub(r2, r1);
    let two = b.f(2.0);
    let h2 = b.mul(h, two);
    let k2 = b.vec2(dr, h2);
    let zero = b.f(0.0);
    let below = b.lt(qy, zero);
    let r = b.select(below, r1, r2);
    let mr = b.min(qx, r);
    let cax = b.sub(qx, mr);
    let ay = b.abs(qy);
    let cay = b.sub(ay, h);
    let ca = b.vec2(cax, cay);
    let k1q = b.sub(k1, q);
    let num = b.dot(k1q, k2);
    let den = b.dot(k2, k2);
    let tiny = b.f(1e-30);
    let den = b.max(den, tiny);
    let t = b.div(num, den);
    let one = b.f(1.0);
    let t = b.clamp(t, zero, one);
    let qk = b.sub(q, k1);
    let k2t = b.mul(k2, t);
    let cb = b.add(qk, k2t);
    // Inside the side line (see the catalog's `sd_capped_cone`): 2h(q.x − r2) + (r1 − r2)(q.y − h) < 0.
    let qr = b.sub(qx, r2);
    let along = b.mul(h2, qr);
    let rr = b.sub(r1, r2);
    let qh = b.sub(qy, h);
    let across = b.mul(rr, qh);
    let side = b.add(along, across);
    let c1 = b.lt(side, zero);
    let c2 = b.lt(cay, zero);
    let both = b.bin(naga::BinaryOperator::LogicalAnd, c1, c2);
    let minus = b.f(-1.0);
    let s = b.select(both, minus, one);
    let da = b.dot(ca, ca);
    let db = b.dot(cb, cb);
    let m = b.min(da, db);
    let m = b.sqrt(m);
    b.mul(s, m)
}

/// The 1-Lipschitz ellipsoid bound (|p / r| − 1)·min(r); radii below 1e-9 are raised to it.
pub fn ellipsoid(b: &mut FnBuilder, p: Ex, a: &[Ex]) -> Ex {
    let floor = b.splat3(crate::catalog::geometry::ELLIPSOID_MIN_RADIUS);
    let r = b.max(a[0], floor);
    let q = b.div(p, r);
    let l = b.length(q);
    let one = b.f(1.0);
    let k = b.sub(l, one);
    let m = b.min3(r);
    b.mul(k, m)
}

/// IQ's exact octahedron, its branches as selects.
pub fn octahedron(b: &mut FnBuilder, p: Ex, a: &[Ex]) -> Ex {
    let s = a[0];
    let p = b.abs(p);
    let [x, y, z] = b.xyz(p);
    let xy = b.add(x, y);
    let xyz = b.add(xy, z);
    let m = b.sub(xyz, s);
    let three = b.f(3.0);
    let cond = |b: &mut FnBuilder, c: Ex| {
        let t = b.mul(three, c);
        b.lt(t, m)
    };
    let (c1, c2, c3) = (cond(b, x), cond(b, y), cond(b, z));
    let yzx = b.swizzle(p, &[1, 2, 0]);
    let zxy = b.swizzle(p, &[2, 0, 1]);
    let q = b.select(c3, zxy, p);
    let q = b.select(c2, yzx, q);
    let q = b.select(c1, p, q);
    let [qx, qy, qz] = b.xyz(q);
    let half = b.f(0.5);
    let zy = b.sub(qz, qy);
    let zys = b.add(zy, s);
    let kk = b.mul(half, zys);
    let zero = b.f(0.0);
    let k = b.clamp(kk, zero, s);
    let ys = b.sub(qy, s);
    let y2 = b.add(ys, k);
    let z2 = b.sub(qz, k);
    let v = b.compose_vec3([qx, y2, z2]);
    let inner = b.length(v);
    let inv = b.f(1.0 / 3f64.sqrt());
    let flat = b.mul(m, inv);
    let any12 = b.bin(naga::BinaryOperator::LogicalOr, c1, c2);
    let any = b.bin(naga::BinaryOperator::LogicalOr, any12, c3);
    b.select(any, inner, flat)
}

/// Generalised dodecahedron: max of |p·nᵢ| (exponent 0) or their `e`-norm, minus the radius.
pub fn dodecahedron(b: &mut FnBuilder, p: Ex, a: &[Ex]) -> Ex {
    let (r, e) = (a[0], a[1]);
    let dots: Vec<Ex> = dodecahedron_normals()
        .iter()
        .map(|n| {
            let n = b.vec3_lit(*n);
            let d = b.dot(p, n);
            b.abs(d)
        })
        .collect();
    let m = dots[1..].iter().fold(dots[0], |acc, &d| b.max(acc, d));
    let zero = b.f(0.0);
    // Σ (dᵢ/m)^e, with m floored so a point at the centre gives 0/tiny = 0.
    let tiny = b.f(1e-30);
    let mm = b.max(m, tiny);
    let terms: Vec<Ex> = dots
        .iter()
        .map(|&d| {
            let q = b.div(d, mm);
            b.math(M::Pow, &[q, e])
        })
        .collect();
    let sum = terms[1..].iter().fold(terms[0], |acc, &t| b.add(acc, t));
    let one = b.f(1.0);
    let is_max = b_eq(b, e, zero);
    let safe_e = b.select(is_max, one, e);
    let inv = b.div(one, safe_e);
    let norm = b.math(M::Pow, &[sum, inv]);
    let smooth = b.mul(m, norm);
    let d = b.select(is_max, m, smooth);
    b.sub(d, r)
}

fn b_eq(b: &mut FnBuilder, x: Ex, y: Ex) -> Ex {
    b.bin(naga::BinaryOperator::Equal, x, y)
}

/// The largest whole Mandelbulb power multiplied out rather than taken by `pow`.
const MAX_WHOLE_POWER: f64 = 32.0;

/// Mandelbulb distance estimate (Bálint's test scene), with θ by atan2 (lavapipe's acos is
/// coarse) and, far outside, the distance to the escape sphere.
pub fn mandelbulb(b: &mut FnBuilder, p: Ex, a: &[Ex]) -> Ex {
    let (power, iterations) = (a[0], a[1]);
    // Escape radius 2^(1/(power − 1)), as `mandelbulb_radius`.
    let one = b.f(1.0);
    let pm1 = b.sub(power, one);
    let escape = match b.literal(power) {
        Some(n) => b.f(crate::catalog::geometry::mandelbulb_radius(n)),
        None => {
            let inv = b.div(one, pm1);
            let two = b.f(2.0);
            b.math(M::Pow, &[two, inv])
        }
    };
    let f32t = b.m.f32();
    let v3 = b.m.vec3();
    let z = b.local("z", v3, Some(p));
    let one = b.f(1.0);
    let dr = b.local("dr", f32t, Some(one));
    let r0 = b.length(p);
    let r = b.local("r", f32t, Some(r0));
    b.repeat("i", iterations, |b, _| {
        let zv = b.load(z);
        // |z|, kept from the end of the last iteration (or |p| at the start), not recomputed.
        let rv = b.load(r);
        let two = b.f(2.0);
        let out = b.gt(rv, two);
        b.break_if(out);
        let [zx, zy, zz] = b.xyz(zv);
        let xy = b.vec2(zx, zy);
        let rxy = b.length(xy);
        let theta = b.math(M::Atan2, &[rxy, zz]);
        let theta = b.mul(theta, power);
        let phi = b.math(M::Atan2, &[zy, zx]);
        let phi = b.mul(phi, power);
        // r^(n−1) once: dr' = n·r^(n−1)·dr + 1 and r^n = r^(n−1)·r (one pow per iteration),
        // multiplied out when the power is a known whole number (`Primitive::bake`).
        let one = b.f(1.0);
        let rp1 = match b.literal(power) {
            Some(n) if n.fract() == 0.0 && (2.0..=MAX_WHOLE_POWER).contains(&n) => {
                super::field::whole_power(b, rv, n as u32 - 1)
            }
            _ => b.math(M::Pow, &[rv, pm1]),
        };
        let drv = b.load(dr);
        let t = b.mul(rp1, power);
        let t = b.mul(t, drv);
        let t = b.add(t, one);
        b.store(dr, t);
        let zr = b.mul(rp1, rv);
        let (st, ct) = (b.math(M::Sin, &[theta]), b.math(M::Cos, &[theta]));
        let (sp, cp) = (b.math(M::Sin, &[phi]), b.math(M::Cos, &[phi]));
        let nx = b.mul(st, cp);
        let ny = b.mul(sp, st);
        let dir = b.compose_vec3([nx, ny, ct]);
        let nz = b.mul(dir, zr);
        let nz = b.add(nz, p);
        b.store(z, nz);
        let nr = b.length(nz);
        b.store(r, nr);
    });
    let rv = b.load(r);
    let tiny = b.f(1e-20);
    let rv = b.max(rv, tiny);
    let half = b.f(0.5);
    let ln = b.math(M::Log, &[rv]);
    let de = b.mul(half, ln);
    let de = b.mul(de, rv);
    let drv = b.load(dr);
    let de = b.div(de, drv);
    let pl = r0;
    let two = b.f(2.0);
    let far_r = b.mul(two, escape);
    let far = b.gt(pl, far_r);
    let far_d = b.sub(pl, escape);
    b.select(far, far_d, de)
}
