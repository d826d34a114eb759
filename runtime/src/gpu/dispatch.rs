//! Running a prepared module: the uniforms of the next frames (parameters, camera, jitter),
//! then a frame as one submission (timed) or tile by tile (with progress).

use super::{Error, Prepared};
use sdfc_compiler::layout::view_field;
use sdfc_compiler::view::View;

/// How long one frame took.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Timing {
    /// Wall time from the submission to the end of the wait, seconds.
    pub wall: f64,
    /// GPU time from the first pass's start to the last pass's end (timestamp queries),
    /// seconds; `None` where the adapter has no timestamps.
    pub gpu: Option<f64>,
}

impl Prepared {
    /// Sets the scene parameters' values of the next frames
    /// (`sdfc_compiler::lower::params::bytes`); nothing for a module without parameters.
    pub fn set_params(&self, bytes: &[u8]) {
        if let Some((buffer, _)) = &self.params {
            let mut bytes = bytes.to_vec();
            bytes.resize(buffer.size() as usize, 0);
            self.gpu.queue.write_buffer(buffer, 0, &bytes);
        }
    }

    /// Points the next frames' camera as `view` (same size; its jitter included): an orbit
    /// camera without preparing again (`sdfc view`). For a module prepared without passes.
    pub fn set_view(&mut self, view: &View) {
        assert_eq!(self.passes.len(), 1, "a view without passes");
        for d in &mut self.passes[0] {
            d.uniform.1 = view.uniform(d.origin.0, d.origin.1, [0.0; 4]);
            self.gpu.queue.write_buffer(&d.uniform.0, 0, &d.uniform.1);
        }
    }

    /// Moves the rays of the next frames to `jitter` within their pixels (`View::jitter`), in
    /// the last pass only: an earlier, coarser pass's cone covers its whole pixels from their
    /// centres, so it stays there.
    pub fn set_jitter(&self, jitter: [f64; 2]) {
        let Some(last) = self.passes.last() else {
            return;
        };
        for d in last {
            let mut bytes = d.uniform.1;
            for (at, v) in [
                (jitter_at("right"), jitter[0]),
                (jitter_at("up"), jitter[1]),
            ] {
                bytes[at..at + 4].copy_from_slice(&(v as f32).to_le_bytes());
            }
            self.gpu.queue.write_buffer(&d.uniform.0, 0, &bytes);
        }
    }

    /// Runs one frame as a single submission (all passes, all tiles) and waits for it.
    pub fn run(&self) -> Result<Timing, Error> {
        let gpu = &self.gpu;
        let mut enc = gpu.device.create_command_encoder(&Default::default());
        for (k, pass) in self.passes.iter().enumerate() {
            let k = k as u32;
            let timestamp_writes =
                self.queries
                    .as_ref()
                    .map(|(set, _)| wgpu::ComputePassTimestampWrites {
                        query_set: set,
                        beginning_of_pass_write_index: Some(2 * k),
                        end_of_pass_write_index: Some(2 * k + 1),
                    });
            let mut cp = enc.begin_compute_pass(&wgpu::ComputePassDescriptor {
                label: Some("frame"),
                timestamp_writes,
            });
            cp.set_pipeline(&self.pipeline);
            for d in pass {
                cp.set_bind_group(0, &d.bind, &[]);
                cp.dispatch_workgroups(d.groups.0, d.groups.1, 1);
            }
        }
        if let Some((set, resolved)) = &self.queries {
            enc.resolve_query_set(set, 0..2 * self.passes.len() as u32, resolved, 0);
        }
        let clock = std::time::Instant::now();
        gpu.queue.submit([enc.finish()]);
        gpu.wait()?;
        let wall = clock.elapsed().as_secs_f64();
        let gpu_time = match &self.queries {
            Some((_, resolved)) => {
                let bytes = gpu.read(resolved, resolved.size())?;
                let ticks: Vec<u64> = bytes
                    .chunks_exact(8)
                    .map(|c| u64::from_le_bytes(c.try_into().unwrap()))
                    .collect();
                let span = ticks[ticks.len() - 1].saturating_sub(ticks[0]);
                Some(span as f64 * gpu.queue.get_timestamp_period() as f64 * 1e-9)
            }
            None => None,
        };
        Ok(Timing {
            wall,
            gpu: gpu_time,
        })
    }

    /// Runs one frame tile by tile, waiting for each and telling `progress` how many are done
    /// (`render`'s way: a long image shows its progress and no dispatch runs for long).
    pub fn run_tiles(&self, mut progress: impl FnMut(u32, u32)) -> Result<f64, Error> {
        let gpu = &self.gpu;
        let total = self.dispatches();
        let mut done = 0;
        let clock = std::time::Instant::now();
        for pass in &self.passes {
            for d in pass {
                let mut enc = gpu.device.create_command_encoder(&Default::default());
                {
                    let mut cp = enc.begin_compute_pass(&Default::default());
                    cp.set_pipeline(&self.pipeline);
                    cp.set_bind_group(0, &d.bind, &[]);
                    cp.dispatch_workgroups(d.groups.0, d.groups.1, 1);
                }
                gpu.queue.submit([enc.finish()]);
                gpu.wait()?;
                done += 1;
                progress(done, total);
            }
        }
        Ok(clock.elapsed().as_secs_f64())
    }
}

/// The byte offset in the `View` uniform of the jitter in `field`'s fourth component (`right.w`
/// and `up.w` hold where in its pixel the ray passes: `View::uniform`).
fn jitter_at(field: &str) -> usize {
    16 * view_field(field) + 12
}
