//! Which vertices a dab paints: those whose projection falls inside the brush disc, that
//! face the camera, and that the camera sees (a ray from the eye reaches them before any
//! other surface — never through the mesh). Rozon's ID-buffer picking under-selects dense
//! meshes and misses sparse ones; projecting every vertex does neither and gives each hit
//! its falloff weight.
//!
//! And the surface under the brush, whatever its tessellation: eye rays through the pixel
//! centres of the disc (at most [`MAX_SURFACE_SAMPLES_ACROSS`] across) hit the visible
//! triangles; each hit is a painted point, where a stroke reads the light as the frame
//! shows it at that pixel (`Transfer::point_shading`), and paints its triangle's three
//! vertices with its falloff weight times their barycentric weights. A stroke on a wall
//! of two triangles paints its corners in the proportions the painted point lies between
//! them: what a stroke reads per vertex (the transfer) is interpolated linearly across a
//! triangle, so the corners weighted by one point's barycentrics give that point's value.
//! Each vertex keeps the largest weight any dab or sample gave it, which keeps the
//! corners' weighted mean within the dab's footprint (tests below) rather than exactly at
//! its centre.

use std::collections::BTreeMap;

use glam::{Vec2, Vec3};
use rayon::prelude::*;

use super::brush::Brush;
use crate::bake::scene_bvh::SceneBvh;
use crate::scene::{Aabb, Camera, Scene};

/// One vertex of the scene: object index and vertex index within it.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash, serde::Serialize, serde::Deserialize)]
pub struct VertexRef {
    pub object: u32,
    pub vertex: u32,
}

/// A camera looking at a viewport of `width_px` × `height_px` pixels; pixel (0, 0) is the
/// top-left corner, x to the right, y down (as egui and image files count).
#[derive(Debug, Clone, PartialEq)]
pub struct View {
    pub camera: Camera,
    pub width_px: u32,
    pub height_px: u32,
}

impl View {
    /// Pixel position of world point `p`, None if it is behind the eye.
    pub fn project(&self, p: Vec3) -> Option<Vec2> {
        let aspect = self.width_px.max(1) as f32 / self.height_px.max(1) as f32;
        let clip = self.camera.view_projection(aspect) * p.extend(1.0);
        if clip.w.is_nan() || clip.w <= 0.0 {
            return None;
        }
        let ndc = clip.truncate() / clip.w;
        Some(Vec2::new(
            (ndc.x + 1.0) * 0.5 * self.width_px as f32,
            (1.0 - ndc.y) * 0.5 * self.height_px as f32,
        ))
    }

    /// The eye ray through pixel `pixel` (the inverse of [`Self::project`]): the camera
    /// position and the unit direction. None for a degenerate camera.
    pub fn ray_through(&self, pixel: Vec2) -> Option<(Vec3, Vec3)> {
        let aspect = self.width_px.max(1) as f32 / self.height_px.max(1) as f32;
        let inverse = self.camera.view_projection(aspect).inverse();
        let ndc = Vec2::new(
            2.0 * pixel.x / self.width_px.max(1) as f32 - 1.0,
            1.0 - 2.0 * pixel.y / self.height_px.max(1) as f32,
        );
        // Depth 0.5 in wgpu's 0..1 range lies in front of the eye for any projection here.
        let point = inverse.project_point3(ndc.extend(0.5));
        let direction = (point - self.camera.position).normalize_or_zero();
        (direction != Vec3::ZERO && direction.is_finite()).then_some((self.camera.position, direction))
    }

    /// Whether the screen rectangle of `bounds` can touch the disc (conservative: a box
    /// reaching behind the eye always can).
    fn may_touch(&self, bounds: &Aabb, center_px: Vec2, radius_px: f32) -> bool {
        if bounds.is_empty() {
            return false;
        }
        let mut min = Vec2::splat(f32::INFINITY);
        let mut max = Vec2::splat(f32::NEG_INFINITY);
        for p in bounds.corners() {
            let Some(q) = self.project(p) else { return true };
            min = min.min(q);
            max = max.max(q);
        }
        let nearest = center_px.clamp(min, max);
        nearest.distance(center_px) <= radius_px
    }
}

/// A point of the surface under the brush, where an eye ray through the dab's disc met a
/// visible front face: what the frame shows at that pixel.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PaintedPoint {
    pub object: u32,
    /// The triangle's corners (vertex indices within the object).
    pub corners: [u32; 3],
    /// The point's barycentric coordinates on the triangle (sum 1).
    pub barycentric: Vec3,
    /// The brush's falloff weight there.
    pub weight: f32,
    /// The base-colour texture's linear colour at the point (None: untextured).
    pub texture_rgb: Option<glam::DVec3>,
}

