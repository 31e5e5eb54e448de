//! The status bar's frame rate: the time between frames drawn one after another, smoothed,
//! with the pauses of an editor at rest left out (egui draws only on input or animation,
//! so an idle editor's "frame time" would be the time since the last mouse move). A frame
//! that follows one which asked to be drawn again at once always counts, however long it
//! took: a large scene's frames of a third of a second are frames, not pauses.

use std::time::{Duration, Instant};

/// A gap between two frames longer than this is the editor waiting for input, not a
/// frame being drawn, unless the earlier frame asked for the next at once: it is not
/// counted.
pub const IDLE_GAP: Duration = Duration::from_millis(250);

/// Smoothed time per drawn frame.
#[derive(Debug, Default)]
pub struct FrameClock {
    last: Option<Instant>,
    smoothed_ms: Option<f32>,
}

impl FrameClock {
    /// A frame starts at `now`; `asked_at_once`: the frame before asked to be followed
    /// at once (egui's `requested_repaint_last_pass`), so the time since it started was
    /// spent drawing it, not waiting for input.
    pub fn tick(&mut self, now: Instant, asked_at_once: bool) {
        if let Some(gap) = self.last.map(|last| now.saturating_duration_since(last))
            && (gap <= IDLE_GAP || asked_at_once)
        {
            let ms = gap.as_secs_f32() * 1000.0;
            // Exponential smoothing keeps the readout legible.
            self.smoothed_ms = Some(self.smoothed_ms.map_or(ms, |s| 0.9 * s + 0.1 * ms));
        }
        self.last = Some(now);
    }

    /// Milliseconds per frame while frames follow each other; None before two have.
    pub fn ms_per_frame(&self) -> Option<f32> {
        self.smoothed_ms
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn pauses_at_rest_are_not_frames() {
        let start = Instant::now();
        let mut clock = FrameClock::default();
        clock.tick(start, false);
        assert_eq!(clock.ms_per_frame(), None);
        // Frames every 20 ms, then three seconds at rest, then frames again.
        for k in 1..=10 {
            clock.tick(start + Duration::from_millis(20 * k), false);
        }
        let drawing = clock.ms_per_frame().expect("frames were drawn");
        assert!((drawing - 20.0).abs() < 0.01, "{drawing}");
        clock.tick(start + Duration::from_millis(3200), false);
        assert_eq!(clock.ms_per_frame(), Some(drawing), "the pause is not counted");
        clock.tick(start + Duration::from_millis(3220), false);
        assert!((clock.ms_per_frame().unwrap() - 20.0).abs() < 0.01);
    }

    #[test]
    fn slow_frames_asked_for_at_once_are_frames() {
        let start = Instant::now();
        let mut clock = FrameClock::default();
        clock.tick(start, false);
        // A large scene redrawn continuously: 400 ms a frame, each asking for the next.
        for k in 1..=5 {
            clock.tick(start + Duration::from_millis(400 * k), true);
        }
        let drawing = clock.ms_per_frame().expect("slow frames are still frames");
        assert!((drawing - 400.0).abs() < 0.01, "{drawing}");
        // Then the editor rests: the first frame after is drawn on input, not asked for.
        clock.tick(start + Duration::from_millis(6000), false);
        assert_eq!(clock.ms_per_frame(), Some(drawing), "the pause is not counted");
    }
}
