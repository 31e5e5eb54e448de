//! The knob settings a study measures: every order and exponentiation method crossed
//! (the CPU's exact exponential up to order 6),
//! then one knob at a time around the defaults (ε, ratio attenuation, the BRDF in the SH, blocker count,
//! per-vertex shading, and on terrain the azimuth count and pyramid levels), plus no
//! shadows at all as the baseline; and the defaults against the global-illumination
//! reference, with and without the bake's indirect light.

use crate::blockers::SphereBudget;
use crate::sh::ExpMethod;
use crate::shading::{BrdfShading, ShadowSettings};

/// One point of the grid.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Knobs {
    /// None: the plain raster pass, no shadows.
    pub shadows: Option<ShadowSettings>,
    pub blockers: SphereBudget,
    pub lighting: Lighting,
}

/// What light the frame is measured against.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Lighting {
    /// The direct-light reference (the real-time renderer's direct light alone).
    Direct,
    /// The reference with one bounce, the bake's default; `baked_indirect` adds the baked
    /// maps' indirect light to the frame.
    Gi { baked_indirect: bool },
}

impl Knobs {
    /// A short label for tables and file names, e.g. `o4-hyb-e0.1`.
    pub fn label(&self) -> String {
        let Some(s) = &self.shadows else {
            return "no-shadows".into();
        };
        let mut label = format!("o{}-{}-e{}", s.order, method_label(s.exp), s.epsilon);
        if s.ratio_attenuation {
            label.push_str("-ratio");
        }
        if s.per_vertex {
            label.push_str("-vertex");
        }
        if s.shading_downsample > 1 {
            label.push_str(&format!("-d{}", s.shading_downsample));
        }
        if s.brdf != crate::shading::BrdfShading::Separate {
            label.push_str(&format!("-{}-brdf", s.brdf.name()));
        }
        if s.shadow_map_size != crate::shading::DEFAULT_SHADOW_MAP_SIZE {
            label.push_str(&format!("-m{}", s.shadow_map_size));
        }
        if let SphereBudget::Total(n) = self.blockers {
            label.push_str(&format!("-s{n}"));
        }
        if s.terrain != crate::shading::TerrainShading::default() {
            label.push_str(&format!("-w{}-l{}", s.terrain.azimuths, s.terrain.pyramid_levels));
        }
        match self.lighting {
            Lighting::Direct => {}
            Lighting::Gi { baked_indirect: false } => label.push_str("-gi"),
            Lighting::Gi { baked_indirect: true } => label.push_str("-gi-baked"),
        }
        label
    }

    /// Whether the CPU shades it (the reference exponential exists only there).
    pub fn on_cpu(&self) -> bool {
        self.shadows.is_some_and(|s| s.exp == ExpMethod::Reference)
    }
}

pub fn method_label(method: ExpMethod) -> String {
    match method {
        ExpMethod::Dc => "dc".into(),
        ExpMethod::Ol => "ol".into(),
        ExpMethod::Hyb => "hyb".into(),
        ExpMethod::Ps(k) => format!("ps{k}"),
        ExpMethod::Reference => "ref".into(),
    }
}

/// The defaults as the editor and `render` draw them (one pixel in d × d shaded).
pub fn shipped_defaults(default_blockers: SphereBudget) -> Knobs {
    Knobs {
        shadows: Some(ShadowSettings::default()),
        blockers: default_blockers,
        lighting: Lighting::Direct,
    }
}

