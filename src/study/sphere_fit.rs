//! Small lights over mesh blockers: how much of the exact path's error the sphere fit
//! causes, and how it falls with more spheres. The penumbra suite's floor and 5° sphere
//! light, with a box, a torus and a cylinder floating over the floor instead of balls;
//! the path tracer sees the meshes, the renderer spheres fitted to them with a total
//! budget (`SphereBudget::Total`) or the automatic fit. The exact path is exact for its
//! spheres, so its penumbra error is the fit's (plus the product over blockers treating
//! overlapping spheres as independent, which over-darkens where they overlap); the SH
//! path's error, band limit included, is measured beside it, and the shadow maps', which
//! see the meshes themselves ([`measure_mesh_maps`]).

use glam::{Affine3A, Quat, Vec3};

use super::StudyError;
use super::penumbra::{
    PenumbraRow, References, compare, compare_maps, floor_scene, overhead_camera, size_and_spp, sphere_light,
};
use crate::blockers::{BlockerSettings, SphereBudget, fit_scene};
use crate::render::{GpuContext, capture_surfaces};
use crate::scene::{MeshObject, shapes};
use crate::shading::{LightPaths, ShadowSettings};

/// The light measured: small enough that the SH path cannot draw its penumbra (§4b).
pub const LIGHT_HALF_ANGLE_DEG: f64 = 5.0;

/// One sphere budget.
#[derive(Debug, Clone, PartialEq)]
pub struct SphereFitRow {
    /// The budget asked for: "auto" or a total count.
    pub budget: String,
    pub spheres: usize,
    /// Mean over the casters of |mesh △ spheres| / |mesh| (volume, voxelised).
    pub fit_error: f64,
    /// RMS of the visibility error over the penumbra (a share of the unshadowed light).
    pub exact_penumbra_rms: f64,
    pub sh_penumbra_rms: f64,
    pub exact_umbra_rms: Option<f64>,
    /// RMS of the reference's own noise over the penumbra.
    pub reference_noise: f64,
}

/// A box, a torus and a cylinder, tilted, floating 0.4–1.2 m over the floor.
fn casters() -> Vec<MeshObject> {
    let place = |rotation: Quat, at: Vec3| Affine3A::from_rotation_translation(rotation, at);
    vec![
        shapes::cuboid(Vec3::new(0.4, 0.2, 0.3))
            .transformed(place(Quat::from_rotation_y(0.5), Vec3::new(0.0, 0.8, 0.0)))
            .into_object("box"),
        shapes::torus(0.35, 0.1, 64, 24)
            .transformed(place(Quat::from_rotation_x(0.6), Vec3::new(1.2, 0.7, 0.6)))
            .into_object("torus"),
        shapes::cylinder(0.12, 1.0, 48)
            .transformed(place(Quat::from_rotation_z(1.2), Vec3::new(-1.0, 1.0, -0.7)))
            .into_object("cylinder"),
    ]
}

/// Measures both paths at each sphere budget (`quick`: fewer budgets, a small image).
pub fn measure_sphere_fit(gpu: &GpuContext, quick: bool) -> Result<Vec<SphereFitRow>, StudyError> {
    let (size, spp) = size_and_spp(quick);
    let camera = overhead_camera();
    let light = sphere_light(LIGHT_HALF_ANGLE_DEG);
    let (scene, open) = (
        floor_scene(Some(light.clone()), casters()),
        floor_scene(Some(light), Vec::new()),
    );
    let surfaces = capture_surfaces(gpu, &scene, &camera, None, size, size)?;
    let reference = References::render(&scene, &open, &surfaces, camera.position, size, spp);
    let totals: &[usize] = if quick { &[3, 12] } else { &[3, 6, 12, 24, 48, 96, 192] };
    let budgets = totals
        .iter()
        .map(|&n| SphereBudget::Total(n))
        .chain([BlockerSettings::default().budget]);
    let mut rows = Vec::new();
    for budget in budgets {
        let fitted = fit_scene(
            &scene,
            &BlockerSettings {
                budget,
                ..BlockerSettings::default()
            },
        );
        let caster_sets: Vec<_> = fitted.per_object.iter().filter(|s| s.skipped.is_none()).collect();
        let fit_error = caster_sets.iter().map(|s| s.fit_error as f64).sum::<f64>() / caster_sets.len().max(1) as f64;
        let blockers = fitted.spheres();
        let path = |light_paths| {
            let shadows = ShadowSettings {
                light_paths,
                ..ShadowSettings::default().every_pixel()
            };
            compare(&scene, &surfaces, &reference, &shadows, &blockers, &camera)
        };
        let (exact, sh) = (path(LightPaths::Exact), path(LightPaths::Harmonics));
        rows.push(SphereFitRow {
            budget: match budget {
                SphereBudget::Total(n) => n.to_string(),
                SphereBudget::FitError(_) => "auto".into(),
            },
            spheres: blockers.len(),
            fit_error,
            exact_penumbra_rms: exact.penumbra_rms,
            sh_penumbra_rms: sh.penumbra_rms,
            exact_umbra_rms: exact.umbra_rms,
            reference_noise: exact.reference_noise,
        });
    }
    Ok(rows)
}

/// The shadow-map path on the same meshes (it needs no spheres): the GPU's maps of the
/// real triangles against the path tracer (`quick`: a small image).
pub fn measure_mesh_maps(gpu: &GpuContext, quick: bool) -> Result<PenumbraRow, StudyError> {
    let (size, spp) = size_and_spp(quick);
    let camera = overhead_camera();
    let light = sphere_light(LIGHT_HALF_ANGLE_DEG);
    let (scene, open) = (
        floor_scene(Some(light.clone()), casters()),
        floor_scene(Some(light.clone()), Vec::new()),
    );
    let surfaces = capture_surfaces(gpu, &scene, &camera, None, size, size)?;
    let reference = References::render(&scene, &open, &surfaces, camera.position, size, spp);
    let mut row = compare_maps(gpu, &scene, &open, &surfaces, &reference, &camera, size)?;
    row.light = light.name;
    Ok(row)
}

/// The rows as a markdown table.
pub fn markdown_table(rows: &[SphereFitRow]) -> String {
    let mut text = String::from(
        "| budget | spheres | fit error | exact penumbra RMS | exact umbra RMS | SH penumbra RMS | reference noise |\n\
         |---|---:|---:|---:|---:|---:|---:|\n",
    );
    for r in rows {
        text += &format!(
            "| {} | {} | {:.3} | {:.4} | {} | {:.4} | {:.4} |\n",
            r.budget,
            r.spheres,
            r.fit_error,
            r.exact_penumbra_rms,
            r.exact_umbra_rms.map_or("–".into(), |e| format!("{e:.4}")),
            r.sh_penumbra_rms,
            r.reference_noise
        );
    }
    text
}
