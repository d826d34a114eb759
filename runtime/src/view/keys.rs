//! The viewer's keys: channel, tracer, anti-aliasing, parameters, time, camera, saving and
//! quitting.

use super::app::App;
use super::live::Live;
use sdfc::images::Channel;
use sdfc_compiler::check::TIME;
use sdfc_compiler::lipschitz::too_small_at;
use std::path::PathBuf;
use winit::event_loop::ActiveEventLoop;

impl App {
    /// A key (as text): the viewer's commands.
    pub(super) fn key(&mut self, event_loop: &ActiveEventLoop, k: &str) {
        let Some(live) = self.started.as_mut().map(|s| &mut s.live) else {
            return;
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
            "[" | "]" => select(live, k == "]"),
            "-" | "=" | "+" => change(live, k != "-"),
            "s" => {
                // The last finished picture, numbered apart from `--screenshots`.
                self.saved += 1;
                save(live, self.saved);
                return;
            }
            c => match channel(c) {
                Some(ch) => live.channel = ch,
                None => return,
            },
        }
        live.touch();
        self.title();
    }
}

/// The channel a digit key shows.
fn channel(key: &str) -> Option<Channel> {
    match key {
        "1" => Some(Channel::Color),
        "2" => Some(Channel::Normal),
        "3" => Some(Channel::Depth),
        "4" => Some(Channel::Steps),
        "5" => Some(Channel::Material),
        _ => None,
    }
}

/// `[` and `]`: the previous or next parameter the keys may change (not `time`, which runs
/// with the clock).
fn select(live: &mut Live, forward: bool) {
    let n = live.scene.params.len().max(1);
    for _ in 0..n {
        live.selected = (live.selected + if forward { 1 } else { n - 1 }) % n;
        if live
            .scene
            .params
            .get(live.selected)
            .is_some_and(|p| p.name != TIME)
        {
            break;
        }
    }
}

/// `-` and `=`: the selected parameter a twentieth of its range down or up (0.1 without one).
fn change(live: &mut Live, up: bool) {
    let Some(p) = live
        .scene
        .params
        .get(live.selected)
        .filter(|p| p.name != TIME)
        .cloned()
    else {
        return;
    };
    let now = live
        .values
        .get(&p.name)
        .cloned()
        .unwrap_or_else(|| p.values());
    let next: Vec<f64> = now
        .iter()
        .enumerate()
        .map(|(i, &x)| match p.range {
            Some((lo, hi)) => {
                (x + (hi[i] - lo[i]) / 20.0 * if up { 1.0 } else { -1.0 }).clamp(lo[i], hi[i])
            }
            None => x + if up { 0.1 } else { -0.1 },
        })
        .collect();
    say!("{} = {next:?}", p.name);
    live.values.insert(p.name.clone(), next);
    verify(live);
}

/// The annotations checked at the parameter values the keys set (as `render --param` checks
/// them): each one too small there is said when the values first make it so.
fn verify(live: &mut Live) {
    let found = too_small_at(&live.scene, &live.values);
    let mut values: Vec<String> = live
        .values
        .iter()
        .map(|(k, v)| format!("{k} = {v:?}"))
        .collect();
    values.sort();
    for d in &found {
        if !live.too_small.contains(&d.span) {
            say!(
                "warning: with {}, {}: {}",
                values.join(", "),
                d.message,
                d.label
            );
        }
    }
    live.too_small = found.iter().map(|d| d.span).collect();
}

/// `s`: the last finished picture to `sdfc-view-NNN.png`.
fn save(live: &Live, number: u32) {
    let path = PathBuf::from(format!("sdfc-view-{number:03}.png"));
    let (w, h) = live.size();
    let written = sdfc::images::png(live.last_picture(), w, h)
        .map_err(|e| e.to_string())
        .and_then(|b| sdfc::files::write_file(&path, &b).map_err(|e| e.to_string()));
    match written {
        Ok(()) => say!("saved {}", path.display()),
        Err(e) => say!("error: cannot save `{}`: {e}", path.display()),
    }
}
