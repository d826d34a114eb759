//! The tracer, normal, shading and entry points: `trace_<method>` (only the chosen variant),
//! `normal`, `shade` (only the lights and material terms the scene has), and the compute,
//! fragment or library interface.

use super::builder::{Ex, FnBuilder, ModuleBuilder};
use super::march::{self, HIT, epsilon};
use crate::scene::{Epsilon, LightKind, Scene};
use glam::DVec3;
use naga::{
    AddressSpace, Binding, BuiltIn, EntryPoint, Expression, Function, Handle, MathFunction as M,
    ResourceBinding, ScalarKind, ShaderStage, Span, StorageAccess, StructMember, Type, TypeInner,
    VectorSize,
};

/// Which interface the module has.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Entry {
    /// `main` compute entry point writing colour, depth, normal, material and steps to storage
    /// buffers (what the runtime uses).
    Compute,
    /// `main` full-screen fragment entry point: `@builtin(position)` in, colour out.
    Fragment,
    /// No entry point: `map`, `trace`, `normal` (and `shade`) for other shaders.
    Library,
    /// `main` compute entry point tracing a list of rays (for tests and benchmarks): binding 0
    /// holds two vec4 per ray (origin and pixel footprint, direction), binding 1 receives
    /// `vec4(t, steps, flags, 0)` per ray. Not offered on the command line.
    Rays,
}

/// Tracer settings after command-line overrides.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Options {
    /// The tracer settings used.
    pub trace: crate::scene::Trace,
}

impl Options {
    /// The scene's own settings.
    pub fn from_scene(scene: &Scene) -> Options {
        Options { trace: scene.trace }
    }
}

/// Workgroup size of the compute entry point (8×8).
pub const WORKGROUP: u32 = 8;

/// Ambient light term of `shade` (Munini §2.3: Lambert with an ambient term).
pub const AMBIENT: f64 = 0.12;

/// Base colour of surfaces without a material.
pub const DEFAULT_COLOR: DVec3 = DVec3::new(0.8, 0.8, 0.8);

/// Smallest hit threshold, relative to the camera's distance from its target: keeps ε above the
/// f32 resolution of positions there (about 6e-8 of their magnitude).
pub const EPSILON_FLOOR: f64 = 1e-5;

/// Phong exponent of the specular term.
pub const SHININESS: f64 = 32.0;

/// The uniform block: camera basis (right and up pre-scaled by tan(fov/2)·aspect and
/// tan(fov/2)), image size, pixel footprint, and the tile's offset.
pub const VIEW_FIELDS: [&str; 6] = ["eye", "right", "up", "forward", "size", "offset"];

/// Adds the tracer, normal, shading and the entry interface to a module that has `map`.
pub fn add(
    mb: &mut ModuleBuilder,
    scene: &Scene,
    map: Handle<Function>,
    material: Option<Handle<Function>>,
    entry: Entry,
    options: &Options,
) {
    let floor = EPSILON_FLOOR * (scene.camera.eye - scene.camera.target).length();
    let result_ty = march::trace_result_type(mb);
    let trace = march::add_trace(mb, map, result_ty, &options.trace, floor);
    let normal = add_normal(mb, map);
    let shade = add_shade(mb, scene);
    match entry {
        Entry::Library => {
            // A stable name whatever the variant.
            let v3 = mb.vec3();
            let f32t = mb.f32();
            let pixel = matches!(options.trace.epsilon, Epsilon::Pixel);
            let mut args = vec![("ro", v3), ("rd", v3)];
            if pixel {
                args.push(("pixel", f32t));
            }
            let mut b = FnBuilder::new(mb, "trace", &args, Some(result_ty));
            let a: Vec<Ex> = (0..args.len() as u32).map(|i| b.arg(i)).collect();
            let r = b.call(trace, a);
            b.ret(Some(r));
            let f = b.finish();
            mb.add_function(f);
        }
        Entry::Rays => add_rays(mb, trace),
        Entry::Compute | Entry::Fragment => {
            let view = add_view(mb);
            let ray = add_camera_ray(mb, view);
            let fns = Fns {
                trace,
                normal,
                shade,
                material,
                ray,
                view,
            };
            if entry == Entry::Compute {
                add_compute(mb, scene, &fns, options, floor);
            } else {
                add_fragment(mb, scene, &fns, options, floor);
            }
        }
    }
}

struct Fns {
    trace: Handle<Function>,
    normal: Handle<Function>,
    shade: Handle<Function>,
    material: Option<Handle<Function>>,
    ray: Handle<Function>,
    view: Handle<naga::GlobalVariable>,
}

