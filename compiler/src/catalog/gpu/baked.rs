//! `bake`'s IR: a call of the volume's read function, and that function — the trilinear
//! interpolation of eight texels of the volume's `r32float` 3D texture and the outside rule,
//! operation for operation as `crate::bake::Volume::field` computes them in f64.
//!
//! Texels are loaded (`textureLoad`) and interpolated here rather than sampled by the texture
//! unit: `r32float` is not filterable in core WebGPU, and filtering hardware may round its
//! weights to 8 bits, which the proven λ (`crate::bake::lambda_of`) does not allow for.

use super::ChildLower;
use crate::bake::Volume;
use crate::catalog::Ctx;
use crate::ir::{Ex, FnBuilder};
use naga::{Expression, Literal, Scalar, ScalarKind, TypeInner, VectorSize};

/// The baked field at `p`: `volume_<i>(p)` (the child is not evaluated).
pub fn bake(b: &mut FnBuilder, c: &Ctx, p: Ex, _: ChildLower) -> Ex {
    let volume = c.baked.as_ref().expect("a checked bake has its volume");
    let f = b.m.volume_fn(volume);
    b.call(f, vec![p])
}

/// The body of `volume_<i>(p: vec3<f32>) -> f32` reading `texture`, a global
/// `texture_3d<f32>` holding `volume`'s values.
pub fn read(b: &mut FnBuilder, volume: &Volume, texture: naga::Handle<naga::GlobalVariable>) -> Ex {
    let g = &volume.grid;
    let p = b.arg(0);
    let lo = b.vec3_lit(g.lo);
    let hi = b.vec3_lit(g.hi);
    let c = b.clamp(p, lo, hi);
    let from_lo = b.sub(c, lo);
    let inv_h = b.f(1.0 / g.h);
    let u = b.mul(from_lo, inv_h);
    // The cell: floor(u) kept within the grid's last cell.
    let floor = b.math(naga::MathFunction::Floor, &[u]);
    let zero = b.splat3(0.0);
    let last = b.vec3_lit(glam::DVec3::new(
        (g.n[0] - 2) as f64,
        (g.n[1] - 2) as f64,
        (g.n[2] - 2) as f64,
    ));
    let low = b.max(floor, zero);
    let cell = b.min(low, last);
    let t = b.sub(u, cell);
    let [tx, ty, tz] = b.xyz(t);
    let ci = b.cast(cell, ScalarKind::Sint);
    let image = b.expr(Expression::GlobalVariable(texture));
    let level = b.expr(Expression::Literal(Literal::I32(0)));
    let ivec = b.m.ty(TypeInner::Vector {
        size: VectorSize::Tri,
        scalar: Scalar::I32,
    });
    let texel = |b: &mut FnBuilder, dx: i32, dy: i32, dz: i32| {
        let offset: Vec<Ex> = [dx, dy, dz]
            .iter()
            .map(|&d| b.expr(Expression::Literal(Literal::I32(d))))
            .collect();
        let coordinate = match (dx, dy, dz) {
            (0, 0, 0) => ci,
            _ => {
                let offset = b.compose(ivec, offset);
                b.add(ci, offset)
            }
        };
        let v = b.expr(Expression::ImageLoad {
            image,
            coordinate,
            array_index: None,
            sample: None,
            level: Some(level),
        });
        b.at(v, 0)
    };
    let lerp_x = |b: &mut FnBuilder, dy: i32, dz: i32| {
        let a = texel(b, 0, dy, dz);
        let c = texel(b, 1, dy, dz);
        lerp(b, a, c, tx)
    };
    let x00 = lerp_x(b, 0, 0);
    let x10 = lerp_x(b, 1, 0);
    let x01 = lerp_x(b, 0, 1);
    let x11 = lerp_x(b, 1, 1);
    let y0 = lerp(b, x00, x10, ty);
    let y1 = lerp(b, x01, x11, ty);
    let v = lerp(b, y0, y1, tz);
    b.name(v, "v");
    // Outside the box: √(d² + v²) where v > 0, else v + d (at d = 0 both are v).
    let outside = b.sub(p, c);
    let d = b.length(outside);
    let d2 = b.mul(d, d);
    let v2 = b.mul(v, v);
    let s = b.add(d2, v2);
    let far = b.sqrt(s);
    let near = b.add(v, d);
    let zero = b.f(0.0);
    let positive = b.gt(v, zero);
    b.select(positive, far, near)
}

/// a + (b − a)·t, as `Volume::inside` computes it.
fn lerp(b: &mut FnBuilder, x: Ex, y: Ex, t: Ex) -> Ex {
    let diff = b.sub(y, x);
    let step = b.mul(diff, t);
    b.add(x, step)
}
