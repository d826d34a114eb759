//! The wgpu runtime: a headless device (Vulkan, then GL), a render of a compiled compute module
//! (through `frames`), and the one-dispatch list entries of the tests.

use sdfc_compiler::passes::Pass;
use sdfc_compiler::view::View;
use std::borrow::Cow;
use std::sync::{Arc, Mutex};

mod open;

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

pub use crate::frames::{Frame, MAX_SIDE, TILE};
use crate::frames::{Layout, Source};

/// A device and its queue.
pub struct Gpu {
    pub(crate) device: wgpu::Device,
    pub(crate) queue: wgpu::Queue,
    /// What the adapter says it is.
    pub info: wgpu::AdapterInfo,
    pub(crate) limits: wgpu::Limits,
    features: wgpu::Features,
    /// What went wrong outside an error scope, checked after every wait so that a render ends
    /// with it instead of a panic or a hang.
    trouble: Arc<Mutex<Trouble>>,
    /// The adapter the device is on.
    adapter: wgpu::Adapter,
    /// The bytes of the `Params` uniform the next prepared modules start with
    /// ([`Gpu::set_params`]).
    params: Mutex<Vec<u8>>,
}

impl Gpu {
    /// Configures a window's surface for this device.
    pub fn configure(&self, surface: &wgpu::Surface, config: &wgpu::SurfaceConfiguration) {
        surface.configure(&self.device, config);
    }

    /// The adapter the device is on.
    pub fn adapter(&self) -> &wgpu::Adapter {
        &self.adapter
    }

    /// Sets the scene parameters' values (`sdfc_compiler::lower::params::bytes`) the modules
    /// prepared from now on read, until set again; a prepared frame changes its own with
    /// `Prepared::set_params`.
    pub fn set_params(&self, bytes: &[u8]) {
        *lock(&self.params) = bytes.to_vec();
    }

    /// The `Params` uniform for a module that reads one (binding
    /// `sdfc_compiler::layout::PARAMS_BINDING`), holding the values last set
    /// ([`Gpu::set_params`]); an internal error when those are not the module's (none set, or
    /// another scene's), rather than a scene drawn at zeros.
    pub(crate) fn params_buffer(
        &self,
        module: &naga::Module,
    ) -> Result<Option<(wgpu::Buffer, u32)>, String> {
        let binding = sdfc_compiler::layout::PARAMS_BINDING;
        let Some(global) = module
            .global_variables
            .iter()
            .find(|(_, g)| g.binding == Some(naga::ResourceBinding { group: 0, binding }))
        else {
            return Ok(None);
        };
        let size = match module.types[global.1.ty].inner {
            naga::TypeInner::Struct { span, .. } => span,
            _ => return Ok(None),
        };
        let bytes = lock(&self.params).clone();
        // The values are laid out for a uniform (the struct rounded up to 16 bytes); a module
        // read from WGSL text (`bench --reference`) spans the struct without that padding.
        let size = size as usize;
        if bytes.len() < size || bytes.len() > size.next_multiple_of(16) {
            return Err(format!(
                "internal error: the module reads {size} bytes of scene parameters, and {} were set (Gpu::set_params)",
                bytes.len()
            ));
        }
        let buffer = self.device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("params"),
            size: bytes.len() as u64,
            usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        self.queue.write_buffer(&buffer, 0, &bytes);
        Ok(Some((buffer, binding)))
    }

    /// The backend in use, as a word.
    pub fn backend(&self) -> String {
        format!("{:?}", self.info.backend).to_lowercase()
    }

    /// Whether frames are timed with GPU timestamp queries.
    pub fn timestamps(&self) -> bool {
        self.features.contains(wgpu::Features::TIMESTAMP_QUERY)
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
        progress: impl FnMut(u32, u32),
    ) -> Result<Frame, String> {
        let mut out = None;
        self.render_samples(module, view, passes, &[view.jitter], progress, |f| {
            out = Some(f);
            Ok(())
        })?;
        Ok(out.expect("one frame"))
    }

