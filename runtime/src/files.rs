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
        // (`create`: a link to a file that does not exist yet makes it.)
        let mut f = std::fs::OpenOptions::new()
            .write(true)
            .create(true)
            .truncate(true)
            .open(path)?;
        f.write_all(bytes)?;
        return f.flush();
    }
    let dir = match path.parent() {
        Some(d) if !d.as_os_str().is_empty() => d,
        _ => Path::new("."),
    };
    if !dir.is_dir() {
        // (Said plainly: the temporary file's error would name a path the user never gave.)
        return Err(std::io::Error::new(
            std::io::ErrorKind::NotFound,
            format!("the folder `{}` does not exist", dir.display()),
        ));
    }
    // Created with 0666 less the umask, as any new file; a replaced file keeps its mode.
    #[cfg(unix)]
    let mode = {
        use std::os::unix::fs::PermissionsExt;
        std::fs::Permissions::from_mode(0o666)
    };
    let mut builder = tempfile::Builder::new();
    builder.prefix(".sdfc-").suffix(".partial");
    #[cfg(unix)]
    builder.permissions(mode);
    let mut tmp = builder.tempfile_in(dir)?;
    tmp.write_all(bytes)?;
    tmp.as_file().sync_all()?;
    if let Ok(old) = std::fs::metadata(path) {
        tmp.as_file().set_permissions(old.permissions())?;
    }
    tmp.persist(path).map_err(|e| e.error)?;
    Ok(())
}
