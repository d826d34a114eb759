//! `sdfc view`: a window that shows the scene live — an orbit camera, hot reload on save,
//! coarse frames while moving and anti-aliasing samples at rest, keys for the channel, the
//! tracer, parameters and screenshots.

use crate::live::{Live, Picture};
use crate::view_events::{Step, Watched, parse_script, watch};
use sdfc::gpu::{BackendChoice, Gpu};
use sdfc::images::Channel;
use sdfc::present::Present;
use std::collections::VecDeque;
use std::path::{Path, PathBuf};
use std::sync::Arc;
use std::time::{Duration, Instant};
use winit::event::MouseButton;
use winit::event_loop::{ActiveEventLoop, EventLoop};
use winit::window::Window;

/// What `sdfc view` was asked for.
pub struct ViewArgs {
    /// The scene file.
    pub file: PathBuf,
    /// The window's size, `WxH`.
    pub size: String,
    /// Vulkan, GL, or either.
    pub backend: BackendChoice,
    /// Tracer overrides.
    pub tracer: crate::cli::TracerArgs,
    /// Write each finished picture (and the picture kept after a failed reload) to this
    /// directory as `000.png`, `001.png`, … and say so on standard error.
    pub screenshots: Option<PathBuf>,
    /// Input to replay, one step per finished picture: `drag DX DY`, `pan DX DY`, `zoom N`,
    /// `key K`, separated by `;`.
    pub script: Option<String>,
    /// Close after this many screenshots.
    pub quit_after: Option<u32>,
    /// Hold `time` at this many seconds (space lets it run).
    pub time: Option<f64>,
}

/// Waits this long after the last write before reloading (editors write in bursts).
pub(crate) const SETTLE: Duration = Duration::from_millis(80);

/// Runs `sdfc view`; returns the exit code.
pub fn run(args: ViewArgs) -> i32 {
    if args.file == Path::new("-") {
        say!("error: `sdfc view` follows a file; standard input cannot be watched");
        return 1;
    }
    if std::env::var_os("DISPLAY").is_none() && std::env::var_os("WAYLAND_DISPLAY").is_none() {
        say!(
            "error: `sdfc view` needs a display, and neither DISPLAY nor WAYLAND_DISPLAY is set\nhelp: without one, run it under Xvfb: `xvfb-run -a sdfc view FILE`, or render a picture with `sdfc render`"
        );
        return 1;
    }
    let size = match crate::render_cmd::parse_size(&args.size) {
        Ok(s) => s,
        Err(e) => {
            say!("{e}");
            return 1;
        }
    };
    if let Some(dir) = &args.screenshots
        && let Err(e) = std::fs::create_dir_all(dir)
    {
        say!("error: cannot create `{}`: {e}", dir.display());
        return 1;
    }
    let Some(scene) = load(&args) else {
        return 1;
    };
    let script = match args.script.as_deref().map(parse_script).transpose() {
        Ok(s) => s.unwrap_or_default(),
        Err(e) => {
            say!("{e}");
            return 1;
        }
    };
    // (The command line runs on a thread with a larger stack than the main one.)
    let mut builder = EventLoop::<Watched>::with_user_event();
    winit::platform::x11::EventLoopBuilderExtX11::with_any_thread(&mut builder, true);
    let event_loop = match builder.build() {
        Ok(e) => e,
        Err(e) => {
            say!(
                "error: cannot open a window: {e}\nhelp: is the display `{}` running?",
                std::env::var("DISPLAY").unwrap_or_default()
            );
            return 1;
        }
    };
    let proxy = event_loop.create_proxy();
    let watcher = match watch(&args.file, move |w| {
        let _ = proxy.send_event(w);
    }) {
        Ok(w) => w,
        Err(e) => {
            say!("error: cannot watch `{}`: {e}", args.file.display());
            return 1;
        }
    };
    let mut app = App {
        args,
        size,
        first: Some(scene),
        window: None,
        surface: None,
        present: None,
        live: None,
        code: 0,
        pointer: (0.0, 0.0),
        drag: None,
        reload_at: None,
        shots: 0,
        saved: 0,
        script,
        broken: false,
        watcher,
    };
    if let Err(e) = event_loop.run_app(&mut app) {
        say!("error: the window's event loop failed: {e}");
        return 1;
    }
    app.code
}

/// Reads and checks the scene with the tracer overrides; diagnostics printed.
fn load(
    args: &ViewArgs,
) -> Option<(
    sdfc_compiler::scene::Scene,
    sdfc_compiler::lower::tracer::Options,
)> {
    let (_, mut scene) = crate::input::load_scene(&args.file)?;
    match args.tracer.settle(&mut scene) {
        Ok(mut options) => {
            // One pass: the viewer's coarse frames take the passes' place.
            options.passes = false;
            Some((scene, options))
        }
        Err(e) => {
            say!("{e}");
            None
        }
    }
}

