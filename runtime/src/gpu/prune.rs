//! The data form's pre-pass on the device (issue 33 §2): the compiler's pruning entry
//! (`lower::prune`) run grid by grid, coarsest first, each cell's program written into the
//! buffers the tracer then reads — nothing comes back to the host but a counter. The CPU's
//! `tape::data::data` is the reference it is tested against (`tests/prepass.rs`).

use super::{Error, Gpu, lock};
use sdfc_compiler::layout::{PRUNE_BINDINGS, PRUNE_SCRATCH_MISSED, PRUNE_WORKGROUP};
use sdfc_compiler::scene::Scene;
use sdfc_compiler::tape::data::HEADER;
use sdfc_compiler::tape::seed::{CHUNK, ROOM_PER_CELL, SCRATCH_PER_CELL, Seed};
use wgpu::util::DeviceExt;

/// The pre-pass's pipeline for a scene, compiled once for every new set of parameters.
pub struct Pruner {
    pipeline: wgpu::ComputePipeline,
    /// How many folds deep its arrays hold.
    height: usize,
}

/// What a pre-pass on the device made.
#[derive(Clone, Copy, Debug)]
pub struct Pruned {
    /// The grid's cells.
    pub cells: usize,
    /// The mean leaves a cell's program evaluates.
    pub mean_leaves: f64,
    /// The bytes of the three buffers the tracer reads (the programs' as used, not as held).
    pub bytes: usize,
    /// How many times the pass ran again with a larger programs' buffer or scratch.
    pub retries: u32,
}

/// The fewest cells a dispatch prunes (where the scratch runs out, fewer than `seed::CHUNK`).
const FEWEST: usize = 1024;

impl Gpu {
    /// The pre-pass's pipeline for `scene` compiled at its defaults; none where the scene has
    /// no data form.
    pub fn pruner(&self, scene: &Scene) -> Result<Option<Pruner>, Error> {
        let made =
            sdfc_compiler::emit::prune_module(scene).map_err(|e| Error::InvalidModule(e.0))?;
        Ok(made.map(|(module, _, height)| Pruner {
            pipeline: self.pipeline(&module),
            height,
        }))
    }

    /// Prunes `seed`'s grid on the device and sets the buffers the modules prepared from now on
    /// read, as [`Gpu::set_tape`] does with buffers made on the CPU. None where the device
    /// cannot hold the programs (or the tree nests deeper than `pruner` holds): make them on
    /// the CPU then.
    pub fn prune(&self, pruner: &Pruner, seed: &Seed) -> Result<Option<Pruned>, Error> {
        if seed.height > pruner.height {
            return Ok(None);
        }
        let limit = self
            .limits
            .max_storage_buffer_binding_size
            .min(self.limits.max_buffer_size)
            / 4;
        let table = seed.nodes.len() as u64 * 16;
        if table > limit * 4 {
            return Err(Error::TapeTooLarge {
                bytes: table,
                limit: limit * 4,
            });
        }
        let cells: u64 = seed.levels.iter().map(|(n, _)| cells_of(*n) as u64).sum();
        let mut room = Room {
            code: (seed.code.len() as u64 + ROOM_PER_CELL * cells).min(limit),
            scratch: (CHUNK as u64 * SCRATCH_PER_CELL).min(limit),
            chunk: CHUNK,
        };
        let mut retries = 0;
        loop {
            let run = self.run_levels(pruner, seed, room)?;
            let (scratch, code) = (
                run.overflow / PRUNE_SCRATCH_MISSED,
                run.overflow % PRUNE_SCRATCH_MISSED,
            );
            if scratch == 0 && code == 0 {
                let (nodes, code, ranges) = run.buffers;
                let bytes = seed.nodes.len() * 16 + run.used as usize * 4 + ranges_bytes(seed);
                *lock(&self.tape) = Some([nodes, code, ranges]);
                return Ok(Some(Pruned {
                    cells: seed.cells(),
                    mean_leaves: run.leaves as f64 / seed.cells().max(1) as f64,
                    bytes,
                    retries,
                }));
            }
            let stuck = (code > 0 && room.code >= limit)
                || (scratch > 0 && room.scratch >= limit && room.chunk <= FEWEST);
            if stuck {
                return Ok(None);
            }
            if code > 0 {
                // The counter took what every cell asked for, those that found no room too.
                room.code = (run.used.max(room.code) * 2).min(limit);
            }
            if scratch > 0 {
                // Fewer cells a dispatch share the scratch, and a larger one.
                room.chunk = (room.chunk / 4).max(FEWEST);
                room.scratch = (room.scratch * 2).min(limit);
            }
            retries += 1;
        }
    }

