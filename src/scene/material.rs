use glam::{Vec3, Vec4};

/// A glTF metallic-roughness material, with the documented mapping to the diffuse + glossy
/// (Phong) model the renderer uses (docs/architecture.md, "Materials").
#[derive(Debug, Clone, PartialEq)]
pub struct Material {
    pub name: String,
    /// Linear RGBA base colour factor.
    pub base_color: Vec4,
    /// Index into [`super::Scene::textures`] of the sRGB base colour texture (UV set 0).
    pub base_color_texture: Option<usize>,
    pub metallic: f32,
    pub roughness: f32,
    /// KHR_materials_specular `specularFactor` (1 when the extension is absent).
    pub specular: f32,
    /// Linear RGB emitted radiance factor (times KHR_materials_emissive_strength).
    pub emissive: Vec3,
    /// glTF `doubleSided`: both faces are seen. When every material of a scene is
    /// single-sided the renderer culls back faces, as glTF asks (see
    /// [`super::Scene::every_material_single_sided`]).
    pub double_sided: bool,
}

impl Default for Material {
    fn default() -> Self {
        // The glTF default material.
        Material {
            name: "default".into(),
            base_color: Vec4::ONE,
            base_color_texture: None,
            metallic: 1.0,
            roughness: 1.0,
            specular: 1.0,
            emissive: Vec3::ZERO,
            // glTF's default material is single-sided; the glTF importer says so per
            // material. Materials made in code keep both faces (planes seen from below).
            double_sided: true,
        }
    }
}

/// Rec. 709 luminance of a linear RGB colour: how the bake, the painting and the UI reduce
/// a colour to one number.
pub fn luminance(rgb: glam::DVec3) -> f64 {
    0.2126 * rgb.x + 0.7152 * rgb.y + 0.0722 * rgb.z
}

/// Reflectance of a dielectric at normal incidence (glTF's fixed 4 %).
pub const DIELECTRIC_F0: f32 = 0.04;

impl Material {
    /// Diffuse albedo k_d = baseColor · (1 − metallic) · (1 − k_s,dielectric): metals have
    /// no diffuse term, and what the dielectric specular reflects is not also diffused.
    pub fn diffuse_albedo(&self) -> Vec3 {
        let dielectric_specular = DIELECTRIC_F0 * self.specular;
        self.base_color.truncate() * (1.0 - self.metallic) * (1.0 - dielectric_specular)
    }

    /// Specular reflectance k_s = mix(0.04 · specular, baseColor, metallic).
    pub fn specular_color(&self) -> Vec3 {
        Vec3::splat(DIELECTRIC_F0 * self.specular).lerp(self.base_color.truncate(), self.metallic)
    }

    /// Phong exponent r of the glossy lobe ((r + 1) / 2π) cos^r, from glTF roughness by the
    /// usual Beckmann match r = 2/α² − 2 with α = roughness², clamped to [0, 10⁴].
    pub fn phong_exponent(&self) -> f32 {
        let alpha = (self.roughness * self.roughness).max(1e-2);
        (2.0 / (alpha * alpha) - 2.0).clamp(0.0, 1.0e4)
    }
}

impl Material {
    /// One line for the UI: the glTF values and what the renderer makes of them.
    pub fn summary(&self) -> String {
        let c = self.base_color;
        let (k_d, k_s) = (self.diffuse_albedo(), self.specular_color());
        let mut text = format!(
            "{}: base colour ({:.2}, {:.2}, {:.2}){}, metallic {:.2}, roughness {:.2} \
             -> diffuse ({:.2}, {:.2}, {:.2}), glossy ({:.2}, {:.2}, {:.2}) Phong {:.0}",
            self.name,
            c.x,
            c.y,
            c.z,
            if self.base_color_texture.is_some() {
                " x texture"
            } else {
                ""
            },
            self.metallic,
            self.roughness,
            k_d.x,
            k_d.y,
            k_d.z,
            k_s.x,
            k_s.y,
            k_s.z,
            self.phong_exponent()
        );
        if self.emissive != Vec3::ZERO {
            let e = self.emissive;
            text.push_str(&format!(", emissive ({:.2}, {:.2}, {:.2})", e.x, e.y, e.z));
        }
        text
    }
}

/// An 8-bit sRGB-encoded RGBA texture.
#[derive(Debug, Clone, PartialEq)]
pub struct TextureImage {
    pub name: String,
    pub width: u32,
    pub height: u32,
    /// Row-major RGBA8, sRGB-encoded colour, linear alpha.
    pub rgba8: Vec<u8>,
}

