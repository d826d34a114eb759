//! The wgpu runtime: a headless device (Vulkan, then GL), a compiled compute module prepared
//! once and dispatched frame after frame (`prepare`, `dispatch`, `readback`), a render of it
//! (`render`), and the one-dispatch list entries of the tests (`lists`).

use sdfc_compiler::layout::GROUP;
use std::borrow::Cow;
use std::sync::{Arc, Mutex};

pub mod cache;
mod dispatch;
mod error;
mod lists;
mod open;
mod prepare;
mod prune;
mod readback;
mod render;
mod tape;
mod volumes;

pub use dispatch::Timing;
pub use error::{Consumed, Error};
pub use lists::ListProgram;
pub use prepare::{Layout, MAX_SIDE, Prepared, Source, TILE};
pub use prune::{Pruned, Pruner};
pub use readback::{Frame, Ray};

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

/// A device and its queue: shared handles, so that a clone is the same device (a prepared
/// module keeps one).
#[derive(Clone)]
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
    /// The pipeline cache on disk, where the backend has one.
    cache: Option<Arc<cache::DiskCache>>,
    /// The bytes of the `Params` uniform the next prepared modules start with
    /// ([`Gpu::set_params`]).
    params: Arc<Mutex<Vec<u8>>>,
    /// The baked volumes the next prepared modules read, each uploaded once
    /// ([`Gpu::set_volumes`]).
    volumes: Arc<Mutex<Vec<volumes::OnDevice>>>,
    /// The data form's parts, programs and ranges the next prepared modules read
    /// ([`Gpu::set_tape`]).
    tape: Arc<Mutex<Option<[wgpu::Buffer; 3]>>>,
    /// Compute pipelines made on this device: each is a shader the driver compiles.
    pipelines: Arc<std::sync::atomic::AtomicU32>,
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

    /// The device (to build pipelines of one's own: the viewer's presentation).
    pub fn device(&self) -> &wgpu::Device {
        &self.device
    }

    /// The device's queue.
    pub fn queue(&self) -> &wgpu::Queue {
        &self.queue
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
    ) -> Result<Option<(wgpu::Buffer, u32)>, Error> {
        let binding = sdfc_compiler::layout::PARAMS_BINDING;
        let Some(global) = module.global_variables.iter().find(|(_, g)| {
            g.binding
                == Some(naga::ResourceBinding {
                    group: GROUP,
                    binding,
                })
        }) else {
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
            return Err(Error::Params {
                needed: size,
                set: bytes.len(),
            });
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

    /// Compute pipelines made on this device so far (shaders the driver compiled; `view`'s
    /// scripted orbit says it, to show that new parameter values compile nothing).
    pub fn pipelines_made(&self) -> u32 {
        self.pipelines.load(std::sync::atomic::Ordering::Relaxed)
    }

    /// The compute pipeline of a compiled module (the driver compiles it here), through the
    /// pipeline cache where there is one.
    pub(crate) fn pipeline(&self, module: &naga::Module) -> wgpu::ComputePipeline {
        self.pipelines
            .fetch_add(1, std::sync::atomic::Ordering::Relaxed);
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
                cache: self.cache.as_ref().map(|c| &c.cache),
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
    pub(crate) fn wait(&self) -> Result<(), Error> {
        self.device
            .poll(wgpu::PollType::wait_indefinitely())
            .map_err(|e| Error::Poll(e.to_string()))?;
        let mut trouble = lock(&self.trouble);
        let error = trouble.error.take();
        match (&trouble.lost, error) {
            (Some(lost), _) => Err(Error::Lost(lost.clone())),
            (None, Some(error)) => Err(Error::Uncaptured(error)),
            (None, None) => Ok(()),
        }
    }

    /// Destroys the device as a driver reset would lose it, so that tests can show a render
    /// that loses its device midway ending with an error. The `Gpu` is unusable afterwards.
    pub fn lose_device(&self) {
        self.device.destroy();
    }

    pub(crate) fn read(&self, buffer: &wgpu::Buffer, size: u64) -> Result<Vec<u8>, Error> {
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
            .map_err(Error::ReadBackLost)?
            .map_err(|e| Error::ReadBack(e.to_string()))?;
        let data = slice
            .get_mapped_range()
            .map_err(|e| Error::Map(format!("{e:?}")))?
            .to_vec();
        staging.unmap();
        Ok(data)
    }
}

/// What went wrong on the device outside an error scope: the first of each kind (later ones
/// are usually its consequences).
#[derive(Default)]
struct Trouble {
    /// The device's loss (its reason and message): every later wait fails with it.
    lost: Option<String>,
    /// An uncaptured error's message: reported by the next wait, then forgotten.
    error: Option<String>,
}

fn lock<T>(m: &Mutex<T>) -> std::sync::MutexGuard<'_, T> {
    m.lock().unwrap_or_else(|e| e.into_inner())
}
