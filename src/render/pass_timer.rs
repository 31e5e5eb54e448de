//! GPU time of a frame's passes, from timestamps the GPU writes between them
//! (`wgpu::Features::TIMESTAMP_QUERY_INSIDE_ENCODERS`; lavapipe has them). What
//! `lightpaint render --time-frames` prints per pass, so that docs/performance.md can say
//! where a frame's time goes. Adapters without timestamps get no timer (`new` is None).

/// Timestamps one frame can hold: far more than the passes a frame has.
const MAX_MARKS: u32 = 32;
const BYTES: u64 = MAX_MARKS as u64 * 8;

/// Marks written between passes, read back after each frame, summed per pass.
pub struct PassTimer {
    queries: wgpu::QuerySet,
    resolved: wgpu::Buffer,
    readback: wgpu::Buffer,
    /// This frame's marks so far: the pass that ends at each.
    marks: Vec<&'static str>,
    /// Per pass (in the order first seen): total milliseconds and frames.
    totals: Vec<(&'static str, f64, u32)>,
}

impl PassTimer {
    /// A timer, if `device` was created with timestamps inside encoders.
    pub fn new(device: &wgpu::Device) -> Option<PassTimer> {
        if !device
            .features()
            .contains(wgpu::Features::TIMESTAMP_QUERY | wgpu::Features::TIMESTAMP_QUERY_INSIDE_ENCODERS)
        {
            return None;
        }
        let buffer = |label, usage| {
            device.create_buffer(&wgpu::BufferDescriptor {
                label: Some(label),
                size: BYTES,
                usage,
                mapped_at_creation: false,
            })
        };
        Some(PassTimer {
            queries: device.create_query_set(&wgpu::QuerySetDescriptor {
                label: Some("pass timestamps"),
                ty: wgpu::QueryType::Timestamp,
                count: MAX_MARKS,
            }),
            resolved: buffer(
                "pass timestamps resolved",
                wgpu::BufferUsages::QUERY_RESOLVE | wgpu::BufferUsages::COPY_SRC,
            ),
            readback: buffer(
                "pass timestamps read back",
                wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST,
            ),
            marks: Vec::new(),
            totals: Vec::new(),
        })
    }

    /// Writes a timestamp: the work recorded since the previous mark is `pass`'s (the first
    /// mark of a frame only starts the clock).
    pub fn mark(&mut self, encoder: &mut wgpu::CommandEncoder, pass: &'static str) {
        let index = self.marks.len() as u32;
        if index < MAX_MARKS {
            encoder.write_timestamp(&self.queries, index);
            self.marks.push(pass);
        }
    }

    /// Reads this frame's marks back (waiting for the GPU) and adds them to the totals.
    pub fn collect(&mut self, device: &wgpu::Device, queue: &wgpu::Queue) -> Result<(), wgpu::PollError> {
        let count = self.marks.len() as u32;
        if count < 2 {
            self.marks.clear();
            return Ok(());
        }
        let mut encoder = device.create_command_encoder(&Default::default());
        encoder.resolve_query_set(&self.queries, 0..count, &self.resolved, 0);
        encoder.copy_buffer_to_buffer(&self.resolved, 0, &self.readback, 0, BYTES);
        queue.submit([encoder.finish()]);
        let slice = self.readback.slice(..);
        slice.map_async(wgpu::MapMode::Read, |_| {});
        device.poll(wgpu::PollType::wait_indefinitely())?;
        let ticks: Vec<u64> = match slice.get_mapped_range() {
            Ok(bytes) => bytemuck::cast_slice(&bytes).to_vec(),
            Err(_) => Vec::new(),
        };
        self.readback.unmap();
        let ns_per_tick = f64::from(queue.get_timestamp_period());
        for (k, pass) in self
            .marks
            .iter()
            .enumerate()
            .skip(1)
            .take(ticks.len().saturating_sub(1))
        {
            let ms = ticks[k].saturating_sub(ticks[k - 1]) as f64 * ns_per_tick * 1e-6;
            match self.totals.iter_mut().find(|(name, _, _)| name == pass) {
                Some(total) => {
                    total.1 += ms;
                    total.2 += 1;
                }
                None => self.totals.push((pass, ms, 1)),
            }
        }
        self.marks.clear();
        Ok(())
    }

    /// Mean milliseconds per frame of each pass, in the order the passes run.
    pub fn mean_ms(&self) -> Vec<(&'static str, f64)> {
        self.totals
            .iter()
            .map(|&(pass, total, frames)| (pass, total / f64::from(frames.max(1))))
            .collect()
    }
}

/// Marks `pass`'s end on `timer`, if there is one.
pub fn mark(timer: &mut Option<PassTimer>, encoder: &mut wgpu::CommandEncoder, pass: &'static str) {
    if let Some(timer) = timer {
        timer.mark(encoder, pass);
    }
}

/// A frame's command encoder with the timer (if any) that marks its passes' ends.
pub struct TimedEncoder<'a> {
    pub encoder: &'a mut wgpu::CommandEncoder,
    pub timer: &'a mut Option<PassTimer>,
}

impl TimedEncoder<'_> {
    /// Marks the end of `pass` (see [`PassTimer::mark`]).
    pub fn mark(&mut self, pass: &'static str) {
        mark(self.timer, self.encoder, pass);
    }
}