pub(crate) struct App {
    pub(crate) args: ViewArgs,
    pub(crate) size: (u32, u32),
    pub(crate) first: Option<(
        sdfc_compiler::scene::Scene,
        sdfc_compiler::lower::tracer::Options,
    )>,
    pub(crate) window: Option<Arc<Window>>,
    pub(crate) surface: Option<(wgpu::Surface<'static>, wgpu::SurfaceConfiguration)>,
    pub(crate) present: Option<Present>,
    pub(crate) live: Option<Live>,
    pub(crate) code: i32,
    pub(crate) pointer: (f64, f64),
    /// The button held and where the pointer was.
    pub(crate) drag: Option<MouseButton>,
    pub(crate) reload_at: Option<Instant>,
    pub(crate) shots: u32,
    /// Pictures saved with `s`.
    pub(crate) saved: u32,
    pub(crate) script: VecDeque<Step>,
    /// Whether the file on disk has errors (the picture is the last good one).
    pub(crate) broken: bool,
    pub(crate) watcher: crate::view_events::SceneWatcher,
}

impl App {
    pub(crate) fn fail(&mut self, event_loop: &ActiveEventLoop, e: String) {
        say!("{e}");
        self.code = 1;
        event_loop.exit();
    }

    pub(crate) fn start(&mut self, event_loop: &ActiveEventLoop) -> Result<(), String> {
        let attrs = Window::default_attributes()
            .with_title(format!("sdfc view {}", self.args.file.display()))
            .with_inner_size(winit::dpi::PhysicalSize::new(self.size.0, self.size.1));
        let window = Arc::new(
            event_loop
                .create_window(attrs)
                .map_err(|e| format!("error: cannot open a window: {e}"))?,
        );
        let (gpu, surface) = Gpu::for_window(self.args.backend, window.clone())?;
        // One device for the process's life: the prepared frames borrow it.
        let gpu: &'static Gpu = Box::leak(Box::new(gpu));
        let inner = window.inner_size();
        let size = (inner.width.max(1), inner.height.max(1));
        let mut config = surface
            .get_default_config(&adapter_less(gpu, &surface), size.0, size.1)
            .ok_or("error: the window's surface cannot be configured")?;
        config.present_mode = wgpu::PresentMode::AutoVsync;
        gpu.configure(&surface, &config);
        let present = Present::new(gpu, config.format)?;
        let (scene, options) = self.first.take().expect("the first scene");
        let mut live = Live::new(gpu, scene, options, size)?;
        if let Some(t) = self.args.time {
            live.hold_time(t);
        }
        self.window = Some(window);
        self.surface = Some((surface, config));
        self.present = Some(present);
        self.live = Some(live);
        self.title();
        Ok(())
    }

    pub(crate) fn gpu(&self) -> &'static Gpu {
        self.live.as_ref().expect("started").gpu()
    }

    pub(crate) fn title(&self) {
        let (Some(w), Some(live)) = (&self.window, &self.live) else {
            return;
        };
        let method = sdfc_compiler::check::tracer::method_entry(live.method()).0;
        let (s, evals) = live.stats;
        let (width, height) = live.size();
        let status = if self.broken {
            " — error, see terminal"
        } else {
            ""
        };
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
        w.set_title(&format!(
            "{} — {:.1} ms, {evals:.1} evals/px, {method}, {width}×{height}, {:?}, {} ({}){param}{status}",
            self.args.file.display(),
            s * 1000.0,
            live.channel,
            self.gpu().info.name,
            self.gpu().backend()
        ));
    }

    /// Renders and shows the next frame; screenshots and script steps on a finished picture.
    pub(crate) fn frame(&mut self, event_loop: &ActiveEventLoop) -> Result<(), String> {
        let picture = self.live.as_mut().expect("started").step()?;
        let (surface, config) = self.surface.as_ref().expect("started");
        let gpu = self.gpu();
        let shown = self.present.as_mut().expect("started").show(
            gpu,
            surface,
            &picture.rgba,
            picture.size,
        )?;
        if !shown {
            // (Routine while a window is resized: configure again and draw the next time.)
            gpu.configure(surface, config);
            if let Some(w) = &self.window {
                w.request_redraw();
            }
        }
        if picture.finished {
            self.title();
            self.finished(event_loop, &picture)?;
        }
        Ok(())
    }

    pub(crate) fn finished(
        &mut self,
        event_loop: &ActiveEventLoop,
        picture: &Picture,
    ) -> Result<(), String> {
        self.screenshot(event_loop, picture)?;
        if let Some(step) = self.script.pop_front() {
            self.apply(event_loop, step);
        }
        Ok(())
    }

    pub(crate) fn screenshot(
        &mut self,
        event_loop: &ActiveEventLoop,
        picture: &Picture,
    ) -> Result<(), String> {
        let Some(dir) = &self.args.screenshots else {
            return Ok(());
        };
        let path = dir.join(format!("{:03}.png", self.shots));
        let bytes = sdfc::images::png(picture.rgba.clone(), picture.size.0, picture.size.1)?;
        sdfc::files::write_file(&path, &bytes)
            .map_err(|e| format!("error: cannot write `{}`: {e}", path.display()))?;
        let (seconds, evals) = self.live.as_ref().map_or((0.0, 0.0), |l| l.stats);
        say!(
            "screenshot {} ({}×{}, last frame {:.1} ms, {evals:.1} evaluations per pixel)",
            path.display(),
            picture.size.0,
            picture.size.1,
            seconds * 1000.0
        );
        self.shots += 1;
        if self.args.quit_after.is_some_and(|n| self.shots >= n) {
            event_loop.exit();
        }
        Ok(())
    }

