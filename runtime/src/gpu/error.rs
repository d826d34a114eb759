//! What can go wrong on the GPU, one variant per cause, so that a caller can tell a lost
//! device from memory running out from a module the driver rejects; each variant's message
//! (its `Display`) is the one the command line prints.

use super::BackendChoice;

/// An error of the wgpu runtime.
#[derive(Debug, thiserror::Error)]
pub enum Error {
    /// No adapter on the backends asked for.
    #[error("{}", no_adapter(*.0))]
    NoAdapter(BackendChoice),
    /// No adapter can present to the window.
    #[error(
        "no GPU adapter can draw to this window (tried Vulkan and GL).\nhelp: `apt-get install mesa-vulkan-drivers` gives lavapipe"
    )]
    NoWindowAdapter,
    /// The adapter would not open a device.
    #[error("the GPU adapter refused a device: {0}")]
    DeviceRefused(String),
    /// The device was lost (its reason and the driver's message).
    #[error("the GPU device was lost ({0})")]
    Lost(String),
    /// Waiting for the queue failed (the device lost or timed out).
    #[error("the GPU device was lost or timed out: {0}")]
    Poll(String),
    /// An error the device reported outside an error scope.
    #[error("the GPU reported an error: {0}")]
    Uncaptured(String),
    /// The device ran out of memory preparing a module.
    #[error("the GPU ran out of memory: {0}")]
    OutOfMemory(String),
    /// An image larger than the device's buffers (or [`super::MAX_SIDE`]) allow.
    #[error(
        "an image of {width}×{height} is too large for this device (at most {max_side} per side and {max_pixels} pixels)"
    )]
    TooLarge {
        /// Asked width.
        width: u32,
        /// Asked height.
        height: u32,
        /// Largest side.
        max_side: u32,
        /// Most pixels.
        max_pixels: u64,
    },
    /// The data form's buffers are larger than the device binds.
    #[error(
        "the scene's data form takes a buffer of {bytes} bytes, and this device binds at most {limit} bytes per buffer\nhelp: each cell keeps every part that can blend in it: fewer cells (`--cells`), smaller blend radii or fewer parts make the buffers smaller, and `--form inline` has none"
    )]
    TapeTooLarge {
        /// The largest buffer's bytes.
        bytes: u64,
        /// The device's limit.
        limit: u64,
    },
    /// The driver rejected a module sdfc compiled (a bug in sdfc).
    #[error("internal error: the GPU rejected the compiled shader: {0}")]
    InvalidModule(String),
    /// The driver rejected a list entry's module (a bug in sdfc).
    #[error("internal error: the GPU rejected the shader: {0}")]
    InvalidListModule(String),
    /// The driver rejected a hand-written WGSL file.
    #[error("error: the GPU rejected `{path}`: {message}")]
    RejectedWgsl {
        /// The file.
        path: String,
        /// What the driver said.
        message: String,
    },
    /// A hand-written WGSL file does not parse: naga's report.
    #[error("{0}")]
    Wgsl(String),
    /// The `Params` bytes set are not the module's.
    #[error(
        "internal error: the module reads {needed} bytes of scene parameters, and {set} were set (Gpu::set_params)"
    )]
    Params {
        /// Bytes the module's struct spans.
        needed: usize,
        /// Bytes set.
        set: usize,
    },
    /// The module reads a baked volume that was not set.
    #[error(
        "internal error: the module reads baked volume {index}, and {set} were set (Gpu::set_volumes)"
    )]
    Volumes {
        /// The volume's index in `Scene::volumes`.
        index: usize,
        /// Volumes set.
        set: usize,
    },
    /// The read-back's completion never came.
    #[error("{0}")]
    ReadBackLost(std::sync::mpsc::RecvError),
    /// Mapping the read-back buffer failed.
    #[error("cannot read the result back from the GPU: {0}")]
    ReadBack(String),
    /// The mapped range could not be had.
    #[error("cannot map the result: {0}")]
    Map(String),
    /// A window's surface refused a frame (a bug in sdfc).
    #[error("internal error: the window's surface refused a frame")]
    SurfaceRefused,
    /// What a caller's frame consumer failed with (`Gpu::render_samples`), as it said it.
    #[error(transparent)]
    Consumer(Box<dyn std::error::Error + Send + Sync>),
}

/// What a frame consumer returns: its own error, handed back as [`Error::Consumer`].
pub type Consumed = Result<(), Box<dyn std::error::Error + Send + Sync>>;

impl Error {
    /// Whether the device is gone: every later use fails too.
    pub fn is_device_lost(&self) -> bool {
        matches!(self, Error::Lost(_) | Error::Poll(_))
    }
}

fn no_adapter(choice: BackendChoice) -> &'static str {
    match choice {
        BackendChoice::Auto => {
            "no GPU adapter was found (tried Vulkan and GL).\n\
     help: on a machine without a GPU, install Mesa's software drivers: \
     `apt-get install mesa-vulkan-drivers` (Vulkan through lavapipe) or \
     `apt-get install libegl1 libegl-mesa0 libgl1-mesa-dri` (GL through llvmpipe)"
        }
        BackendChoice::Vulkan => {
            "no Vulkan adapter was found.\nhelp: `apt-get install mesa-vulkan-drivers` gives lavapipe"
        }
        BackendChoice::Gl => {
            "no GL adapter was found.\nhelp: `apt-get install libegl1 libegl-mesa0 libgl1-mesa-dri` gives llvmpipe over EGL"
        }
    }
}
