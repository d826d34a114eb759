//! What a module has besides `map`: the chosen tracer (`trace_<method>`, behind a convex
//! bound's `trace_bounded` if the scene declares one), `normal`, `shade`, and the compute,
//! fragment, library, ray-list or field-list interface (`entry.rs`, `rays.rs`); the options
//! that choose them.

use super::builder::{Ex, FnBuilder, ModuleBuilder};
use super::march::{self, Inputs};
use super::{entry, rays, shading};
use crate::scene::{Epsilon, Scene};
use naga::{Function, Handle, StructMember, Type, TypeInner};

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
    /// holds two vec4 per ray (origin and pixel footprint; direction and the t to start at),
    /// binding 1 receives `vec4(t, steps, flags, cover)` per ray (cover: the anti-aliasing
    /// coverage, 0 without). Not offered on the command line.
    Rays,
    /// `main` compute entry point evaluating the scene's field at a list of points (for
    /// tests): binding 0 holds one `vec4<f32>` per point (xyz, w unused), binding 1 receives
    /// `vec4(map(p), raw, 0, 0)` per point, `raw` being the root's field before the division by
    /// its λ (`map(p)·λ`); 64 points per workgroup. The module has no tracer, `normal` or
    /// `shade`. Not offered on the command line.
    Field,
    /// `main` compute entry point that only traces (what `sdfc bench` times as "trace only",
    /// as a hand-written tracer would): binding 0 the `View` uniform, binding 1 receives
    /// `vec2<u32>(bitcast<u32>(t), steps | hit << 31)` per pixel, t where the ray stopped.
    /// No normal, material or shading. With `Options::passes`, the hand-over buffers of the
    /// compute entry at bindings 6 and 7.
    Trace,
}

/// Tracer settings after command-line overrides.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Options {
    /// The tracer settings used.
    pub trace: crate::scene::Trace,
    /// Compile the compute entry for multi-resolution passes (Bálint §4): a `pass` field in
    /// the view and two buffers handing each pixel's t and step count to the next pass.
    pub passes: bool,
    /// Which unions test their bounding-volume tree in `map` (`catalog::prune`): the same
    /// field with groups of far parts skipped.
    pub bounding_volumes: BoundingVolumes,
    /// Start shadow, reflected and refracted rays a fixed 2·ε_floor from the surface instead
    /// of Keinert's ε_dynamic = 2·max(h, |f(p)|) (§3.3): only to measure what ε_dynamic
    /// prevents (`--fixed-offset`).
    pub fixed_offset: bool,
    /// Keep the parameters in a private global the shader itself sets (`params = Params(…)`)
    /// instead of the `Params` uniform: for hosts without uniforms of their own (Shadertoy).
    pub private_params: bool,
    /// The `Params` uniform's binding in group 0 (`emit --params-binding`, so that two
    /// scenes' libraries can share a shader).
    pub params_binding: u32,
}

/// Which unions' bounding-volume trees (`catalog::prune::Tree`) the shader tests.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum BoundingVolumes {
    /// None: every child of every union is evaluated each time (`--no-bvh`).
    Off,
    /// Unions whose tree groups at least `prune::GPU_MIN_GROUPED` children: where the tests
    /// measured faster than the plain union (the default).
    #[default]
    Large,
    /// Every union that has a tree (`--bvh`).
    All,
}

impl BoundingVolumes {
    /// Whether the shader tests `tree`.
    pub fn uses(self, tree: &crate::catalog::prune::Tree) -> bool {
        match self {
            BoundingVolumes::Off => false,
            BoundingVolumes::Large => tree.grouped() >= crate::catalog::prune::GPU_MIN_GROUPED,
            BoundingVolumes::All => true,
        }
    }
}

impl Options {
    /// The scene's own settings, one pass.
    pub fn from_scene(scene: &Scene) -> Options {
        Options {
            trace: scene.trace,
            passes: false,
            bounding_volumes: BoundingVolumes::default(),
            fixed_offset: false,
            private_params: false,
            params_binding: crate::layout::PARAMS_BINDING,
        }
    }
}

/// The function the entries call to trace a ray, and the inputs it takes.
#[derive(Clone, Copy)]
pub(super) struct Tracer {
    function: Handle<Function>,
    inputs: Inputs,
    max_distance: f64,
    pub steps: u32,
    /// Whether results carry cone anti-aliasing's cover fields.
    pub antialias: bool,
}

