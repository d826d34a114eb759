//! What `sdfc view` shows, apart from the window: the last good scene compiled and prepared
//! at the window's size (and a quarter of it for moving), the orbit camera, the channel,
//! parameters and anti-aliasing samples accumulated while nothing moves.

use super::moments::{animated_cells, follows_time, next_cells};
use super::orbit::Orbit;
use crate::cli::Error;
use sdfc::gpu::{Gpu, Layout, MAX_SIDE, Prepared, Pruner, Source};
use sdfc::images::{self, Accumulator, Channel};
use sdfc_compiler::check::TIME;
use sdfc_compiler::emit;
use sdfc_compiler::lower::{Entry, params::bytes, tracer::Options};
use sdfc_compiler::scene::{Method, Scene};
use sdfc_compiler::view::View;
use std::collections::HashMap;
use std::time::{Duration, Instant};

/// How long after the last input the camera counts as moving (coarse frames).
const MOVING: Duration = Duration::from_millis(150);
/// Coarse frames are this many times smaller per side.
const COARSE: u32 = 4;

/// The tracers `t` cycles through.
pub const METHODS: [Method; 5] = [
    Method::Basic,
    Method::Relaxed,
    Method::Enhanced,
    Method::Hybrid,
    Method::Auto,
];

/// A picture to show: sRGB RGBA8 pixels and their size.
pub struct Picture {
    /// The pixels, row-major, y down.
    pub rgba: Vec<u8>,
    /// Width and height.
    pub size: (u32, u32),
    /// Whether it is the finished picture (every sample of a still camera).
    pub finished: bool,
}

/// The viewer's state.
pub struct Live {
    gpu: Gpu,
    /// The last scene that checked, at the current parameter values.
    pub scene: Scene,
    options: Options,
    full: Prepared,
    coarse: Prepared,
    /// The data form's pre-pass on the device (none: on the CPU, or inline).
    pruner: Option<Pruner>,
    size: (u32, u32),
    /// The camera.
    pub orbit: Orbit,
    /// What is shown.
    pub channel: Channel,
    /// Samples per pixel once still (1: no anti-aliasing).
    pub samples: u32,
    acc: Accumulator,
    /// Until when the camera counts as moving.
    moving_until: Instant,
    /// Parameter values set with the keys (others at their defaults).
    pub values: HashMap<String, Vec<f64>>,
    /// The parameter the keys change.
    pub selected: usize,
    /// Where annotations are too small at the current parameter values (said once on the way
    /// in: `keys::verify`).
    pub too_small: Vec<sdfc_compiler::diag::Span>,
    /// When `time` last started running, and its value then.
    started: (Instant, f64),
    /// `time` stopped at this value (space).
    paused: Option<f64>,
    /// The last frame's GPU time and mean evaluations per pixel.
    pub stats: (f64, f64),
    /// The last finished picture at full size (kept through a failed reload).
    last: Vec<u8>,
    /// The values the data form's buffers were made at (they are made again, the shader
    /// kept, when the keys change one).
    tape_values: HashMap<String, Vec<f64>>,
    /// Whether the data form's parts follow `time` (their buffers are then made again for
    /// every new moment).
    tape_follows_time: bool,
    /// The grid's cells a side the buffers were made with (`None`: as many as the parts call
    /// for), and those the next moment of a running `time` makes them with: fewer, where the
    /// pre-pass takes longer than [`ANIMATED_PREPASS`].
    tape_cells: (Option<usize>, Option<usize>),
    /// The most cells a running `time`'s grid takes: `--cells`, else the parts' own count
    /// (the parts' number does not change with values; 0 where `time` moves no part).
    tape_full_cells: usize,
}

