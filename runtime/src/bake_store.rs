//! Baked volumes kept on disk between runs: the compiler's cache store (`bake::cache::Store`)
//! in the cache folder's `volumes/`, so that rendering a scene again does not bake it again.

use sdfc_compiler::bake::{Volume, cache::Store, file};
use std::path::PathBuf;

/// Most bytes the store keeps: past this, the least recently written files go first.
pub const MAX_BYTES: u64 = 4 << 30;

/// Volumes as files named by their key, each a header that says its grid and its values
/// (`bake::file::with_header`), written whole or not at all.
pub struct DiskStore {
    dir: PathBuf,
}

impl DiskStore {
    /// The store in the cache folder (`gpu::cache::folder`: `$SDFC_CACHE_DIR`, …), if there is
    /// one.
    pub fn open() -> Option<DiskStore> {
        Some(DiskStore {
            dir: crate::gpu::cache::folder()?.join("volumes"),
        })
    }

    fn path(&self, key: u64) -> PathBuf {
        self.dir.join(format!("{key:016x}.sdfcvol"))
    }

    /// Removes the oldest files while the folder holds more than [`MAX_BYTES`].
    fn trim(&self) {
        let Ok(entries) = std::fs::read_dir(&self.dir) else {
            return;
        };
        let mut files: Vec<(std::time::SystemTime, u64, PathBuf)> = entries
            .flatten()
            .filter_map(|e| {
                let m = e.metadata().ok().filter(|m| m.is_file())?;
                Some((m.modified().ok()?, m.len(), e.path()))
            })
            .collect();
        files.sort();
        let mut total: u64 = files.iter().map(|f| f.1).sum();
        for (_, len, path) in files {
            if total <= MAX_BYTES {
                break;
            }
            if std::fs::remove_file(&path).is_ok() {
                total -= len;
            }
        }
    }
}

impl Store for DiskStore {
    fn load(&self, key: u64) -> Option<Volume> {
        let path = self.path(key);
        let meta = std::fs::metadata(&path).ok().filter(|m| m.is_file())?;
        if meta.len() > MAX_BYTES {
            return None;
        }
        file::from_header(&std::fs::read(&path).ok()?)
    }

    fn save(&self, key: u64, volume: &Volume) {
        let written = std::fs::create_dir_all(&self.dir)
            .and_then(|()| crate::files::write_file(&self.path(key), &file::with_header(volume)));
        match written {
            Ok(()) => self.trim(),
            // Said, not fatal: the volume is in memory for this run either way.
            Err(e) => eprintln!(
                "warning: cannot keep the baked volume in `{}`: {e}",
                self.dir.display()
            ),
        }
    }
}
