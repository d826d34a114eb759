//! A compute module prepared once — pipeline, buffers, bind groups — and dispatched frame after
//! frame: `render` runs it tile by tile with a progress report, `bench` times whole frames (one
//! dispatch per pass, one submission, GPU timestamps where the adapter has them).

use crate::gpu::Gpu;
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
    /// The compute entry (`Entry::Compute`): colour, depth, normal, material and steps at
    /// bindings 1–5, shading's evaluations at 8; with `passes`, the hand-over buffers at 6
    /// and 7.
    Full {
        /// Compiled with `Options::passes`.
        passes: bool,
    },
    /// The trace-only entry (`Entry::Trace`) and hand-written references: one
    /// `vec2<u32>(bitcast(t), steps | hit << 31)` per pixel at binding 1; with `passes`, the
    /// hand-over buffers at 6 and 7.
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

/// The per-pixel outputs of a render, row-major, y down.
#[derive(Clone, Debug, PartialEq)]
pub struct Frame {
    /// Width in pixels.
    pub width: u32,
    /// Height in pixels.
    pub height: u32,
    /// RGBA8, packed little-endian (r in the low byte).
    pub color: Vec<u32>,
    /// Distance t to the hit, −1 for a miss.
    pub depth: Vec<f32>,
    /// Unit normal (xyz) at the hit, 0 for a miss.
    pub normal: Vec<[f32; 4]>,
    /// Material id (0 default, i + 1 the i-th declared).
    pub material: Vec<u32>,
    /// Evaluations of the field by the camera ray's trace.
    pub steps: Vec<u32>,
    /// Evaluations of the field by shading: the normal, the material, shadow rays, occlusion,
    /// reflected and refracted rays.
    pub shading: Vec<u32>,
    /// Wall time of the dispatches: from the first tile's submission to the last one's
    /// completion (pipeline creation, buffer set-up and read-back excluded).
    pub seconds: f64,
    /// With passes: the t where each pixel's ray stopped in the last pass, hit or not (the
    /// hand-over buffer); empty otherwise.
    pub reached: Vec<f32>,
}

/// One ray of a trace-only frame.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Ray {
    /// Where the ray stopped, hit or not.
    pub t: f32,
    /// Evaluations of the field.
    pub steps: u32,
    /// Whether it hit.
    pub hit: bool,
}

/// How long one frame took.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Timing {
    /// Wall time from the submission to the end of the wait, seconds.
    pub wall: f64,
    /// GPU time from the first pass's start to the last pass's end (timestamp queries),
    /// seconds; `None` where the adapter has no timestamps.
    pub gpu: Option<f64>,
}

/// One dispatch: its uniform (the buffer and what was written to it), bind group and
/// workgroup counts.
struct Dispatch {
    uniform: (wgpu::Buffer, [u8; 112]),
    /// The tile's origin, for a new view's uniform (`Prepared::set_view`).
    origin: (u32, u32),
    bind: wgpu::BindGroup,
    groups: (u32, u32),
}