    pub(crate) fn apply(&mut self, event_loop: &ActiveEventLoop, step: Step) {
        let height = f64::from(self.live.as_ref().map_or(1, |l| l.size().1));
        let Some(live) = self.live.as_mut() else {
            return;
        };
        match step {
            Step::Drag(dx, dy) => live.orbit.turn(dx, dy),
            Step::Pan(dx, dy) => live.orbit.pan(dx, dy, height),
            Step::Zoom(n) => live.orbit.zoom(n),
            Step::Key(k) => {
                self.key(event_loop, &k);
                return;
            }
        }
        live.touch();
    }

    /// A key (as text): the viewer's commands.
    pub(crate) fn key(&mut self, event_loop: &ActiveEventLoop, k: &str) {
        let Some(live) = self.live.as_mut() else {
            return;
        };
        let channel = |c| match c {
            "1" => Some(Channel::Color),
            "2" => Some(Channel::Normal),
            "3" => Some(Channel::Depth),
            "4" => Some(Channel::Steps),
            "5" => Some(Channel::Material),
            _ => None,
        };
        match k {
            "q" | "Escape" => event_loop.exit(),
            "r" | "Home" => live.orbit.reset(),
            "a" => live.samples = if live.samples > 1 { 1 } else { 4 },
            " " | "Space" => match live.toggle_time() {
                Some(t) => say!("time held at {t:.2} s"),
                None => say!("time runs on from {:.2} s", live.time()),
            },
            "t" => match live.cycle_method() {
                Ok(m) => say!(
                    "tracer: {}",
                    sdfc_compiler::check::tracer::method_entry(m).0
                ),
                Err(e) => say!("{e}"),
            },
            "[" | "]" => {
                // The parameters the keys may change: not `time`, which runs with the clock.
                let n = live.scene.params.len().max(1);
                for _ in 0..n {
                    live.selected = (live.selected + if k == "]" { 1 } else { n - 1 }) % n;
                    let time = sdfc_compiler::check::TIME;
                    if live
                        .scene
                        .params
                        .get(live.selected)
                        .is_some_and(|p| p.name != time)
                    {
                        break;
                    }
                }
            }
            "-" | "=" | "+" => {
                let up = k != "-";
                if let Some(p) = live
                    .scene
                    .params
                    .get(live.selected)
                    .filter(|p| p.name != sdfc_compiler::check::TIME)
                    .cloned()
                {
                    let now = live
                        .values
                        .get(&p.name)
                        .cloned()
                        .unwrap_or_else(|| p.values());
                    let next: Vec<f64> = now
                        .iter()
                        .enumerate()
                        .map(|(i, &x)| match p.range {
                            Some((lo, hi)) => (x
                                + (hi[i] - lo[i]) / 20.0 * if up { 1.0 } else { -1.0 })
                            .clamp(lo[i], hi[i]),
                            None => x + if up { 0.1 } else { -0.1 },
                        })
                        .collect();
                    say!("{} = {next:?}", p.name);
                    live.values.insert(p.name.clone(), next);
                }
            }
            "s" => {
                // The last finished picture, numbered apart from `--screenshots`.
                self.saved += 1;
                let path = PathBuf::from(format!("sdfc-view-{:03}.png", self.saved));
                let (w, h) = live.size();
                match sdfc::images::png(live.last_picture(), w, h)
                    .and_then(|b| sdfc::files::write_file(&path, &b).map_err(|e| e.to_string()))
                {
                    Ok(()) => say!("saved {}", path.display()),
                    Err(e) => say!("error: cannot save `{}`: {e}", path.display()),
                }
                return;
            }
            c => match channel(c) {
                Some(ch) => live.channel = ch,
                None => return,
            },
        }
        if let Some(live) = self.live.as_mut() {
            live.touch();
        }
        self.title();
    }

    pub(crate) fn reload(&mut self, event_loop: &ActiveEventLoop) {
        let Some(live) = self.live.as_mut() else {
            return;
        };
        let started = Instant::now();
        let loaded = load(&self.args);
        self.watcher.follow(&self.args.file);
        match loaded {
            Some((scene, options)) => match live.replace(scene, options) {
                Ok(()) => {
                    self.broken = false;
                    say!(
                        "reloaded {} in {:.0} ms",
                        self.args.file.display(),
                        started.elapsed().as_secs_f64() * 1000.0
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

/// The adapter a surface was made for, to ask its default configuration.
fn adapter_less(gpu: &Gpu, _surface: &wgpu::Surface) -> wgpu::Adapter {
    gpu.adapter().clone()
}
