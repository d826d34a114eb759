//! The viewer's window events: mouse and keys, redraws, resizing, reloads after a save, and
//! rest (no redraw while nothing changes).

use super::app::App;
use super::live::Live;
use super::script::Step;
use super::watch::{SETTLE, Watched};
use std::time::Instant;
use winit::application::ApplicationHandler;
use winit::event::{ElementState, MouseButton, MouseScrollDelta, WindowEvent};
use winit::event_loop::{ActiveEventLoop, ControlFlow};
use winit::keyboard::{Key, NamedKey};
use winit::window::WindowId;

impl ApplicationHandler<Watched> for App {
    fn resumed(&mut self, event_loop: &ActiveEventLoop) {
        if self.started.is_none()
            && let Err(e) = self.start(event_loop)
        {
            self.fail(event_loop, e);
        }
    }

    fn user_event(&mut self, _: &ActiveEventLoop, event: Watched) {
        match event {
            Watched::Changed => self.reload_at = Some(Instant::now() + SETTLE),
            Watched::Gone => {
                say!(
                    "`{}` was deleted or moved away; watching for it to come back",
                    self.args.file.display()
                );
                self.missing = true;
                self.title();
            }
        }
    }

    fn window_event(&mut self, event_loop: &ActiveEventLoop, _: WindowId, event: WindowEvent) {
        match event {
            WindowEvent::CloseRequested => event_loop.exit(),
            WindowEvent::Resized(s) => {
                if let Some(started) = self.started.as_mut() {
                    started.config.width = s.width.max(1);
                    started.config.height = s.height.max(1);
                    started.gpu().configure(&started.surface, &started.config);
                    if let Err(e) = started.live.resize((s.width, s.height)) {
                        self.fail(event_loop, e);
                    }
                }
            }
            WindowEvent::RedrawRequested => {
                if let Err(e) = self.frame(event_loop) {
                    self.fail(event_loop, e);
                }
            }
            WindowEvent::MouseInput { state, button, .. } => {
                self.drag = (state == ElementState::Pressed).then_some(button);
            }
            WindowEvent::CursorMoved { position, .. } => {
                let (dx, dy) = (position.x - self.pointer.0, position.y - self.pointer.1);
                self.pointer = (position.x, position.y);
                match self.drag {
                    Some(MouseButton::Left) => self.apply(event_loop, Step::Drag(dx, dy)),
                    Some(MouseButton::Right | MouseButton::Middle) => {
                        self.apply(event_loop, Step::Pan(dx, dy))
                    }
                    _ => {}
                }
            }
            WindowEvent::MouseWheel { delta, .. } => {
                let steps = match delta {
                    MouseScrollDelta::LineDelta(_, y) => f64::from(y),
                    MouseScrollDelta::PixelDelta(p) => p.y / 40.0,
                };
                self.apply(event_loop, Step::Zoom(steps));
            }
            WindowEvent::KeyboardInput { event, .. } if event.state == ElementState::Pressed => {
                let k = match &event.logical_key {
                    Key::Character(c) => c.to_string(),
                    Key::Named(NamedKey::Escape) => "Escape".into(),
                    Key::Named(NamedKey::Home) => "Home".into(),
                    Key::Named(NamedKey::Space) => "Space".into(),
                    _ => return,
                };
                self.key(event_loop, &k);
            }
            _ => {}
        }
    }

    fn about_to_wait(&mut self, event_loop: &ActiveEventLoop) {
        if let Some(at) = self.reload_at {
            if Instant::now() >= at {
                self.reload_at = None;
                self.reload(event_loop);
            } else {
                event_loop.set_control_flow(ControlFlow::WaitUntil(at));
                return;
            }
        }
        // Nothing to do when the picture is finished and nothing moves: the CPU rests.
        if let Some(started) = &self.started
            && Live::busy(&started.live)
        {
            started.window.request_redraw();
        }
        event_loop.set_control_flow(ControlFlow::Wait);
    }
}
