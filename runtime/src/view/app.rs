//! The viewer's application: what it was asked for, and once its window is open (`Started`)
//! the window, its surface, the presenter and the live picture, all or none of them.

use super::live::{Live, Picture};
use super::present::Present;
use super::script::Step;
use super::watch::SceneWatcher;
use crate::cli::input::load_scene;
use crate::cli::{Error, ViewArgs, write_file};
use sdfc::gpu::Gpu;
use sdfc_compiler::lower::tracer::Options;
use sdfc_compiler::scene::Scene;
use std::collections::VecDeque;
use std::sync::Arc;
use std::time::Instant;
use winit::event::MouseButton;
use winit::event_loop::ActiveEventLoop;
use winit::window::Window;

/// `sdfc view` from its arguments to its exit code.
pub struct App {
    pub(super) args: ViewArgs,
    size: (u32, u32),
    /// The scene checked before the window opened, until it does.
    first: Option<(Scene, Options)>,
    code: i32,
    pub(super) pointer: (f64, f64),
    /// The button held.
    pub(super) drag: Option<MouseButton>,
    pub(super) reload_at: Option<Instant>,
    shots: u32,
    /// Pictures saved with `s`.
    pub(super) saved: u32,
    script: VecDeque<Step>,
    /// Whether the file on disk has errors (the picture is the last good one).
    broken: bool,
    /// Whether the file is gone (deleted or moved away): the title says the viewer waits.
    pub(super) missing: bool,
    /// When the title last changed: it follows the frame time while the picture moves.
    titled: std::cell::Cell<Option<Instant>>,
    watcher: SceneWatcher,
    /// A scripted `orbit` under way.
    orbiting: Option<Orbiting>,
    /// The window and what draws to it, once it is open.
    pub(super) started: Option<Started>,
}

/// A scripted `orbit S` (`Step::Orbit`): until when it turns the camera, when it began, and
/// the frames shown and their GPU seconds since.
pub(super) struct Orbiting {
    until: Instant,
    began: Instant,
    frames: u32,
    gpu_seconds: f64,
}

/// Pixels the scripted orbit turns the camera by each frame (a slow, steady drag).
const ORBIT_STEP: f64 = 3.0;

/// The open window and what draws to it.
pub(super) struct Started {
    pub(super) window: Arc<Window>,
    pub(super) surface: wgpu::Surface<'static>,
    pub(super) config: wgpu::SurfaceConfiguration,
    present: Present,
    /// The picture (and the device it is rendered on).
    pub(super) live: Live,
}

impl Started {
    /// The device.
    pub(super) fn gpu(&self) -> &Gpu {
        self.live.gpu()
    }
}

/// Reads and checks the scene with the tracer overrides; diagnostics printed.
pub fn load(args: &ViewArgs) -> Option<(Scene, Options)> {
    let (sources, mut scene) = load_scene(&args.file, args.bake.bake_res)?;
    let options = args.tracer.settle(&mut scene).and_then(|mut options| {
        // One pass: the viewer's coarse frames take the passes' place.
        options.passes = false;
        let allow = args.allow_slow_compile;
        crate::cli::driver::driver_module(&scene, &sources, &mut options, allow)?;
        Ok(options)
    });
    match options {
        Ok(options) => Some((scene, options)),
        Err(crate::cli::Error::Reported) => None,
        Err(e) => {
            say!("{e}");
            None
        }
    }
}

impl App {
    /// The viewer of `args`, for a window of `size`, `first` the scene checked ([`load`]),
    /// `script` to replay and the file followed by `watcher`.
    pub fn new(
        args: ViewArgs,
        size: (u32, u32),
        first: (Scene, Options),
        script: VecDeque<Step>,
        watcher: SceneWatcher,
    ) -> App {
        App {
            args,
            size,
            first: Some(first),
            code: 0,
            pointer: (0.0, 0.0),
            drag: None,
            reload_at: None,
            shots: 0,
            saved: 0,
            script,
            broken: false,
            missing: false,
            titled: std::cell::Cell::new(None),
            watcher,
            orbiting: None,
            started: None,
        }
    }

    /// The exit code: 0, or 1 after an error.
    pub fn code(&self) -> i32 {
        self.code
    }

    pub(super) fn fail(&mut self, event_loop: &ActiveEventLoop, e: Error) {
        say!("{e}");
        self.code = 1;
        event_loop.exit();
    }

