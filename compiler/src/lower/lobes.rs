//! What one bounce of `path` continues with: the material's reflect, transparent, ior and tint,
//! and the reflected and refracted lobes weighed by Schlick's reflectance (the f64 reference:
//! `crate::reference::pixel::path`).

use crate::ir::builder::{Ex, FnBuilder};
use crate::scene::Scene;
use naga::{BinaryOperator as Op, MathFunction as M, VectorSize};

/// What a material continues the path with, seen from outside: reflect, transparent, ior, tint
/// (linear colour).
pub(super) struct Continuing {
    pub(super) r: Ex,
    pub(super) t: Ex,
    pub(super) ior: Ex,
    pub(super) tint: Ex,
}

/// The two lobes of a bounce: refracted (leaving, or entering tinted) and reflected, about the
/// normal on the ray's side.
pub(super) struct Lobes {
    pub(super) facing: Ex,
    /// The index of the solid the ray is in or enters.
    pub(super) s_ior: Ex,
    pub(super) dir_t: Ex,
    pub(super) reflected: Ex,
    pub(super) refracted: Ex,
    /// Whether the path goes on through the refraction (the heavier lobe).
    pub(super) through: Ex,
}

/// The material terms of material `m` where it continues the path (`Material::continues`):
/// select chains over the declared materials.
pub(super) fn continuing(b: &mut FnBuilder, scene: &Scene, m: Ex) -> Continuing {
    let (mut r, mut t, mut ior, mut tint) = (b.f(0.0), b.f(0.0), b.f(1.0), b.splat3(1.0));
    for (i, mat) in scene.materials.iter().enumerate() {
        if !mat.continues() {
            continue;
        }
        let id = b.u(i as u32 + 1);
        let is = b.bin(Op::Equal, m, id);
        let (mr, mt, mi) = (b.f(mat.reflect), b.f(mat.transparent), b.f(mat.ior));
        let mc = super::params::linear_color(b, mat.color, super::params::setting(&mat.sym, 0), m);
        r = b.select(is, mr, r);
        t = b.select(is, mt, t);
        ior = b.select(is, mi, ior);
        tint = b.select(is, mc, tint);
    }
    Continuing { r, t, ior, tint }
}

impl Lobes {
    /// The lobes: refracted (leaving, or entering tinted) and reflected, about the normal on
    /// the ray's side (`faceForward`: a silhouette's normal may face away from it), weighed by
    /// Schlick's reflectance; the path goes through where the refraction is the heavier.
    /// `ior_var`: the variable holding the index of the solid the ray is in.
    pub(super) fn new(
        b: &mut FnBuilder,
        (inside, ior_var): (Ex, Ex),
        mat: &Continuing,
        (n, rd): (Ex, Ex),
        (one, zero): (Ex, Ex),
    ) -> Lobes {
        let solid_ior = b.load(ior_var);
        let s_ior = b.select(inside, solid_ior, mat.ior);
        let facing = b.math(M::FaceForward, &[n, rd, n]);
        let inv = b.div(one, mat.ior);
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
        let has_t = b.gt(mat.t, zero);
        let f_out = b.select(has_t, f, zero);
        let tf = b.mul(mat.t, f_out);
        let refl_out = b.add(mat.r, tf);
        let reflected = b.select(inside, f_in, refl_out);
        let keep = b.sub(one, f_out);
        let keep = b.mul(mat.t, keep);
        let refr_out = b.mul(mat.tint, keep);
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
        Lobes {
            facing,
            s_ior,
            dir_t,
            reflected,
            refracted,
            through,
        }
    }
}

/// Schlick's reflectance at cosine `c` for index `ior` (`crate::reference::pixel::schlick`), with the
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