impl Live {
    /// Compiles and prepares `scene` for a window of `size`.
    pub fn new(gpu: Gpu, scene: Scene, options: Options, size: (u32, u32)) -> Result<Live, Error> {
        let orbit = Orbit::new(&scene.camera);
        let pruner = crate::cli::pruner(&gpu, &scene, &options)?;
        let (full, coarse) = prepare(
            &gpu,
            (&scene, &options),
            size,
            &HashMap::new(),
            pruner.as_ref(),
        )?;
        Ok(Live {
            gpu,
            full,
            coarse,
            pruner,
            size,
            orbit,
            channel: Channel::Color,
            samples: 4,
            acc: Accumulator::new(pixels(size), true),
            moving_until: Instant::now(),
            values: HashMap::new(),
            selected: 0,
            too_small: Vec::new(),
            started: (Instant::now(), 0.0),
            paused: None,
            stats: (0.0, 0.0),
            last: Vec::new(),
            tape_values: HashMap::new(),
            tape_follows_time: follows_time(&scene, &options),
            tape_cells: (options.cells, None),
            tape_full_cells: animated_cells(&scene, &options),
            scene,
            options,
        })
    }

    /// A new scene (a reload that checked): compiled and prepared; the camera stays where the
    /// user turned it.
    pub fn replace(&mut self, scene: Scene, options: Options) -> Result<(), Error> {
        let pruner = crate::cli::pruner(&self.gpu, &scene, &options)?;
        let none = HashMap::new();
        let (full, coarse) = prepare(
            &self.gpu,
            (&scene, &options),
            self.size,
            &none,
            pruner.as_ref(),
        )?;
        self.tape_values.clear();
        self.tape_follows_time = follows_time(&scene, &options);
        self.tape_cells = (options.cells, None);
        self.tape_full_cells = animated_cells(&scene, &options);
        // Values set with the keys stay only where the new scene still has the parameter,
        // of the same size, and within its range.
        self.values.retain(|name, v| {
            scene.params.iter().any(|p| {
                p.name == *name
                    && p.kind.components() == v.len()
                    && p.range.is_none_or(|(lo, hi)| {
                        (0..v.len()).all(|i| (lo[i]..=hi[i]).contains(&v[i]))
                    })
            })
        });
        self.selected = self.selected.min(scene.params.len().saturating_sub(1));
        self.orbit.rehome(&scene.camera);
        (self.full, self.coarse, self.pruner) = (full, coarse, pruner);
        (self.scene, self.options) = (scene, options);
        // Coarse frames first, as when the camera moves: the change shows at once.
        self.touch();
        Ok(())
    }

    /// The window's new size.
    pub fn resize(&mut self, size: (u32, u32)) -> Result<(), Error> {
        let size = (size.0.clamp(1, MAX_SIDE), size.1.clamp(1, MAX_SIDE));
        let values = &self.tape_values;
        // (The same scene: its pre-pass's pipeline is kept.)
        let scene = (&self.scene, &self.options);
        (self.full, self.coarse) = prepare(&self.gpu, scene, size, values, self.pruner.as_ref())?;
        self.size = size;
        self.restart();
        Ok(())
    }

    /// Another tracer: the module compiled again.
    pub fn cycle_method(&mut self) -> Result<Method, Error> {
        let now = METHODS
            .iter()
            .position(|m| *m == self.options.trace.method)
            .unwrap_or(0);
        let next = METHODS[(now + 1) % METHODS.len()];
        let mut scene = self.scene.clone();
        let name = sdfc_compiler::check::tracer::method_entry(next).0;
        scene.trace = sdfc_compiler::check::tracer::with_overrides(scene.trace, Some(name), &[])?;
        let mut options = self.options;
        options.trace = scene.trace;
        self.replace(scene, options)?;
        Ok(next)
    }

    /// The camera moved (or a setting changed): coarse frames for a moment, then the samples
    /// again.
    pub fn touch(&mut self) {
        self.moving_until = Instant::now() + MOVING;
        self.restart();
    }

    /// Start accumulating again.
    pub fn restart(&mut self) {
        self.acc = Accumulator::new(pixels(self.size), self.channel == Channel::Color);
    }

    /// Whether the picture will change without input: moving, samples left, or `time` running.
    pub fn busy(&self) -> bool {
        Instant::now() < self.moving_until
            || self.acc.frames() < self.samples_now()
            || self.animated()
    }

