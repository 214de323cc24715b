//! Temporal filtering (Wyman & Davis 2006 Sec. 3.2.3): "we store photon counts from the
//! previous three frames and utilize them in conjunction with photons from the current frame".
//! A view's photon buffer (power and count per pixel) has four history layers, written in turn;
//! the gather reads the mean of those that hold a frame (`gather.comp`, `photons_of`). Only the
//! current frame's photon data (directions) is kept, as in the paper. Without the filter there
//! is one layer.

use std::cell::Cell;

/// Frames a filtered gather averages: the current one and the previous three.
pub const FILTERED_FRAMES: u32 = 4;

/// Which history layer a frame writes, and how many hold a frame.
pub struct History {
    layers: u32,
    /// The layer the next frame writes.
    next: Cell<u32>,
    /// Layers holding a frame (saturates at `layers`).
    filled: Cell<u32>,
}

impl History {
    pub fn new(filter: bool) -> History {
        History { layers: if filter { FILTERED_FRAMES } else { 1 }, next: Cell::new(0), filled: Cell::new(0) }
    }

    /// History layers per view (per light in light space).
    pub fn layers(&self) -> u32 {
        self.layers
    }

    /// The layer this frame writes.
    pub fn slot(&self) -> u32 {
        self.next.get()
    }

    /// Layers holding a frame once this frame is written (1..=layers).
    pub fn frames(&self) -> u32 {
        (self.filled.get() + 1).min(self.layers)
    }

    /// The frame was recorded: the next one writes the next layer.
    pub fn advance(&self) {
        self.next.set((self.next.get() + 1) % self.layers);
        self.filled.set((self.filled.get() + 1).min(self.layers));
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn four_layers_in_turn_and_the_count_of_frames_saturates() {
        let h = History::new(true);
        let mut seen = vec![];
        for _ in 0..6 {
            seen.push((h.slot(), h.frames()));
            h.advance();
        }
        assert_eq!(seen, vec![(0, 1), (1, 2), (2, 3), (3, 4), (0, 4), (1, 4)]);
        let off = History::new(false);
        off.advance();
        assert_eq!((off.layers(), off.slot(), off.frames()), (1, 0, 1));
    }
}
