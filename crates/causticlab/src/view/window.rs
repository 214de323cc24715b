//! The winit side of the viewer: an application handler that makes the window when the event
//! loop starts and keeps the window's events for the viewer's own loop, which pumps the event
//! loop once a frame (`EventLoopExtPumpEvents`) so that the renderer, its device and the
//! presenter live on the viewer's stack, not inside the event loop.

use std::sync::Arc;
use winit::application::ApplicationHandler;
use winit::dpi::PhysicalSize;
use winit::event::WindowEvent;
use winit::event_loop::ActiveEventLoop;
use winit::window::{Window, WindowId};

pub struct Handler {
    title: String,
    size: (u32, u32),
    pub window: Option<Arc<Window>>,
    /// Window events since the viewer last took them.
    pub events: Vec<WindowEvent>,
    /// The window could not be made.
    pub error: Option<String>,
}

impl Handler {
    pub fn new(title: String, size: (u32, u32)) -> Handler {
        Handler { title, size, window: None, events: vec![], error: None }
    }
}

impl ApplicationHandler for Handler {
    fn resumed(&mut self, event_loop: &ActiveEventLoop) {
        if self.window.is_some() {
            return;
        }
        let attributes = Window::default_attributes()
            .with_title(self.title.clone())
            .with_inner_size(PhysicalSize::new(self.size.0, self.size.1));
        match event_loop.create_window(attributes) {
            Ok(w) => self.window = Some(Arc::new(w)),
            Err(e) => self.error = Some(e.to_string()),
        }
    }

    fn window_event(&mut self, _event_loop: &ActiveEventLoop, _id: WindowId, event: WindowEvent) {
        self.events.push(event);
    }
}
