//! A compute module prepared once — pipeline, buffers, bind groups — to be dispatched frame
//! after frame (`dispatch`) and read back (`readback`): `render` runs it tile by tile with a
//! progress report, `bench` times whole frames (one dispatch per pass, one submission, GPU
//! timestamps where the adapter has them). Bindings and sizes come from
//! `sdfc_compiler::layout`, the table the lowering declares its globals from.

use super::readback::Output;
use super::{Error, Gpu};
use sdfc_compiler::layout::{
    self, HAND_OVER, PIXEL_OUTPUTS, TRACE_OUTPUT, VIEW_BINDING, VIEW_BYTES, WORKGROUP,
};
use sdfc_compiler::passes::Pass;
use sdfc_compiler::view::View;

/// Largest image side accepted.
pub const MAX_SIDE: u32 = 16384;

/// Side of the square tiles `render` splits an image into, so that no single dispatch runs
/// long enough for a driver to kill it.
pub const TILE: u32 = 256;

/// What a module binds and writes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Layout {
    /// The compute entry (`Entry::Compute`): colour, depth, normal, material, steps and
    /// shading's evaluations (`layout::PIXEL_OUTPUTS`); with `passes`, the hand-over buffers
    /// (`layout::HAND_OVER`).
    Full {
        /// Compiled with `Options::passes`.
        passes: bool,
    },
    /// The trace-only entry (`Entry::Trace`) and hand-written references: one
    /// `vec2<u32>(bitcast(t), steps | hit << 31)` per pixel (`layout::TRACE_OUTPUT`); with
    /// `passes`, the hand-over buffers (`layout::HAND_OVER`).
    TraceOnly {
        /// Compiled with `Options::passes`.
        passes: bool,
    },
}

/// Where a module comes from.
pub enum Source<'a> {
    /// Compiled by sdfc.
    Module(&'a naga::Module),
    /// WGSL text (a hand-written reference) and the file it came from.
    Wgsl(&'a str, &'a str),
}

/// One dispatch: its uniform (the buffer and what was written to it), bind group and
/// workgroup counts.
pub(super) struct Dispatch {
    pub(super) uniform: (wgpu::Buffer, [u8; VIEW_BYTES]),
    /// The tile's origin, for a new view's uniform (`Prepared::set_view`).
    pub(super) origin: (u32, u32),
    pub(super) bind: wgpu::BindGroup,
    pub(super) groups: (u32, u32),
}

/// A module ready to run for one view (it keeps a handle on its device).
pub struct Prepared {
    pub(super) gpu: Gpu,
    pub(super) pipeline: wgpu::ComputePipeline,
    /// Per pass, its dispatches (tiles).
    pub(super) passes: Vec<Vec<Dispatch>>,
    /// Output buffers, in binding order.
    pub(super) outputs: Vec<Output>,
    pub(super) hand_over: Vec<wgpu::Buffer>,
    /// The `Params` uniform and its binding, if the module reads one.
    pub(super) params: Option<(wgpu::Buffer, u32)>,
    /// The baked volumes' views and bindings (kept for [`Prepared::retape`]).
    volumes: Vec<(u32, wgpu::TextureView)>,
    /// Whether the module reads the data form's buffers.
    reads_tape: bool,
    /// Two timestamps per pass, resolved into a buffer.
    pub(super) queries: Option<(wgpu::QuerySet, wgpu::Buffer)>,
    pub(super) layout: Layout,
    pub(super) width: u32,
    pub(super) height: u32,
    pub(super) pixels: u64,
}

impl Layout {
    /// The output buffers a module of this layout writes.
    fn outputs(self) -> &'static [layout::Buffer] {
        match self {
            Layout::Full { .. } => &PIXEL_OUTPUTS,
            Layout::TraceOnly { .. } => std::slice::from_ref(&TRACE_OUTPUT),
        }
    }

    /// Whether the module hands (t, steps) from pass to pass.
    fn passes(self) -> bool {
        matches!(
            self,
            Layout::Full { passes: true } | Layout::TraceOnly { passes: true }
        )
    }
}

/// What the bind groups of every dispatch share.
struct Bindings<'a> {
    layout: &'a wgpu::BindGroupLayout,
    outputs: &'a [Output],
    params: Option<&'a (wgpu::Buffer, u32)>,
    hand_over: &'a [wgpu::Buffer],
    /// The baked volumes' textures and their bindings.
    volumes: &'a [(u32, wgpu::TextureView)],
    /// The data form's buffers and their bindings.
    tape: &'a [(u32, wgpu::Buffer)],
}