impl PaintedPoint {
    /// The corners as vertices, with their barycentric weights.
    pub fn weighted_corners(&self) -> [(VertexRef, f64); 3] {
        let share = self.barycentric.to_array();
        std::array::from_fn(|k| {
            (
                VertexRef {
                    object: self.object,
                    vertex: self.corners[k],
                },
                share[k] as f64,
            )
        })
    }
}

/// The vertices a stroke painted, each with its largest dab weight, in vertex order, and
/// what the base-colour texture shows around each; and the points of the surface under
/// the brush, which stand for the pixels a stroke's mean luminance is read over.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Hits {
    pub weights: BTreeMap<VertexRef, f32>,
    /// The surface points under the dabs (eye rays through the pixels of each dab's disc).
    pub points: Vec<PaintedPoint>,
    /// The pixels sampled so far (on the brush's lattice) and their points' indices.
    sampled: BTreeMap<(i64, i64), usize>,
    /// Per vertex on a textured material: (Σ w·τ, Σ w) over the points of the surface that
    /// painted it, τ the luminance of the base-colour texture there (linear).
    texture: BTreeMap<VertexRef, (f64, f64)>,
}

impl Hits {
    pub fn is_empty(&self) -> bool {
        self.weights.is_empty()
    }

    pub fn len(&self) -> usize {
        self.weights.len()
    }

    /// Paints a point's corners with its weight times their barycentric shares.
    fn paint_corners(&mut self, point: &PaintedPoint) {
        let texture = point.texture_rgb.map(crate::scene::luminance);
        for (vertex, share) in point.weighted_corners() {
            if share > 0.0 {
                let weight = point.weight * share as f32;
                self.add(vertex, weight);
                self.add_texture(vertex, weight, texture);
            }
        }
    }

    fn add(&mut self, vertex: VertexRef, weight: f32) {
        let entry = self.weights.entry(vertex).or_insert(0.0);
        *entry = entry.max(weight);
    }

    /// Records that the texture shows luminance `texture` where `vertex` was painted with
    /// `weight` (nothing for an untextured material: None).
    fn add_texture(&mut self, vertex: VertexRef, weight: f32, texture: Option<f64>) {
        if let Some(tau) = texture.filter(|t| t.is_finite())
            && weight > 0.0
        {
            let entry = self.texture.entry(vertex).or_insert((0.0, 0.0));
            entry.0 += weight as f64 * tau;
            entry.1 += weight as f64;
        }
    }

    /// What the base-colour texture multiplies `vertex`'s light by where it was painted:
    /// the weighted mean of its luminance over the painted points (1 untextured). The
    /// transfer of a vertex is per unit of the material's colour factors; the frame shows
    /// it times the texture, so strokes read it times this (the diffuse and glossy parts
    /// alike: glTF's texture colours the base colour, which the glossy lobe of a metal
    /// takes too, and a dielectric's glossy part is small).
    pub fn texture_factor(&self, vertex: VertexRef) -> f64 {
        match self.texture.get(&vertex) {
            Some(&(sum, weights)) if weights > 0.0 => sum / weights,
            _ => 1.0,
        }
    }
}

/// The linear colour of `object`'s base-colour texture at `uv`, if it has one.
fn texture_colour(scene: &Scene, object: usize, uv: Vec2) -> Option<glam::DVec3> {
    let material = scene.materials.get(scene.objects.get(object)?.material)?;
    let texture = scene.textures.get(material.base_color_texture?)?;
    Some(texture.sample_bilinear(uv))
}

/// The luminance of `object`'s base-colour texture at `uv` (linear), if it has one.
fn texture_luminance(scene: &Scene, object: usize, uv: Vec2) -> Option<f64> {
    texture_colour(scene, object, uv).map(crate::scene::luminance)
}

/// Most pixels sampled across a dab's diameter: a brush up to this wide reads every pixel
/// centre of its disc, as the frame shows them; a wider one every k-th pixel on a lattice
/// fixed to the frame, so that overlapping dabs meet the same pixels.
pub const MAX_SURFACE_SAMPLES_ACROSS: f32 = 16.0;

/// The lattice step (pixels) of a brush's surface samples.
fn sample_stride_px(radius_px: f32) -> i32 {
    (2.0 * radius_px / MAX_SURFACE_SAMPLES_ACROSS).ceil().clamp(1.0, 1e6) as i32
}

