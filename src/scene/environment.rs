//! Environment lighting from an equirectangular HDR image, kept as order-3 SH of radiance
//! (9 RGB coefficients, world axes, shading-model.md conventions) — enough for diffuse light,
//! whose clamped-cosine filter leaves under 1 % of the energy above band 2.

use std::f64::consts::PI;
use std::path::{Path, PathBuf};

use glam::DVec3;

use super::SceneError;

/// SH order of environment radiance.
pub const ENVIRONMENT_SH_ORDER: usize = 3;

#[derive(Debug, Clone, PartialEq)]
pub struct Environment {
    /// The .hdr file it came from (empty for generated environments).
    pub hdr: PathBuf,
    /// Multiplier on the image's radiance.
    pub intensity: f32,
    /// Rotation about world +y, radians.
    pub rotation_rad: f32,
    /// Radiance SH (9 coefficients × RGB) of the image, before `intensity`.
    pub radiance_sh: Vec<[f64; 3]>,
}

impl Environment {
    /// A constant environment of radiance `radiance` (W/sr/m² in linear RGB units).
    pub fn uniform(radiance: [f64; 3]) -> Environment {
        let c0 = (4.0 * PI).sqrt();
        let mut radiance_sh = vec![[0.0; 3]; ENVIRONMENT_SH_ORDER * ENVIRONMENT_SH_ORDER];
        radiance_sh[0] = radiance.map(|r| r * c0);
        Environment {
            hdr: PathBuf::new(),
            intensity: 1.0,
            rotation_rad: 0.0,
            radiance_sh,
        }
    }

    /// Loads an equirectangular Radiance .hdr (or any float image the image crate reads):
    /// +y up, the image's left edge at azimuth −x, turning towards −z... see
    /// [`equirect_direction`].
    pub fn load(hdr: &Path, intensity: f32, rotation_rad: f32) -> Result<Environment, SceneError> {
        if !hdr.exists() {
            return Err(SceneError::NotFound {
                path: hdr.to_path_buf(),
            });
        }
        let image = image::open(hdr)
            .map_err(|e| SceneError::Malformed {
                path: hdr.to_path_buf(),
                reason: format!("cannot read the environment image: {e}"),
            })?
            .to_rgb32f();
        let pixels: Vec<[f32; 3]> = image.pixels().map(|p| p.0).collect();
        if let Some(bad) = pixels.iter().position(|p| p.iter().any(|v| !v.is_finite() || *v < 0.0)) {
            return Err(SceneError::invalid(
                hdr,
                format!("pixel {bad} is not a finite, non-negative radiance"),
            ));
        }
        Ok(Environment {
            hdr: hdr.to_path_buf(),
            intensity,
            rotation_rad,
            radiance_sh: project_equirect(image.width() as usize, image.height() as usize, &pixels),
        })
    }

    /// Radiance SH in world axes: the image's, rotated about +y and scaled by `intensity`.
    pub fn world_radiance_sh(&self) -> Vec<[f64; 3]> {
        let rotation = glam::DMat3::from_rotation_y(self.rotation_rad as f64);
        let channels: Vec<Vec<f64>> = (0..3)
            .map(|c| {
                let f: Vec<f64> = self.radiance_sh.iter().map(|rgb| rgb[c]).collect();
                crate::sh::rotate(&f, rotation)
            })
            .collect();
        (0..self.radiance_sh.len())
            .map(|i| [0, 1, 2].map(|c| channels[c][i] * self.intensity as f64))
            .collect()
    }
}

/// Direction of the centre of pixel (column, row) of a width × height equirectangular
/// image: rows run from +y (top) to −y, columns turn once around +y starting at −z.
pub fn equirect_direction(column: usize, row: usize, width: usize, height: usize) -> DVec3 {
    let theta = PI * (row as f64 + 0.5) / height as f64;
    let phi = 2.0 * PI * (column as f64 + 0.5) / width as f64;
    DVec3::new(theta.sin() * phi.sin(), theta.cos(), -theta.sin() * phi.cos())
}

