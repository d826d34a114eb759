//! Procedural textures in IR: `lattice_hash`, `value_noise`, the octave sums and one weight expression per
//! patterned material, operation for operation as `crate::reference::texture` computes them in f64; each
//! function only when a material's pattern needs it.

use crate::ir::builder::{Ex, FnBuilder, ModuleBuilder};
use crate::reference::texture::{LATTICE_PERIOD, NORMAL_STEP, NORMAL_STEP_FLOOR};
use crate::scene::{Pattern, PatternKind, Scene};
use naga::{BinaryOperator as Op, Expression, Function, Handle, MathFunction as M, ScalarKind};

/// The texture functions a module has.
pub(super) struct Textures {
    /// `map_texture(p)`: the point in the tagged shape's own coordinates.
    map_texture: Handle<Function>,
    /// The patterned materials some shape has, by index.
    used: Vec<usize>,
    /// `value_noise(q)`, when a pattern uses noise.
    noise: Option<Handle<Function>>,
}

impl Textures {
    /// Adds the noise functions if some pattern needs them.
    pub fn new(mb: &mut ModuleBuilder, scene: &Scene, map_texture: Handle<Function>) -> Textures {
        let used = super::used_patterns(scene);
        let noisy = used.iter().any(|&m| {
            scene.materials[m]
                .pattern
                .is_some_and(|p| p.kind.uses_noise())
        });
        Textures {
            map_texture,
            used,
            noise: noisy.then(|| add_noise(mb)),
        }
    }

    /// The linear base colour of each patterned material at the surface point `p` of normal
    /// `n` (`crate::reference::shading::albedo`): (material index, colour).
    pub fn colors(&self, b: &mut FnBuilder, scene: &Scene, p: Ex, n: Ex) -> Vec<(usize, Ex)> {
        super::count::count(b, 1);
        let q = b.call(self.map_texture, vec![p]);
        let mut out = Vec::new();
        for &i in &self.used {
            let m = &scene.materials[i];
            let Some(pattern) = m.pattern else { continue };
            let nq = (pattern.kind == PatternKind::Tiles).then(|| {
                // The normal in the shape's own coordinates: where a step along n goes there,
                // the step at least NORMAL_STEP_FLOOR·|p| (`texture::normal_step`).
                let e = b.f(NORMAL_STEP * pattern.scale);
                let len = b.length(p);
                let floor = b.f(NORMAL_STEP_FLOOR);
                let least = b.mul(floor, len);
                let e = b.max(e, least);
                let step = b.mul(n, e);
                let p2 = b.add(p, step);
                super::count::count(b, 1);
                let q2 = b.call(self.map_texture, vec![p2]);
                let d = b.sub(q2, q);
                super::vector::unit_or_zero(b, d)
            });
            let w = self.weight(b, &pattern, q, nq);
            let first = b.vec3_lit(crate::color::linear(m.color));
            let second = b.vec3_lit(crate::color::linear(pattern.other));
            let w3 = b.splat(w, naga::VectorSize::Tri);
            out.push((i, b.math(M::Mix, &[first, second, w3])));
        }
        out
    }

