//! The entry points: the compute entry the runtime uses (one pixel per invocation, with
//! multi-resolution passes if asked), the full-screen fragment entry, the trace-only entry and
//! the library's `color`; the view uniform and the pinhole camera they share are in
//! `camera.rs`, the functions they call in `fns.rs`.

use super::camera::{storage_array, view_field};
use super::fns::{Fns, trace_pixel};
use super::handoff::{hand_over, trace_in_pass};
use super::march::{epsilon, is_hit};
use super::tracer::Options;
use crate::ir::builder::{Ex, FnBuilder, ModuleBuilder};
use crate::layout::{self, Element, WORKGROUP};
use crate::scene::{Epsilon, Scene};
use naga::{
    Binding, BuiltIn, EntryPoint, Expression, Function, Handle, MathFunction as M, ScalarKind,
    ShaderStage, VectorSize,
};

/// The shaded colour (or background), normal and material of a traced ray: shared by both
/// entry points.
struct Shaded {
    color: Ex,
    normal: Ex,
    material: Ex,
}

fn shade_hit(
    b: &mut FnBuilder,
    scene: &Scene,
    fns: &Fns,
    options: &Options,
    floor: f64,
    (ro, rd, result, px): (Ex, Ex, Ex, Ex),
) -> Shaded {
    let v3 = b.m.vec3();
    let u32t = b.m.u32();
    let bg = b.vec3_lit(crate::color::linear(scene.background));
    let color = b.local("color", v3, Some(bg));
    let zero3 = b.splat3(0.0);
    let normal = b.local("n", v3, Some(zero3));
    let zero_u = b.u(0);
    let material = b.local("material", u32t, Some(zero_u));
    let is_hit = hit_bit(b, result);
    let surface = |b: &mut FnBuilder, t: Ex| surface(b, fns, (options, floor), (ro, rd, px), t);
    b.if_(
        is_hit,
        |b| {
            let t = b.at(result, 0);
            let (c, n, m) = surface(b, t);
            b.store(normal, n);
            b.store(material, m);
            b.store(color, c);
        },
        |_| {},
    );
    if options.trace.antialias {
        // Hart's cone anti-aliasing (Munini §2.4): the near miss in front, blended over what
        // the ray hit (or the background) with its coverage, c = α·c₁ + (1 − α)·c₂.
        let alpha = b.at(result, 4);
        let zero = b.f(0.0);
        let some = b.gt(alpha, zero);
        b.if_(
            some,
            |b| {
                let t = b.at(result, 3);
                let (near, _, _) = surface(b, t);
                let behind = b.load(color);
                let a3 = b.splat(alpha, VectorSize::Tri);
                let mixed = b.math(M::Mix, &[behind, near, a3]);
                b.store(color, mixed);
            },
            |_| {},
        );
    }
    Shaded {
        color: b.load(color),
        normal: b.load(normal),
        material: b.load(material),
    }
}

/// The surface at `t` along the ray from `ro` in direction `rd` (pixel footprint `px`): its
/// colour (shaded, followed along the path of reflected and refracted rays, through the fog),
/// normal and material.
fn surface(
    b: &mut FnBuilder,
    fns: &Fns,
    (options, floor): (&Options, f64),
    (ro, rd, px): (Ex, Ex, Ex),
    t: Ex,
) -> (Ex, Ex, Ex) {
    let pixel_mode = matches!(options.trace.epsilon, Epsilon::Pixel);
    let step = b.mul(rd, t);
    let p = b.add(ro, step);
    let h = pixel_mode.then_some(px);
    let h = epsilon(b, &options.trace, t, h, floor);
    let n = b.call(fns.normal, vec![p, h]);
    let m = match fns.material {
        Some(f) => {
            super::count::count(b, 1);
            b.call(f, vec![p])
        }
        None => b.u(0),
    };
    let c = super::shading::call_shade(b, fns.shade, [p, n, rd, m], h);
    // Mirrors and transparent solids: the path of reflected and refracted rays.
    let c = match fns.path {
        Some(f) => b.call(f, vec![p, n, rd, m, h, c]),
        None => c,
    };
    let c = match fns.fog {
        Some(f) => b.call(f, vec![c, t]),
        None => c,
    };
    (c, n, m)
}

/// Whether a `TraceResult` has its hit bit.
fn hit_bit(b: &mut FnBuilder, result: Ex) -> Ex {
    let flags = b.at(result, 2);
    is_hit(b, flags)
}