/// A module ready to run for one view.
pub struct Prepared<'g> {
    gpu: &'g Gpu,
    pipeline: wgpu::ComputePipeline,
    /// Per pass, its dispatches (tiles).
    passes: Vec<Vec<Dispatch>>,
    /// Output buffers, their sizes and bindings, in binding order.
    outputs: Vec<(wgpu::Buffer, u64, u32)>,
    hand_over: Vec<wgpu::Buffer>,
    /// The `Params` uniform, if the module reads one.
    params: Option<wgpu::Buffer>,
    /// Two timestamps per pass, resolved into a buffer.
    queries: Option<(wgpu::QuerySet, wgpu::Buffer)>,
    layout: Layout,
    width: u32,
    height: u32,
    pixels: u64,
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
    ) -> Result<Prepared<'_>, String> {
        let (w, h) = (view.width, view.height);
        let pixels = w as u64 * h as u64;
        if w == 0
            || h == 0
            || w > MAX_SIDE
            || h > MAX_SIDE
            || pixels * 16 > self.limits.max_storage_buffer_binding_size
        {
            return Err(format!(
                "an image of {w}×{h} is too large for this device (at most {MAX_SIDE} per side and {} pixels)",
                self.limits.max_storage_buffer_binding_size / 16
            ));
        }
        let device = &self.device;
        let validation = device.push_error_scope(wgpu::ErrorFilter::Validation);
        let memory = device.push_error_scope(wgpu::ErrorFilter::OutOfMemory);
        let parsed;
        let module = match source {
            Source::Module(m) => m,
            Source::Wgsl(text, path) => {
                parsed = naga::front::wgsl::parse_str(text)
                    .map_err(|e| e.emit_to_string_with_path(text, path))?;
                &parsed
            }
        };
        let pipeline = self.pipeline(module);
        let params = self.params_buffer(module)?;
        // (bytes per pixel, binding)
        let sizes: Vec<(u64, u32)> = match layout {
            Layout::Full { .. } => vec![(4, 1), (4, 2), (16, 3), (4, 4), (4, 5), (4, 8)],
            Layout::TraceOnly { .. } => vec![(8, 1)],
        };
        let outputs: Vec<(wgpu::Buffer, u64, u32)> = sizes
            .iter()
            .map(|&(bytes, binding)| {
                let size = pixels * bytes;
                (self.storage("output", size), size, binding)
            })
            .collect();
        let with_passes = matches!(
            layout,
            Layout::Full { passes: true } | Layout::TraceOnly { passes: true }
        );
        // Two buffers of (t, steps) per pixel, read and written alternately by the passes.
        let hand_over: Vec<wgpu::Buffer> = (0..if with_passes { 2 } else { 0 })
            .map(|_| self.storage("pass", pixels * 8))
            .collect();
        let one = [Pass {
            view: *view,
            budget: 0,
            cone: 0.0,
        }];
        let schedule = passes.unwrap_or(&one);
        let layout_0 = pipeline.get_bind_group_layout(0);
        let step = tile.min(MAX_SIDE) / sdfc_compiler::layout::WORKGROUP
            * sdfc_compiler::layout::WORKGROUP;
        let step = step.max(sdfc_compiler::layout::WORKGROUP);
        let mut runs = Vec::new();
        for (k, pass) in schedule.iter().enumerate() {
            let field = match (passes, k.checked_sub(1)) {
                (None, _) => [0.0; 4],
                (Some(_), before) => {
                    let (pw, ph) = before.map_or((0, 0), |b| {
                        (schedule[b].view.width, schedule[b].view.height)
                    });
                    [pass.cone as f32, pass.budget as f32, pw as f32, ph as f32]
                }
            };
            let (pw, ph) = (pass.view.width, pass.view.height);
            let mut dispatches = Vec::new();
            for y in (0..ph).step_by(step as usize) {
                for x in (0..pw).step_by(step as usize) {
                    let uniform = self.device.create_buffer(&wgpu::BufferDescriptor {
                        label: Some("view"),
                        size: 112,
                        usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
                        mapped_at_creation: false,
                    });
                    let bytes = pass.view.uniform(x, y, field);
                    self.queue.write_buffer(&uniform, 0, &bytes);
                    let mut entries = vec![wgpu::BindGroupEntry {
                        binding: 0,
                        resource: uniform.as_entire_binding(),
                    }];
                    for (b, _, binding) in &outputs {
                        entries.push(wgpu::BindGroupEntry {
                            binding: *binding,
                            resource: b.as_entire_binding(),
                        });
                    }
                    if let Some((buffer, binding)) = &params {
                        entries.push(wgpu::BindGroupEntry {
                            binding: *binding,
                            resource: buffer.as_entire_binding(),
                        });
                    }
                    if with_passes {
                        for (binding, b) in [(6, k % 2), (7, 1 - k % 2)] {
                            entries.push(wgpu::BindGroupEntry {
                                binding,
                                resource: hand_over[b].as_entire_binding(),
                            });
                        }
                    }
                    let bind = device.create_bind_group(&wgpu::BindGroupDescriptor {
                        label: Some("scene"),
                        layout: &layout_0,
                        entries: &entries,
                    });
                    let groups = |n: u32| n.min(step).div_ceil(sdfc_compiler::layout::WORKGROUP);
                    dispatches.push(Dispatch {
                        uniform: (uniform, bytes),
                        origin: (x, y),
                        bind,
                        groups: (groups(pw - x), groups(ph - y)),
                    });
                }
            }
            runs.push(dispatches);
        }
        let queries = self.timestamps().then(|| {
            let count = 2 * schedule.len() as u32;
            let set = device.create_query_set(&wgpu::QuerySetDescriptor {
                label: Some("frame"),
                ty: wgpu::QueryType::Timestamp,
                count,
            });
            let resolved = device.create_buffer(&wgpu::BufferDescriptor {
                label: Some("timestamps"),
                size: 8 * count as u64,
                usage: wgpu::BufferUsages::QUERY_RESOLVE | wgpu::BufferUsages::COPY_SRC,
                mapped_at_creation: false,
            });
            (set, resolved)
        });
        // Pipeline creation is where the driver compiles: finish it before anything is timed.
        self.wait()?;
        if let Some(e) = pollster::block_on(memory.pop()) {
            return Err(format!("the GPU ran out of memory: {e}"));
        }
        if let Some(e) = pollster::block_on(validation.pop()) {
            return Err(match source {
                Source::Module(_) => {
                    format!("internal error: the GPU rejected the compiled shader: {e}")
                }
                Source::Wgsl(_, path) => format!("error: the GPU rejected `{path}`: {e}"),
            });
        }
        Ok(Prepared {
            gpu: self,
            pipeline,
            passes: runs,
            outputs,
            hand_over,
            params: params.map(|(b, _)| b),
            queries,
            layout,
            width: w,
            height: h,
            pixels,
        })
    }
}

