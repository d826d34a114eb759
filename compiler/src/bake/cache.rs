//! Baked volumes kept while a part's content and resolution do not change: in memory for the
//! process (the viewer recompiles on every edit), and in a store the host may provide (the
//! command line's cache directory), so that editing other parts does not bake again.

use super::Volume;
use std::sync::{Arc, Mutex, RwLock};

/// Where volumes outlive the process, keyed as [`get_or_bake`] keys them.
pub trait Store: Send + Sync {
    /// The volume saved under `key`, if any (and readable).
    fn load(&self, key: u64) -> Option<Volume>;
    /// Saves a volume under `key` (failures are the store's to report or ignore: the volume is
    /// in memory either way).
    fn save(&self, key: u64, volume: &Volume);
}

/// Most bytes of values kept in memory; the least recently used go first past it.
pub const MEMORY_BYTES: u64 = 1 << 30;

/// A volume in memory: its key, itself, and the seconds its bake took (`None`: read from the
/// store).
type Entry = (u64, Arc<Volume>, Option<f64>);

/// Volumes in memory, most recently used last.
static MEMORY: Mutex<Vec<Entry>> = Mutex::new(Vec::new());

/// The host's store, if it set one.
static STORE: RwLock<Option<Box<dyn Store>>> = RwLock::new(None);

/// Sets (or clears) the store volumes are also looked up in and saved to.
pub fn set_store(store: Option<Box<dyn Store>>) {
    *STORE.write().unwrap_or_else(|e| e.into_inner()) = store;
}

/// Where [`get_or_bake`] found a volume.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Origin {
    /// Baked now.
    Baked,
    /// Kept in memory from an earlier compile in this process.
    Memory,
    /// Read from the host's store.
    Store,
}

/// The volume under `key` from memory or the store, else `make()`'s, kept for next time; one
/// found that is not `fits` (another grid under the same key) is baked again and replaced.
pub fn get_or_bake(
    key: u64,
    fits: impl Fn(&Volume) -> bool,
    make: impl FnOnce() -> Volume,
) -> (Arc<Volume>, Origin) {
    {
        let mut memory = MEMORY.lock().unwrap_or_else(|e| e.into_inner());
        if let Some(at) = memory.iter().position(|(k, _, _)| *k == key) {
            let entry = memory.remove(at);
            if fits(&entry.1) {
                let v = entry.1.clone();
                memory.push(entry);
                return (v, Origin::Memory);
            }
        }
    }
    let store = STORE.read().unwrap_or_else(|e| e.into_inner());
    let stored = store.as_ref().and_then(|s| s.load(key)).filter(|v| fits(v));
    let (volume, origin, seconds) = match stored {
        Some(v) => (Arc::new(v), Origin::Store, None),
        None => {
            let (v, seconds) = timed(make);
            if let Some(s) = store.as_ref() {
                s.save(key, &v);
            }
            (Arc::new(v), Origin::Baked, seconds)
        }
    };
    drop(store);
    let mut memory = MEMORY.lock().unwrap_or_else(|e| e.into_inner());
    memory.push((key, volume.clone(), seconds));
    let mut total: u64 = memory.iter().map(|(_, v, _)| v.bytes()).sum();
    while total > MEMORY_BYTES && memory.len() > 1 {
        total -= memory.remove(0).1.bytes();
    }
    (volume, origin)
}

/// The wall-clock seconds `volume` took to bake in this process (sampling, distance transform
/// and λ), while it is in memory; `None` if it was read from the store or is no longer kept.
pub fn bake_seconds(volume: &Arc<Volume>) -> Option<f64> {
    let memory = MEMORY.lock().unwrap_or_else(|e| e.into_inner());
    memory
        .iter()
        .find(|(_, v, _)| Arc::ptr_eq(v, volume))
        .and_then(|(_, _, s)| *s)
}

/// `make()` and the seconds it took, where there is a clock (WebAssembly in a page has none:
/// `Instant::now` panics there).
fn timed<T>(make: impl FnOnce() -> T) -> (T, Option<f64>) {
    if cfg!(target_arch = "wasm32") {
        return (make(), None);
    }
    let clock = std::time::Instant::now();
    let v = make();
    (v, Some(clock.elapsed().as_secs_f64()))
}