/// Adds to `hits` the vertices one dab at `center_px` paints; the objects `hidden` lists
/// are neither painted nor in the way.
pub fn pick_dab(
    scene: &Scene,
    bvh: &SceneBvh,
    view: &View,
    center_px: Vec2,
    brush: &Brush,
    hidden: &[u32],
    hits: &mut Hits,
) {
    if !center_px.is_finite() {
        return;
    }
    let eye = view.camera.position;
    for (o, object) in scene.objects.iter().enumerate() {
        if hidden.contains(&(o as u32)) || !view.may_touch(&object.bounds(), center_px, brush.radius_px) {
            continue;
        }
        let found: Vec<(u32, f32)> = object
            .positions
            .par_iter()
            .zip(object.normals.par_iter())
            .enumerate()
            .filter_map(|(v, (&p, &n))| {
                let weight = brush.weight(view.project(p)?.distance(center_px))?;
                let to_eye = eye - p;
                let distance = to_eye.length();
                if distance.is_nan() || distance <= 0.0 || n.dot(to_eye) <= 0.0 {
                    return None;
                }
                // Anything on the segment from the eye to just short of the vertex hides it.
                let direction = -to_eye / distance;
                let margin = 1e-4 * distance + 1e-6;
                (!bvh.occluded_ignoring(eye, direction, 0.0, distance - margin, hidden)).then_some((v as u32, weight))
            })
            .collect();
        for (vertex, weight) in found {
            let at = VertexRef {
                object: o as u32,
                vertex,
            };
            hits.add(at, weight);
            let uv = object.uvs.get(vertex as usize).copied().unwrap_or(Vec2::ZERO);
            hits.add_texture(at, weight, texture_luminance(scene, o, uv));
        }
    }
    pick_surface(scene, bvh, view, center_px, brush, hidden, hits);
}

/// The surface under the dab (see the module's comment): eye rays through the pixel
/// centres of the disc (on the lattice of [`sample_stride_px`]; the centre itself when
/// the disc holds none), each visible front-facing hit a painted point that paints its
/// triangle's corners. A pixel an earlier dab of the stroke sampled keeps its point, with
/// the larger weight.
fn pick_surface(
    scene: &Scene,
    bvh: &SceneBvh,
    view: &View,
    center_px: Vec2,
    brush: &Brush,
    hidden: &[u32],
    hits: &mut Hits,
) {
    // A disc far wider than the view samples as one that covers it (bounded work).
    let view_span_px = 4.0 * (view.width_px as f32 + view.height_px as f32) + 1.0;
    let radius = brush.radius_px.max(0.5).min(view_span_px);
    let stride = sample_stride_px(radius);
    let lattice = |x: f32| ((x / stride as f32).floor() as i64).clamp(-(1 << 40), 1 << 40);
    let centre_of = |ix: i64, iy: i64| Vec2::new((ix * stride as i64) as f32 + 0.5, (iy * stride as i64) as f32 + 0.5);
    let mut samples: Vec<((i64, i64), Vec2, f32)> = Vec::new();
    for iy in lattice(center_px.y - radius)..=lattice(center_px.y + radius) {
        for ix in lattice(center_px.x - radius)..=lattice(center_px.x + radius) {
            let pixel = centre_of(ix, iy);
            if let Some(weight) = brush.weight(pixel.distance(center_px)) {
                samples.push(((ix * stride as i64, iy * stride as i64), pixel, weight));
            }
        }
    }
    if samples.is_empty() {
        let at = (center_px.x.floor() as i64, center_px.y.floor() as i64);
        samples.push((at, center_px, 1.0));
    }
    for (key, pixel, weight) in samples {
        if let Some(&index) = hits.sampled.get(&key) {
            let point: &mut PaintedPoint = &mut hits.points[index];
            if weight > point.weight {
                point.weight = weight;
                let point = *point;
                hits.paint_corners(&point);
            }
            continue;
        }
        let Some(point) = surface_point(scene, bvh, view, pixel, weight, hidden) else {
            continue;
        };
        hits.sampled.insert(key, hits.points.len());
        hits.points.push(point);
        hits.paint_corners(&point);
    }
}