    /// One pre-pass with the room `room` gives.
    fn run_levels(&self, pruner: &Pruner, seed: &Seed, room: Room) -> Result<Run, Error> {
        let device = &self.device;
        let storage = |label: &str, words: &[u32], extra: wgpu::BufferUsages| {
            let mut bytes: Vec<u8> = words.iter().flat_map(|w| w.to_le_bytes()).collect();
            bytes.resize(bytes.len().max(16), 0);
            device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
                label: Some(label),
                contents: &bytes,
                usage: wgpu::BufferUsages::STORAGE | extra,
            })
        };
        let empty = |label: &str, words: u64, usage: wgpu::BufferUsages| {
            device.create_buffer(&wgpu::BufferDescriptor {
                label: Some(label),
                size: words.max(4) * 4,
                usage: wgpu::BufferUsages::STORAGE | usage,
                mapped_at_creation: false,
            })
        };
        let flat = |v: &[[u32; 4]]| v.iter().flatten().copied().collect::<Vec<u32>>();
        let copy = wgpu::BufferUsages::COPY_SRC;
        let nodes = storage("tape nodes", &flat(&seed.nodes), copy);
        let meta = storage("tape meta", &flat(&seed.meta), copy);
        let code = empty("tape code", room.code, wgpu::BufferUsages::COPY_DST | copy);
        self.queue.write_buffer(&code, 0, &le_bytes(&seed.code));
        let scratch = empty("prune scratch", room.scratch, wgpu::BufferUsages::empty());
        let (ranges_words, bases) = seed.ranges();
        let ranges = storage("tape ranges", &ranges_words, copy);
        let start = [seed.code.len() as u32, 0, 0, 0];
        let counter = storage("prune counter", &start, copy | wgpu::BufferUsages::COPY_DST);
        let layout = pruner
            .pipeline
            .get_bind_group_layout(sdfc_compiler::layout::GROUP);
        let validation = device.push_error_scope(wgpu::ErrorFilter::Validation);
        let mut enc = device.create_command_encoder(&Default::default());
        for l in 0..seed.levels.len() {
            let total = cells_of(seed.levels[l].0);
            for first in (0..total).step_by(room.chunk) {
                let uniform = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
                    label: Some("prune level"),
                    contents: &le_bytes(&seed.level_words(
                        l,
                        &bases,
                        (room.code as u32, room.scratch as u32, first as u32),
                    )),
                    usage: wgpu::BufferUsages::UNIFORM,
                });
                let buffers = [&nodes, &meta, &code, &ranges, &uniform, &counter, &scratch];
                let entries: Vec<wgpu::BindGroupEntry> = PRUNE_BINDINGS
                    .iter()
                    .zip(buffers)
                    .map(|(&binding, b)| wgpu::BindGroupEntry {
                        binding,
                        resource: b.as_entire_binding(),
                    })
                    .collect();
                let bind = device.create_bind_group(&wgpu::BindGroupDescriptor {
                    label: Some("prune"),
                    layout: &layout,
                    entries: &entries,
                });
                let cells = room.chunk.min(total - first) as u32;
                let mut pass = enc.begin_compute_pass(&Default::default());
                pass.set_pipeline(&pruner.pipeline);
                pass.set_bind_group(sdfc_compiler::layout::GROUP, &bind, &[]);
                pass.dispatch_workgroups(cells.div_ceil(PRUNE_WORKGROUP), 1, 1);
                drop(pass);
                // The scratch is empty again for the next dispatch.
                enc.clear_buffer(&counter, 12, Some(4));
            }
        }
        self.queue.submit([enc.finish()]);
        self.wait()?;
        if let Some(e) = pollster::block_on(validation.pop()) {
            return Err(Error::InvalidModule(e.to_string()));
        }
        let c = self.read(&counter, 16)?;
        let word = |i: usize| u32::from_le_bytes(c[4 * i..4 * i + 4].try_into().unwrap());
        Ok(Run {
            buffers: (nodes, code, ranges),
            used: u64::from(word(0)),
            overflow: word(1),
            leaves: u64::from(word(2)),
        })
    }
}

/// The room a pre-pass has: words of the programs' buffer and of the scratch, and cells a
/// dispatch (which share the scratch).
#[derive(Clone, Copy, Debug)]
struct Room {
    code: u64,
    scratch: u64,
    chunk: usize,
}

/// One pre-pass's buffers and counter.
struct Run {
    buffers: (wgpu::Buffer, wgpu::Buffer, wgpu::Buffer),
    /// The words the cells asked for (more than were written where some found no room).
    used: u64,
    /// Cells that found no room.
    overflow: u32,
    /// The leaves of the last grid's programs.
    leaves: u64,
}

/// Cells of a grid of `n` a side.
fn cells_of(n: [usize; 3]) -> usize {
    n.iter().product()
}

/// The words as little-endian bytes.
fn le_bytes(words: &[u32]) -> Vec<u8> {
    words.iter().flat_map(|w| w.to_le_bytes()).collect()
}

/// The bytes of the ranges the tracer reads: the header, the grid's cells, the outside one.
fn ranges_bytes(seed: &Seed) -> usize {
    (HEADER + seed.cells() + 1) * 8
}
