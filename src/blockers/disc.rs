//! Disc blockers: how many a frame shades, apart from the spheres ([`spheres_and_discs`]),
//! and how one looks from a receiver: its solid angle and the mean direction over it (the
//! WGSL twin is `disc_seen` in logsh.wgsl).
//!
//! Within [`NEAR_FIELD_RADII`] radii the disc is the square of its area centred on it: its
//! solid angle the sum over the square's two triangles of Van Oosterom and Strackee's
//! tan(Ω/2) = a·(b × c) / (abc + (a·b)c + (a·c)b + (b·c)a), its mean direction the
//! square's vector form factor, Σ over the edges of the edge's angle times the unit normal
//! of the plane through the eye and the edge (Lambert; Arvo 1995, "Applications of
//! irradiance tensors"). Both hold in the near field, where a receiver just above a
//! floor's disc sees it fill the hemisphere below. Farther away, the cap toward its centre
//! that is exact on its axis and of its projected area, 2π(1 − d/√(d² + r²|cos θ|)).

use glam::DVec3;

use super::Sphere;

/// Sides of the polygon standing for the disc: a square of its area is within 1 % of its
/// solid angle on its axis at any distance (4 arcsin(a²/(a² + 4h²)) against
/// 2π(1 − h/√(h² + r²)), a = r√π) and exact far away.
pub const DISC_SIDES: usize = 4;

/// Circumradius of the square with a disc's area, over the disc's radius: √(π/2).
pub const POLYGON_SCALE: f64 = 1.253_314_137_315_500_3;

/// Beyond this many radii from its centre a disc is seen in the far field.
pub const NEAR_FIELD_RADII: f64 = 4.0;

/// Receivers this close to a disc's plane (metres, or this share of its radius if more)
/// are in it and see nothing of it: a planar mesh does not shadow itself, whatever the
/// rounding of its receivers' positions.
pub const DISC_PLANE_TOLERANCE_M: f64 = 1e-3;

/// Whether a disc blocker at `center` with unit `normal` may stand between the receiver
/// `p` and a light seen toward unit `to_light`, `distance_m` away: false when the light's
/// emitter lies wholly on `p`'s side of the disc's plane (a backdrop behind a soft box
/// hides none of it from the set in front; the cap that stands for the disc has no depth
/// and would), true when it reaches the plane or beyond. `emitter_support_m` is how far
/// the emitter reaches from its centre along `normal` (`penumbra::Emitter::support_m`);
/// None for a light at infinity, which is on `p`'s side when it shines from there more
/// steeply than its angular radius (sine `sin_light`). The same in exact_lights.wgsl
/// (`disc_plane_between`).
pub fn disc_plane_between(
    center: DVec3,
    normal: DVec3,
    p: DVec3,
    to_light: DVec3,
    distance_m: f64,
    sin_light: f64,
    emitter_support_m: Option<f64>,
) -> bool {
    let side_p = (p - center).dot(normal);
    let toward = to_light.dot(normal);
    let (side_light, extent) = match emitter_support_m {
        Some(support_m) if distance_m.is_finite() => (side_p + distance_m * toward, support_m),
        // Both sides over the distance, in the limit.
        _ => (toward, sin_light),
    };
    !(side_light * side_p > 0.0 && side_light.abs() > extent)
}

/// An orthonormal pair perpendicular to unit `n` (Duff et al. 2017), the same in WGSL.
pub fn disc_frame(n: DVec3) -> (DVec3, DVec3) {
    let sign = if n.z >= 0.0 { 1.0 } else { -1.0 };
    let a = -1.0 / (sign + n.z);
    let b = n.x * n.y * a;
    (
        DVec3::new(1.0 + sign * n.x * n.x * a, sign * b, -sign * n.x),
        DVec3::new(b, sign + n.y * n.y * a, -n.y),
    )
}

