//! Handles to the functions the entries call: the tracer (`Tracer`), normal, shading, fog and
//! path (`Fns`), and a camera pixel's ray traced through them.

use super::camera::{add_camera_ray, add_view, view_field};
use super::march::Inputs;
use super::tracer::Pass;
use crate::ir::builder::{Ex, FnBuilder, ModuleBuilder};
use crate::scene::Trace;
use naga::{Function, Handle};

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

impl Tracer {
    /// The tracer `function`, taking `inputs`, with the settings `trace`.
    pub fn new(function: Handle<Function>, inputs: Inputs, trace: &Trace) -> Tracer {
        Tracer {
            function,
            inputs,
            max_distance: trace.max_distance,
            steps: trace.steps,
            antialias: trace.antialias,
        }
    }

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

/// The functions and globals the camera entries share.
pub(super) struct Fns {
    pub(super) tracer: Tracer,
    pub(super) normal: Handle<Function>,
    pub(super) shade: Handle<Function>,
    /// `map_material`, if the module has one.
    pub(super) material: Option<Handle<Function>>,
    pub(super) fog: Option<Handle<Function>>,
    /// `path`, if some material reflects or is transparent.
    pub(super) path: Option<Handle<Function>>,
    /// `camera_ray` and the `View` uniform: none in the library (the host has its camera).
    camera: Option<(Handle<Function>, Handle<naga::GlobalVariable>)>,
    pub(super) passes: bool,
}

impl Fns {
    /// Adds the view uniform and `camera_ray`.
    pub fn new(
        mb: &mut ModuleBuilder,
        tracer: Tracer,
        [normal, shade]: [Handle<Function>; 2],
        material: Option<Handle<Function>>,
        [fog, path]: [Option<Handle<Function>>; 2],
        passes: bool,
    ) -> Fns {
        let view = add_view(mb, passes);
        let ray = add_camera_ray(mb, view);
        Fns {
            camera: Some((ray, view)),
            passes,
            ..Fns::library(tracer, [normal, shade], material, [fog, path])
        }
    }

    /// The functions without a camera: the library's.
    pub fn library(
        tracer: Tracer,
        [normal, shade]: [Handle<Function>; 2],
        material: Option<Handle<Function>>,
        [fog, path]: [Option<Handle<Function>>; 2],
    ) -> Fns {
        Fns {
            tracer,
            normal,
            shade,
            material,
            fog,
            path,
            camera: None,
            passes: false,
        }
    }

    /// The `View` uniform (the camera entries have one).
    pub(super) fn view(&self) -> Handle<naga::GlobalVariable> {
        self.camera.expect("a camera entry").1
    }
}

/// The ray through `pixel` traced (in a pass if given): (origin, direction, `TraceResult`,
/// pixel footprint).
pub(super) fn trace_pixel(
    b: &mut FnBuilder,
    fns: &Fns,
    pixel: Ex,
    pass: Option<Pass>,
) -> (Ex, Ex, Ex, Ex) {
    let rd = b.call(fns.camera.expect("a camera entry").0, vec![pixel]);
    let eye = view_field(b, fns.view(), "eye");
    let ro = b.swizzle(eye, &[0, 1, 2]);
    let size = view_field(b, fns.view(), "size");
    let px = b.at(size, 2);
    let result = fns.tracer.call(b, ro, rd, px, pass);
    b.name(result, "traced");
    (ro, rd, result, px)
}