/// The visible front-facing surface point an eye ray through `pixel` meets, if any.
fn surface_point(
    scene: &Scene,
    bvh: &SceneBvh,
    view: &View,
    pixel: Vec2,
    weight: f32,
    hidden: &[u32],
) -> Option<PaintedPoint> {
    let (origin, direction) = view.ray_through(pixel)?;
    let hit = bvh.closest_hit_ignoring(origin, direction, f32::INFINITY, hidden)?;
    if !hit.front_facing {
        return None;
    }
    let object = scene.objects.get(hit.object)?;
    let corners = object.indices.get(3 * hit.triangle..3 * hit.triangle + 3)?;
    let texture_rgb = texture_colour(scene, hit.object, object.interpolated_uv(hit.triangle, hit.barycentric));
    Some(PaintedPoint {
        object: hit.object as u32,
        corners: [corners[0], corners[1], corners[2]],
        barycentric: hit.barycentric,
        weight,
        texture_rgb,
    })
}

#[cfg(test)]
mod tests {
    use glam::Affine3A;

    use super::*;
    use crate::paint::brush::BrushKind;
    use crate::scene::shapes;

    fn view_down_from(height: f32) -> View {
        View {
            camera: Camera {
                position: Vec3::new(0.0, height, 0.0),
                forward: Vec3::NEG_Y,
                up: Vec3::NEG_Z,
                yfov_rad: 60f32.to_radians(),
                znear: 0.01,
                zfar: None,
            },
            width_px: 200,
            height_px: 200,
        }
    }

    #[test]
    fn rays_through_pixels_meet_the_points_that_project_there() {
        let view = View {
            camera: Camera {
                position: Vec3::new(1.0, 2.0, 5.0),
                forward: Vec3::new(-0.2, -0.3, -1.0).normalize(),
                up: Vec3::Y,
                yfov_rad: 50f32.to_radians(),
                znear: 0.01,
                zfar: None,
            },
            width_px: 320,
            height_px: 200,
        };
        for pixel in [Vec2::new(160.0, 100.0), Vec2::new(3.0, 190.0), Vec2::new(300.0, 20.0)] {
            let (origin, direction) = view.ray_through(pixel).expect("a ray");
            assert!((direction.length() - 1.0).abs() < 1e-5);
            for distance in [0.5, 4.0, 30.0] {
                let back = view.project(origin + distance * direction).expect("in front");
                assert!(back.distance(pixel) < 0.02, "{pixel} came back as {back}");
            }
        }
    }

    #[test]
    fn the_centre_of_the_screen_projects_from_the_point_ahead() {
        let view = view_down_from(5.0);
        let q = view.project(Vec3::ZERO).unwrap();
        assert!((q - Vec2::new(100.0, 100.0)).length() < 1e-3);
        assert!(view.project(Vec3::new(0.0, 10.0, 0.0)).is_none());
    }

    /// A wall of two triangles whose corners all lie far outside the brush is painted:
    /// its corners carry the stroke in the proportions of where it lies between them
    /// (their weighted mean is the point under the brush), and nothing behind it is.
    #[test]
    fn a_dab_on_a_large_triangle_paints_its_corners_as_the_point_lies_between_them() {
        let wall = shapes::plane(10.0, 1, 1.0).into_object("wall");
        let behind = shapes::plane(10.0, 40, 1.0)
            .transformed(Affine3A::from_translation(Vec3::new(0.0, -1.0, 0.0)))
            .into_object("behind");
        let scene = Scene {
            objects: vec![wall, behind],
            ..Default::default()
        };
        let bvh = SceneBvh::build(&scene);
        let brush = Brush {
            radius_px: 8.0,
            ..Brush::new(BrushKind::Positive)
        };
        let view = view_down_from(5.0);
        for pixel in [Vec2::new(100.0, 100.0), Vec2::new(70.0, 130.0), Vec2::new(150.0, 40.0)] {
            let mut hits = Hits::default();
            pick_dab(&scene, &bvh, &view, pixel, &brush, &[], &mut hits);
            assert!(!hits.is_empty(), "the wall under {pixel} is painted");
            assert!(hits.weights.keys().all(|v| v.object == 0), "nothing through the wall");
            let (sum, total) = hits.weights.iter().fold((Vec3::ZERO, 0.0), |(sum, total), (v, w)| {
                (sum + *w * scene.objects[0].positions[v.vertex as usize], total + w)
            });
            let (origin, direction) = view.ray_through(pixel).expect("a ray");
            let under = origin + direction * (origin.y / -direction.y);
            // Within the brush's footprint on the wall (8 px of 200 across 5.8 m: 0.23 m).
            assert!((sum / total).distance(under) < 0.25, "{} vs {under}", sum / total);
        }
    }