/// Order-3 SH projection of an equirectangular radiance image (row-major RGB), each pixel
/// weighted by its solid angle (2π/W)(π/H) sin θ.
pub fn project_equirect(width: usize, height: usize, pixels: &[[f32; 3]]) -> Vec<[f64; 3]> {
    let order = ENVIRONMENT_SH_ORDER;
    let mut sh = vec![[0.0f64; 3]; order * order];
    for row in 0..height {
        let theta = PI * (row as f64 + 0.5) / height as f64;
        let solid_angle = (2.0 * PI / width as f64) * (PI / height as f64) * theta.sin();
        for column in 0..width {
            let radiance = pixels[row * width + column];
            let y = crate::sh::basis(order, equirect_direction(column, row, width, height));
            for (coefficient, basis_value) in sh.iter_mut().zip(y) {
                for c in 0..3 {
                    coefficient[c] += radiance[c] as f64 * basis_value * solid_angle;
                }
            }
        }
    }
    sh
}

/// Irradiance SH: radiance convolved with the clamped cosine, E_lm = √(4π/(2l+1))·ĉ_l·L_lm
/// with ĉ_l the ZH of max(cos θ, 0) (Funk–Hecke). Evaluating it at a normal gives the
/// irradiance E(n) = ∫ L(ω) max(n·ω, 0) dω.
pub fn irradiance_sh(radiance_sh: &[[f64; 3]]) -> Vec<[f64; 3]> {
    let order = crate::sh::order_of(radiance_sh.len()).expect("square SH length");
    let cosine: Vec<f64> = crate::sh::clamped_cosine_zh(order)
        .into_iter()
        .map(|z| z * PI)
        .collect();
    radiance_sh
        .iter()
        .enumerate()
        .map(|(i, rgb)| {
            let l = (i as f64).sqrt() as usize;
            let scale = (4.0 * PI / (2 * l + 1) as f64).sqrt() * cosine[l];
            rgb.map(|v| v * scale)
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_uniform_image_projects_to_its_dc_and_irradiance_pi_l() {
        let (w, h) = (128, 64);
        let pixels = vec![[2.0f32, 1.0, 0.5]; w * h];
        let sh = project_equirect(w, h, &pixels);
        // The midpoint rule in θ errs by O(1/rows²): about 1e-3 at 64 rows.
        assert!((sh[0][0] / (4.0 * PI).sqrt() - 2.0).abs() < 2e-3, "{:?}", sh[0]);
        assert!(
            sh[1..].iter().all(|c| c.iter().all(|v| v.abs() < 1e-3 * sh[0][0])),
            "{sh:?}"
        );
        let e = irradiance_sh(&Environment::uniform([1.0, 1.0, 1.0]).radiance_sh);
        let at_up = crate::sh::evaluate(&e.iter().map(|c| c[0]).collect::<Vec<_>>(), DVec3::Y);
        assert!((at_up - PI).abs() < 1e-9, "E = {at_up}");
    }

    #[test]
    fn a_sky_brighter_above_lights_upward_normals_more() {
        let (w, h) = (32, 16);
        let pixels: Vec<[f32; 3]> = (0..w * h)
            .map(|i| if i / w < h / 2 { [1.0; 3] } else { [0.0; 3] })
            .collect();
        let e = irradiance_sh(&project_equirect(w, h, &pixels));
        let red: Vec<f64> = e.iter().map(|c| c[0]).collect();
        let (up, down) = (
            crate::sh::evaluate(&red, DVec3::Y),
            crate::sh::evaluate(&red, DVec3::NEG_Y),
        );
        // Exact: a bright upper hemisphere gives π at the zenith, 0 at the nadir; order 3
        // smooths that to about 2.9 and 0.2.
        assert!(up > 2.7 && down < 0.4, "up {up}, down {down}");
    }
}
