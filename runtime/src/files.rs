//! Writing output files whole: atomically over regular files, straight through to devices,
//! FIFOs and links.

use std::path::Path;

/// Writes `bytes` to `path` so that no reader ever sees a partial file. A regular file (or a
/// new one) is replaced by renaming over it a temporary sibling with a unique name (the
/// `tempfile` crate: two writers of one stem cannot meet), written whole and synced first;
/// anything else — a symbolic link, a FIFO, a device such as `/dev/null` — is written straight
/// through, never replaced, and its errors (`/dev/full`: no space) are reported.
pub fn write_file(path: &Path, bytes: &[u8]) -> std::io::Result<()> {
    use std::io::Write;
    if let Ok(meta) = std::fs::symlink_metadata(path)
        && !meta.file_type().is_file()
    {
        let mut f = std::fs::OpenOptions::new()
            .write(true)
            .truncate(true)
            .open(path)?;
        f.write_all(bytes)?;
        return f.flush();
    }
    let dir = match path.parent() {
        Some(d) if !d.as_os_str().is_empty() => d,
        _ => Path::new("."),
    };
    let mut tmp = tempfile::Builder::new()
        .prefix(".sdfc-")
        .suffix(".partial")
        .tempfile_in(dir)?;
    tmp.write_all(bytes)?;
    tmp.as_file().sync_all()?;
    // The temporary file is private (0600); the result gets the usual permissions, or keeps
    // those of the file it replaces.
    #[cfg(unix)]
    {
        use std::os::unix::fs::PermissionsExt;
        let mode = std::fs::metadata(path).map_or(0o644, |m| m.permissions().mode());
        tmp.as_file()
            .set_permissions(std::fs::Permissions::from_mode(mode))?;
    }
    tmp.persist(path).map_err(|e| e.error)?;
    Ok(())
}
