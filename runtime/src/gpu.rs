//! The wgpu runtime: a headless device (Vulkan, then GL), and a tiled dispatch of a compiled
//! compute module that reads back colour, depth, normal, material and step count.

use sdfc_compiler::passes::Pass;
use sdfc_compiler::view::View;
use std::borrow::Cow;
use std::sync::{Arc, Mutex};

/// Which graphics API to use.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum BackendChoice {
    /// Vulkan, then GL.
    Auto,
    /// Vulkan only (lavapipe on machines without a GPU).
    Vulkan,
    /// GL only (llvmpipe over EGL on machines without a GPU).
    Gl,
}

/// Largest image side accepted.
pub const MAX_SIDE: u32 = 16384;

/// Side of the square tiles a render is split into, so that no single dispatch runs long
/// enough for a driver to kill it.
pub const TILE: u32 = 256;

/// A device and its queue.
pub struct Gpu {
    device: wgpu::Device,
    queue: wgpu::Queue,
    /// What the adapter says it is.
    pub info: wgpu::AdapterInfo,
    limits: wgpu::Limits,
    /// What went wrong outside an error scope, checked after every wait so that a render ends
    /// with it instead of a panic or a hang.
    trouble: Arc<Mutex<Trouble>>,
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
    /// Evaluations of the field.
    pub steps: Vec<u32>,
    /// Wall time of the dispatches: from the first tile's submission to the last one's
    /// completion (pipeline creation, buffer set-up and read-back excluded).
    pub seconds: f64,
    /// With passes: the t where each pixel's ray stopped in the last pass, hit or not (the
    /// hand-over buffer); empty otherwise.
    pub reached: Vec<f32>,
}

const NO_ADAPTER: &str = "no GPU adapter was found (tried Vulkan and GL).\n\
     help: on a machine without a GPU, install Mesa's software drivers: \
     `apt-get install mesa-vulkan-drivers` (Vulkan through lavapipe) or \
     `apt-get install libegl1 libegl-mesa0 libgl1-mesa-dri` (GL through llvmpipe)";

impl Gpu {
    /// Opens a device on the first backend that has an adapter.
    pub fn new(choice: BackendChoice) -> Result<Gpu, String> {
        let order = match choice {
            BackendChoice::Auto => vec![wgpu::Backends::VULKAN, wgpu::Backends::GL],
            BackendChoice::Vulkan => vec![wgpu::Backends::VULKAN],
            BackendChoice::Gl => vec![wgpu::Backends::GL],
        };
        for backends in order {
            let mut desc = wgpu::InstanceDescriptor::new_without_display_handle();
            desc.backends = backends;
            let instance = wgpu::Instance::new(desc);
            let options = wgpu::RequestAdapterOptions {
                power_preference: wgpu::PowerPreference::HighPerformance,
                force_fallback_adapter: false,
                compatible_surface: None,
                ..Default::default()
            };
            let Ok(adapter) = pollster::block_on(instance.request_adapter(&options)) else {
                continue;
            };
            let limits = adapter.limits();
            let desc = wgpu::DeviceDescriptor {
                label: Some("sdfc"),
                required_limits: limits.clone(),
                ..Default::default()
            };
            let (device, queue) = pollster::block_on(adapter.request_device(&desc))
                .map_err(|e| format!("the GPU adapter refused a device: {e}"))?;
            // wgpu's default for an error outside a scope is a panic; keep the first instead.
            let trouble = Arc::new(Mutex::new(Trouble::default()));
            let keep = trouble.clone();
            device.on_uncaptured_error(Arc::new(move |e: wgpu::Error| {
                lock(&keep)
                    .error
                    .get_or_insert(format!("the GPU reported an error: {e}"));
            }));
            let keep = trouble.clone();
            device.set_device_lost_callback(move |reason, message| {
                let why = match message.is_empty() {
                    true => format!("{reason:?}"),
                    false => format!("{reason:?}: {message}"),
                };
                lock(&keep)
                    .lost
                    .get_or_insert(format!("the GPU device was lost ({why})"));
            });
            return Ok(Gpu {
                device,
                queue,
                info: adapter.get_info(),
                limits,
                trouble,
            });
        }
        Err(match choice {
            BackendChoice::Auto => NO_ADAPTER.to_string(),
            BackendChoice::Vulkan => "no Vulkan adapter was found.\nhelp: `apt-get install mesa-vulkan-drivers` gives lavapipe".into(),
            BackendChoice::Gl => "no GL adapter was found.\nhelp: `apt-get install libegl1 libegl-mesa0 libgl1-mesa-dri` gives llvmpipe over EGL".into(),
        })
    }

