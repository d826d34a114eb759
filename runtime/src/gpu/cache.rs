//! The pipeline cache on disk: what the driver compiled, kept between runs where wgpu's
//! backend has a cache (Vulkan), so that a scene rendered again skips the driver's compile.

use std::path::PathBuf;

/// The environment variable that moves the cache (`off` or empty: no cache).
const CACHE_ENV: &str = "SDFC_CACHE_DIR";

/// Largest cache file read back or written: the cache grows with every new shader compiled,
/// and past this it is dropped to start again (a larger file is ignored).
const MAX_BYTES: u64 = 256 << 20;

/// The folder the cache lives in: `$SDFC_CACHE_DIR`, else `$XDG_CACHE_HOME/sdfc`, else
/// `$HOME/.cache/sdfc`; `None` when `SDFC_CACHE_DIR` is `off` or empty, or no folder is known.
pub fn folder() -> Option<PathBuf> {
    if let Some(dir) = std::env::var_os(CACHE_ENV) {
        return (!dir.is_empty() && dir != "off").then(|| PathBuf::from(dir));
    }
    let base = match std::env::var_os("XDG_CACHE_HOME") {
        Some(d) if !d.is_empty() => PathBuf::from(d),
        _ => PathBuf::from(std::env::var_os("HOME")?).join(".cache"),
    };
    Some(base.join("sdfc"))
}

/// An open cache and the file it is saved to when dropped (by the last clone of the device
/// that holds it: at the end of a command).
pub(crate) struct DiskCache {
    pub(crate) cache: wgpu::PipelineCache,
    file: PathBuf,
}

impl DiskCache {
    /// The cache for `device` (which has `Features::PIPELINE_CACHE`), started from its file if
    /// one was saved for this adapter; `None` where there is no folder or no key for the
    /// backend.
    pub(crate) fn open(device: &wgpu::Device, info: &wgpu::AdapterInfo) -> Option<DiskCache> {
        let key = wgpu::util::pipeline_cache_key(info)?;
        let file = folder()?.join(format!("{key}.bin"));
        let data = std::fs::metadata(&file)
            .ok()
            .filter(|m| m.is_file() && m.len() <= MAX_BYTES)
            .and_then(|_| std::fs::read(&file).ok());
        // SAFETY: the data is only ever what `PipelineCache::get_data` gave for this key
        // (written whole by `save`, atomically); wgpu and the driver check its header against
        // the adapter and driver version, and `fallback` starts an empty cache when they do
        // not match.
        let cache = unsafe {
            device.create_pipeline_cache(&wgpu::PipelineCacheDescriptor {
                label: Some("sdfc"),
                data: data.as_deref(),
                fallback: true,
            })
        };
        Some(DiskCache { cache, file })
    }

    /// Saves the cache's data, creating the folder; a failure is only said (the render does
    /// not depend on it).
    fn save(&self) {
        let Some(data) = self.cache.get_data() else {
            return;
        };
        if data.len() as u64 > MAX_BYTES {
            let _ = std::fs::remove_file(&self.file);
            return;
        }
        let written = self
            .file
            .parent()
            .map_or(Ok(()), std::fs::create_dir_all)
            .and_then(|()| crate::files::write_file(&self.file, &data));
        if let Err(e) = written {
            eprintln!(
                "warning: cannot save the pipeline cache `{}`: {e}",
                self.file.display()
            );
        }
    }
}

impl Drop for DiskCache {
    fn drop(&mut self) {
        self.save();
    }
}
