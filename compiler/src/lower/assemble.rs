//! What a module has besides `map`, as the options choose: the tracer (`trace_<method>`, behind
//! a convex bound's `trace_bounded` if the scene declares one), `normal`, `shade`, `fog`,
//! `path`, and the compute, fragment, library, ray-list or field-list interface (`entry.rs`,
//! `rays.rs`).

use super::fns::{Fns, Tracer};
use super::march::{self, Inputs};
use super::tracer::{Entry, Options};
use super::{bounce, bound, count, entry, interface, rays, shading, variants};
use crate::ir::builder::{FnBuilder, ModuleBuilder};
use crate::scene::{Epsilon, Scene};
use naga::{Function, Handle, Type};

/// Adds the tracer, normal, shading and the entry interface to a module that has `map` (for
/// [`Entry::Field`], only the entry: it calls `map` alone); the tracer calls `trace_map` (the
/// data form's `tape_trace`, else `map`).
pub(super) fn add(
    mb: &mut ModuleBuilder,
    scene: &Scene,
    (map, trace_map): (Handle<Function>, Handle<Function>),
    [material, texture, blend]: [Option<Handle<Function>>; 3],
    loose: Option<Handle<Function>>,
    entry: Entry,
    options: &Options,
) {
    if entry == Entry::Field {
        rays::add_field(mb, map, scene.root_node().lambda);
        return;
    }
    let floor = scene.camera.epsilon_floor();
    let (tracer, result_ty) = add_tracer(mb, scene, (trace_map, loose), options, floor);
    if entry == Entry::Compute && mb.evaluations.is_none() {
        count::add_counter(mb);
    }
    let normal = shading::add_normal(mb, map);
    // The offset of secondary rays' origins: ε_dynamic, or a fixed one to compare with.
    let fixed = options
        .fixed_offset
        .then(|| 2.0 * scene.camera.epsilon_floor());
    let shade = shading::add_shade(mb, scene, (map, texture, blend), fixed);
    let fog = shading::add_fog(mb, scene);
    let path = material.and_then(|material| {
        let calls = (map, normal, material, shade);
        add_path(mb, scene, calls, fixed)
    });
    let shaded = ([normal, shade], material, [fog, path]);
    match entry {
        Entry::Library => {
            add_library_trace(mb, &tracer, result_ty);
            let fns = Fns::library(tracer, shaded.0, shaded.1, shaded.2);
            entry::add_color(mb, scene, &fns, options, floor);
            interface::add_material_constants(mb, scene);
        }
        Entry::Rays => rays::add_rays(mb, &tracer),
        Entry::Field => unreachable!("the field entry returned above"),
        Entry::Compute | Entry::Fragment | Entry::Trace => {
            let passes = options.passes && entry != Entry::Fragment;
            let fns = Fns::new(mb, tracer, shaded.0, shaded.1, shaded.2, passes);
            match entry {
                Entry::Compute => entry::add_compute(mb, scene, &fns, options, floor),
                Entry::Fragment => entry::add_fragment(mb, scene, &fns, options, floor),
                _ => entry::add_trace_only(mb, &fns),
            }
        }
    }
}

/// The settings' variant `trace_<method>` (calling `map_loose` to confirm hits if the scene has
/// one), behind the convex bound's `trace_bounded` if the scene declares one: the tracer the
/// entries call, and its result type.
fn add_tracer(
    mb: &mut ModuleBuilder,
    scene: &Scene,
    (map, loose): (Handle<Function>, Option<Handle<Function>>),
    options: &Options,
    floor: f64,
) -> (Tracer, Handle<Type>) {
    let result_ty = march::trace_result_type(mb, options.trace.antialias);
    let inputs = Inputs {
        pixel: matches!(options.trace.epsilon, Epsilon::Pixel) || options.trace.antialias,
        segment: scene.bound.is_some() || options.passes,
        pass: options.passes,
    };
    let trace = &options.trace;
    let variant = march::add_trace(
        mb,
        (map, loose),
        result_ty,
        trace,
        (inputs, floor),
        variants::body,
    );
    let function = match &scene.bound {
        Some(shape) => {
            let out = (result_ty, options.trace.antialias);
            bound::add(mb, map, out, variant, inputs, shape)
        }
        None => variant,
    };
    (Tracer::new(function, inputs, trace), result_ty)
}

/// `march` and `path` where some material reflects or is transparent (the module has
/// `map_material`): `calls` are `map`, `normal`, `map_material` and `shade`.
fn add_path(
    mb: &mut ModuleBuilder,
    scene: &Scene,
    (map, normal, material, shade): (
        Handle<Function>,
        Handle<Function>,
        Handle<Function>,
        Handle<Function>,
    ),
    fixed: Option<f64>,
) -> Option<Handle<Function>> {
    if !crate::reference::pixel::has_paths(scene) {
        return None;
    }
    let march = bounce::add_march(mb, map);
    let calls = bounce::Calls {
        map,
        normal,
        material,
        shade,
        march,
    };
    Some(bounce::add_path(mb, scene, &calls, fixed))
}

/// The library's `trace(ro, rd, pixel)` (`pixel` unused with an absolute ε): with
/// `color(ro, rd, pixel)`, the whole pixel, its names and signatures are stable whatever the
/// variant and settings (docs/interface.md).
fn add_library_trace(mb: &mut ModuleBuilder, tracer: &Tracer, result_ty: Handle<Type>) {
    let v3 = mb.vec3();
    let f32t = mb.f32();
    let args = [("ro", v3), ("rd", v3), ("pixel", f32t)];
    let mut b = FnBuilder::new(mb, "trace", &args, Some(result_ty));
    let (ro, rd, pixel) = (b.arg(0), b.arg(1), b.arg(2));
    let r = tracer.call(&mut b, ro, rd, pixel, None);
    b.ret(Some(r));
    let f = b.finish();
    mb.add_function(f);
}
