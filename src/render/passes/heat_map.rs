//! The importance heat map: one value per vertex (how much of the selected light reaches
//! it, say) drawn as colour on the meshes instead of the shading, so an artist sees where
//! a light matters. Pure colour mapping here, plus its small pipeline.

use wgpu::util::DeviceExt;

use super::raster::{draw_meshes, mesh_pipeline};
use crate::render::descriptors::create_module;
use crate::render::resources::{GpuScene, SceneLayouts};
use crate::render::target::RenderTarget;
use crate::shading::wgsl;

/// The heat colours from cold to hot, sRGB: near-black blue, purple, red, orange, pale
/// yellow (a perceptually ordered ramp like the "inferno" family).
const RAMP_SRGB: [[f32; 3]; 5] = [
    [0.05, 0.03, 0.18],
    [0.42, 0.09, 0.50],
    [0.80, 0.20, 0.30],
    [0.98, 0.55, 0.10],
    [0.99, 0.96, 0.64],
];

/// The linear RGB heat colour of `t` in [0, 1] (clamped; NaN counts as 0).
pub fn heat_color(t: f32) -> [f32; 3] {
    let t = if t.is_nan() { 0.0 } else { t.clamp(0.0, 1.0) };
    let x = t * (RAMP_SRGB.len() - 1) as f32;
    let i = (x.floor() as usize).min(RAMP_SRGB.len() - 2);
    let f = x - i as f32;
    let (a, b) = (RAMP_SRGB[i], RAMP_SRGB[i + 1]);
    [0, 1, 2].map(|c| srgb_to_linear(a[c] + f * (b[c] - a[c])))
}

fn srgb_to_linear(c: f32) -> f32 {
    if c <= 0.04045 {
        c / 12.92
    } else {
        ((c + 0.055) / 1.055).powf(2.4)
    }
}

/// The scale the values are shown against: their 99th percentile (so one hot vertex does
/// not wash out the rest), at least the smallest positive normal f32.
pub fn heat_scale(values: &[f32]) -> f32 {
    let mut finite: Vec<f32> = values.iter().copied().filter(|v| v.is_finite() && *v > 0.0).collect();
    if finite.is_empty() {
        return f32::MIN_POSITIVE;
    }
    let k = ((finite.len() - 1) as f32 * 0.99).round() as usize;
    let (_, value, _) = finite.select_nth_unstable_by(k, f32::total_cmp);
    value.max(f32::MIN_POSITIVE)
}

/// Draws the scene coloured by per-vertex heat instead of shaded.
pub struct HeatMapPipeline {
    pipeline: wgpu::RenderPipeline,
    frame_group: Option<wgpu::BindGroup>,
}

impl HeatMapPipeline {
    pub fn new(device: &wgpu::Device, layouts: &SceneLayouts, samples: u32) -> HeatMapPipeline {
        let module = create_module(device, "heat map", &wgsl::heat_map_source());
        HeatMapPipeline {
            pipeline: mesh_pipeline(device, layouts, &module, "fs_heat", samples),
            frame_group: None,
        }
    }

    /// Sets the values, one list per object of the scene `scene` was uploaded from (an
    /// object's list as long as its vertex count; missing values are cold), shown as
    /// √(value / scale) on the ramp; None clears the map.
    pub fn set_values(
        &mut self,
        device: &wgpu::Device,
        layouts: &SceneLayouts,
        scene: &GpuScene,
        values: Option<(&[Vec<f32>], f32)>,
    ) {
        let Some((values, scale)) = values else {
            self.frame_group = None;
            return;
        };
        let mut colors: Vec<[f32; 3]> = Vec::with_capacity(scene.vertex_total() as usize);
        for object in &scene.objects {
            let of_object = values.get(object.source).map_or(&[][..], Vec::as_slice);
            colors.extend((0..object.vertex_count as usize).map(|v| {
                let value = of_object.get(v).copied().unwrap_or(0.0);
                // Square root: equal steps of colour are closer to equal steps of
                // perceived brightness than linear luminance is.
                heat_color((value / scale).max(0.0).sqrt())
            }));
        }
        colors.push([0.0; 3]); // never an empty buffer
        let buffer = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some("heat colours"),
            contents: bytemuck::cast_slice(&colors),
            usage: wgpu::BufferUsages::STORAGE,
        });
        self.frame_group = Some(scene.frame_bind_group_with(device, layouts, &buffer));
    }

    pub fn is_set(&self) -> bool {
        self.frame_group.is_some()
    }

    /// Clears `target` and draws the heat map; false (nothing drawn) without values.
    pub fn draw(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        target: &RenderTarget,
        scene: &GpuScene,
        background_linear: [f64; 3],
    ) -> bool {
        let Some(group) = &self.frame_group else { return false };
        draw_meshes(encoder, target, &self.pipeline, group, scene, background_linear);
        true
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_ramp_runs_from_dark_to_bright_and_clamps() {
        let luma = |c: [f32; 3]| 0.2126 * c[0] + 0.7152 * c[1] + 0.0722 * c[2];
        let mut previous = -1.0;
        for k in 0..=20 {
            let l = luma(heat_color(k as f32 / 20.0));
            assert!(l > previous, "luminance rises along the ramp");
            previous = l;
        }
        assert_eq!(heat_color(-3.0), heat_color(0.0));
        assert_eq!(heat_color(7.0), heat_color(1.0));
        assert_eq!(heat_color(f32::NAN), heat_color(0.0));
    }

    #[test]
    fn the_scale_ignores_the_hottest_percent_and_bad_values() {
        let mut values: Vec<f32> = (1..=1000).map(|v| v as f32).collect();
        values.extend([1e30, f32::NAN, f32::INFINITY, -5.0]);
        let scale = heat_scale(&values);
        assert!((985.0..=995.0).contains(&scale), "{scale}");
        assert_eq!(heat_scale(&[]), f32::MIN_POSITIVE);
        assert_eq!(heat_scale(&[0.0, f32::NAN]), f32::MIN_POSITIVE);
    }
}