/// The solid angle (steradians, 0–2π) a disc at `center` of `radius` facing unit `normal`
/// subtends from `p`, and the unit mean direction over it (toward the disc); 0 from its
/// own plane (within [`DISC_PLANE_TOLERANCE_M`]).
pub fn disc_seen(center: DVec3, radius: f64, normal: DVec3, p: DVec3) -> (f64, DVec3) {
    let to_center = center - p;
    let height = to_center.dot(normal).abs();
    let distance = to_center.length();
    if height <= DISC_PLANE_TOLERANCE_M * radius.max(1.0) {
        return (0.0, to_center.normalize_or(normal));
    }
    if distance > NEAR_FIELD_RADII * radius {
        // The cap exact on the disc's axis, of its projected area far away:
        // 2π(1 − d/√(d² + r′²)), r′² = r²|cos θ|.
        let seen_radius2 = radius * radius * height / distance;
        let solid_angle = std::f64::consts::TAU * (1.0 - distance / (distance * distance + seen_radius2).sqrt());
        return (solid_angle, to_center / distance);
    }
    // The square's corners on the diagonals of the frame, so its edges run along the
    // frame's axes: for a disc facing a world axis (most walls, floors and shelves) those
    // are the world's axes, along the mesh's own edges. (Corners on the axes, as until
    // 2026-12-04, turned the square 45° to them: where a 2 m wall met the floor it
    // spanned 0.84 m of it.)
    let (frame_u, frame_v) = disc_frame(normal);
    let (u, v) = (
        (frame_u + frame_v) * std::f64::consts::FRAC_1_SQRT_2,
        (frame_v - frame_u) * std::f64::consts::FRAC_1_SQRT_2,
    );
    let reach = radius * POLYGON_SCALE;
    let corners = [
        to_center + reach * u,
        to_center + reach * v,
        to_center - reach * u,
        to_center - reach * v,
    ];
    let solid_angle = triangle_solid_angle(corners[0], corners[1], corners[2])
        + triangle_solid_angle(corners[0], corners[2], corners[3]);
    let form_factor: DVec3 = (0..DISC_SIDES)
        .map(|k| edge_form_factor(corners[k], corners[(k + 1) % DISC_SIDES]))
        .sum();
    let mut direction = form_factor.normalize_or(to_center / distance.max(1e-300));
    if direction.dot(to_center) < 0.0 {
        direction = -direction;
    }
    (solid_angle.abs().min(std::f64::consts::TAU), direction)
}

/// An edge's share of a polygon's vector form factor seen from the origin (Lambert): the
/// angle the edge a → b subtends times the unit normal of the plane through the origin and
/// the edge (zero for an edge seen end-on). Half the sum over a polygon's edges is its
/// vector irradiance per unit radiance (`shading::cpu::area`); WGSL `edge_form_factor`.
pub fn edge_form_factor(a: DVec3, b: DVec3) -> DVec3 {
    let plane = a.cross(b);
    // atan2 rather than acos: exact for the small angles of distant polygons.
    plane.length().atan2(a.dot(b)) * plane.normalize_or_zero()
}

/// Signed solid angle of the triangle a, b, c seen from the origin (Van Oosterom and
/// Strackee 1983).
fn triangle_solid_angle(a: DVec3, b: DVec3, c: DVec3) -> f64 {
    let (la, lb, lc) = (a.length(), b.length(), c.length());
    let numerator = a.dot(b.cross(c));
    let denominator = la * lb * lc + a.dot(b) * lc + a.dot(c) * lb + b.dot(c) * la;
    2.0 * numerator.atan2(denominator)
}

/// The sine of the half-angle of the cap of solid angle `solid_angle` (≤ 2π).
pub fn cap_sine_of_solid_angle(solid_angle: f64) -> f64 {
    let cos = 1.0 - solid_angle.clamp(0.0, std::f64::consts::TAU) / std::f64::consts::TAU;
    (1.0 - cos * cos).max(0.0).sqrt()
}

/// Most disc blockers a frame shades: they are shaded in their own loop at every receiver
/// (WGSL `ShadowParams.discs`), apart from the spheres' culled walk.
pub const MAX_DISCS: usize = 64;