/// The grid: `quick` keeps it to what runs in well under two minutes; a scene with a
/// `terrain` adds its azimuth counts W (at the default levels) and pyramid levels (at the
/// default W).
pub fn knob_grid(quick: bool, default_blockers: SphereBudget, terrain: bool) -> Vec<Knobs> {
    let defaults = ShadowSettings::default().every_pixel();
    let (orders, methods, epsilons, budgets): (Vec<usize>, Vec<ExpMethod>, Vec<f32>, Vec<usize>) = if quick {
        (
            vec![2, 4, 6],
            vec![ExpMethod::Dc, ExpMethod::Ol, ExpMethod::Hyb],
            vec![0.05, 0.3],
            vec![8, 48],
        )
    } else {
        (
            (2..=8).collect(),
            vec![
                ExpMethod::Dc,
                ExpMethod::Ol,
                ExpMethod::Hyb,
                ExpMethod::Ps(8),
                ExpMethod::Reference,
            ],
            vec![0.02, 0.05, 0.2, 0.3, 0.5],
            vec![4, 8, 16, 32, 64, 128],
        )
    };
    let with = |change: &dyn Fn(&mut ShadowSettings)| {
        let mut s = defaults;
        change(&mut s);
        Knobs {
            shadows: Some(s),
            blockers: default_blockers,
            lighting: Lighting::Direct,
        }
    };
    // The settings' grid shades every pixel, as the CPU reference does; the shipped
    // defaults shade one pixel in d × d and upsample the rest: what the editor shows.
    let mut grid = vec![
        Knobs {
            shadows: None,
            blockers: default_blockers,
            lighting: Lighting::Direct,
        },
        shipped_defaults(default_blockers),
    ];
    for &order in &orders {
        for &exp in &methods {
            // The CPU's exact exponential costs seconds a frame from order 7 on: up to
            // order 6 it already shows where the approximations stop mattering.
            if exp == ExpMethod::Reference && order > 6 {
                continue;
            }
            grid.push(with(&|s| {
                s.order = order;
                s.exp = exp;
            }));
        }
    }
    if quick {
        grid.push(with(&|s| s.exp = ExpMethod::Reference));
    }
    for &epsilon in &epsilons {
        grid.push(with(&|s| s.epsilon = epsilon));
    }
    grid.push(with(&|s| s.ratio_attenuation = true));
    // The BRDF carried in the SH (Ren et al.'s log-BRDF and product) against the default
    // separate shading, at the default order and at 8, which carries sharper lobes.
    let brdf_orders: Vec<usize> = if quick { vec![4] } else { vec![4, 8] };
    for order in brdf_orders {
        for brdf in [BrdfShading::Log, BrdfShading::Product] {
            grid.push(with(&|s| {
                s.order = order;
                s.brdf = brdf;
            }));
        }
    }
    // The shadow maps' size, the knob that should take their shadows to the path
    // tracer's as it rises (0: no maps, those lights take the exact path or the SH).
    let map_sizes: Vec<u32> = if quick { vec![] } else { vec![0, 512, 2048, 4096] };
    for size in map_sizes {
        grid.push(with(&|s| s.shadow_map_size = size));
        let mut shipped = shipped_defaults(default_blockers);
        if let Some(s) = shipped.shadows.as_mut() {
            s.shadow_map_size = size;
        }
        grid.push(shipped);
    }
    let per_vertex_orders: Vec<usize> = if quick { vec![4] } else { (2..=6).collect() };
    for order in per_vertex_orders {
        grid.push(with(&|s| {
            s.order = order;
            s.per_vertex = true;
        }));
    }
    for count in budgets {
        grid.push(Knobs {
            shadows: Some(defaults),
            blockers: SphereBudget::Total(count),
            lighting: Lighting::Direct,
        });
    }
    if terrain {
        for azimuths in [4, 8, 32] {
            grid.push(with(&|s| s.terrain.azimuths = azimuths));
        }
        for pyramid_levels in [1, 3] {
            grid.push(with(&|s| s.terrain.pyramid_levels = pyramid_levels));
        }
    }
    for baked_indirect in [false, true] {
        grid.push(Knobs {
            lighting: Lighting::Gi { baked_indirect },
            ..with(&|_| {})
        });
    }
    grid
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_grid_point_is_valid_and_labelled_once() {
        for (quick, terrain) in [(true, false), (false, false), (false, true)] {
            let grid = knob_grid(quick, SphereBudget::FitError(0.35), terrain);
            let mut labels: Vec<String> = grid.iter().map(Knobs::label).collect();
            for knobs in &grid {
                if let Some(s) = knobs.shadows {
                    let problems = if knobs.on_cpu() { s.problems() } else { s.gpu_problems() };
                    assert!(problems.is_empty(), "{}: {problems:?}", knobs.label());
                }
            }
            labels.sort();
            let before = labels.len();
            labels.dedup();
            assert_eq!(before, labels.len(), "labels are unique");
        }
    }
}