    /// Whether `time` runs: every frame is then a new picture.
    pub fn animated(&self) -> bool {
        self.paused.is_none() && self.scene.params.iter().any(|p| p.name == TIME)
    }

    /// The seconds `time` is at: the clock since it last ran on, from where it stood, wrapped
    /// into its declared range if it has one (λ and bounds hold only there).
    pub fn time(&self) -> f64 {
        let t = self
            .paused
            .unwrap_or_else(|| self.started.1 + self.started.0.elapsed().as_secs_f64());
        let range = self
            .scene
            .params
            .iter()
            .find(|p| p.name == TIME)
            .and_then(|p| p.range);
        match range {
            Some((lo, hi)) if hi.x > lo.x => lo.x + (t - lo.x).rem_euclid(hi.x - lo.x),
            Some((lo, _)) => lo.x,
            None => t,
        }
    }

    /// Holds `time` where it is, or lets it run on from there; the value it is held at.
    pub fn toggle_time(&mut self) -> Option<f64> {
        match self.paused {
            Some(t) => {
                self.paused = None;
                self.started = (Instant::now(), t);
                None
            }
            None => {
                let t = self.time();
                self.paused = Some(t);
                Some(t)
            }
        }
    }

    /// Holds `time` at `t` seconds (`--time`).
    pub fn hold_time(&mut self, t: f64) {
        self.paused = Some(t);
    }

    fn samples_now(&self) -> u32 {
        // Averages of depths, normals or ids are none of them; a running `time` moves.
        if self.channel != Channel::Color || self.animated() {
            1
        } else {
            self.samples
        }
    }

    /// The `Params` bytes now: the values set, `time` running (only the declarations change:
    /// the shader reads nothing else of them).
    fn params(&self) -> Vec<u8> {
        let time = self.time();
        let params: Vec<_> = self
            .scene
            .params
            .iter()
            .map(|p| {
                let mut p = p.clone();
                if p.name == TIME {
                    p.value.x = time;
                } else if let Some(v) = self.values.get(&p.name) {
                    for (i, x) in v.iter().take(p.kind.components()).enumerate() {
                        p.value[i] = *x;
                    }
                }
                p
            })
            .collect();
        bytes(&params)
    }

    /// Renders the next frame: coarse while moving, else the next sample of the full picture.
    pub fn step(&mut self) -> Result<Picture, Error> {
        // (Asked before the data form's buffers are made again, which may take longer than a
        // moment of motion: a moving camera gets a coarse frame.)
        let moving = Instant::now() < self.moving_until;
        let mut wanted = self.values.clone();
        let running = self.tape_follows_time && self.animated();
        if self.tape_follows_time {
            wanted.insert(TIME.to_string(), vec![self.time()]);
        }
        // While `time` runs, a grid as fine as a moment's pre-pass allows; at rest, the parts'.
        let cells = if running {
            self.tape_cells.1.or(self.options.cells)
        } else {
            self.options.cells
        };
        if self.options.form == sdfc_compiler::lower::tracer::Form::Data
            && (wanted != self.tape_values || cells != self.tape_cells.0)
        {
            // The data form at new values (or a new moment): its buffers made again and bound
            // to the same pipelines (no new shader for the driver).
            let clock = Instant::now();
            let valued = self.scene.with_values(&wanted);
            let pruner = self.pruner.as_ref();
            crate::cli::set_tape(&self.gpu, (&self.scene, &valued), cells, pruner)?;
            self.full.retape();
            self.coarse.retape();
            self.tape_values = wanted;
            if running {
                let full = self.tape_full_cells;
                self.tape_cells = (cells, next_cells(cells, full, clock.elapsed()));
            } else {
                self.tape_cells = (cells, None);
            }
        }
        let camera = self.orbit.camera();
        let params = self.params();
        if moving {
            let size = coarse_size(self.size);
            let mut view = View::new(&camera, size.0, size.1);
            view.jitter = [0.5, 0.5];
            self.coarse.set_params(&params);
            self.coarse.set_view(&view);
            let seconds = self.coarse.run_tiles(|_, _| {})?;
            let frame = self.coarse.frame(seconds)?;
            self.note(&frame);
            return Ok(Picture {
                rgba: images::rgba(&frame, self.channel, self.scene.trace.steps),
                size,
                finished: false,
            });
        }
        let n = self.samples_now();
        if self.acc.frames() >= n {
            if !self.animated() && self.last.len() == pixels(self.size) * 4 {
                // A redraw the system asked for (an expose): the finished picture again.
                return Ok(Picture {
                    rgba: self.last.clone(),
                    size: self.size,
                    finished: false,
                });
            }
            self.restart();
        }
        let k = self.acc.frames();
        let mut view = View::new(&camera, self.size.0, self.size.1);
        view.jitter = images::sample_points(n)[k as usize];
        self.full.set_params(&params);
        self.full.set_view(&view);
        let seconds = self.full.run_tiles(|_, _| {})?;
        let frame = self.full.frame(seconds)?;
        self.note(&frame);
        self.acc
            .add(&images::rgba(&frame, self.channel, self.scene.trace.steps));
        let rgba = self.acc.mean();
        // (With `time` running, every frame is a finished picture of its moment.)
        let finished = self.acc.frames() >= n;
        if finished {
            self.last = rgba.clone();
        }
        Ok(Picture {
            rgba,
            size: self.size,
            finished,
        })
    }