/// `blockers` with at most [`MAX_DISCS`] discs: the largest are kept (the others, the
/// smallest patches of open meshes, are dropped with a warning), spheres untouched.
pub fn within_disc_capacity(mut blockers: Vec<Sphere>) -> Vec<Sphere> {
    let discs = blockers.iter().filter(|b| b.is_disc()).count();
    if discs <= MAX_DISCS {
        return blockers;
    }
    let mut radii: Vec<f32> = blockers.iter().filter(|b| b.is_disc()).map(|b| b.radius_m).collect();
    radii.sort_by(|a, b| b.total_cmp(a));
    let smallest_kept = radii[MAX_DISCS - 1];
    let mut kept = 0;
    blockers.retain(|b| {
        let keep = !b.is_disc() || (b.radius_m >= smallest_kept && kept < MAX_DISCS);
        kept += (keep && b.is_disc()) as usize;
        keep
    });
    log::warn!(
        "{discs} disc blockers on open and thin meshes; the {MAX_DISCS} largest cast soft shadows, the others not"
    );
    blockers
}

/// `blockers` split as every shadow path shades them: the spheres, walked in culling groups,
/// and the discs (at most [`MAX_DISCS`], [`within_disc_capacity`]), seen at every receiver.
pub fn spheres_and_discs(blockers: &[Sphere]) -> (Vec<Sphere>, Vec<Sphere>) {
    let (discs, spheres) = within_disc_capacity(blockers.to_vec())
        .into_iter()
        .partition(Sphere::is_disc);
    (spheres, discs)
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::{PI, TAU};

    #[test]
    fn a_disc_stands_between_only_lights_that_reach_its_plane_from_the_receivers_side() {
        // A wall in the plane z = 0 facing +z; the receiver 2 m in front of it.
        let (center, normal, p) = (DVec3::ZERO, DVec3::Z, DVec3::new(0.3, 0.0, 2.0));
        let between = |light: DVec3, support_m: f64| {
            let (to_light, distance) = ((light - p).normalize(), (light - p).length());
            disc_plane_between(center, normal, p, to_light, distance, 0.0, Some(support_m))
        };
        // In front of the wall, between it and the receiver: nothing of the wall can hide it.
        assert!(!between(DVec3::new(0.0, 1.0, 0.5), 0.1));
        // Behind the wall.
        assert!(between(DVec3::new(0.0, 1.0, -0.5), 0.1));
        // An emitter reaching the plane or through it.
        assert!(between(DVec3::new(0.0, 1.0, 0.15), 0.2));
        assert!(!between(DVec3::new(0.0, 1.0, 0.25), 0.2));
        // The receiver behind the wall and the light in front: between.
        let behind = DVec3::new(0.0, 0.0, -1.0);
        let light = DVec3::new(0.0, 1.0, 0.5);
        let to_light = (light - behind).normalize();
        assert!(disc_plane_between(
            center,
            normal,
            behind,
            to_light,
            (light - behind).length(),
            0.0,
            Some(0.0)
        ));
        // A sun: on the receiver's side if it shines from the front more steeply than its size.
        let sun_between = |to_light: DVec3| disc_plane_between(center, normal, p, to_light, f64::INFINITY, 0.01, None);
        assert!(!sun_between(DVec3::new(0.0, 0.6, 0.8)));
        assert!(sun_between(DVec3::new(0.0, 0.6, -0.8)));
        assert!(sun_between(DVec3::new(0.0, 0.999, 0.005)));
    }

    #[test]
    fn the_polygon_has_the_discs_area() {
        let polygon = 0.5 * DISC_SIDES as f64 * POLYGON_SCALE.powi(2) * (TAU / DISC_SIDES as f64).sin();
        assert!((polygon - PI).abs() < 1e-12, "{polygon}");
    }

    #[test]
    fn the_frame_is_orthonormal_for_every_normal() {
        for n in [DVec3::Z, -DVec3::Z, DVec3::X, DVec3::new(0.3, -0.8, 0.2).normalize()] {
            let (u, v) = disc_frame(n);
            for (a, b) in [(u, v), (u, n), (v, n)] {
                assert!(a.dot(b).abs() < 1e-12);
            }
            assert!((u.length() - 1.0).abs() < 1e-12 && (v.length() - 1.0).abs() < 1e-12);
        }
    }

    #[test]
    fn on_its_axis_a_disc_subtends_its_closed_form() {
        for h in [0.05, 0.5, 2.0, 3.9, 4.1, 20.0] {
            let (omega, direction) = disc_seen(DVec3::ZERO, 1.0, DVec3::Y, DVec3::new(0.0, h, 0.0));
            let exact = TAU * (1.0 - h / (h * h + 1.0f64).sqrt());
            // The square of equal area near, the far field beyond four radii: within 1.5 %.
            assert!((omega / exact - 1.0).abs() < 0.015, "h {h}: {omega} against {exact}");
            assert!((direction + DVec3::Y).length() < 1e-9, "{direction}");
        }
    }

    #[test]
    fn far_away_it_subtends_its_projected_area_over_the_distance_squared() {
        let d = 300.0;
        let p = DVec3::new(0.0, 0.5, 3f64.sqrt() / 2.0) * d;
        let (omega, direction) = disc_seen(DVec3::ZERO, 1.0, DVec3::Y, p);
        let expected = PI * 0.5 / (d * d);
        assert!((omega / expected - 1.0).abs() < 1e-3, "{omega} against {expected}");
        assert!((direction + p.normalize()).length() < 1e-3);
    }

    #[test]
    fn just_above_a_large_disc_it_fills_the_hemisphere_below() {
        // 2 cm above a 5 m disc, 4 m from its centre: nearly half the sphere, straight down.
        let (omega, direction) = disc_seen(DVec3::ZERO, 5.0, DVec3::Y, DVec3::new(4.0, 0.02, 0.0));
        assert!(omega > 0.9 * TAU, "{omega}");
        assert!(direction.dot(-DVec3::Y) > 0.95, "{direction}");
        // Beside it, just above its plane, almost nothing.
        let (outside, _) = disc_seen(DVec3::ZERO, 5.0, DVec3::Y, DVec3::new(9.0, 0.02, 0.0));
        assert!(outside < 0.01, "{outside}");
        // In its plane, nothing at all (a floor's own receivers), even rounded off it.
        for height in [0.0, 1e-5, -1e-5] {
            let (own, _) = disc_seen(DVec3::ZERO, 5.0, DVec3::Y, DVec3::new(2.0, height, 1.0));
            assert!(own.abs() < 1e-9, "{own}");
        }
    }

    #[test]
    fn a_cap_of_the_solid_angle() {
        assert!((cap_sine_of_solid_angle(TAU) - 1.0).abs() < 1e-12);
        let alpha = 0.3f64;
        let omega = TAU * (1.0 - alpha.cos());
        assert!((cap_sine_of_solid_angle(omega) - alpha.sin()).abs() < 1e-12);
    }

    #[test]
    fn a_frame_keeps_the_largest_discs_and_every_sphere() {
        let mut blockers: Vec<Sphere> = (0..MAX_DISCS + 6)
            .map(|k| {
                Sphere::disc(
                    glam::Vec3::new(k as f32, 0.0, 0.0),
                    0.1 + 0.01 * k as f32,
                    glam::Vec3::Y,
                )
            })
            .collect();
        blockers.extend((0..3).map(|k| Sphere::ball(glam::Vec3::new(0.0, k as f32, 0.0), 0.01)));
        let kept = within_disc_capacity(blockers.clone());
        assert_eq!(kept.iter().filter(|b| b.is_disc()).count(), MAX_DISCS);
        assert_eq!(kept.iter().filter(|b| !b.is_disc()).count(), 3);
        // The six smallest went.
        assert!(
            kept.iter()
                .filter(|b| b.is_disc())
                .all(|b| b.radius_m > 0.1 + 0.01 * 5.5)
        );
        // Within the capacity nothing changes.
        assert_eq!(within_disc_capacity(blockers[6..].to_vec()), blockers[6..].to_vec());
    }
}
