//! `sdfc view`: the checks before a window opens, then the viewer's event loop
//! (`crate::view`).

use crate::cli::ViewArgs;
use crate::cli::values::parse_size;
use crate::view::script::parse_script;
use crate::view::watch::{Watched, watch};
use crate::view::{App, load};
use std::path::Path;
use winit::event_loop::EventLoop;

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
    let size = match parse_size(&args.size) {
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
    let mut app = App::new(args, size, scene, script, watcher);
    if let Err(e) = event_loop.run_app(&mut app) {
        say!("error: the window's event loop failed: {e}");
        return 1;
    }
    app.code()
}