    /// [`Gpu::render`] once per point of `jitters` (where in its pixel each frame's ray
    /// passes, `View::jitter`), the module prepared once; each frame is handed to `each` as
    /// it is read back, so that memory does not grow with the number of samples. `progress`
    /// counts the tiles of all frames.
    pub fn render_samples(
        &self,
        module: &naga::Module,
        view: &View,
        passes: Option<&[Pass]>,
        jitters: &[[f64; 2]],
        progress: impl FnMut(u32, u32),
        mut each: impl FnMut(Frame) -> Result<(), String>,
    ) -> Result<(), String> {
        let current = lock(&self.params).clone();
        self.render_sequence(
            module,
            (view, passes),
            jitters,
            &[current],
            progress,
            |_, f| each(f),
        )
    }

    /// [`Gpu::render_samples`] for each of `settings` (the `Params` uniform's bytes, one per
    /// picture: an animation's frames), the module prepared once; `each` gets the setting's
    /// index with every sample's frame.
    pub fn render_sequence(
        &self,
        module: &naga::Module,
        (view, passes): (&View, Option<&[Pass]>),
        jitters: &[[f64; 2]],
        settings: &[Vec<u8>],
        mut progress: impl FnMut(u32, u32),
        mut each: impl FnMut(usize, Frame) -> Result<(), String>,
    ) -> Result<(), String> {
        let layout = Layout::Full {
            passes: passes.is_some(),
        };
        let prepared = self.prepare(Source::Module(module), layout, view, passes, TILE)?;
        let per_frame = prepared.dispatches();
        let total = per_frame * (jitters.len() * settings.len()) as u32;
        let mut k = 0;
        for (s, bytes) in settings.iter().enumerate() {
            prepared.set_params(bytes);
            for &jitter in jitters {
                prepared.set_jitter(jitter);
                let validation = self.device.push_error_scope(wgpu::ErrorFilter::Validation);
                let before = k * per_frame;
                let seconds = prepared.run_tiles(|done, _| progress(before + done, total))?;
                if let Some(e) = pollster::block_on(validation.pop()) {
                    return Err(format!(
                        "internal error: the GPU rejected the compiled shader: {e}"
                    ));
                }
                each(s, prepared.frame(seconds)?)?;
                k += 1;
            }
        }
        Ok(())
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
        let groups = (rays.len() as u32).div_ceil(sdfc_compiler::layout::RAYS_WORKGROUP);
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
        let groups = (points.len() as u32).div_ceil(sdfc_compiler::layout::FIELD_WORKGROUP);
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
        let params = self.params_buffer(module)?;
        let mut entries = vec![
            wgpu::BindGroupEntry {
                binding: 0,
                resource: input_buf.as_entire_binding(),
            },
            wgpu::BindGroupEntry {
                binding: 1,
                resource: output.as_entire_binding(),
            },
        ];
        if let Some((buffer, binding)) = &params {
            entries.push(wgpu::BindGroupEntry {
                binding: *binding,
                resource: buffer.as_entire_binding(),
            });
        }
        let bind = device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some(input_label),
            layout: &pipeline.get_bind_group_layout(0),
            entries: &entries,
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

    pub(crate) fn pipeline(&self, module: &naga::Module) -> wgpu::ComputePipeline {
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

    /// A storage buffer the shader writes and the host reads back.
    pub(crate) fn storage(&self, label: &str, size: u64) -> wgpu::Buffer {
        self.device.create_buffer(&wgpu::BufferDescriptor {
            label: Some(label),
            size,
            usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_SRC,
            mapped_at_creation: false,
        })
    }

    /// Waits for the queue, then reports any error or loss the device had meanwhile.
    pub(crate) fn wait(&self) -> Result<(), String> {
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

    pub(crate) fn read(&self, buffer: &wgpu::Buffer, size: u64) -> Result<Vec<u8>, String> {
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

fn lock<T>(m: &Mutex<T>) -> std::sync::MutexGuard<'_, T> {
    m.lock().unwrap_or_else(|e| e.into_inner())
}
