//! The warps' lowering (`twist`, `bend`), as `catalog::warp` evaluates them, and the plane
//! turn they share with `rotate` about a coordinate axis.

use super::{ChildLower, scale_by};
use crate::catalog::Ctx;
use crate::catalog::warp::twist_stretch;
use crate::ir::{Ex, FnBuilder};
use glam::DVec3;
use naga::MathFunction as M;

/// A warp as `catalog::warp::warp`: project onto the bounding cylinder, deform, normalise
/// by `stretch`, and take the max with the distance to the cylinder.
/// Where a warp's surface lies: the cylinder across coordinates `radial` of radius `rho_max`,
/// inside which the deformation stretches distances by at most `stretch`.
struct Cylinder {
    radial: [u32; 2],
    rho_max: f64,
    stretch: f64,
}

fn warp(
    b: &mut FnBuilder,
    c: &Ctx,
    p: Ex,
    cyl: Cylinder,
    deform: &dyn Fn(&mut FnBuilder, Ex) -> Ex,
    child: ChildLower,
) -> Ex {
    let Cylinder {
        radial,
        rho_max,
        stretch,
    } = cyl;
    if !rho_max.is_finite() {
        let q = deform(b, p);
        return child(b, 0, q);
    }
    let across = b.swizzle(p, &radial);
    let rho = b.length(across);
    let rm = b.f(rho_max);
    let out = b.gt(rho, rm);
    let ratio = b.div(rm, rho);
    let one = b.f(1.0);
    let s = b.select(out, ratio, one);
    let mut scale = [one; 3];
    scale[radial[0] as usize] = s;
    scale[radial[1] as usize] = s;
    let scale = b.compose_vec3(scale);
    let projected = b.mul(p, scale);
    let q = deform(b, projected);
    let d = child(b, 0, q);
    let inside = scale_by(b, d, 1.0 / (c.child_lambda[0] * stretch));
    let outside = b.sub(rho, rm);
    b.max(inside, outside)
}

/// Rotates coordinates `plane` of `p` by `rate` times coordinate `by` (twist: xz by y; bend: xy
/// by x), as `catalog::warp::twist_point` and `bend_point`.
fn plane_rotation(b: &mut FnBuilder, p: Ex, plane: [usize; 2], by: usize, rate: f64) -> Ex {
    let k = b.f(rate);
    let along = b.at(p, by as u32);
    let a = b.mul(k, along);
    let (s, co) = (b.math(M::Sin, &[a]), b.math(M::Cos, &[a]));
    turn(b, p, plane, (s, co))
}

/// `p` turned in the plane of coordinates `[i, j]` by the angle whose sine and cosine are given:
/// (c·pᵢ − s·pⱼ, s·pᵢ + c·pⱼ).
pub(super) fn turn(b: &mut FnBuilder, p: Ex, [i, j]: [usize; 2], (s, co): (Ex, Ex)) -> Ex {
    let mut c = b.xyz(p);
    let (ci, sj) = (b.mul(co, c[i]), b.mul(s, c[j]));
    let (si, cj) = (b.mul(s, c[i]), b.mul(co, c[j]));
    c[i] = b.sub(ci, sj);
    c[j] = b.add(si, cj);
    b.compose_vec3(c)
}

/// Rotation of the xz plane by rate·y.
pub fn twist(b: &mut FnBuilder, c: &Ctx, p: Ex, child: ChildLower) -> Ex {
    let rho_max = c.child_bound[0].cylinder_radius(DVec3::Y);
    let rate = c.num(0);
    let deform = move |b: &mut FnBuilder, p: Ex| plane_rotation(b, p, [0, 2], 1, rate);
    let cyl = Cylinder {
        radial: [0, 2],
        rho_max,
        stretch: twist_stretch(rate, rho_max),
    };
    warp(b, c, p, cyl, &deform, child)
}

/// Rotation of the xy plane by rate·x.
pub fn bend(b: &mut FnBuilder, c: &Ctx, p: Ex, child: ChildLower) -> Ex {
    let rho_max = c.child_bound[0].cylinder_radius(DVec3::Z);
    let rate = c.num(0);
    let deform = move |b: &mut FnBuilder, p: Ex| plane_rotation(b, p, [0, 1], 0, rate);
    let cyl = Cylinder {
        radial: [0, 1],
        rho_max,
        stretch: 1.0 + rate.abs() * rho_max,
    };
    warp(b, c, p, cyl, &deform, child)
}