/// Where a multi-resolution pass starts a ray and with what budget and cone slope.
#[derive(Clone, Copy)]
pub(super) struct Pass {
    pub start: Ex,
    pub budget: Ex,
    pub cone: Ex,
}

impl Tracer {
    /// Calls the tracer on a ray; `pixel` is used in pixel-ε mode, `pass` when the module has
    /// passes (otherwise the whole ray with the full budget).
    pub fn call(&self, b: &mut FnBuilder, ro: Ex, rd: Ex, pixel: Ex, pass: Option<Pass>) -> Ex {
        let mut args = vec![ro, rd];
        if self.inputs.pixel {
            args.push(pixel);
        }
        if self.inputs.segment {
            let start = match pass {
                Some(p) => p.start,
                None => b.f(0.0),
            };
            args.extend([start, b.f(self.max_distance)]);
        }
        if self.inputs.pass {
            let (budget, cone) = match pass {
                Some(p) => (p.budget, p.cone),
                None => (b.u(self.steps), b.f(0.0)),
            };
            args.extend([budget, cone]);
        }
        b.call(self.function, args)
    }
}

/// Adds the tracer, normal, shading and the entry interface to a module that has `map` (for
/// [`Entry::Field`], only the entry: it calls `map` alone).
pub fn add(
    mb: &mut ModuleBuilder,
    scene: &Scene,
    map: Handle<Function>,
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
    let result_ty = march::trace_result_type(mb, options.trace.antialias);
    let inputs = Inputs {
        pixel: matches!(options.trace.epsilon, Epsilon::Pixel) || options.trace.antialias,
        segment: scene.bound.is_some() || options.passes,
        pass: options.passes,
    };
    let variant = march::add_trace(mb, map, result_ty, &options.trace, inputs, floor, loose);
    let function = match &scene.bound {
        Some(bound) => {
            let out = (result_ty, options.trace.antialias);
            super::bound::add(mb, map, out, variant, inputs, bound)
        }
        None => variant,
    };
    let tracer = Tracer {
        function,
        inputs,
        max_distance: options.trace.max_distance,
        steps: options.trace.steps,
        antialias: options.trace.antialias,
    };
    if entry == Entry::Compute {
        super::count::add_counter(mb);
    }
    let normal = shading::add_normal(mb, map);
    // The offset of secondary rays' origins: ε_dynamic, or a fixed one to compare with.
    let fixed = options
        .fixed_offset
        .then(|| 2.0 * scene.camera.epsilon_floor());
    let shade = shading::add_shade(mb, scene, (map, texture, blend), fixed);
    let fog = shading::add_fog(mb, scene);
    let path = match material {
        Some(material) if crate::shading::has_paths(scene) => {
            let march = super::bounce::add_march(mb, map);
            let calls = super::bounce::Calls {
                map,
                normal,
                material,
                shade,
                march,
            };
            Some(super::bounce::add_path(mb, scene, &calls, fixed))
        }
        _ => None,
    };
    match entry {
        Entry::Library => {
            // Stable names and signatures whatever the variant and settings
            // (docs/interface.md): `trace(ro, rd, pixel)` (`pixel` unused with an absolute ε)
            // and `color(ro, rd, pixel)`, the whole pixel.
            let v3 = mb.vec3();
            let f32t = mb.f32();
            let args = [("ro", v3), ("rd", v3), ("pixel", f32t)];
            let mut b = FnBuilder::new(mb, "trace", &args, Some(result_ty));
            let (ro, rd, pixel) = (b.arg(0), b.arg(1), b.arg(2));
            let r = tracer.call(&mut b, ro, rd, pixel, None);
            b.ret(Some(r));
            let f = b.finish();
            mb.add_function(f);
            let fns = entry::Fns::library(tracer, [normal, shade], material, [fog, path]);
            entry::add_color(mb, scene, &fns, options, floor);
            super::interface::add_material_constants(mb, scene);
        }
        Entry::Rays => rays::add_rays(mb, &tracer),
        Entry::Field => unreachable!("the field entry returned above"),
        Entry::Compute | Entry::Fragment | Entry::Trace => {
            let passes = options.passes && entry != Entry::Fragment;
            let fns = entry::Fns::new(mb, tracer, [normal, shade], material, [fog, path], passes);
            match entry {
                Entry::Compute => entry::add_compute(mb, scene, &fns, options, floor),
                Entry::Fragment => entry::add_fragment(mb, scene, &fns, options, floor),
                _ => entry::add_trace_only(mb, &fns),
            }
        }
    }
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