/// The pixel of a compute invocation (`gid` plus the tile origin in `view.offset.xy`), or a
/// return when it lies outside the image (`view.offset.zw`): (index in the image, the point
/// in it the ray passes through: the pixel's corner plus `(right.w, up.w)`).
fn compute_pixel(b: &mut FnBuilder, fns: &Fns) -> (Ex, Ex) {
    let gid = b.arg(0);
    let offset = view_field(b, fns.view(), "offset");
    let gxy = b.swizzle(gid, &[0, 1]);
    let oxy = b.swizzle(offset, &[0, 1]);
    let pxy = b.add(gxy, oxy);
    let (x, y) = (b.at(pxy, 0), b.at(pxy, 1));
    let (w, h) = (b.at(offset, 2), b.at(offset, 3));
    let ox = b.ge(x, w);
    let oy = b.ge(y, h);
    let outside = b.bin(naga::BinaryOperator::LogicalOr, ox, oy);
    b.if_(outside, |b| b.ret(None), |_| {});
    let row = b.mul(y, w);
    let index = b.add(row, x);
    b.name(index, "index");
    let pf = b.cast(pxy, ScalarKind::Float);
    // Where in the pixel the ray passes: `right.w`, `up.w` (the centre, 0.5, unless
    // anti-aliasing samples move it).
    let right = view_field(b, fns.view(), "right");
    let up = view_field(b, fns.view(), "up");
    let (jx, jy) = (b.at(right, 3), b.at(up, 3));
    let jitter = b.vec2(jx, jy);
    (index, b.add(pf, jitter))
}

/// The trace-only compute entry ([`super::Entry::Trace`]): each pixel's ray traced (in passes
/// if the module has them), and `vec2<u32>(bitcast(t), steps | hit << 31)` stored at binding 1.
pub(super) fn add_trace_only(mb: &mut ModuleBuilder, fns: &Fns) {
    let u3 = mb.uvec(VectorSize::Tri);
    let u2 = mb.uvec(VectorSize::Bi);
    let out = storage_array(mb, layout::TRACE_OUTPUT, (u2, true));
    let hand_over = hand_over(mb, fns);
    let mut b = FnBuilder::new(mb, "main", &[("gid", u3)], None);
    b.func.arguments[0].binding = Some(Binding::BuiltIn(BuiltIn::GlobalInvocationId));
    let (index, pixel) = compute_pixel(&mut b, fns);
    let ((_, _, result, _), steps) = trace_in_pass(&mut b, fns, hand_over, (index, pixel));
    // Counting primitive evaluations: their count where the steps go.
    let steps = match b.m.evaluations {
        Some(g) if b.m.primitives => {
            let g = b.expr(Expression::GlobalVariable(g));
            b.load(g)
        }
        _ => steps,
    };
    let t = b.at(result, 0);
    let bits = b.expr(Expression::As {
        expr: t,
        kind: ScalarKind::Uint,
        convert: None,
    });
    let flags = b.at(result, 2);
    let one = b.u(1);
    let hit = b.bin(naga::BinaryOperator::And, flags, one);
    let shift = b.u(31);
    let hit = b.bin(naga::BinaryOperator::ShiftLeft, hit, shift);
    let word = b.bin(naga::BinaryOperator::InclusiveOr, steps, hit);
    let v = b.compose(u2, vec![bits, word]);
    let base = b.expr(Expression::GlobalVariable(out));
    let ptr = b.expr(Expression::Access { base, index });
    b.store(ptr, v);
    let f = b.finish();
    compute_main(mb, f, [WORKGROUP, WORKGROUP, 1]);
}

