//! Opening the device: the first backend with an adapter (headless, or able to present to a
//! window), and the error and loss handlers every command relies on.

use super::{BackendChoice, Error, Gpu, Trouble, lock};
use std::sync::{Arc, Mutex};

impl Gpu {
    /// Opens a device on the first backend that has an adapter.
    pub fn new(choice: BackendChoice) -> Result<Gpu, Error> {
        for backends in order(choice) {
            let mut desc = wgpu::InstanceDescriptor::new_without_display_handle();
            desc.backends = backends;
            let instance = wgpu::Instance::new(desc);
            if let Some(adapter) = adapter(&instance, None) {
                return Gpu::open(&adapter);
            }
        }
        Err(Error::NoAdapter(choice))
    }

    /// Opens a device that can present to `window` (`sdfc view`), on the first backend with
    /// an adapter for it; the surface comes with it, not yet configured.
    pub fn for_window<W>(
        choice: BackendChoice,
        window: Arc<W>,
    ) -> Result<(Gpu, wgpu::Surface<'static>), Error>
    where
        W: wgpu::WindowHandle + wgpu::rwh::HasDisplayHandle + std::fmt::Debug + 'static,
    {
        for backends in order(choice) {
            let mut desc =
                wgpu::InstanceDescriptor::new_with_display_handle(Box::new(window.clone()));
            desc.backends = backends;
            let instance = wgpu::Instance::new(desc);
            let Ok(surface) = instance.create_surface(window.clone()) else {
                continue;
            };
            // (A device that refuses to open is another reason to try the next backend.)
            if let Some(adapter) = adapter(&instance, Some(&surface))
                && let Ok(gpu) = Gpu::open(&adapter)
            {
                return Ok((gpu, surface));
            }
        }
        Err(Error::NoWindowAdapter)
    }

    /// A device on `adapter`, with the error and loss handlers every command relies on.
    fn open(adapter: &wgpu::Adapter) -> Result<Gpu, Error> {
        let limits = adapter.limits();
        // Timestamps where the adapter has them: `bench` times frames on the GPU with them.
        // The pipeline cache where the backend has one (`cache`).
        let features = adapter.features()
            & (wgpu::Features::TIMESTAMP_QUERY
                | wgpu::Features::SUBGROUP
                | wgpu::Features::PIPELINE_CACHE);
        let desc = wgpu::DeviceDescriptor {
            label: Some("sdfc"),
            required_limits: limits.clone(),
            required_features: features,
            ..Default::default()
        };
        let (device, queue) = pollster::block_on(adapter.request_device(&desc))
            .map_err(|e| Error::DeviceRefused(e.to_string()))?;
        // wgpu's default for an error outside a scope is a panic; keep the first instead.
        let trouble = Arc::new(Mutex::new(Trouble::default()));
        let keep = trouble.clone();
        device.on_uncaptured_error(Arc::new(move |e: wgpu::Error| {
            lock(&keep).error.get_or_insert(e.to_string());
        }));
        let keep = trouble.clone();
        device.set_device_lost_callback(move |reason, message| {
            let why = match message.is_empty() {
                true => format!("{reason:?}"),
                false => format!("{reason:?}: {message}"),
            };
            lock(&keep).lost.get_or_insert(why);
        });
        let info = adapter.get_info();
        let cache = features
            .contains(wgpu::Features::PIPELINE_CACHE)
            .then(|| super::cache::DiskCache::open(&device, &info))
            .flatten()
            .map(Arc::new);
        Ok(Gpu {
            cache,
            device,
            queue,
            info,
            limits,
            features,
            trouble,
            params: Arc::default(),
            volumes: Arc::default(),
            tape: Arc::default(),
            pipelines: Arc::default(),
            adapter: adapter.clone(),
        })
    }
}

/// The backends to try, in order.
fn order(choice: BackendChoice) -> Vec<wgpu::Backends> {
    match choice {
        BackendChoice::Auto => vec![wgpu::Backends::VULKAN, wgpu::Backends::GL],
        BackendChoice::Vulkan => vec![wgpu::Backends::VULKAN],
        BackendChoice::Gl => vec![wgpu::Backends::GL],
    }
}

/// The instance's adapter (one that can present to `surface` if given).
fn adapter(instance: &wgpu::Instance, surface: Option<&wgpu::Surface>) -> Option<wgpu::Adapter> {
    let options = wgpu::RequestAdapterOptions {
        power_preference: wgpu::PowerPreference::HighPerformance,
        force_fallback_adapter: false,
        compatible_surface: surface,
        ..Default::default()
    };
    pollster::block_on(instance.request_adapter(&options)).ok()
}
