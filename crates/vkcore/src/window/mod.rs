//! Showing frames in a window (the viewer, `causticlab view`): the window's surface, a
//! swapchain recreated when the window changes size, and a presenter that copies an image the
//! frame rendered into the next swapchain image and draws an egui panel over it.

mod present;
mod surface;
mod swapchain;

pub use present::{Overlay, PresentOptions, Presented, Presenter};
pub use surface::Surface;