/// `@compute @workgroup_size(8, 8)` `main`: one pixel per invocation, offset by the tile origin
/// in `view.offset.xy`, the full image size in `view.offset.zw`; writes the outputs at
/// bindings 1 (colour, rgba8 packed), 2 (depth t, −1 for a miss), 3 (normal), 4 (material id),
/// 5 (steps: the camera ray's evaluations of the field), 8 (the evaluations shading took:
/// normal, material, shadow rays, occlusion, reflected and refracted rays).
pub(super) fn add_compute(
    mb: &mut ModuleBuilder,
    scene: &Scene,
    fns: &Fns,
    options: &Options,
    floor: f64,
) {
    let u3 = mb.uvec(VectorSize::Tri);
    let (u, f, v4) = (mb.u32(), mb.f32(), mb.vec(VectorSize::Quad));
    let outputs: Vec<Handle<naga::GlobalVariable>> = layout::PIXEL_OUTPUTS
        .iter()
        .map(|&out| {
            let base = match out.element {
                Element::U32 => u,
                Element::F32 => f,
                Element::Vec4F32 => v4,
                Element::Vec2U32 => unreachable!("no pixel output is a vec2"),
            };
            storage_array(mb, out, (base, true))
        })
        .collect();
    let hand_over = hand_over(mb, fns);
    let mut b = FnBuilder::new(mb, "main", &[("gid", u3)], None);
    b.func.arguments[0].binding = Some(Binding::BuiltIn(BuiltIn::GlobalInvocationId));
    let (index, pixel) = compute_pixel(&mut b, fns);
    let (traced, steps) = trace_in_pass(&mut b, fns, hand_over, (index, pixel));
    let counter =
        b.m.evaluations
            .expect("the compute entry counts evaluations");
    // (What the trace counted: primitive evaluations, where those are counted.)
    let traced_count = b.m.primitives.then(|| {
        let c = b.expr(Expression::GlobalVariable(counter));
        b.load(c)
    });
    let result = traced.2;
    let s = shade_hit(&mut b, scene, fns, options, floor, traced);
    let zero = b.f(0.0);
    let one = b.f(1.0);
    let z3 = b.splat(zero, VectorSize::Tri);
    let o3 = b.splat(one, VectorSize::Tri);
    let c = b.clamp(s.color, z3, o3);
    // Linear light encoded to sRGB once, here, as the PNG stores it.
    let c = encode_srgb(&mut b, c);
    let [r, g, bl] = b.xyz(c);
    let v4t = b.m.vec(VectorSize::Quad);
    let rgba = b.compose(v4t, vec![r, g, bl, one]);
    let packed = b.math(M::Pack4x8unorm, &[rgba]);
    let is_hit = hit_bit(&mut b, result);
    let t = b.at(result, 0);
    let miss = b.f(-1.0);
    let depth = b.select(is_hit, t, miss);
    let [nx, ny, nz] = b.xyz(s.normal);
    let n4 = b.compose(v4t, vec![nx, ny, nz, zero]);
    let counter = b.expr(Expression::GlobalVariable(counter));
    let mut shading = b.load(counter);
    if let Some(traced) = traced_count {
        shading = b.sub(shading, traced);
    }
    let values = [packed, depth, n4, s.material, steps, shading];
    for (g, v) in outputs.iter().zip(values) {
        let base = b.expr(Expression::GlobalVariable(*g));
        let ptr = b.expr(Expression::Access { base, index });
        b.store(ptr, v);
    }
    let f = b.finish();
    compute_main(mb, f, [WORKGROUP, WORKGROUP, 1]);
}

/// Adds `f` as the compute entry point `main`.
pub(super) fn compute_main(mb: &mut ModuleBuilder, function: Function, workgroup_size: [u32; 3]) {
    mb.module.entry_points.push(EntryPoint {
        name: "main".into(),
        stage: ShaderStage::Compute,
        early_depth_test: None,
        workgroup_size,
        workgroup_size_overrides: None,
        function,
        mesh_info: None,
        task_payload: None,
        incoming_ray_payload: None,
    });
}

/// The library's `color(ro, rd, pixel) -> vec4<f32>`: the ray traced and its surface shaded
/// as the camera entries do (reflections, refraction, fog, cone anti-aliasing included) in
/// linear light, the background where it misses; `w` is 1 on a hit, else 0.
pub(super) fn add_color(
    mb: &mut ModuleBuilder,
    scene: &Scene,
    fns: &Fns,
    options: &Options,
    floor: f64,
) {
    let (v3, f, v4) = (mb.vec3(), mb.f32(), mb.vec(VectorSize::Quad));
    let args = [("ro", v3), ("rd", v3), ("pixel", f)];
    let mut b = FnBuilder::new(mb, "color", &args, Some(v4));
    let (ro, rd, px) = (b.arg(0), b.arg(1), b.arg(2));
    let result = fns.tracer.call(&mut b, ro, rd, px, None);
    let s = shade_hit(&mut b, scene, fns, options, floor, (ro, rd, result, px));
    let hit = hit_bit(&mut b, result);
    let (one, zero) = (b.f(1.0), b.f(0.0));
    let w = b.select(hit, one, zero);
    let [r, g, bl] = b.xyz(s.color);
    let out = b.compose(v4, vec![r, g, bl, w]);
    b.ret(Some(out));
    let f = b.finish();
    mb.add_function(f);
}

