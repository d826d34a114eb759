//! The command line's error: a bad argument or input, diagnostics already printed, a bug in
//! the compiler, or what the runtime's layers (GPU, pictures, benchmark) failed with. Its
//! message (`Display`) is what the user sees.

use std::path::PathBuf;

/// Why a command failed.
#[derive(Debug, thiserror::Error)]
pub enum Error {
    /// A bad argument, flag or input file: the whole message (`error: …`).
    #[error("{0}")]
    Usage(String),
    /// The scene's diagnostics (or the error) were printed already.
    #[error("")]
    Reported,
    /// The compiler failed on a scene that checked: a bug in sdfc.
    #[error("internal compiler error: {0}")]
    Compiler(String),
    /// A file could not be written.
    #[error("error: cannot write `{}`: {source}", path.display())]
    Write {
        /// The file.
        path: PathBuf,
        /// The I/O error.
        source: std::io::Error,
    },
    /// The GPU failed.
    #[error(transparent)]
    Gpu(#[from] sdfc::gpu::Error),
    /// A picture could not be encoded.
    #[error(transparent)]
    Image(#[from] sdfc::images::Error),
    /// A benchmark cell could not be measured.
    #[error(transparent)]
    Bench(#[from] sdfc::bench::Error),
    /// The benchmark's plot could not be written.
    #[error(transparent)]
    Plot(#[from] sdfc::bench::plot::PlotError),
}

impl From<String> for Error {
    fn from(message: String) -> Error {
        Error::Usage(message)
    }
}

impl From<&str> for Error {
    fn from(message: &str) -> Error {
        Error::Usage(message.to_string())
    }
}

/// Writes a whole file (`sdfc::files::write_file`), the error naming it.
pub fn write_file(path: &std::path::Path, bytes: &[u8]) -> Result<(), Error> {
    sdfc::files::write_file(path, bytes).map_err(|source| Error::Write {
        path: path.to_path_buf(),
        source,
    })
}
