//! The interface between an emitted module and its host, written once: bindings, buffer
//! element sizes, the `View` uniform's fields and size, workgroup sizes.
//!
//! The lowering declares its globals from these tables and the runtime creates its buffers
//! from them, so the two cannot disagree. Every binding is in group [`GROUP`].

/// The bind group of every resource a module declares.
pub const GROUP: u32 = 0;

/// A storage buffer an entry reads or writes: its global's name, binding and bytes per element.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Buffer {
    /// The global variable's name in the module.
    pub name: &'static str,
    /// Its binding in [`GROUP`].
    pub binding: u32,
    /// Bytes per element (per pixel, ray or point).
    pub stride: u64,
    /// What one element holds.
    pub element: Element,
}

/// The type of a buffer's elements.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Element {
    /// `u32`
    U32,
    /// `f32`
    F32,
    /// `vec2<u32>`
    Vec2U32,
    /// `vec4<f32>`
    Vec4F32,
}

/// The `View` uniform's binding (camera, image size, tile offset, pass).
pub const VIEW_BINDING: u32 = 0;

/// The `View` uniform's fields, each a 16-byte vector: camera basis (right and up pre-scaled by
/// tan(fov/2)·aspect and tan(fov/2)), image size and pixel footprint, the tile's offset and
/// the image size as integers, and (only in a module with multi-resolution passes) the pass:
/// cone slope, step budget and the previous pass's size.
pub const VIEW_FIELDS: [&str; 7] = ["eye", "right", "up", "forward", "size", "offset", "handoff"];

/// The index of the `View` uniform's field `name` (one of [`VIEW_FIELDS`]); its byte offset is
/// 16 times that.
pub fn view_field(name: &str) -> usize {
    VIEW_FIELDS
        .iter()
        .position(|f| *f == name)
        .unwrap_or_else(|| panic!("`{name}` is not a field of the View uniform"))
}

/// Where the fragment entry reads its origin convention: `size.w` (field, component). 0: pixel
/// coordinates with y down, as WebGPU's, Vulkan's, Metal's and Direct3D's `position`; 1: y up,
/// as GL's `gl_FragCoord` (the entry flips y itself). Every other entry ignores it.
pub const FRAGMENT_Y_UP: (&str, usize) = ("size", 3);

/// Where the fragment entry reads its output encoding: `forward.w` (field, component). 0: linear
/// light, for an sRGB render target; 1: clamped to 0…1 and sRGB-encoded, for a plain 8-bit
/// target (a WebGL2 canvas). Every other entry ignores it.
pub const FRAGMENT_SRGB: (&str, usize) = ("forward", 3);

/// The `View` uniform's size in bytes with every field (a module without passes declares the
/// first six, 96 bytes; a host may always bind all of them).
pub const VIEW_BYTES: usize = 16 * VIEW_FIELDS.len();

/// The `Params` uniform's binding, in every module of a scene with parameters (unless
/// `Options::params_binding` moves it).
pub const PARAMS_BINDING: u32 = 9;

/// The first baked volume's binding: a `texture_3d<f32>` of `r32float` texels (`bake`), volume
/// i of `Scene::volumes` at this + i.
pub const VOLUME_BINDING: u32 = 16;

/// The data form's buffers (`crate::tape::data`, `lower/data.rs`), read only: the table of
/// the scene's parts (`array<vec4<u32>>`), the cells' programs (`array<u32>`) and each cell's
/// range in them (`array<vec2<u32>>`).
pub const TAPE_BINDINGS: [u32; 3] = [12, 13, 14];

/// The data form's pre-pass on the GPU (`lower/data/prune.rs`): the table (read only), what
/// the pre-pass knows of each part (`tape::program::Table::meta`, read only), the programs and
/// the ranges (read and written), the level's uniform (`PRUNE_LEVEL_FIELDS`), the counter
/// (`PRUNE_COUNTER_FIELDS`, atomic u32s) and the cells' scratch (u32s).
pub const PRUNE_BINDINGS: [u32; 7] = [0, 1, 2, 3, 4, 5, 6];

