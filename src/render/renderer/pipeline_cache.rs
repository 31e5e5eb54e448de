//! The log-SH pipelines a renderer has compiled, keyed by everything that is compiled into
//! them ([`PipelineKey`]), and the one being compiled on a background thread: lavapipe
//! takes over a second for a high order, and the editor must keep drawing meanwhile.

use std::collections::HashMap;
use std::sync::Arc;

use crate::render::passes::logsh::LogShPipeline;
use crate::render::resources::SceneLayouts;
use crate::sh::ExpMethod;
use crate::shading::{BrdfShading, CompiledPaths, ShadowSettings};

/// What a [`LogShPipeline`] is compiled for: two frames with equal keys can share one.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct PipelineKey {
    pub order: usize,
    pub exp: ExpMethod,
    pub brdf: BrdfShading,
    /// Pixels per shaded sample along each side (1: every pixel).
    pub shading_downsample: u32,
    /// Samples per pixel of the targets it draws into.
    pub samples: u32,
    pub paths: CompiledPaths,
}

impl PipelineKey {
    pub fn new(settings: &ShadowSettings, samples: u32, paths: CompiledPaths) -> PipelineKey {
        PipelineKey {
            order: settings.order,
            exp: settings.exp,
            brdf: settings.brdf,
            shading_downsample: settings.shading_downsample,
            samples,
            paths,
        }
    }

    /// The shadow settings the pipeline is built from (the parts it compiles in).
    fn settings(self) -> ShadowSettings {
        ShadowSettings {
            order: self.order,
            exp: self.exp,
            brdf: self.brdf,
            shading_downsample: self.shading_downsample,
            ..ShadowSettings::default()
        }
    }

    fn compile(self, device: &wgpu::Device, layouts: &SceneLayouts) -> LogShPipeline {
        LogShPipeline::new(device, layouts, &self.settings(), self.samples, self.paths)
    }
}

/// How new pipelines are compiled.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Compilation {
    /// On a background thread; frames keep the previous pipeline meanwhile (the editor).
    Background,
    /// At once, on the calling thread (the CLI, tests, benchmarks).
    Blocking,
}

/// Compiled pipelines that stay cached: switching back to recent settings is instant.
const CACHED_PIPELINES: usize = 4;

pub struct PipelineCache {
    device: wgpu::Device,
    layouts: SceneLayouts,
    compilation: Compilation,
    /// Compiled pipelines with the time each was last asked for.
    compiled: HashMap<PipelineKey, (Arc<LogShPipeline>, u64)>,
    clock: u64,
    compiling: Option<(PipelineKey, std::thread::JoinHandle<LogShPipeline>)>,
}

impl PipelineCache {
    pub fn new(device: &wgpu::Device, layouts: &SceneLayouts, compilation: Compilation) -> PipelineCache {
        PipelineCache {
            device: device.clone(),
            layouts: layouts.clone(),
            compilation,
            compiled: HashMap::new(),
            clock: 0,
            compiling: None,
        }
    }

    /// The pipeline for `key`, compiled now whatever the compilation policy.
    pub fn get_now(&mut self, key: PipelineKey) -> Arc<LogShPipeline> {
        if let Some(pipeline) = self.lookup(key) {
            return pipeline;
        }
        let pipeline = Arc::new(key.compile(&self.device, &self.layouts));
        self.insert(key, pipeline.clone());
        pipeline
    }

    /// The pipeline for `key` if it is ready: at once when cached or compiled blocking,
    /// else None while a background thread compiles it (one at a time: asking for
    /// another key leaves the older compile to finish unused).
    pub fn request(&mut self, key: PipelineKey) -> Option<Arc<LogShPipeline>> {
        if let Some(pipeline) = self.lookup(key) {
            return Some(pipeline);
        }
        if self.compilation == Compilation::Blocking {
            return Some(self.get_now(key));
        }
        self.collect_finished();
        if let Some(pipeline) = self.lookup(key) {
            return Some(pipeline);
        }
        if self.compiling.as_ref().is_none_or(|(k, _)| *k != key) {
            let (device, layouts) = (self.device.clone(), self.layouts.clone());
            let handle = std::thread::spawn(move || key.compile(&device, &layouts));
            self.compiling = Some((key, handle));
        }
        None
    }

    /// The key being compiled in the background, if any.
    pub fn compiling(&self) -> Option<PipelineKey> {
        self.compiling.as_ref().map(|(key, _)| *key)
    }

    /// Stops waiting for a background compile (its result is dropped).
    pub fn forget_compiling(&mut self) {
        self.compiling = None;
    }

    /// Moves a finished background compile into the cache.
    fn collect_finished(&mut self) {
        if self.compiling.as_ref().is_none_or(|(_, handle)| !handle.is_finished()) {
            return;
        }
        if let Some((key, handle)) = self.compiling.take()
            && let Ok(pipeline) = handle.join()
        {
            self.insert(key, Arc::new(pipeline));
        }
    }

    fn lookup(&mut self, key: PipelineKey) -> Option<Arc<LogShPipeline>> {
        self.clock += 1;
        let clock = self.clock;
        self.compiled.get_mut(&key).map(|(pipeline, used)| {
            *used = clock;
            pipeline.clone()
        })
    }

    fn insert(&mut self, key: PipelineKey, pipeline: Arc<LogShPipeline>) {
        self.clock += 1;
        self.compiled.insert(key, (pipeline, self.clock));
        while self.compiled.len() > CACHED_PIPELINES {
            let oldest = self.compiled.iter().min_by_key(|(_, (_, used))| *used).map(|(k, _)| *k);
            if let Some(oldest) = oldest {
                self.compiled.remove(&oldest);
            }
        }
    }
}