impl Gpu {
    /// Prepares `source` for `view` (with `passes`, pass by pass: Bálint §4), split into square
    /// tiles of side `tile` (a multiple of the workgroup's 8; `u32::MAX`: one dispatch per
    /// pass). Shader and pipeline errors are reported here, before anything is timed.
    pub fn prepare(
        &self,
        source: Source,
        layout: Layout,
        view: &View,
        passes: Option<&[Pass]>,
        tile: u32,
    ) -> Result<Prepared, Error> {
        let (w, h) = (view.width, view.height);
        let pixels = self.check_size(w, h)?;
        let validation = self.device.push_error_scope(wgpu::ErrorFilter::Validation);
        let memory = self.device.push_error_scope(wgpu::ErrorFilter::OutOfMemory);
        let parsed;
        let module = match source {
            Source::Module(m) => m,
            Source::Wgsl(text, path) => {
                parsed = naga::front::wgsl::parse_str(text)
                    .map_err(|e| Error::Wgsl(e.emit_to_string_with_path(text, path)))?;
                &parsed
            }
        };
        let pipeline = self.pipeline(module);
        let params = self.params_buffer(module)?;
        let volumes = self.volume_views(module)?;
        let reads_tape = super::tape::reads_tape(module);
        let tape = self.tape_buffers(reads_tape);
        let outputs: Vec<Output> = layout
            .outputs()
            .iter()
            .map(|&spec| {
                let size = pixels * spec.stride;
                let buffer = self.storage("output", size);
                Output { buffer, size, spec }
            })
            .collect();
        // Two buffers of (t, steps) per pixel, read and written alternately by the passes.
        let hand_over: Vec<wgpu::Buffer> = (0..if layout.passes() { 2 } else { 0 })
            .map(|_| self.storage("pass", pixels * HAND_OVER[0].stride))
            .collect();
        let one = [Pass {
            view: *view,
            budget: 0,
            cone: 0.0,
        }];
        let schedule = passes.unwrap_or(&one);
        let bindings = Bindings {
            layout: &pipeline.get_bind_group_layout(layout::GROUP),
            outputs: &outputs,
            params: params.as_ref(),
            hand_over: &hand_over,
            volumes: &volumes,
            tape: &tape,
        };
        let runs = (0..schedule.len())
            .map(|k| self.tiles(&bindings, schedule, passes.is_some(), k, tile))
            .collect();
        let queries = self.queries(schedule.len());
        // Pipeline creation is where the driver compiles: finish it before anything is timed.
        self.wait()?;
        if let Some(e) = pollster::block_on(memory.pop()) {
            return Err(Error::OutOfMemory(e.to_string()));
        }
        if let Some(e) = pollster::block_on(validation.pop()) {
            return Err(match source {
                Source::Module(_) => Error::InvalidModule(e.to_string()),
                Source::Wgsl(_, path) => Error::RejectedWgsl {
                    path: path.to_string(),
                    message: e.to_string(),
                },
            });
        }
        Ok(Prepared {
            gpu: self.clone(),
            pipeline,
            passes: runs,
            outputs,
            hand_over,
            params,
            volumes,
            reads_tape,
            queries,
            layout,
            width: w,
            height: h,
            pixels,
        })
    }

    /// The pixels of a `w`×`h` image, or why this device cannot hold its outputs.
    fn check_size(&self, w: u32, h: u32) -> Result<u64, Error> {
        let pixels = w as u64 * h as u64;
        let widest = PIXEL_OUTPUTS.iter().map(|b| b.stride).max().unwrap_or(16);
        let limit = self.limits.max_storage_buffer_binding_size;
        if w == 0 || h == 0 || w > MAX_SIDE || h > MAX_SIDE || pixels * widest > limit {
            return Err(Error::TooLarge {
                width: w,
                height: h,
                max_side: MAX_SIDE,
                max_pixels: limit / widest,
            });
        }
        Ok(pixels)
    }

