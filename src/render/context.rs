use super::RenderError;

/// A wgpu device and queue, created headless or borrowed from the editor window.
#[derive(Clone)]
pub struct GpuContext {
    pub device: wgpu::Device,
    pub queue: wgpu::Queue,
    pub adapter_info: wgpu::AdapterInfo,
}

impl GpuContext {
    /// Opens the best Vulkan, Metal or DX12 adapter without a window. `WGPU_BACKEND` and
    /// the other wgpu environment variables are honoured. On a machine without a GPU this
    /// is Mesa's lavapipe (software Vulkan); without it, [`RenderError::NoAdapter`].
    pub fn headless() -> Result<GpuContext, RenderError> {
        GpuContext::headless_with_limits(|limits| limits)
    }

    /// [`Self::headless`] with the device's limits changed by `limits` from those
    /// lightpaint asks for (tests of what a device with lower limits does).
    pub fn headless_with_limits(limits: impl FnOnce(wgpu::Limits) -> wgpu::Limits) -> Result<GpuContext, RenderError> {
        // No fallback to GL without `WGPU_BACKEND`: its shader translation has no
        // `textureLoad` of depth textures, which the shadow maps need, so a GL adapter
        // failed at the first pipeline (a panic inside wgpu) instead of here, with the
        // cause and the package to install.
        let adapter = request_adapter(primary_backends_unless_env())?;
        let adapter_info = adapter.get_info();
        let (device, queue) = pollster::block_on(adapter.request_device(&wgpu::DeviceDescriptor {
            label: Some("lightpaint"),
            required_limits: limits(wgpu::Limits::default().using_resolution(adapter.limits())),
            // For `render --time-frames`' time per pass (render::pass_timer), where the
            // adapter has them.
            required_features: adapter.features()
                & (wgpu::Features::TIMESTAMP_QUERY | wgpu::Features::TIMESTAMP_QUERY_INSIDE_ENCODERS),
            ..Default::default()
        }))
        .map_err(|e| RenderError::Device(e.to_string()))?;
        log::info!(
            "wgpu adapter: {} ({:?}, {:?})",
            adapter_info.name,
            adapter_info.device_type,
            adapter_info.backend
        );
        Ok(GpuContext {
            device,
            queue,
            adapter_info,
        })
    }

    /// A one-line description of the adapter, e.g. "llvmpipe (LLVM 15.0.6, 256 bits) (Cpu, Vulkan)".
    pub fn adapter_summary(&self) -> String {
        describe_adapter(&self.adapter_info)
    }
}

/// Instance options from the environment; without `WGPU_BACKEND`, only the primary
/// backends, so that a GPU-less machine does not probe (and log errors from) EGL.
fn primary_backends_unless_env() -> wgpu::InstanceDescriptor {
    let mut descriptor = wgpu::InstanceDescriptor::new_without_display_handle_from_env();
    if std::env::var_os("WGPU_BACKEND").is_none() {
        descriptor.backends = wgpu::Backends::PRIMARY;
    }
    descriptor
}

fn request_adapter(descriptor: wgpu::InstanceDescriptor) -> Result<wgpu::Adapter, RenderError> {
    let instance = wgpu::Instance::new(descriptor);
    pollster::block_on(instance.request_adapter(&wgpu::RequestAdapterOptions {
        power_preference: wgpu::PowerPreference::HighPerformance,
        ..Default::default()
    }))
    .map_err(|e| RenderError::NoAdapter(e.to_string()))
}

pub fn describe_adapter(info: &wgpu::AdapterInfo) -> String {
    format!("{} ({:?}, {:?})", info.name, info.device_type, info.backend)
}
