//! A bake running on a background thread while the editor stays responsive: progress for
//! the panel (with an ETA from the rate so far), cancellation that keeps nothing, and the
//! maps handed over when it finishes.

use std::path::PathBuf;
use std::sync::Arc;
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};
use std::thread::JoinHandle;
use std::time::{Duration, Instant};

use crate::bake::{BakeSettings, ImportanceMaps, bake_maps_with, rebake_lights};
use crate::project::bake_cache::bake_with_cache;
use crate::scene::Scene;

pub struct BakeJob {
    done: Arc<AtomicUsize>,
    total: usize,
    cancel: Arc<AtomicBool>,
    started: Instant,
    handle: Option<JoinHandle<Option<(ImportanceMaps, String)>>>,
}

/// What a poll of the job found.
pub enum BakePoll {
    Running,
    /// The maps and what happened (baked, read from the cache, …).
    Finished(ImportanceMaps, String),
    Cancelled,
}

impl BakeJob {
    /// Starts baking a copy of `scene` on its own thread (which uses rayon's pool); with a
    /// `cache` file, reads it when it is fresh and writes it after a bake.
    pub fn start(scene: &Scene, settings: BakeSettings, cache: Option<PathBuf>) -> BakeJob {
        BakeJob::spawn(scene, move |scene, progress, cancel| match cache {
            Some(path) => bake_with_cache(scene, &settings, &path, progress, cancel),
            None => bake_maps_with(scene, &settings, progress, cancel).map(|m| (m, "baked".to_string())),
        })
    }

    /// Re-bakes only `lights` of a copy of `scene` on its own thread, keeping every other
    /// light's maps from `previous` (see [`rebake_lights`]).
    pub fn start_rebake(
        scene: &Scene,
        settings: BakeSettings,
        previous: ImportanceMaps,
        lights: Vec<usize>,
    ) -> BakeJob {
        BakeJob::spawn(scene, move |scene, progress, cancel| {
            let count = lights.len();
            rebake_lights(scene, &settings, &previous, &lights, progress, cancel)
                .map(|maps| (maps, format!("re-baked {count} moved light(s)")))
        })
    }

    /// Runs `work` on a copy of `scene` on its own thread, with progress and cancellation.
    fn spawn<F>(scene: &Scene, work: F) -> BakeJob
    where
        F: FnOnce(&Scene, &(dyn Fn(usize, usize) + Sync), &AtomicBool) -> Option<(ImportanceMaps, String)>
            + Send
            + 'static,
    {
        let scene = scene.clone();
        let done = Arc::new(AtomicUsize::new(0));
        let cancel = Arc::new(AtomicBool::new(false));
        let total = scene.vertex_count();
        let (done_in, cancel_in) = (done.clone(), cancel.clone());
        let handle = std::thread::spawn(move || {
            let progress = |finished, _| done_in.store(finished, Ordering::Relaxed);
            work(&scene, &progress, &cancel_in)
        });
        BakeJob {
            done,
            total,
            cancel,
            started: Instant::now(),
            handle: Some(handle),
        }
    }

    /// Share of the vertices baked, 0–1.
    pub fn fraction(&self) -> f32 {
        if self.total == 0 {
            return 1.0;
        }
        self.done.load(Ordering::Relaxed) as f32 / self.total as f32
    }

    /// Time left at the rate so far, once there is a rate to go by.
    pub fn eta(&self) -> Option<Duration> {
        let fraction = self.fraction() as f64;
        let elapsed = self.started.elapsed().as_secs_f64();
        (fraction > 0.02 && fraction < 1.0).then(|| Duration::from_secs_f64(elapsed * (1.0 - fraction) / fraction))
    }

    pub fn elapsed(&self) -> Duration {
        self.started.elapsed()
    }

    pub fn cancel(&self) {
        self.cancel.store(true, Ordering::Relaxed);
    }

    /// Collects the result once the thread has finished.
    pub fn poll(&mut self) -> BakePoll {
        if self.handle.as_ref().is_some_and(|h| !h.is_finished()) {
            return BakePoll::Running;
        }
        match self.handle.take().map(JoinHandle::join) {
            Some(Ok(Some((maps, what)))) => BakePoll::Finished(maps, what),
            _ => BakePoll::Cancelled,
        }
    }
}

impl Drop for BakeJob {
    fn drop(&mut self) {
        // A job dropped with its document (closing, opening another) stops working.
        self.cancel();
    }
}