    /// Opens the window, the device that draws to it and the live picture of the first scene.
    pub(super) fn start(&mut self, event_loop: &ActiveEventLoop) -> Result<(), Error> {
        let attrs = Window::default_attributes()
            .with_title(format!("sdfc view {}", self.args.file.display()))
            .with_inner_size(winit::dpi::PhysicalSize::new(self.size.0, self.size.1));
        let window = Arc::new(
            event_loop
                .create_window(attrs)
                .map_err(|e| Error::Usage(format!("error: cannot open a window: {e}")))?,
        );
        let (gpu, surface) = Gpu::for_window(self.args.backend.into(), window.clone())?;
        let inner = window.inner_size();
        let size = (inner.width.max(1), inner.height.max(1));
        let mut config = surface
            .get_default_config(gpu.adapter(), size.0, size.1)
            .ok_or("error: the window's surface cannot be configured")?;
        config.present_mode = wgpu::PresentMode::AutoVsync;
        gpu.configure(&surface, &config);
        let present = Present::new(&gpu, config.format)?;
        let (scene, options) = self.first.take().expect("the first scene");
        let mut live = Live::new(gpu, scene, options, size)?;
        if let Some(t) = self.args.time {
            live.hold_time(t);
        }
        self.started = Some(Started {
            window,
            surface,
            config,
            present,
            live,
        });
        self.title();
        self.say_what_quits();
        Ok(())
    }

    /// With `--quit-after N`, says when fewer than N pictures will come by themselves: a still
    /// scene makes one picture, then one per script step and per save of its file.
    fn say_what_quits(&self) {
        let (Some(n), Some(started)) = (self.args.quit_after, &self.started) else {
            return;
        };
        let coming = 1 + self.script.len() as u32;
        if started.live.animated() || n <= coming {
            return;
        }
        say!(
            "note: `--quit-after {n}`: this still scene makes {coming} picture{} (one, then one per script step); the window closes after {n}, counting a new picture at each save of {}",
            if coming == 1 { "" } else { "s" },
            self.args.file.display()
        );
    }

    pub(super) fn title(&self) {
        let Some(started) = &self.started else {
            return;
        };
        let live = &started.live;
        let method = sdfc_compiler::check::tracer::method_entry(live.method()).0;
        let (s, evals) = live.stats;
        let (width, height) = live.size();
        let status = if self.missing {
            format!(" — waiting for {}", self.args.file.display())
        } else if self.broken {
            " — error, see terminal".to_string()
        } else {
            String::new()
        };
        self.titled.set(Some(Instant::now()));
        let param = live
            .scene
            .params
            .get(live.selected)
            .filter(|p| p.name != sdfc_compiler::check::TIME)
            .map(|p| {
                format!(
                    ", [{}] {:?}",
                    p.name,
                    live.values.get(&p.name).unwrap_or(&p.values())
                )
            })
            .unwrap_or_default();
        started.window.set_title(&format!(
            "{} — {:.1} ms, {evals:.1} evals/px, {method}, {width}×{height}, {:?}, {} ({}){param}{status}",
            self.args.file.display(),
            s * 1000.0,
            live.channel,
            started.gpu().info.name,
            started.gpu().backend()
        ));
    }

    /// Renders and shows the next frame; screenshots and script steps on a finished picture.
    pub(super) fn frame(&mut self, event_loop: &ActiveEventLoop) -> Result<(), Error> {
        let Some(started) = &mut self.started else {
            return Ok(());
        };
        let picture = started.live.step()?;
        let gpu = started.live.gpu();
        let shown = started
            .present
            .show(gpu, &started.surface, &picture.rgba, picture.size)?;
        if !shown {
            // (Routine while a window is resized: configure again and draw the next time.)
            gpu.configure(&started.surface, &started.config);
            started.window.request_redraw();
        }
        // While the picture moves, the frame time in the title four times a second.
        let stale = self
            .titled
            .get()
            .is_none_or(|t| t.elapsed() >= std::time::Duration::from_millis(250));
        if picture.finished || stale {
            self.title();
        }
        self.orbit_on(picture.size);
        if picture.finished {
            self.screenshot(event_loop, &picture)?;
            if let Some(step) = self.script.pop_front() {
                self.apply(event_loop, step);
            }
        }
        Ok(())
    }