impl Prepared<'_> {
    /// Dispatches how many tiles there are in all passes.
    pub fn dispatches(&self) -> u32 {
        self.passes.iter().map(|p| p.len() as u32).sum()
    }

    /// Sets the scene parameters' values of the next frames
    /// (`sdfc_compiler::lower::params::bytes`); nothing for a module without parameters.
    pub fn set_params(&self, bytes: &[u8]) {
        if let Some(buffer) = &self.params {
            let mut bytes = bytes.to_vec();
            bytes.resize(buffer.size() as usize, 0);
            self.gpu.queue.write_buffer(buffer, 0, &bytes);
        }
    }

    /// Points the next frames' camera as `view` (same size; its jitter included): an orbit
    /// camera without preparing again (`sdfc view`). For a module prepared without passes.
    pub fn set_view(&mut self, view: &View) {
        assert_eq!(self.passes.len(), 1, "a view without passes");
        for d in &mut self.passes[0] {
            d.uniform.1 = view.uniform(d.origin.0, d.origin.1, [0.0; 4]);
            self.gpu.queue.write_buffer(&d.uniform.0, 0, &d.uniform.1);
        }
    }

    /// Moves the rays of the next frames to `jitter` within their pixels (`View::jitter`), in
    /// the last pass only: an earlier, coarser pass's cone covers its whole pixels from their
    /// centres, so it stays there.
    pub fn set_jitter(&self, jitter: [f64; 2]) {
        let Some(last) = self.passes.last() else {
            return;
        };
        for d in last {
            let mut bytes = d.uniform.1;
            for (at, v) in [(28, jitter[0]), (44, jitter[1])] {
                bytes[at..at + 4].copy_from_slice(&(v as f32).to_le_bytes());
            }
            self.gpu.queue.write_buffer(&d.uniform.0, 0, &bytes);
        }
    }

    /// Runs one frame as a single submission (all passes, all tiles) and waits for it.
    pub fn run(&self) -> Result<Timing, String> {
        let gpu = self.gpu;
        let mut enc = gpu.device.create_command_encoder(&Default::default());
        for (k, pass) in self.passes.iter().enumerate() {
            let k = k as u32;
            let timestamp_writes =
                self.queries
                    .as_ref()
                    .map(|(set, _)| wgpu::ComputePassTimestampWrites {
                        query_set: set,
                        beginning_of_pass_write_index: Some(2 * k),
                        end_of_pass_write_index: Some(2 * k + 1),
                    });
            let mut cp = enc.begin_compute_pass(&wgpu::ComputePassDescriptor {
                label: Some("frame"),
                timestamp_writes,
            });
            cp.set_pipeline(&self.pipeline);
            for d in pass {
                cp.set_bind_group(0, &d.bind, &[]);
                cp.dispatch_workgroups(d.groups.0, d.groups.1, 1);
            }
        }
        if let Some((set, resolved)) = &self.queries {
            enc.resolve_query_set(set, 0..2 * self.passes.len() as u32, resolved, 0);
        }
        let clock = std::time::Instant::now();
        gpu.queue.submit([enc.finish()]);
        gpu.wait()?;
        let wall = clock.elapsed().as_secs_f64();
        let gpu_time = match &self.queries {
            Some((_, resolved)) => {
                let bytes = gpu.read(resolved, resolved.size())?;
                let ticks: Vec<u64> = bytes
                    .chunks_exact(8)
                    .map(|c| u64::from_le_bytes(c.try_into().unwrap()))
                    .collect();
                let span = ticks[ticks.len() - 1].saturating_sub(ticks[0]);
                Some(span as f64 * gpu.queue.get_timestamp_period() as f64 * 1e-9)
            }
            None => None,
        };
        Ok(Timing {
            wall,
            gpu: gpu_time,
        })
    }

    /// Runs one frame tile by tile, waiting for each and telling `progress` how many are done
    /// (`render`'s way: a long image shows its progress and no dispatch runs for long).
    pub fn run_tiles(&self, mut progress: impl FnMut(u32, u32)) -> Result<f64, String> {
        let gpu = self.gpu;
        let total = self.dispatches();
        let mut done = 0;
        let clock = std::time::Instant::now();
        for pass in &self.passes {
            for d in pass {
                let mut enc = gpu.device.create_command_encoder(&Default::default());
                {
                    let mut cp = enc.begin_compute_pass(&Default::default());
                    cp.set_pipeline(&self.pipeline);
                    cp.set_bind_group(0, &d.bind, &[]);
                    cp.dispatch_workgroups(d.groups.0, d.groups.1, 1);
                }
                gpu.queue.submit([enc.finish()]);
                gpu.wait()?;
                done += 1;
                progress(done, total);
            }
        }
        Ok(clock.elapsed().as_secs_f64())
    }

    /// Reads a trace-only frame back.
    pub fn rays(&self) -> Result<Vec<Ray>, String> {
        assert!(
            matches!(self.layout, Layout::TraceOnly { .. }),
            "a trace-only module"
        );
        let (b, size, _) = &self.outputs[0];
        let bytes = self.gpu.read(b, *size)?;
        Ok(bytes
            .chunks_exact(8)
            .map(|c| {
                let t = f32::from_le_bytes(c[..4].try_into().unwrap());
                let s = u32::from_le_bytes(c[4..].try_into().unwrap());
                Ray {
                    t,
                    steps: s & 0x7fff_ffff,
                    hit: s >> 31 == 1,
                }
            })
            .collect())
    }

    /// Reads a full frame back; `seconds` is recorded in it.
    pub fn frame(&self, seconds: f64) -> Result<Frame, String> {
        assert!(matches!(self.layout, Layout::Full { .. }), "a full module");
        let reached = match self.hand_over.len() {
            0 => Vec::new(),
            _ => {
                // The last pass wrote binding 7 of its bind group: buffer 1 − (its index % 2).
                let last = (self.passes.len() - 1) % 2;
                let b = self.gpu.read(&self.hand_over[1 - last], self.pixels * 8)?;
                b.chunks_exact(8)
                    .map(|c| f32::from_le_bytes(c[..4].try_into().unwrap()))
                    .collect()
            }
        };
        let bytes: Vec<Vec<u8>> = self
            .outputs
            .iter()
            .map(|(b, s, _)| self.gpu.read(b, *s))
            .collect::<Result<_, _>>()?;
        let words = |b: &[u8]| -> Vec<u32> {
            b.chunks_exact(4)
                .map(|c| u32::from_le_bytes(c.try_into().unwrap()))
                .collect()
        };
        let floats = |b: &[u8]| -> Vec<f32> {
            b.chunks_exact(4)
                .map(|c| f32::from_le_bytes(c.try_into().unwrap()))
                .collect()
        };
        let n = floats(&bytes[2]);
        Ok(Frame {
            width: self.width,
            height: self.height,
            color: words(&bytes[0]),
            depth: floats(&bytes[1]),
            normal: n
                .chunks_exact(4)
                .map(|c| [c[0], c[1], c[2], c[3]])
                .collect(),
            material: words(&bytes[3]),
            steps: words(&bytes[4]),
            shading: words(&bytes[5]),
            seconds,
            reached,
        })
    }
}