    #[test]
    fn a_plate_hides_the_floor_under_it_and_back_faces_are_never_hit() {
        let floor = shapes::plane(4.0, 16, 1.0).into_object("floor");
        let plate = shapes::plane(1.0, 2, 1.0)
            .transformed(Affine3A::from_translation(Vec3::new(0.0, 1.0, 0.0)))
            .into_object("plate");
        let scene = Scene {
            objects: vec![floor, plate],
            ..Default::default()
        };
        let bvh = SceneBvh::build(&scene);
        let brush = Brush {
            radius_px: 60.0,
            ..Brush::new(BrushKind::Positive)
        };
        let view = view_down_from(5.0);
        let mut hits = Hits::default();
        pick_dab(&scene, &bvh, &view, Vec2::new(100.0, 100.0), &brush, &[], &mut hits);
        let floor_hits: Vec<Vec3> = hits
            .weights
            .keys()
            .filter(|v| v.object == 0)
            .map(|v| scene.objects[0].positions[v.vertex as usize])
            .collect();
        assert!(!floor_hits.is_empty());
        assert!(hits.weights.keys().any(|v| v.object == 1), "the plate is painted");
        for p in floor_hits {
            // The plate (±0.5 m at 1 m) hides |x|, |z| < 0.5·5/4 of the floor from 5 m up.
            assert!(p.x.abs() > 0.62 || p.z.abs() > 0.62, "hidden floor vertex {p} was hit");
        }
        // From below, every face points away: nothing is painted.
        let mut below = view_down_from(-5.0);
        below.camera.forward = Vec3::Y;
        let mut none = Hits::default();
        pick_dab(&scene, &bvh, &below, Vec2::new(100.0, 100.0), &brush, &[], &mut none);
        assert!(none.is_empty());
    }

    /// The painted points are the pixels the frame shows under the brush: one per pixel
    /// centre within the disc for a brush up to 16 px across (a 6 px disc at a pixel
    /// centre holds the 113 centres of a 13 × 13 square within 6 px), each on the surface
    /// its eye ray meets; a second dab over the same pixels adds none; a disc of 0.5 px
    /// between pixel centres still reads the surface there; a disc far wider than the
    /// view takes bounded work.
    #[test]
    fn the_painted_points_are_the_pixels_under_the_brush() {
        let scene = Scene {
            objects: vec![shapes::plane(10.0, 1, 1.0).into_object("wall")],
            ..Default::default()
        };
        let bvh = SceneBvh::build(&scene);
        let view = view_down_from(5.0);
        let brush = |radius_px: f32| Brush {
            radius_px,
            ..Brush::new(BrushKind::Positive)
        };
        let centre = Vec2::new(100.5, 100.5);
        let expected = (-6i32..=6)
            .flat_map(|y| (-6i32..=6).map(move |x| (x, y)))
            .filter(|&(x, y)| x * x + y * y <= 36)
            .count();
        let mut hits = Hits::default();
        pick_dab(&scene, &bvh, &view, centre, &brush(6.0), &[], &mut hits);
        assert_eq!(hits.points.len(), expected);
        for point in &hits.points {
            let b = point.barycentric;
            assert!((b.x + b.y + b.z - 1.0).abs() < 1e-4 && b.min_element() >= -1e-6, "{b}");
        }
        pick_dab(
            &scene,
            &bvh,
            &view,
            centre + Vec2::new(0.3, -0.2),
            &brush(6.0),
            &[],
            &mut hits,
        );
        let moved = (-7i32..=7)
            .flat_map(|y| (-7i32..=7).map(move |x| (x, y)))
            .filter(|&(x, y)| (Vec2::new(x as f32, y as f32) - Vec2::new(0.3, -0.2)).length() <= 6.0)
            .filter(|&(x, y)| x * x + y * y > 36)
            .count();
        assert_eq!(hits.points.len(), expected + moved, "only the new pixels are added");
        let mut tiny = Hits::default();
        pick_dab(
            &scene,
            &bvh,
            &view,
            Vec2::new(100.0, 100.0),
            &brush(0.5),
            &[],
            &mut tiny,
        );
        assert_eq!(tiny.points.len(), 1);
        let mut huge = Hits::default();
        pick_dab(&scene, &bvh, &view, centre, &brush(1e30), &[], &mut huge);
        assert!(
            !huge.points.is_empty() && huge.points.len() <= 17 * 17,
            "{}",
            huge.points.len()
        );
    }
}