    /// The backend in use, as a word.
    pub fn backend(&self) -> String {
        format!("{:?}", self.info.backend).to_lowercase()
    }

    /// Renders a compiled compute module (`emit` with `Entry::Compute`) for `view`, tile by
    /// tile; with `passes` (a module compiled with `Options::passes`), pass by pass, each
    /// handing its t and step counts to the next (Bálint §4). `progress` is told how many
    /// tiles are done.
    pub fn render(
        &self,
        module: &naga::Module,
        view: &View,
        passes: Option<&[Pass]>,
        mut progress: impl FnMut(u32, u32),
    ) -> Result<Frame, String> {
        let (w, h) = (view.width, view.height);
        let pixels = w as u64 * h as u64;
        let largest = pixels * 16;
        if w == 0
            || h == 0
            || w > MAX_SIDE
            || h > MAX_SIDE
            || largest > self.limits.max_storage_buffer_binding_size
        {
            return Err(format!(
                "an image of {w}×{h} is too large for this device (at most {MAX_SIDE} per side and {} pixels)",
                self.limits.max_storage_buffer_binding_size / 16
            ));
        }
        let device = &self.device;
        let validation = device.push_error_scope(wgpu::ErrorFilter::Validation);
        let memory = device.push_error_scope(wgpu::ErrorFilter::OutOfMemory);
        let pipeline = self.pipeline(module);
        let uniform = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("view"),
            size: 112,
            usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        let sizes = [4, 4, 16, 4, 4].map(|b| pixels * b);
        let outputs: Vec<wgpu::Buffer> = sizes
            .iter()
            .map(|&size| {
                device.create_buffer(&wgpu::BufferDescriptor {
                    label: Some("output"),
                    size,
                    usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_SRC,
                    mapped_at_creation: false,
                })
            })
            .collect();
        let layout = pipeline.get_bind_group_layout(0);
        let mut entries = vec![wgpu::BindGroupEntry {
            binding: 0,
            resource: uniform.as_entire_binding(),
        }];
        for (i, b) in outputs.iter().enumerate() {
            entries.push(wgpu::BindGroupEntry {
                binding: i as u32 + 1,
                resource: b.as_entire_binding(),
            });
        }
        // Two buffers of (t, steps) per pixel, read and written alternately by the passes.
        let hand_over: Vec<wgpu::Buffer> = (0..if passes.is_some() { 2 } else { 0 })
            .map(|_| {
                device.create_buffer(&wgpu::BufferDescriptor {
                    label: Some("pass"),
                    size: pixels * 8,
                    usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_SRC,
                    mapped_at_creation: false,
                })
            })
            .collect();
        let binds: Vec<wgpu::BindGroup> = (0..hand_over.len().max(1))
            .map(|k| {
                let mut entries = entries.clone();
                if !hand_over.is_empty() {
                    for (binding, b) in [(6, k), (7, 1 - k)] {
                        entries.push(wgpu::BindGroupEntry {
                            binding,
                            resource: hand_over[b].as_entire_binding(),
                        });
                    }
                }
                device.create_bind_group(&wgpu::BindGroupDescriptor {
                    label: Some("scene"),
                    layout: &layout,
                    entries: &entries,
                })
            })
            .collect();
        let one = [Pass {
            view: *view,
            budget: 0,
            cone: 0.0,
        }];
        let schedule = passes.unwrap_or(&one);
        let tiles = |v: &View| (v.width.div_ceil(TILE), v.height.div_ceil(TILE));
        let total: u32 = schedule
            .iter()
            .map(|p| tiles(&p.view).0 * tiles(&p.view).1)
            .sum();
        let groups = TILE / sdfc_compiler::lower::tracer::WORKGROUP;
        let mut done = 0;
        let clock = std::time::Instant::now();
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
            let (tx, ty) = tiles(&pass.view);
            for j in 0..ty {
                for i in 0..tx {
                    let bytes = pass.view.uniform(i * TILE, j * TILE, field);
                    self.queue.write_buffer(&uniform, 0, &bytes);
                    let mut enc = device.create_command_encoder(&Default::default());
                    {
                        let mut cp = enc.begin_compute_pass(&Default::default());
                        cp.set_pipeline(&pipeline);
                        cp.set_bind_group(0, &binds[k % binds.len()], &[]);
                        cp.dispatch_workgroups(groups, groups, 1);
                    }
                    self.queue.submit([enc.finish()]);
                    self.wait()?;
                    done += 1;
                    progress(done, total);
                }
            }
        }
        let seconds = clock.elapsed().as_secs_f64();
        if let Some(e) = pollster::block_on(memory.pop()) {
            return Err(format!("the GPU ran out of memory: {e}"));
        }
        if let Some(e) = pollster::block_on(validation.pop()) {
            return Err(format!(
                "internal error: the GPU rejected the compiled shader: {e}"
            ));
        }
        let reached = match hand_over.len() {
            0 => Vec::new(),
            _ => {
                // The last pass wrote binding 7 of its bind group: buffer 1 − (its index % 2).
                let last = (schedule.len() - 1) % 2;
                let b = self.read(&hand_over[1 - last], pixels * 8)?;
                b.chunks_exact(8)
                    .map(|c| f32::from_le_bytes(c[..4].try_into().unwrap()))
                    .collect()
            }
        };
        let bytes: Vec<Vec<u8>> = outputs
            .iter()
            .zip(sizes)
            .map(|(b, s)| self.read(b, s))
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
            width: w,
            height: h,
            color: words(&bytes[0]),
            depth: floats(&bytes[1]),
            normal: n
                .chunks_exact(4)
                .map(|c| [c[0], c[1], c[2], c[3]])
                .collect(),
            material: words(&bytes[3]),
            steps: words(&bytes[4]),
            seconds,
            reached,
        })
    }

    /// Traces a list of rays with a module compiled for `Entry::Rays`: each ray is an origin,
    /// a direction and the pixel footprint (for ε `pixel`); returns (t, steps, flags) per ray.
    pub fn trace_rays(
        &self,
        module: &naga::Module,
        rays: &[([f32; 3], [f32; 3], f32)],
    ) -> Result<Vec<(f32, u32, u32)>, String> {
        Ok(self
            .trace_rays_full(module, rays)?
            .iter()
            .map(|v| (v[0], v[1] as u32, v[2] as u32))
            .collect())
    }

    /// [`Gpu::trace_rays`] with the whole `vec4(t, steps, flags, cover)` per ray.
    pub fn trace_rays_full(
        &self,
        module: &naga::Module,
        rays: &[([f32; 3], [f32; 3], f32)],
    ) -> Result<Vec<[f32; 4]>, String> {
        let input: Vec<f32> = rays
            .iter()
            .flat_map(|(o, d, px)| [o[0], o[1], o[2], *px, d[0], d[1], d[2], 0.0])
            .collect();
        let groups = (rays.len() as u32).div_ceil(sdfc_compiler::lower::tracer::RAYS_WORKGROUP);
        self.run_list(module, ("rays", "hits"), &input, rays.len(), groups)
    }

    /// Evaluates the scene's field at a list of points with a module compiled for
    /// `Entry::Field`, in one dispatch: `map(p)` (the distance bound, already divided by the
    /// root's λ) per point.
    pub fn eval_points(
        &self,
        module: &naga::Module,
        points: &[[f32; 3]],
    ) -> Result<Vec<f32>, String> {
        let input: Vec<f32> = points
            .iter()
            .flat_map(|p| [p[0], p[1], p[2], 0.0])
            .collect();
        let groups = (points.len() as u32).div_ceil(sdfc_compiler::lower::tracer::FIELD_WORKGROUP);
        let out = self.run_list(module, ("points", "values"), &input, points.len(), groups)?;
        Ok(out.iter().map(|v| v[0]).collect())
    }

    /// Runs a list entry (binding 0: `input`, read only; binding 1: one vec4 of output per
    /// item) in one dispatch of `groups` workgroups and reads the output back.
    fn run_list(
        &self,
        module: &naga::Module,
        (input_label, output_label): (&str, &str),
        input: &[f32],
        items: usize,
        groups: u32,
    ) -> Result<Vec<[f32; 4]>, String> {
        if items == 0 {
            return Ok(Vec::new());
        }
        let device = &self.device;
        let validation = device.push_error_scope(wgpu::ErrorFilter::Validation);
        let pipeline = self.pipeline(module);
        let bytes: Vec<u8> = input.iter().copied().flat_map(f32::to_le_bytes).collect();
        let input_buf = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some(input_label),
            size: bytes.len() as u64,
            usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        self.queue.write_buffer(&input_buf, 0, &bytes);
        let size = items as u64 * 16;
        let output = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some(output_label),
            size,
            usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_SRC,
            mapped_at_creation: false,
        });
        let bind = device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some(input_label),
            layout: &pipeline.get_bind_group_layout(0),
            entries: &[
                wgpu::BindGroupEntry {
                    binding: 0,
                    resource: input_buf.as_entire_binding(),
                },
                wgpu::BindGroupEntry {
                    binding: 1,
                    resource: output.as_entire_binding(),
                },
            ],
        });
        let mut enc = device.create_command_encoder(&Default::default());
        {
            let mut pass = enc.begin_compute_pass(&Default::default());
            pass.set_pipeline(&pipeline);
            pass.set_bind_group(0, &bind, &[]);
            pass.dispatch_workgroups(groups, 1, 1);
        }
        self.queue.submit([enc.finish()]);
        self.wait()?;
        if let Some(e) = pollster::block_on(validation.pop()) {
            return Err(format!("internal error: the GPU rejected the shader: {e}"));
        }
        let bytes = self.read(&output, size)?;
        Ok(bytes
            .chunks_exact(16)
            .map(|c| {
                let f = |i: usize| f32::from_le_bytes(c[i * 4..i * 4 + 4].try_into().unwrap());
                [f(0), f(1), f(2), f(3)]
            })
            .collect())
    }

    fn pipeline(&self, module: &naga::Module) -> wgpu::ComputePipeline {
        let shader = self
            .device
            .create_shader_module(wgpu::ShaderModuleDescriptor {
                label: Some("scene"),
                source: wgpu::ShaderSource::Naga(Cow::Owned(module.clone())),
            });
        self.device
            .create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
                label: Some("scene"),
                layout: None,
                module: &shader,
                entry_point: Some("main"),
                compilation_options: Default::default(),
                cache: None,
            })
    }

    /// Waits for the queue, then reports any error or loss the device had meanwhile.
    fn wait(&self) -> Result<(), String> {
        self.device
            .poll(wgpu::PollType::wait_indefinitely())
            .map_err(|e| format!("the GPU device was lost or timed out: {e}"))?;
        let mut trouble = lock(&self.trouble);
        let error = trouble.error.take();
        match (&trouble.lost, error) {
            (Some(lost), _) => Err(lost.clone()),
            (None, Some(error)) => Err(error),
            (None, None) => Ok(()),
        }
    }

    /// Destroys the device as a driver reset would lose it, so that tests can show a render
    /// that loses its device midway ending with an error. The `Gpu` is unusable afterwards.
    pub fn lose_device(&self) {
        self.device.destroy();
    }

    fn read(&self, buffer: &wgpu::Buffer, size: u64) -> Result<Vec<u8>, String> {
        let staging = self.device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("readback"),
            size,
            usage: wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        let mut enc = self.device.create_command_encoder(&Default::default());
        enc.copy_buffer_to_buffer(buffer, 0, &staging, 0, size);
        self.queue.submit([enc.finish()]);
        let slice = staging.slice(..);
        let (send, recv) = std::sync::mpsc::channel();
        slice.map_async(wgpu::MapMode::Read, move |r| {
            let _ = send.send(r);
        });
        self.wait()?;
        recv.recv()
            .map_err(|e| e.to_string())?
            .map_err(|e| format!("cannot read the result back from the GPU: {e}"))?;
        let data = slice
            .get_mapped_range()
            .map_err(|e| format!("cannot map the result: {e:?}"))?
            .to_vec();
        staging.unmap();
        Ok(data)
    }
}

/// What went wrong on the device outside an error scope: the first of each kind (later ones
/// are usually its consequences).
#[derive(Default)]
struct Trouble {
    /// The device's loss: every later wait fails with it.
    lost: Option<String>,
    /// An uncaptured error: reported by the next wait, then forgotten.
    error: Option<String>,
}

fn lock(trouble: &Mutex<Trouble>) -> std::sync::MutexGuard<'_, Trouble> {
    trouble.lock().unwrap_or_else(|e| e.into_inner())
}
