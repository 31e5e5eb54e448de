//! The f64 twin of logsh_per_vertex.wgsl's cs_vertex_light: the SH path's light at a
//! vertex through the visibility there, split as the separate BRDF shades it, radiance =
//! k_d · diffuse + k_s · glossy (`shading::vertex_lighting` says which meshes take it).

use glam::DVec3;

use super::lobes::environment_through_visibility;
use super::surface::{SurfacePoint, direct_lobes, incidence};
use super::visibility::visibility_toward;
use crate::shading::gpu_types::{GpuLight, SHADOW_PATH_SH};

/// The light of the SH path at one vertex, per unit k_d and k_s.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct VertexLight {
    /// The environment's light through the visibility, clamped to the unshadowed
    /// (`environment_through_visibility`), plus each light's irradiance times its
    /// diffuse lobe and its clamped mean visibility (`light_through`).
    pub diffuse: DVec3,
    /// Each light's irradiance times its glossy lobe and its clamped mean visibility.
    pub glossy: DVec3,
}

/// The light at a vertex at `position` on the side `normal` faces (the stored normal for
/// the front, its opposite for the back, which a fragment of a back face takes), with
/// visibility SH `g`, of a material of glossy exponent `phong_exponent`, seen from `eye`,
/// from `lights` (those on the SH path: the others are shaded per pixel) and the
/// environment's irradiance SH (`Frame::environment_irradiance`).
pub fn vertex_light(
    (position, normal): (DVec3, DVec3),
    g: &[f64],
    phong_exponent: f64,
    (lights, environment_irradiance): (&[GpuLight], &[[f32; 4]; 9]),
    eye: DVec3,
) -> VertexLight {
    let s = SurfacePoint {
        position,
        normal: normal.normalize_or_zero(),
        k_d: DVec3::ONE,
        k_s: DVec3::ONE,
        phong_exponent,
        emissive: DVec3::ZERO,
    };
    let mut light = VertexLight {
        // k_d = 1: the environment's share per unit diffuse albedo.
        diffuse: environment_through_visibility(&s, environment_irradiance, g),
        glossy: DVec3::ZERO,
    };
    for each in lights.iter().filter(|l| l.shadow_path == SHADOW_PATH_SH) {
        let inc = incidence(each, position);
        let (diffuse, glossy) = direct_lobes(&s, &inc, eye);
        let seen = inc.irradiance * visibility_toward(g, inc.to_light, inc.cap_ratio).clamp(0.0, 1.0);
        light.diffuse += seen * diffuse;
        light.glossy += seen * glossy;
    }
    light
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::{Light, LightKind};

    fn lamp(position: glam::Vec3) -> GpuLight {
        GpuLight::new(&Light {
            name: "lamp".into(),
            kind: LightKind::Point,
            color: glam::Vec3::ONE,
            intensity: 20.0,
            position,
            direction: glam::Vec3::NEG_Y,
            range: None,
            locked: false,
        })
    }

    /// The visibility SH of `share` everywhere: `share`·√(4π) in the DC band (order 4).
    fn visibility_of(share: f64) -> Vec<f64> {
        let mut g = vec![0.0; 16];
        g[0] = share * (4.0 * std::f64::consts::PI).sqrt();
        g
    }

    /// Unshadowed (G = the SH of 1: √(4π) in the DC band), a Lambertian vertex 2 m below a
    /// 20 cd lamp takes E/π = 20/4/π in its diffuse part, and a glossy lobe of exponent 0
    /// (r + 1)/(2π) · E.
    #[test]
    fn an_unshadowed_vertex_under_a_lamp_takes_its_closed_form() {
        let light = vertex_light(
            (DVec3::ZERO, DVec3::Y),
            &visibility_of(1.0),
            0.0,
            (&[lamp(glam::Vec3::new(0.0, 2.0, 0.0))], &[[0.0; 4]; 9]),
            DVec3::new(1.0, 1.0, 0.0),
        );
        let irradiance = 20.0 / 4.0;
        assert!(
            (light.diffuse - DVec3::splat(irradiance / std::f64::consts::PI))
                .abs()
                .max_element()
                < 1e-9
        );
        let glossy = irradiance / (2.0 * std::f64::consts::PI);
        assert!(
            (light.glossy - DVec3::splat(glossy)).abs().max_element() < 1e-9,
            "{light:?}"
        );
    }

    /// The back of a vertex whose front faces a lamp takes nothing from it.
    #[test]
    fn the_back_of_a_vertex_takes_nothing_from_a_lamp_before_its_front() {
        let light = vertex_light(
            (DVec3::ZERO, DVec3::NEG_Y),
            &visibility_of(1.0),
            0.0,
            (&[lamp(glam::Vec3::new(0.0, 2.0, 0.0))], &[[0.0; 4]; 9]),
            DVec3::new(0.0, 3.0, 1.0),
        );
        assert_eq!(light.diffuse, DVec3::ZERO);
        assert_eq!(light.glossy, DVec3::ZERO);
    }

    /// Fully blocked toward the lamp (G = 0) nothing comes through; half (G = ½ the
    /// unshadowed) half does.
    #[test]
    fn the_light_scales_with_the_visibility() {
        let lights = [lamp(glam::Vec3::new(0.5, 2.0, 0.0))];
        let at = |share: f64| {
            vertex_light(
                (DVec3::ZERO, DVec3::Y),
                &visibility_of(share),
                8.0,
                (&lights, &[[0.0; 4]; 9]),
                DVec3::new(-1.0, 1.0, 0.0),
            )
        };
        let (open, half, shut) = (at(1.0), at(0.5), at(0.0));
        assert!(open.diffuse.x > 0.0 && open.glossy.x > 0.0);
        assert!((half.diffuse - 0.5 * open.diffuse).abs().max_element() < 1e-12);
        assert!((half.glossy - 0.5 * open.glossy).abs().max_element() < 1e-12);
        assert_eq!(shut.diffuse, DVec3::ZERO);
    }
}