    /// The pattern's weight at `q` (`crate::reference::texture::weight`).
    fn weight(&self, b: &mut FnBuilder, pattern: &Pattern, q: Ex, nq: Option<Ex>) -> Ex {
        let s = pattern.scale;
        let k = pattern.octaves;
        let inv = b.f(1.0 / s);
        let qs = b.mul(q, inv);
        let [x, y, z] = b.xyz(q);
        match pattern.kind {
            PatternKind::Checker => parity(b, &[x, y, z], s),
            PatternKind::Tiles => {
                let nq = nq.expect("tiles have an own-space normal");
                let a = b.abs(nq);
                let a2 = b.mul(a, a);
                let w = b.mul(a2, a2);
                let planes = [
                    parity(b, &[y, z], s),
                    parity(b, &[x, z], s),
                    parity(b, &[x, y], s),
                ];
                let [wx, wy, wz] = b.xyz(w);
                let total = b.add(wx, wy);
                let total = b.add(total, wz);
                let t0 = b.mul(wx, planes[0]);
                let t1 = b.mul(wy, planes[1]);
                let t2 = b.mul(wz, planes[2]);
                let sum = b.add(t0, t1);
                let sum = b.add(sum, t2);
                let mixed = b.div(sum, total);
                let zero = b.f(0.0);
                let some = b.gt(total, zero);
                b.select(some, mixed, planes[1])
            }
            PatternKind::Noise => self.octaves(b, qs, k, false),
            PatternKind::Turbulence => self.octaves(b, qs, k, true),
            PatternKind::Marble => {
                let t = self.octaves(b, qs, k, true);
                let tau = b.f(std::f64::consts::TAU);
                let xs = b.mul(tau, x);
                let xs = b.mul(xs, inv);
                let six = b.f(6.0);
                let bend = b.mul(six, t);
                let arg = b.add(xs, bend);
                wave(b, arg)
            }
            PatternKind::Wood => {
                let xx = b.mul(x, x);
                let zz = b.mul(z, z);
                let r = b.add(xx, zz);
                let r = b.math(M::Sqrt, &[r]);
                let r = b.mul(r, inv);
                let n = self.octaves(b, qs, k, false);
                let k4 = b.f(0.4);
                let bend = b.mul(k4, n);
                let r = b.add(r, bend);
                let tau = b.f(std::f64::consts::TAU);
                let arg = b.mul(tau, r);
                wave(b, arg)
            }
        }
    }

    /// `octaves` layers of noise (`|2·noise − 1|` for turbulence) at doubling frequencies and
    /// halving amplitudes, over their total amplitude; unrolled (the count is a constant).
    fn octaves(&self, b: &mut FnBuilder, q: Ex, octaves: u32, turbulence: bool) -> Ex {
        let noise = self.noise.expect("noise was added for this pattern");
        let (mut sum, mut total, mut a, mut f) = (None, 0.0, 1.0, 1.0);
        for _ in 0..octaves {
            let fe = b.f(f);
            let qf = b.mul(q, fe);
            let mut v = b.call(noise, vec![qf]);
            if turbulence {
                let two = b.f(2.0);
                let one = b.f(1.0);
                let v2 = b.mul(two, v);
                let v2 = b.sub(v2, one);
                v = b.abs(v2);
            }
            let ae = b.f(a);
            let term = b.mul(ae, v);
            sum = Some(match sum {
                None => term,
                Some(s) => b.add(s, term),
            });
            total += a;
            a *= 0.5;
            f *= 2.0;
        }
        let inv = b.f(1.0 / total);
        b.mul(sum.expect("at least one octave"), inv)
    }
}

/// 0.5 + 0.5·sin(arg).
fn wave(b: &mut FnBuilder, arg: Ex) -> Ex {
    let s = b.math(M::Sin, &[arg]);
    let half = b.f(0.5);
    let hs = b.mul(half, s);
    b.add(half, hs)
}

/// 1 on odd cells of the checker of cell size `s` in `coords`, else 0: Σ floor(c/s) mod 2.
fn parity(b: &mut FnBuilder, coords: &[Ex], s: f64) -> Ex {
    let inv = b.f(1.0 / s);
    let mut sum = None;
    for &c in coords {
        let cs = b.mul(c, inv);
        let cell = b.math(M::Floor, &[cs]);
        sum = Some(match sum {
            None => cell,
            Some(t) => b.add(t, cell),
        });
    }
    let sum = sum.expect("coordinates");
    let half = b.f(0.5);
    let h = b.mul(sum, half);
    let h = b.math(M::Floor, &[h]);
    let two = b.f(2.0);
    let even = b.mul(h, two);
    b.sub(sum, even)
}