/// `@fragment` `main`: `@builtin(position)` in, `@location(0)` colour out.
pub(super) fn add_fragment(
    mb: &mut ModuleBuilder,
    scene: &Scene,
    fns: &Fns,
    options: &Options,
    floor: f64,
) {
    let v4 = mb.vec(VectorSize::Quad);
    let mut b = FnBuilder::new(mb, "main", &[("position", v4)], Some(v4));
    b.func.arguments[0].binding = Some(Binding::BuiltIn(BuiltIn::Position { invariant: false }));
    b.func.result.as_mut().expect("result").binding = Some(Binding::Location {
        location: 0,
        interpolation: None,
        sampling: None,
        blend_src: None,
        per_primitive: false,
    });
    let pos = b.arg(0);
    // The host's conventions (`layout::FRAGMENT_Y_UP`, `layout::FRAGMENT_SRGB`): GL's window
    // origin is bottom-left, and a plain 8-bit target wants sRGB.
    let size = view_field(&mut b, fns.view(), layout::FRAGMENT_Y_UP.0);
    let forward = view_field(&mut b, fns.view(), layout::FRAGMENT_SRGB.0);
    let half = b.f(0.5);
    let y_up = b.at(size, layout::FRAGMENT_Y_UP.1 as u32);
    let y_up = b.bin(naga::BinaryOperator::Greater, y_up, half);
    let srgb = b.at(forward, layout::FRAGMENT_SRGB.1 as u32);
    let srgb = b.bin(naga::BinaryOperator::Greater, srgb, half);
    let (x, y, height) = (b.at(pos, 0), b.at(pos, 1), b.at(size, 1));
    let flipped = b.sub(height, y);
    let y = b.select(y_up, flipped, y);
    let v2 = b.m.vec(VectorSize::Bi);
    let pixel = b.compose(v2, vec![x, y]);
    let traced = trace_pixel(&mut b, fns, pixel, None);
    let s = shade_hit(&mut b, scene, fns, options, floor, traced);
    let (zero, one) = (b.f(0.0), b.f(1.0));
    let (z3, o3) = (
        b.splat(zero, VectorSize::Tri),
        b.splat(one, VectorSize::Tri),
    );
    let clamped = b.clamp(s.color, z3, o3);
    let encoded = encode_srgb(&mut b, clamped);
    let c = b.select(srgb, encoded, s.color);
    let [r, g, bl] = b.xyz(c);
    let out = b.compose(v4, vec![r, g, bl, one]);
    b.ret(Some(out));
    let f = b.finish();
    mb.module.entry_points.push(EntryPoint {
        name: "main".into(),
        stage: ShaderStage::Fragment,
        early_depth_test: None,
        workgroup_size: [0, 0, 0],
        workgroup_size_overrides: None,
        function: f,
        mesh_info: None,
        task_payload: None,
        incoming_ray_payload: None,
    });
}

/// `c` (linear, in 0…1) encoded as sRGB, per component: 12.92·c up to 0.0031308, else
/// 1.055·c^(1/2.4) − 0.055 (as `crate::color::to_srgb`).
fn encode_srgb(b: &mut FnBuilder, c: Ex) -> Ex {
    let k = b.f(12.92);
    let k3 = b.splat(k, VectorSize::Tri);
    let low = b.mul(c, k3);
    let e = b.f(1.0 / 2.4);
    let e3 = b.splat(e, VectorSize::Tri);
    let p = b.math(M::Pow, &[c, e3]);
    let a = b.f(1.055);
    let a3 = b.splat(a, VectorSize::Tri);
    let p = b.mul(p, a3);
    let o = b.f(0.055);
    let o3 = b.splat(o, VectorSize::Tri);
    let high = b.sub(p, o3);
    let t = b.f(0.003_130_8);
    let t3 = b.splat(t, VectorSize::Tri);
    let dark = b.bin(naga::BinaryOperator::LessEqual, c, t3);
    b.select(dark, low, high)
}