    /// The dispatches of pass `k` of `schedule`: one per square tile of side `tile` (rounded
    /// down to whole workgroups), each with its own `View` uniform and bind group.
    fn tiles(
        &self,
        bindings: &Bindings,
        schedule: &[Pass],
        with_passes: bool,
        k: usize,
        tile: u32,
    ) -> Vec<Dispatch> {
        let pass = &schedule[k];
        let field = match (with_passes, k.checked_sub(1)) {
            (false, _) => [0.0; 4],
            (true, before) => {
                let (pw, ph) = before.map_or((0, 0), |b| {
                    (schedule[b].view.width, schedule[b].view.height)
                });
                [pass.cone as f32, pass.budget as f32, pw as f32, ph as f32]
            }
        };
        let step = (tile.min(MAX_SIDE) / WORKGROUP * WORKGROUP).max(WORKGROUP);
        let groups = |n: u32| n.min(step).div_ceil(WORKGROUP);
        let (pw, ph) = (pass.view.width, pass.view.height);
        let mut dispatches = Vec::new();
        for y in (0..ph).step_by(step as usize) {
            for x in (0..pw).step_by(step as usize) {
                let uniform = self.device.create_buffer(&wgpu::BufferDescriptor {
                    label: Some("view"),
                    size: VIEW_BYTES as u64,
                    usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
                    mapped_at_creation: false,
                });
                let bytes = pass.view.uniform(x, y, field);
                self.queue.write_buffer(&uniform, 0, &bytes);
                let bind = self.bind_group(bindings, &uniform, k);
                dispatches.push(Dispatch {
                    uniform: (uniform, bytes),
                    origin: (x, y),
                    bind,
                    groups: (groups(pw - x), groups(ph - y)),
                });
            }
        }
        dispatches
    }

    /// The bind group of one dispatch of pass `k`: its `View` uniform, the outputs, the
    /// `Params` uniform and (with passes) the hand-over buffers, `pass_in` the one pass
    /// k − 1 wrote.
    fn bind_group(&self, bindings: &Bindings, uniform: &wgpu::Buffer, k: usize) -> wgpu::BindGroup {
        fn entry(binding: u32, buffer: &wgpu::Buffer) -> wgpu::BindGroupEntry<'_> {
            wgpu::BindGroupEntry {
                binding,
                resource: buffer.as_entire_binding(),
            }
        }
        let mut entries = vec![entry(VIEW_BINDING, uniform)];
        for o in bindings.outputs {
            entries.push(entry(o.spec.binding, &o.buffer));
        }
        if let Some((buffer, binding)) = bindings.params {
            entries.push(entry(*binding, buffer));
        }
        if !bindings.hand_over.is_empty() {
            let [pass_in, pass_out] = HAND_OVER;
            for (spec, b) in [(pass_in, k % 2), (pass_out, 1 - k % 2)] {
                entries.push(entry(spec.binding, &bindings.hand_over[b]));
            }
        }
        for (binding, buffer) in bindings.tape {
            entries.push(entry(*binding, buffer));
        }
        for (binding, view) in bindings.volumes {
            entries.push(wgpu::BindGroupEntry {
                binding: *binding,
                resource: wgpu::BindingResource::TextureView(view),
            });
        }
        self.device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("scene"),
            layout: bindings.layout,
            entries: &entries,
        })
    }

    /// Two timestamp queries per pass and the buffer they resolve into, where the adapter has
    /// timestamps.
    fn queries(&self, passes: usize) -> Option<(wgpu::QuerySet, wgpu::Buffer)> {
        self.timestamps().then(|| {
            let count = 2 * passes as u32;
            let set = self.device.create_query_set(&wgpu::QuerySetDescriptor {
                label: Some("frame"),
                ty: wgpu::QueryType::Timestamp,
                count,
            });
            let resolved = self.device.create_buffer(&wgpu::BufferDescriptor {
                label: Some("timestamps"),
                size: 8 * count as u64,
                usage: wgpu::BufferUsages::QUERY_RESOLVE | wgpu::BufferUsages::COPY_SRC,
                mapped_at_creation: false,
            });
            (set, resolved)
        })
    }
}

impl Prepared {
    /// Dispatches how many tiles there are in all passes.
    pub fn dispatches(&self) -> u32 {
        self.passes.iter().map(|p| p.len() as u32).sum()
    }

    /// Binds the data form's buffers set since (`Gpu::set_tape`) in place of those it was
    /// prepared with: the same pipeline — no new shader for the driver — reads the parts at new
    /// parameter values. Nothing for a module that does not read them.
    pub fn retape(&mut self) {
        if !self.reads_tape {
            return;
        }
        let tape = self.gpu.tape_buffers(true);
        let layout = self.pipeline.get_bind_group_layout(layout::GROUP);
        let bindings = Bindings {
            layout: &layout,
            outputs: &self.outputs,
            params: self.params.as_ref(),
            hand_over: &self.hand_over,
            volumes: &self.volumes,
            tape: &tape,
        };
        for (k, pass) in self.passes.iter_mut().enumerate() {
            for d in pass {
                d.bind = self.gpu.bind_group(&bindings, &d.uniform.0, k);
            }
        }
    }
}