    /// During a scripted orbit: counts the frame just shown and turns the camera on; at its
    /// end, says the frames shown, the rate and the mean GPU time of a frame.
    fn orbit_on(&mut self, size: (u32, u32)) {
        let (Some(o), Some(started)) = (self.orbiting.as_mut(), self.started.as_mut()) else {
            return;
        };
        let live = &mut started.live;
        o.frames += 1;
        o.gpu_seconds += live.stats.0;
        if Instant::now() < o.until {
            live.orbit.turn(ORBIT_STEP, 0.0);
            live.touch();
            return;
        }
        let seconds = o.began.elapsed().as_secs_f64();
        say!(
            "orbit: {} frames in {seconds:.2} s, {:.1} frames a second at {}×{} (GPU {:.1} ms a frame); {} shaders compiled since the window opened",
            o.frames,
            f64::from(o.frames) / seconds,
            size.0,
            size.1,
            1000.0 * o.gpu_seconds / f64::from(o.frames),
            live.gpu().pipelines_made()
        );
        self.orbiting = None;
    }

    pub(super) fn screenshot(
        &mut self,
        event_loop: &ActiveEventLoop,
        picture: &Picture,
    ) -> Result<(), Error> {
        // Every finished picture counts for `--quit-after`, saved or not.
        if let Some(dir) = &self.args.screenshots {
            let path = dir.join(format!("{:03}.png", self.shots));
            let bytes = sdfc::images::png(picture.rgba.clone(), picture.size.0, picture.size.1)?;
            write_file(&path, &bytes)?;
            let (seconds, evals) = self.started.as_ref().map_or((0.0, 0.0), |s| s.live.stats);
            say!(
                "screenshot {} ({}×{}, last frame {:.1} ms, {evals:.1} evaluations per pixel)",
                path.display(),
                picture.size.0,
                picture.size.1,
                seconds * 1000.0
            );
        }
        self.shots += 1;
        if self.args.quit_after.is_some_and(|n| self.shots >= n) {
            event_loop.exit();
        }
        Ok(())
    }

    pub(super) fn apply(&mut self, event_loop: &ActiveEventLoop, step: Step) {
        let Some(live) = self.started.as_mut().map(|s| &mut s.live) else {
            return;
        };
        let height = f64::from(live.size().1);
        match step {
            Step::Drag(dx, dy) => live.orbit.turn(dx, dy),
            Step::Pan(dx, dy) => live.orbit.pan(dx, dy, height),
            Step::Zoom(n) => live.orbit.zoom(n),
            Step::Orbit(seconds) => {
                let now = Instant::now();
                self.orbiting = Some(Orbiting {
                    until: now + std::time::Duration::from_secs_f64(seconds),
                    began: now,
                    frames: 0,
                    gpu_seconds: 0.0,
                });
                live.orbit.turn(ORBIT_STEP, 0.0);
            }
            Step::Key(k) => {
                self.key(event_loop, &k);
                return;
            }
        }
        live.touch();
    }

    /// Loads the scene again after a save: the new picture, or the last good one kept (and a
    /// screenshot of it) when the file has errors.
    pub(super) fn reload(&mut self, event_loop: &ActiveEventLoop) {
        let Some(started) = self.started.as_mut() else {
            return;
        };
        let live = &mut started.live;
        let clock = Instant::now();
        let loaded = load(&self.args);
        self.watcher.follow(&self.args.file);
        match loaded {
            Some((scene, options)) => match live.replace(scene, options) {
                Ok(()) => {
                    self.broken = false;
                    self.missing = false;
                    say!(
                        "reloaded {} in {:.0} ms",
                        self.args.file.display(),
                        clock.elapsed().as_secs_f64() * 1000.0
                    );
                }
                Err(e) => {
                    say!("{e}");
                    self.broken = true;
                }
            },
            None => {
                // The diagnostics are printed; the last good picture stays.
                self.broken = true;
                self.missing = !self.args.file.exists();
                say!("the picture is the last one that checked; fix the file and save again");
                let (rgba, size) = (live.last_picture(), live.size());
                let picture = Picture {
                    rgba,
                    size,
                    finished: true,
                };
                if let Err(e) = self.screenshot(event_loop, &picture) {
                    say!("{e}");
                }
            }
        }
        self.title();
    }
}