    fn note(&mut self, frame: &sdfc::gpu::Frame) {
        let evals = frame.steps.iter().map(|&s| f64::from(s)).sum::<f64>()
            / frame.steps.len().max(1) as f64;
        self.stats = (frame.seconds, evals);
    }

    /// The device.
    pub fn gpu(&self) -> &Gpu {
        &self.gpu
    }

    /// The last finished picture (black before the first).
    pub fn last_picture(&self) -> Vec<u8> {
        if self.last.len() == pixels(self.size) * 4 {
            self.last.clone()
        } else {
            vec![0; pixels(self.size) * 4]
        }
    }

    /// The size of the full picture.
    pub fn size(&self) -> (u32, u32) {
        self.size
    }

    /// The tracer now.
    pub fn method(&self) -> Method {
        self.options.trace.method
    }
}

fn pixels((w, h): (u32, u32)) -> usize {
    (w * h) as usize
}

fn coarse_size((w, h): (u32, u32)) -> (u32, u32) {
    (w.div_ceil(COARSE).max(1), h.div_ceil(COARSE).max(1))
}

/// The compute module of `scene`, prepared at `size` and at a quarter of it (one dispatch
/// each: a frame is one submission); the data form's buffers made at `values`, by `pruner`
/// on the device where given.
fn prepare(
    gpu: &Gpu,
    (scene, options): (&Scene, &Options),
    size: (u32, u32),
    values: &HashMap<String, Vec<f64>>,
    pruner: Option<&Pruner>,
) -> Result<(Prepared, Prepared), Error> {
    let (module, _) =
        emit::module(scene, Entry::Compute, options).map_err(|e| Error::Compiler(e.0))?;
    gpu.set_params(&bytes(&scene.params));
    gpu.set_volumes(&scene.volumes());
    if options.form == sdfc_compiler::lower::tracer::Form::Data {
        let valued = scene.with_values(values);
        crate::cli::set_tape(gpu, (scene, &valued), options.cells, pruner)?;
    } else {
        gpu.set_tape(None)?;
    }
    let layout = Layout::Full { passes: false };
    let full = View::new(&scene.camera, size.0, size.1);
    let c = coarse_size(size);
    let small = View::new(&scene.camera, c.0, c.1);
    Ok((
        gpu.prepare(Source::Module(&module), layout, &full, None, u32::MAX)?,
        gpu.prepare(Source::Module(&module), layout, &small, None, u32::MAX)?,
    ))
}