/// `value_noise(q)`: value noise (`crate::reference::texture::noise`) with the lattice hash inlined once.
fn add_noise(mb: &mut ModuleBuilder) -> Handle<Function> {
    let hash = add_hash(mb);
    let v3 = mb.vec3();
    let f32t = mb.f32();
    let mut b = FnBuilder::new(mb, "value_noise", &[("q", v3)], Some(f32t));
    let q = b.arg(0);
    let i = b.math(M::Floor, &[q]);
    let f = b.sub(q, i);
    let two = b.splat3(2.0);
    let three = b.splat3(3.0);
    let tf = b.mul(two, f);
    let u = b.sub(three, tf);
    let ff = b.mul(f, f);
    let u = b.mul(ff, u);
    // The lattice cell modulo the period (`crate::reference::texture::noise`): 0 ≤ c < 65536.
    let inv = b.f(1.0 / LATTICE_PERIOD);
    let inv3 = b.splat(inv, naga::VectorSize::Tri);
    let wraps = b.mul(i, inv3);
    let wraps = b.math(M::Floor, &[wraps]);
    let period = b.f(LATTICE_PERIOD);
    let period3 = b.splat(period, naga::VectorSize::Tri);
    let back = b.mul(period3, wraps);
    let cell = b.sub(i, back);
    let c = b.cast(cell, ScalarKind::Sint);
    let [ux, uy, uz] = b.xyz(u);
    let corner = |b: &mut FnBuilder, dx: i32, dy: i32, dz: i32| {
        let ty = ivec3(b.m);
        let parts = [dx, dy, dz].map(|v| b.expr(Expression::Literal(naga::Literal::I32(v))));
        let d = b.compose(ty, parts.to_vec());
        let at = b.bin(Op::Add, c, d);
        b.call(hash, vec![at])
    };
    let lerp = |b: &mut FnBuilder, a: Ex, c: Ex, t: Ex| {
        let d = b.sub(c, a);
        let dt = b.mul(d, t);
        b.add(a, dt)
    };
    let h000 = corner(&mut b, 0, 0, 0);
    let h100 = corner(&mut b, 1, 0, 0);
    let h010 = corner(&mut b, 0, 1, 0);
    let h110 = corner(&mut b, 1, 1, 0);
    let h001 = corner(&mut b, 0, 0, 1);
    let h101 = corner(&mut b, 1, 0, 1);
    let h011 = corner(&mut b, 0, 1, 1);
    let h111 = corner(&mut b, 1, 1, 1);
    let x00 = lerp(&mut b, h000, h100, ux);
    let x10 = lerp(&mut b, h010, h110, ux);
    let x01 = lerp(&mut b, h001, h101, ux);
    let x11 = lerp(&mut b, h011, h111, ux);
    let y0 = lerp(&mut b, x00, x10, uy);
    let y1 = lerp(&mut b, x01, x11, uy);
    let v = lerp(&mut b, y0, y1, uz);
    b.ret(Some(v));
    let f = b.finish();
    mb.add_function(f)
}

/// The `vec3<i32>` type.
fn ivec3(mb: &mut ModuleBuilder) -> naga::Handle<naga::Type> {
    mb.ty(naga::TypeInner::Vector {
        size: naga::VectorSize::Tri,
        scalar: naga::Scalar::I32,
    })
}

/// `lattice_hash(i)`: `crate::reference::texture::hash` in u32 arithmetic (wrapping, as WGSL's u32 is).
fn add_hash(mb: &mut ModuleBuilder) -> Handle<Function> {
    let ivec = ivec3(mb);
    let f32t = mb.f32();
    let mut b = FnBuilder::new(mb, "lattice_hash", &[("i", ivec)], Some(f32t));
    let i = b.arg(0);
    let u = b.expr(Expression::As {
        expr: i,
        kind: ScalarKind::Uint,
        convert: None,
    });
    let [x, y, z] = b.xyz(u);
    let kx = b.u(0x8da6_b343);
    let ky = b.u(0xd816_3841);
    let kz = b.u(0xcb1a_b31f);
    let hx = b.mul(x, kx);
    let hy = b.mul(y, ky);
    let hz = b.mul(z, kz);
    let h = b.bin(Op::ExclusiveOr, hx, hy);
    let mut h = b.bin(Op::ExclusiveOr, h, hz);
    for (shift, mul) in [(16, Some(0x7feb_352d)), (15, Some(0x846c_a68b)), (16, None)] {
        let sh = b.u(shift);
        let hs = b.bin(Op::ShiftRight, h, sh);
        h = b.bin(Op::ExclusiveOr, h, hs);
        if let Some(m) = mul {
            let mc = b.u(m);
            h = b.mul(h, mc);
        }
    }
    let eight = b.u(8);
    let top = b.bin(Op::ShiftRight, h, eight);
    let v = b.cast(top, ScalarKind::Float);
    let scale = b.f(1.0 / 16_777_216.0);
    let v = b.mul(v, scale);
    b.ret(Some(v));
    let f = b.finish();
    mb.add_function(f)
}