impl TextureImage {
    /// Linear RGB at `uv`, bilinear between texel centres, repeating (the renderer's
    /// sampler without its mip chain); white if the pixels are missing.
    pub fn sample_bilinear(&self, uv: glam::Vec2) -> glam::DVec3 {
        use glam::DVec3;
        let (w, h) = (self.width.max(1) as usize, self.height.max(1) as usize);
        if self.rgba8.len() < w * h * 4 || !uv.is_finite() {
            return DVec3::ONE;
        }
        let x = uv.x as f64 * w as f64 - 0.5;
        let y = uv.y as f64 * h as f64 - 0.5;
        let (x0, y0) = (x.floor(), y.floor());
        let (fx, fy) = (x - x0, y - y0);
        let texel = |i: f64, j: f64| {
            let column = (i as i64).rem_euclid(w as i64) as usize;
            let row = (j as i64).rem_euclid(h as i64) as usize;
            let at = (row * w + column) * 4;
            let c = &self.rgba8[at..at + 3];
            DVec3::new(c[0] as f64, c[1] as f64, c[2] as f64).map(|v| srgb_to_linear(v / 255.0))
        };
        let top = texel(x0, y0).lerp(texel(x0 + 1.0, y0), fx);
        let bottom = texel(x0, y0 + 1.0).lerp(texel(x0 + 1.0, y0 + 1.0), fx);
        top.lerp(bottom, fy)
    }
}

/// sRGB electro-optical transfer: encoded [0, 1] → linear (IEC 61966-2-1).
pub fn srgb_to_linear(encoded: f64) -> f64 {
    if encoded <= 0.04045 {
        encoded / 12.92
    } else {
        ((encoded + 0.055) / 1.055).powf(2.4)
    }
}

/// Inverse of [`srgb_to_linear`]: linear [0, 1] → encoded.
pub fn linear_to_srgb(linear: f64) -> f64 {
    if linear <= 0.0031308 {
        linear * 12.92
    } else {
        1.055 * linear.powf(1.0 / 2.4) - 0.055
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bilinear_sampling_returns_texels_at_their_centres_and_blends_between() {
        use glam::{DVec3, Vec2};
        // 2×1: black, white (sRGB 255 → linear 1).
        let texture = TextureImage {
            name: "ramp".into(),
            width: 2,
            height: 1,
            rgba8: vec![0, 0, 0, 255, 255, 255, 255, 255],
        };
        assert!(texture.sample_bilinear(Vec2::new(0.25, 0.5)).length() < 1e-12);
        assert!((texture.sample_bilinear(Vec2::new(0.75, 0.5)) - DVec3::ONE).length() < 1e-12);
        let middle = texture.sample_bilinear(Vec2::new(0.5, 0.5));
        assert!((middle - DVec3::splat(0.5)).length() < 1e-12, "{middle}");
        // Repeats: u = 1.25 is u = 0.25.
        assert!(texture.sample_bilinear(Vec2::new(1.25, 0.5)).length() < 1e-12);
    }

    #[test]
    fn the_summary_names_the_values_and_their_mapping() {
        let m = Material {
            name: "brass".into(),
            base_color: Vec4::new(0.9, 0.6, 0.2, 1.0),
            metallic: 1.0,
            roughness: 0.3,
            emissive: Vec3::new(0.0, 2.0, 0.0),
            ..Material::default()
        };
        let text = m.summary();
        assert!(text.starts_with("brass: base colour (0.90, 0.60, 0.20)"), "{text}");
        assert!(
            text.contains("metallic 1.00") && text.contains("roughness 0.30"),
            "{text}"
        );
        assert!(
            text.contains("diffuse (0.00, 0.00, 0.00)"),
            "metals do not diffuse: {text}"
        );
        assert!(text.contains("emissive (0.00, 2.00, 0.00)"), "{text}");
        assert!(!Material::default().summary().contains("emissive"));
    }

    #[test]
    fn white_rough_dielectric_without_specular_is_pure_lambert() {
        let m = Material {
            metallic: 0.0,
            specular: 0.0,
            ..Material::default()
        };
        assert_eq!(m.diffuse_albedo(), Vec3::ONE);
        assert_eq!(m.specular_color(), Vec3::ZERO);
    }

    #[test]
    fn metals_reflect_their_base_colour_and_do_not_diffuse() {
        let m = Material {
            base_color: Vec4::new(0.9, 0.6, 0.2, 1.0),
            metallic: 1.0,
            ..Material::default()
        };
        assert_eq!(m.diffuse_albedo(), Vec3::ZERO);
        assert_eq!(m.specular_color(), Vec3::new(0.9, 0.6, 0.2));
    }

    #[test]
    fn phong_exponent_falls_with_roughness() {
        let exps: Vec<f32> = [0.0, 0.3, 0.6, 1.0]
            .iter()
            .map(|&r| {
                Material {
                    roughness: r,
                    ..Material::default()
                }
                .phong_exponent()
            })
            .collect();
        assert!(exps.windows(2).all(|w| w[0] > w[1]));
        assert_eq!(exps[3], 0.0);
    }
}