/// The pre-pass's level uniform, in order, with byte offsets: the grid's lowest corner
/// (vec3<f32>), cells' edge (f32), cells along x, y, z (vec3<u32>), their count, the coarser
/// grid's cells along x, y, z (vec3<u32>), fine cells a side of a coarse one
/// (`tape::cells::SPLIT`, or more than the grid has for the coarsest level, whose parent is the
/// whole program), the ranges' entry of the coarser grid's first cell, that of this grid's
/// first cell, the words the programs buffer holds, the scene's size for f32's margin (f32), 1
/// where the cells' leaves are counted, the words of the scratch, and the first cell of this
/// dispatch (a grid is pruned in several, the scratch emptied between them).
pub const PRUNE_LEVEL_FIELDS: [(&str, u32); 13] = [
    ("lo", 0),
    ("size", 12),
    ("n", 16),
    ("total", 28),
    ("up", 32),
    ("split", 44),
    ("in_base", 48),
    ("out_base", 52),
    ("capacity", 56),
    ("scale", 60),
    ("count_leaves", 64),
    ("scratch_capacity", 68),
    ("first_cell", 72),
];

/// The pre-pass's level uniform's size in bytes.
pub const PRUNE_LEVEL_BYTES: u32 = 80;

/// The pre-pass's counter: the next free word of the programs buffer, how many cells found no
/// room, the leaves the counted cells' programs evaluate, and the next free word of the
/// scratch.
pub const PRUNE_COUNTER_FIELDS: [&str; 4] = ["next", "overflow", "leaves", "scratch"];

/// What the counter's overflow adds for a cell that found no room in the scratch (1 where the
/// programs' buffer had none).
pub const PRUNE_SCRATCH_MISSED: u32 = 1 << 16;

/// Cells a workgroup of the pre-pass prunes.
pub const PRUNE_WORKGROUP: u32 = 64;

/// Most baked volumes a scene may have: each is a texture every entry reads (WebGPU promises
/// 16 sampled textures per shader stage).
pub const MAX_VOLUMES: usize = 8;

/// The full compute entry's outputs, per pixel, in binding order: colour (rgba8 packed), depth
/// t (−1 for a miss), normal, material id, steps (the camera ray's evaluations of the field)
/// and the evaluations shading took.
pub const PIXEL_OUTPUTS: [Buffer; 6] = [
    Buffer {
        name: "out_color",
        binding: 1,
        stride: 4,
        element: Element::U32,
    },
    Buffer {
        name: "out_depth",
        binding: 2,
        stride: 4,
        element: Element::F32,
    },
    Buffer {
        name: "out_normal",
        binding: 3,
        stride: 16,
        element: Element::Vec4F32,
    },
    Buffer {
        name: "out_material",
        binding: 4,
        stride: 4,
        element: Element::U32,
    },
    Buffer {
        name: "out_steps",
        binding: 5,
        stride: 4,
        element: Element::U32,
    },
    Buffer {
        name: "out_shading",
        binding: 8,
        stride: 4,
        element: Element::U32,
    },
];

/// The trace-only entry's output: `vec2<u32>(bitcast(t), steps | hit << 31)` per pixel.
pub const TRACE_OUTPUT: Buffer = Buffer {
    name: "out",
    binding: 1,
    stride: 8,
    element: Element::Vec2U32,
};

/// With multi-resolution passes: the buffer a pass reads its rays' start from, and the one it
/// hands its (t, steps) to; the host swaps them between passes.
pub const HAND_OVER: [Buffer; 2] = [
    Buffer {
        name: "pass_in",
        binding: 6,
        stride: 8,
        element: Element::Vec2U32,
    },
    Buffer {
        name: "pass_out",
        binding: 7,
        stride: 8,
        element: Element::Vec2U32,
    },
];

/// The ray-list and field-list entries' input (rays or points) and output, one `vec4<f32>`
/// each; the names are the entry's own (`rays`/`hits`, `points`/`values`).
pub const LIST_BINDINGS: [u32; 2] = [0, 1];

/// Bytes per element of a list entry's input and output.
pub const LIST_STRIDE: u64 = 16;

/// Workgroup size of the camera compute entries (8×8).
pub const WORKGROUP: u32 = 8;

/// Workgroup size of the ray-list entry.
pub const RAYS_WORKGROUP: u32 = 64;

/// Workgroup size of the field-list entry.
pub const FIELD_WORKGROUP: u32 = 64;