pub(super) fn struct_ty(
    mb: &mut ModuleBuilder,
    name: &str,
    members: &[(&str, Handle<Type>, u32)],
    span: u32,
) -> Handle<Type> {
    let members = members
        .iter()
        .map(|&(n, ty, offset)| StructMember {
            name: Some(n.to_string()),
            ty,
            binding: None,
            offset,
        })
        .collect();
    mb.named_ty(name, TypeInner::Struct { members, span })
}

/// `normal(p, h)`: central differences of `map` (Munini §2.3); a zero gradient gives zero, not NaN.
fn add_normal(mb: &mut ModuleBuilder, map: Handle<Function>) -> Handle<Function> {
    let v3 = mb.vec3();
    let f32t = mb.f32();
    let mut b = FnBuilder::new(mb, "normal", &[("p", v3), ("h", f32t)], Some(v3));
    let (p, h) = (b.arg(0), b.arg(1));
    let zero = b.f(0.0);
    let mut comps = Vec::new();
    for axis in 0..3 {
        let mut e = [zero; 3];
        e[axis] = h;
        let off = b.compose_vec3(e);
        let hi = b.add(p, off);
        let lo = b.sub(p, off);
        let a = b.call(map, vec![hi]);
        let c = b.call(map, vec![lo]);
        comps.push(b.sub(a, c));
    }
    let g = b.compose_vec3([comps[0], comps[1], comps[2]]);
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

/// `shade(p, n, rd, material)`: Lambert with an ambient term (Munini §2.3), a Blinn–Phong
/// highlight only if some material is specular, the scene's lights folded in as constants.
fn add_shade(mb: &mut ModuleBuilder, scene: &Scene) -> Handle<Function> {
    let v3 = mb.vec3();
    let u32t = mb.u32();
    let mut b = FnBuilder::new(
        mb,
        "shade",
        &[("p", v3), ("n", v3), ("rd", v3), ("material", u32t)],
        Some(v3),
    );
    let (p, n, rd, mat) = (b.arg(0), b.arg(1), b.arg(2), b.arg(3));
    let mut base = b.vec3_lit(DEFAULT_COLOR);
    let mut spec = None;
    for (i, m) in scene.materials.iter().enumerate() {
        let id = b.u(i as u32 + 1);
        let is = b.bin(naga::BinaryOperator::Equal, mat, id);
        let c = b.vec3_lit(m.color);
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
        let l = match light.kind {
            LightKind::Directional(d) => b.vec3_lit(d.normalize()),
            LightKind::Point(pos) => {
                let pv = b.vec3_lit(pos);
                let d = b.sub(pv, p);
                b.math(M::Normalize, &[d])
            }
        };
        let ndl = b.dot(n, l);
        let zero = b.f(0.0);
        let diff = b.max(ndl, zero);
        let lc = b.vec3_lit(light.color * light.intensity);
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

/// The `View` uniform at group 0, binding 0.
fn add_view(mb: &mut ModuleBuilder) -> Handle<naga::GlobalVariable> {
    let v4 = mb.vec(VectorSize::Quad);
    let u4 = mb.uvec(VectorSize::Quad);
    let members: Vec<(&str, Handle<Type>, u32)> = VIEW_FIELDS
        .iter()
        .enumerate()
        .map(|(i, n)| (*n, if *n == "offset" { u4 } else { v4 }, 16 * i as u32))
        .collect();
    let ty = struct_ty(mb, "View", &members, 96);
    global(mb, "view", ty, AddressSpace::Uniform, 0)
}

fn global(
    mb: &mut ModuleBuilder,
    name: &str,
    ty: Handle<Type>,
    space: AddressSpace,
    binding: u32,
) -> Handle<naga::GlobalVariable> {
    mb.module.global_variables.append(
        naga::GlobalVariable {
            name: Some(name.to_string()),
            space,
            binding: Some(ResourceBinding { group: 0, binding }),
            ty,
            init: None,
            memory_decorations: naga::MemoryDecorations::empty(),
        },
        Span::UNDEFINED,
    )
}

/// Loads member `i` of the view uniform.
fn view_field(b: &mut FnBuilder, view: Handle<naga::GlobalVariable>, i: u32) -> Ex {
    let g = b.expr(Expression::GlobalVariable(view));
    let ptr = b.at(g, i);
    b.load(ptr)
}

/// `camera_ray(pixel)`: the pinhole camera (Munini §2.1), pixel coordinates with y down.
fn add_camera_ray(mb: &mut ModuleBuilder, view: Handle<naga::GlobalVariable>) -> Handle<Function> {
    let v2 = mb.vec(VectorSize::Bi);
    let v3 = mb.vec3();
    let mut b = FnBuilder::new(mb, "camera_ray", &[("pixel", v2)], Some(v3));
    let pixel = b.arg(0);
    let [right, up, forward, size] = [1, 2, 3, 4].map(|i| {
        let v = view_field(&mut b, view, i);
        b.swizzle(v, &[0, 1, 2])
    });
    let size = b.swizzle(size, &[0, 1]);
    let two = b.f(2.0);
    let one = b.f(1.0);
    let uv = b.div(pixel, size);
    let uv = b.mul(uv, two);
    let [u, v] = [b.at(uv, 0), b.at(uv, 1)];
    let u = b.sub(u, one);
    let v = b.sub(one, v);
    let ru = b.mul(right, u);
    let uvv = b.mul(up, v);
    let d = b.add(forward, ru);
    let d = b.add(d, uvv);
    let d = b.math(M::Normalize, &[d]);
    b.ret(Some(d));
    let f = b.finish();
    mb.add_function(f)
}

/// The shaded colour (or background), hit flag, t, normal and material of the ray through
/// `pixel`: shared by both entry points.
struct Shaded {
    color: Ex,
    result: Ex,
    normal: Ex,
    material: Ex,
}

fn shade_pixel(
    b: &mut FnBuilder,
    scene: &Scene,
    fns: &Fns,
    options: &Options,
    floor: f64,
    pixel: Ex,
) -> Shaded {
    let v3 = b.m.vec3();
    let u32t = b.m.u32();
    let rd = b.call(fns.ray, vec![pixel]);
    let eye = view_field(b, fns.view, 0);
    let ro = b.swizzle(eye, &[0, 1, 2]);
    let size = view_field(b, fns.view, 4);
    let px = b.at(size, 2);
    let mut args = vec![ro, rd];
    let pixel_mode = matches!(options.trace.epsilon, Epsilon::Pixel);
    if pixel_mode {
        args.push(px);
    }
    let result = b.call(fns.trace, args);
    b.name(result, "traced");
    let bg = b.vec3_lit(scene.background);
    let color = b.local("color", v3, Some(bg));
    let zero3 = b.splat3(0.0);
    let normal = b.local("n", v3, Some(zero3));
    let zero_u = b.u(0);
    let material = b.local("material", u32t, Some(zero_u));
    let is_hit = hit_bit(b, result);
    b.if_(
        is_hit,
        |b| {
            let t = b.at(result, 0);
            let step = b.mul(rd, t);
            let p = b.add(ro, step);
            let h = if pixel_mode { Some(px) } else { None };
            let h = epsilon(b, &options.trace, t, h, floor);
            let n = b.call(fns.normal, vec![p, h]);
            b.store(normal, n);
            let m = match fns.material {
                Some(f) => b.call(f, vec![p]),
                None => b.u(0),
            };
            b.store(material, m);
            let c = b.call(fns.shade, vec![p, n, rd, m]);
            b.store(color, c);
        },
        |_| {},
    );
    Shaded {
        color: b.load(color),
        result,
        normal: b.load(normal),
        material: b.load(material),
    }
}

/// The ray-list compute entry ([`Entry::Rays`]), 64 rays per workgroup.
fn add_rays(mb: &mut ModuleBuilder, trace: Handle<Function>) {
    let v4 = mb.vec(VectorSize::Quad);
    let u3 = mb.uvec(VectorSize::Tri);
    let arr = mb.ty(TypeInner::Array {
        base: v4,
        size: naga::ArraySize::Dynamic,
        stride: 16,
    });
    let pixel_mode = mb.module.functions[trace].arguments.len() == 3;
    let rays = global(
        mb,
        "rays",
        arr,
        AddressSpace::Storage {
            access: StorageAccess::LOAD,
        },
        0,
    );
    let hits = global(
        mb,
        "hits",
        arr,
        AddressSpace::Storage {
            access: StorageAccess::LOAD | StorageAccess::STORE,
        },
        1,
    );
    let mut b = FnBuilder::new(mb, "main", &[("gid", u3)], None);
    b.func.arguments[0].binding = Some(Binding::BuiltIn(BuiltIn::GlobalInvocationId));
    let gid = b.arg(0);
    let i = b.at(gid, 0);
    let out = b.expr(Expression::GlobalVariable(hits));
    let n = b.expr(Expression::ArrayLength(out));
    let beyond = b.ge(i, n);
    b.if_(beyond, |b| b.ret(None), |_| {});
    let two = b.u(2);
    let first = b.mul(i, two);
    let one = b.u(1);
    let second = b.add(first, one);
    let input = b.expr(Expression::GlobalVariable(rays));
    let [o, d] = [first, second].map(|index| {
        let ptr = b.expr(Expression::Access { base: input, index });
        b.load(ptr)
    });
    let ro = b.swizzle(o, &[0, 1, 2]);
    let rd = b.swizzle(d, &[0, 1, 2]);
    let mut args = vec![ro, rd];
    if pixel_mode {
        args.push(b.at(o, 3));
    }
    let r = b.call(trace, args);
    let t = b.at(r, 0);
    let s = b.at(r, 1);
    let s = b.cast(s, ScalarKind::Float);
    let fl = b.at(r, 2);
    let fl = b.cast(fl, ScalarKind::Float);
    let zero = b.f(0.0);
    let v = b.compose(v4, vec![t, s, fl, zero]);
    let ptr = b.expr(Expression::Access {
        base: out,
        index: i,
    });
    b.store(ptr, v);
    let f = b.finish();
    compute_main(mb, f, [RAYS_WORKGROUP, 1, 1]);
}

/// Workgroup size of the ray-list entry.
pub const RAYS_WORKGROUP: u32 = 64;

/// Whether a `TraceResult` has its hit bit.
fn hit_bit(b: &mut FnBuilder, result: Ex) -> Ex {
    let flags = b.at(result, 2);
    let bit = b.u(HIT);
    let masked = b.bin(naga::BinaryOperator::And, flags, bit);
    let zero = b.u(0);
    b.bin(naga::BinaryOperator::NotEqual, masked, zero)
}

/// `@compute @workgroup_size(8, 8)` `main`: one pixel per invocation, offset by the tile origin
/// in `view.offset.xy`, the full image size in `view.offset.zw`; writes the outputs at
/// bindings 1 (colour, rgba8 packed), 2 (depth t, −1 for a miss), 3 (normal), 4 (material id),
/// 5 (steps).
fn add_compute(mb: &mut ModuleBuilder, scene: &Scene, fns: &Fns, options: &Options, floor: f64) {
    let u3 = mb.uvec(VectorSize::Tri);
    let (u, f, v4) = (mb.u32(), mb.f32(), mb.vec(VectorSize::Quad));
    let outputs: Vec<Handle<naga::GlobalVariable>> = [
        ("out_color", u),
        ("out_depth", f),
        ("out_normal", v4),
        ("out_material", u),
        ("out_steps", u),
    ]
    .iter()
    .enumerate()
    .map(|(i, &(name, base))| {
        let stride = if base == v4 { 16 } else { 4 };
        let ty = mb.ty(TypeInner::Array {
            base,
            size: naga::ArraySize::Dynamic,
            stride,
        });
        global(
            mb,
            name,
            ty,
            AddressSpace::Storage {
                access: StorageAccess::LOAD | StorageAccess::STORE,
            },
            i as u32 + 1,
        )
    })
    .collect();
    let mut b = FnBuilder::new(mb, "main", &[("gid", u3)], None);
    b.func.arguments[0].binding = Some(Binding::BuiltIn(BuiltIn::GlobalInvocationId));
    let gid = b.arg(0);
    let offset = view_field(&mut b, fns.view, 5);
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
    let half = b.f(0.5);
    let half2 = b.splat(half, VectorSize::Bi);
    let pixel = b.add(pf, half2);
    let s = shade_pixel(&mut b, scene, fns, options, floor, pixel);
    let zero = b.f(0.0);
    let one = b.f(1.0);
    let z3 = b.splat(zero, VectorSize::Tri);
    let o3 = b.splat(one, VectorSize::Tri);
    let c = b.clamp(s.color, z3, o3);
    let [r, g, bl] = b.xyz(c);
    let v4t = b.m.vec(VectorSize::Quad);
    let rgba = b.compose(v4t, vec![r, g, bl, one]);
    let packed = b.math(M::Pack4x8unorm, &[rgba]);
    let is_hit = hit_bit(&mut b, s.result);
    let t = b.at(s.result, 0);
    let miss = b.f(-1.0);
    let depth = b.select(is_hit, t, miss);
    let [nx, ny, nz] = b.xyz(s.normal);
    let n4 = b.compose(v4t, vec![nx, ny, nz, zero]);
    let steps = b.at(s.result, 1);
    for (g, v) in outputs.iter().zip([packed, depth, n4, s.material, steps]) {
        let base = b.expr(Expression::GlobalVariable(*g));
        let ptr = b.expr(Expression::Access { base, index });
        b.store(ptr, v);
    }
    let f = b.finish();
    compute_main(mb, f, [WORKGROUP, WORKGROUP, 1]);
}

/// Adds `f` as the compute entry point `main`.
fn compute_main(mb: &mut ModuleBuilder, function: Function, workgroup_size: [u32; 3]) {
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

/// `@fragment` `main`: `@builtin(position)` in, `@location(0)` colour out.
fn add_fragment(mb: &mut ModuleBuilder, scene: &Scene, fns: &Fns, options: &Options, floor: f64) {
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
    let pixel = b.swizzle(pos, &[0, 1]);
    let s = shade_pixel(&mut b, scene, fns, options, floor, pixel);
    let [r, g, bl] = b.xyz(s.color);
    let one = b.f(1.0);
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
