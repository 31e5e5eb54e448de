//! Lights culled per region of space: a uniform grid of boxes over the scene's bounds,
//! each listing the lights on the SH and shadow-map paths that can reach some point of
//! it, so that a shaded point walks the lights of its box (scene.wgsl `harmonic_lights_at`,
//! `mapped_lights_at`) instead of every light of the scene.
//!
//! A light with a range reaches the boxes its range sphere meets: KHR_lights_punctual's
//! window, which `incidence` (scene.wgsl, `cpu::incidence`) applies to every light with a
//! range, is exactly 0 from the range on. A spot whose outer cone is under 90° reaches no
//! box wholly behind the plane through its apex: its cone factor is exactly 0 there. Any
//! other light reaches every box. A light left out of a box therefore adds exactly 0 at
//! every point of it, and the frame is the same with or without the grid
//! (tests/light_grid.rs compares them byte for byte); what the grid saves is the walk
//! over lights that add nothing, which lavapipe pays in full whatever a branch skips.
//!
//! Layout of [`LightGrid::words`], one `u32` array the shaders read (`light_grid`): for
//! every box `c` in x-fastest order and then one more, the outside box (points beyond the
//! grid, which lists every gridded light), three words — the first entry of its SH-path
//! lights, the first of its shadow-map lights, the end of its entries — then the entries,
//! each the index of a light in the uploaded order (`gpu_types::order_by_shadow_path`),
//! ascending within each path, so a point adds its lights in the order the whole loop
//! would.

use glam::{UVec3, Vec3};

use super::gpu_types::{GpuLight, LIGHT_DIRECTIONAL, LIGHT_SPOT, SHADOW_PATH_EXACT};
use crate::scene::Aabb;

/// Frames with at least this many lights on the SH and shadow-map paths that have a
/// range walk the grid (`CompiledPaths::light_grid`); with fewer the list's
/// indirection costs more than the lights it leaves out.
pub const LIGHT_GRID_MIN_LIGHTS: usize = 8;

/// Boxes along the scene's longest side: at least this many, and more — up to
/// [`MOST_BOXES_ALONG_LONGEST_SIDE`] — where the lights' ranges are short beside the scene
/// (a street of lamps), so that a box is about a third of the median range across: a box
/// lists the lights within about its side plus their range of it, so boxes much larger
/// than the ranges list many lights that reach only a corner of them.
const BOXES_ALONG_LONGEST_SIDE: f32 = 24.0;
const MOST_BOXES_ALONG_LONGEST_SIDE: f32 = 64.0;
const BOX_SIDES_PER_RANGE: f32 = 3.0;

/// The most words a grid may take (16 MiB): past it the grid is built coarser.
const MAX_WORDS: usize = 4 << 20;

/// How far the grid reaches past the scene's bounds, over their longest side and in
/// metres.
const BOUNDS_PADDING_OVER_SIDE: f32 = 0.01;
const BOUNDS_PADDING_M: f32 = 0.01;

/// Words per box in the header.
const HEADER_WORDS: usize = 3;

/// How far a box is grown before the reach tests, over its side and in metres: the
/// shaders find a point's box in f32, and a point on a face may fall in either box.
const BOX_MARGIN_OVER_SIDE: f32 = 1e-3;
const BOX_MARGIN_M: f32 = 1e-4;

/// The grid of one frame's lights; see the module's documentation.
#[derive(Debug, Clone, PartialEq)]
pub struct LightGrid {
    /// The corner of the first box (world, metres).
    pub origin: Vec3,
    /// The side of a box, metres.
    pub box_side_m: f32,
    /// Boxes along x, y and z.
    pub boxes: UVec3,
    pub words: Vec<u32>,
}

/// Whether a frame's lights, each on its shadow path, are worth a grid: at least
/// [`LIGHT_GRID_MIN_LIGHTS`] on the SH and shadow-map paths with a range.
pub fn grid_worth_it(shaded: &[GpuLight]) -> bool {
    shaded
        .iter()
        .filter(|light| light.shadow_path != SHADOW_PATH_EXACT && bounded(light))
        .count()
        >= LIGHT_GRID_MIN_LIGHTS
}

/// How many boxes go along the longest side (`longest_m`) for `lights`: see
/// [`BOXES_ALONG_LONGEST_SIDE`].
fn boxes_along_longest_side(lights: &[GpuLight], longest_m: f32) -> f32 {
    let mut ranges: Vec<f32> = lights
        .iter()
        .map(|light| light.direction_range[3])
        .filter(|range| *range > 0.0 && range.is_finite())
        .collect();
    if ranges.is_empty() {
        return BOXES_ALONG_LONGEST_SIDE;
    }
    let middle = ranges.len() / 2;
    let median_m = *ranges.select_nth_unstable_by(middle, f32::total_cmp).1;
    (BOX_SIDES_PER_RANGE * longest_m / median_m)
        .ceil()
        .clamp(BOXES_ALONG_LONGEST_SIDE, MOST_BOXES_ALONG_LONGEST_SIDE)
}

/// A light whose reach ends within some distance: it has a range. (A spot's cone alone
/// leaves out only the boxes behind its apex: a rig of spots aimed at a stage reaches
/// most of the scene, and its frames would pay the list's indirection for little.)
pub(super) fn bounded(light: &GpuLight) -> bool {
    light.kind != LIGHT_DIRECTIONAL && light.direction_range[3] > 0.0
}

/// A spot whose cone factor is 0 behind the plane through its apex: cos(outer cone) > 0
/// (with a margin for the f32 cosine the shaders compare).
fn half_space_cone(light: &GpuLight) -> bool {
    light.kind == LIGHT_SPOT && light.spot_cone[0] > 1e-3 && light.spot_cone[1] >= 0.0
}

impl LightGrid {
    /// The grid over `bounds`, grown a little (a box of a few centimetres at the origin
    /// when they are empty or not finite: most points then walk the outside box's whole
    /// list), of the lights `ordered[..first_exact_light]`: those on the SH path before
    /// `first_mapped_light`, the shadow-map ones after.
    pub fn build(ordered: &[GpuLight], [first_mapped_light, first_exact_light]: [usize; 2], bounds: Aabb) -> LightGrid {
        let first_exact_light = first_exact_light.min(ordered.len());
        let first_mapped_light = first_mapped_light.min(first_exact_light);
        let mut extent = bounds.max - bounds.min;
        let mut origin = bounds.min;
        if !extent.is_finite() || !origin.is_finite() || extent.min_element() < 0.0 {
            (origin, extent) = (Vec3::ZERO, Vec3::ZERO);
        }
        // Grown on every side: points on the scene's outermost surfaces, rebuilt from a
        // depth by the deferred passes, fall a little outside its bounds (a floor at the
        // bounds' bottom face would otherwise walk every light).
        let padding_m = BOUNDS_PADDING_OVER_SIDE * extent.max_element() + BOUNDS_PADDING_M;
        origin -= Vec3::splat(padding_m);
        extent += Vec3::splat(2.0 * padding_m);
        let longest = extent.max_element();
        let mut along_longest = boxes_along_longest_side(&ordered[..first_exact_light], longest);
        loop {
            let box_side_m = longest / along_longest;
            let boxes = (extent / box_side_m).ceil().as_uvec3().max(UVec3::ONE);
            let grid = LightGrid {
                origin,
                box_side_m,
                boxes,
                words: Vec::new(),
            };
            if let Some(words) = grid.list(ordered, [first_mapped_light, first_exact_light]) {
                return LightGrid { words, ..grid };
            }
            along_longest = (along_longest * 0.5).floor().max(1.0);
        }
    }

    /// Every box's lists, or None past [`MAX_WORDS`] (a grid of one box always fits:
    /// two boxes' headers and two lists of the lights). Each light is tested against the
    /// boxes its range's bounding box covers (all of them without a range), so a grid of
    /// many small lights costs the boxes near each.
    fn list(&self, ordered: &[GpuLight], [first_mapped, first_exact]: [usize; 2]) -> Option<Vec<u32>> {
        let box_count = self.box_count();
        let mut per_box: Vec<[Vec<u32>; 2]> = vec![[Vec::new(), Vec::new()]; box_count + 1];
        let mut entries = 0;
        for (i, light) in ordered[..first_exact].iter().enumerate() {
            let path = usize::from(i >= first_mapped);
            // The outside box lists every light.
            per_box[box_count][path].push(i as u32);
            let (lo, hi) = self.boxes_around(light);
            for z in lo.z..=hi.z {
                for y in lo.y..=hi.y {
                    for x in lo.x..=hi.x {
                        let index = (x + self.boxes.x * (y + self.boxes.y * z)) as usize;
                        if reaches_box(light, self.box_bounds(index)) {
                            per_box[index][path].push(i as u32);
                            entries += 1;
                        }
                    }
                }
            }
            if HEADER_WORDS * (box_count + 1) + entries > MAX_WORDS && box_count > 1 {
                return None;
            }
        }
        let header = HEADER_WORDS * (box_count + 1);
        let mut words = Vec::with_capacity(header + entries + first_exact);
        words.resize(header, 0);
        for (index, [harmonic, mapped]) in per_box.iter().enumerate() {
            let start = words.len() as u32;
            words.extend_from_slice(harmonic);
            let split = words.len() as u32;
            words.extend_from_slice(mapped);
            let end = words.len() as u32;
            words[HEADER_WORDS * index..HEADER_WORDS * (index + 1)].copy_from_slice(&[start, split, end]);
        }
        Some(words)
    }

    /// The first and last box (inclusive, clamped to the grid) that the bounding box of
    /// `light`'s range covers, or every box for a light without one.
    fn boxes_around(&self, light: &GpuLight) -> (UVec3, UVec3) {
        let last = self.boxes - UVec3::ONE;
        let range_m = light.direction_range[3];
        if light.kind == LIGHT_DIRECTIONAL || range_m <= 0.0 || !range_m.is_finite() {
            return (UVec3::ZERO, last);
        }
        let reach = Vec3::splat(range_m * (1.0 + 1e-3) + BOX_MARGIN_OVER_SIDE * self.box_side_m + BOX_MARGIN_M);
        let position = Vec3::from_slice(&light.position[..3]);
        let box_at = |p: Vec3| {
            ((p - self.origin) / self.box_side_m)
                .floor()
                .clamp(Vec3::ZERO, last.as_vec3())
                .as_uvec3()
        };
        (box_at(position - reach), box_at(position + reach))
    }

    /// A grid of no box, for frames not worth one ([`grid_worth_it`]): every point walks
    /// the outside box, which lists every light on the SH and shadow-map paths, at the
    /// cost of those lights alone. A pipeline compiled for earlier lights that walks a
    /// grid, drawing while the next one compiles, then walks every light.
    pub fn every_light(ordered: &[GpuLight], [first_mapped_light, first_exact_light]: [usize; 2]) -> LightGrid {
        let first_exact_light = first_exact_light.min(ordered.len());
        let first_mapped_light = first_mapped_light.min(first_exact_light);
        let header = HEADER_WORDS as u32;
        let mut words = vec![
            header,
            header + first_mapped_light as u32,
            header + first_exact_light as u32,
        ];
        words.extend(0..first_exact_light as u32);
        LightGrid {
            origin: Vec3::ZERO,
            box_side_m: 1.0,
            boxes: UVec3::ZERO,
            words,
        }
    }

    pub fn box_count(&self) -> usize {
        (self.boxes.x * self.boxes.y * self.boxes.z) as usize
    }

    /// The box holding `p` (the outside box, [`Self::box_count`], beyond the grid or for a
    /// point that is not finite), as scene.wgsl's `light_box` finds it.
    pub fn box_of(&self, p: Vec3) -> usize {
        let q = (p - self.origin) * (1.0 / self.box_side_m);
        let inside = q.cmpge(Vec3::ZERO).all() && q.cmplt(self.boxes.as_vec3()).all();
        if !inside {
            return self.box_count();
        }
        let c = q.as_uvec3().min(self.boxes - UVec3::ONE);
        (c.x + self.boxes.x * (c.y + self.boxes.y * c.z)) as usize
    }

    /// The bounds of box `index` (below [`Self::box_count`]), grown by the margin.
    fn box_bounds(&self, index: usize) -> Aabb {
        let index = index as u32;
        let c = UVec3::new(
            index % self.boxes.x,
            (index / self.boxes.x) % self.boxes.y,
            index / (self.boxes.x * self.boxes.y),
        );
        let margin = Vec3::splat(BOX_MARGIN_OVER_SIDE * self.box_side_m + BOX_MARGIN_M);
        let min = self.origin + c.as_vec3() * self.box_side_m;
        Aabb {
            min: min - margin,
            max: min + Vec3::splat(self.box_side_m) + margin,
        }
    }

    /// The lights listed for the box of `p`: those on the SH path, then those with maps.
    pub fn lights_at(&self, p: Vec3) -> [&[u32]; 2] {
        let index = self.box_of(p);
        let [start, split, end] = [0, 1, 2].map(|k| self.words[HEADER_WORDS * index + k] as usize);
        [&self.words[start..split], &self.words[split..end]]
    }

    /// The entries over the boxes' count: how many lights a box lists on average (the
    /// outside box's, without boxes).
    pub fn mean_listed(&self) -> f64 {
        if self.box_count() == 0 {
            return (self.words.len() - HEADER_WORDS) as f64;
        }
        let header = HEADER_WORDS * (self.box_count() + 1);
        let outside = self.words[HEADER_WORDS * self.box_count() + 2] - self.words[HEADER_WORDS * self.box_count()];
        (self.words.len() - header - outside as usize) as f64 / self.box_count() as f64
    }
}

/// Whether `light` can light some point of `bounds` (see the module's documentation).
fn reaches_box(light: &GpuLight, bounds: Aabb) -> bool {
    if light.kind == LIGHT_DIRECTIONAL {
        return true;
    }
    let position = Vec3::from_slice(&light.position[..3]);
    let range_m = light.direction_range[3];
    if range_m > 0.0 {
        let nearest = position.clamp(bounds.min, bounds.max);
        // The shaders compare d²/range² with 1 in f32: a relative margin.
        let reach = range_m * (1.0 + 1e-3);
        if nearest.distance_squared(position) > reach * reach {
            return false;
        }
    }
    if half_space_cone(light) {
        let direction = Vec3::from_slice(&light.direction_range[..3]);
        // The corner furthest along the spot's direction.
        let corner = Vec3::select(direction.cmpge(Vec3::ZERO), bounds.max, bounds.min);
        if (corner - position).dot(direction) <= 0.0 {
            return false;
        }
    }
    true
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::random::SplitMix64;
    use crate::scene::{Light, LightKind};

    fn point(position: Vec3, range: Option<f32>) -> GpuLight {
        GpuLight::new(&Light {
            name: "lamp".into(),
            kind: LightKind::Point,
            color: Vec3::ONE,
            intensity: 3.0,
            position,
            direction: Vec3::NEG_Y,
            range,
            locked: false,
        })
    }

    fn spot(position: Vec3, direction: Vec3, outer_cone_rad: f32, range: Option<f32>) -> GpuLight {
        GpuLight::new(&Light {
            name: "spot".into(),
            kind: LightKind::Spot {
                inner_cone_rad: 0.5 * outer_cone_rad,
                outer_cone_rad,
            },
            color: Vec3::ONE,
            intensity: 5.0,
            position,
            direction: direction.normalize(),
            range,
            locked: false,
        })
    }

    fn bounds() -> Aabb {
        Aabb {
            min: Vec3::new(-4.0, 0.0, -3.0),
            max: Vec3::new(4.0, 2.0, 3.0),
        }
    }

    fn lights(random: &mut SplitMix64, count: usize) -> Vec<GpuLight> {
        let mut at = || {
            Vec3::new(
                (random.next_f64() as f32) * 10.0 - 5.0,
                (random.next_f64() as f32) * 3.0 - 0.5,
                (random.next_f64() as f32) * 8.0 - 4.0,
            )
        };
        (0..count)
            .map(|k| match k % 4 {
                0 => point(at(), Some(0.3 + 1.5 * (k as f32 / count as f32))),
                1 => spot(at(), at() - Vec3::Y, 0.3 + 0.1 * (k % 7) as f32, None),
                2 => spot(at(), at(), 0.6, Some(2.0)),
                _ => point(at(), None),
            })
            .collect()
    }

    /// Every light the f64 twin's incidence gives any light at a point is listed for
    /// that point's box, on its path, in ascending order: the grid leaves out only
    /// lights that add exactly nothing there.
    #[test]
    fn a_box_lists_every_light_that_reaches_a_point_of_it() {
        let mut random = SplitMix64(7);
        let lights = lights(&mut random, 64);
        let first_mapped = 40;
        let grid = LightGrid::build(&lights, [first_mapped, lights.len()], bounds());
        let mut left_out = 0;
        for k in 0..20_000 {
            // Points inside and a little outside the bounds, some on the boxes' faces, and
            // some just inside a light's range, where its light is faintest.
            let mut p = Vec3::new(
                (random.next_f64() as f32) * 9.0 - 4.5,
                (random.next_f64() as f32) * 2.4 - 0.2,
                (random.next_f64() as f32) * 7.0 - 3.5,
            );
            if (random.next_f64() as f32) < 0.2 {
                p.x = grid.origin.x + grid.box_side_m * (p.x / grid.box_side_m).round();
            }
            let ranged = &lights[k % lights.len()];
            if k % 2 == 0 && ranged.direction_range[3] > 0.0 {
                let towards = (p - Vec3::from_slice(&ranged.position[..3])).normalize_or(Vec3::X);
                p = Vec3::from_slice(&ranged.position[..3]) + towards * ranged.direction_range[3] * 0.999;
            }
            let [harmonic, mapped] = grid.lights_at(p);
            for (i, light) in lights.iter().enumerate() {
                let lit = crate::shading::cpu::incidence(light, p.as_dvec3())
                    .irradiance
                    .max_element()
                    > 0.0;
                let listed = if i < first_mapped {
                    harmonic.contains(&(i as u32))
                } else {
                    mapped.contains(&(i as u32))
                };
                assert!(!lit || listed, "light {i} reaches {p} but its box leaves it out");
                left_out += usize::from(!listed);
            }
            assert!(harmonic.windows(2).all(|w| w[0] < w[1]) && mapped.windows(2).all(|w| w[0] < w[1]));
            assert!(harmonic.iter().all(|&i| (i as usize) < first_mapped));
            assert!(mapped.iter().all(|&i| (i as usize) >= first_mapped));
        }
        // And it does leave lights out: most of these reach a small part of the scene.
        assert!(left_out > 20_000 * 64 / 4, "only {left_out} left out");
    }

    /// A box whose nearest point lies just inside a light's range is reached (the light
    /// there is faint, but not 0), one just beyond it is not; likewise a spot's apex plane.
    #[test]
    fn the_reach_ends_where_the_light_does() {
        let cube = |near_x: f32| Aabb {
            min: Vec3::new(near_x, -0.5, -0.5),
            max: Vec3::new(near_x + 1.0, 0.5, 0.5),
        };
        let lamp = point(Vec3::ZERO, Some(2.0));
        assert!(reaches_box(&lamp, cube(1.9995)));
        assert!(
            crate::shading::cpu::incidence(&lamp, glam::DVec3::new(1.9995, 0.0, 0.0))
                .irradiance
                .x
                > 0.0
        );
        assert!(!reaches_box(&lamp, cube(2.01)));
        assert_eq!(
            crate::shading::cpu::incidence(&lamp, glam::DVec3::new(2.01, 0.0, 0.0))
                .irradiance
                .x,
            0.0
        );
        let ahead = spot(Vec3::ZERO, Vec3::X, 0.7, None);
        assert!(reaches_box(&ahead, cube(-0.9995)));
        assert!(!reaches_box(&ahead, cube(-1.01)));
        let wide = spot(Vec3::ZERO, Vec3::X, 1.6, None);
        assert!(reaches_box(&wide, cube(-1.5)), "a cone past 90° lights behind its apex");
    }

    /// A floor at the bounds' bottom face, its points rebuilt a little below it, still
    /// walks its own box's lights.
    #[test]
    fn points_just_outside_the_bounds_are_in_the_grid() {
        let lights: Vec<GpuLight> = (0..8)
            .map(|k| point(Vec3::new(k as f32 - 4.0, 0.4, 0.0), Some(0.5)))
            .collect();
        let grid = LightGrid::build(&lights, [8, 8], bounds());
        for p in [
            Vec3::new(0.1, -1e-4, 0.0),
            Vec3::new(-4.0 - 1e-4, 0.0, 0.0),
            Vec3::new(0.0, 2.0 + 1e-4, 3.0),
        ] {
            assert_ne!(grid.box_of(p), grid.box_count(), "{p} is outside the grid");
            assert!(grid.lights_at(p)[0].len() <= 2);
        }
    }

    /// A street 100 m long lit by a lamp every 2 m, each of 2 m range: its boxes follow
    /// the lamps' range, not the street's length, and a point walks a handful of lamps.
    #[test]
    fn short_ranges_in_a_long_scene_take_finer_boxes() {
        let street = Aabb {
            min: Vec3::new(-50.0, 0.0, -4.0),
            max: Vec3::new(50.0, 6.0, 4.0),
        };
        let lamps: Vec<GpuLight> = (0..50)
            .map(|k| point(Vec3::new(-49.0 + 2.0 * k as f32, 1.0, 0.0), Some(2.0)))
            .collect();
        let grid = LightGrid::build(&lamps, [50, 50], street);
        assert_eq!(grid.boxes.x, 64, "the most boxes along the street: {grid:?}");
        for x in [-40.3, -3.3, 0.0, 27.9] {
            let on_the_ground = Vec3::new(x, 0.0, 1.0);
            let listed = grid.lights_at(on_the_ground)[0].len();
            assert!((2..=5).contains(&listed), "{listed} lamps listed at {on_the_ground}");
        }
        // Without ranges, the grid stays as coarse as before.
        let unranged: Vec<GpuLight> = lamps
            .iter()
            .map(|l| GpuLight {
                direction_range: [0.0, -1.0, 0.0, 0.0],
                ..*l
            })
            .collect();
        assert_eq!(LightGrid::build(&unranged, [50, 50], street).boxes.x, 24);
    }

    /// The grid of no box lists every light at every point, as the shaders' walk over
    /// every light takes them.
    #[test]
    fn the_grid_of_no_box_lists_every_light_everywhere() {
        let mut random = SplitMix64(11);
        let lights = lights(&mut random, 20);
        let grid = LightGrid::every_light(&lights, [12, 18]);
        assert_eq!(grid.box_count(), 0);
        for p in [Vec3::ZERO, Vec3::new(3.0, -1.0, 2.0), Vec3::splat(f32::NAN)] {
            let [harmonic, mapped] = grid.lights_at(p);
            assert_eq!(harmonic, (0..12).collect::<Vec<u32>>().as_slice());
            assert_eq!(mapped, (12..18).collect::<Vec<u32>>().as_slice());
        }
        assert_eq!(grid.mean_listed(), 18.0);
    }

    #[test]
    fn points_beyond_the_grid_and_not_finite_walk_every_light() {
        let mut random = SplitMix64(3);
        let lights = lights(&mut random, 24);
        let grid = LightGrid::build(&lights, [10, 20], bounds());
        for p in [
            Vec3::new(50.0, 0.0, 0.0),
            Vec3::splat(f32::NAN),
            Vec3::new(0.0, -1.0, 0.0),
        ] {
            let [harmonic, mapped] = grid.lights_at(p);
            assert_eq!(harmonic, (0..10).collect::<Vec<u32>>().as_slice());
            assert_eq!(mapped, (10..20).collect::<Vec<u32>>().as_slice());
        }
    }

    #[test]
    fn a_grid_past_its_budget_is_built_coarser() {
        // Lights without a range fill every box: 2,000 of them over 24 × 6 × 18 boxes
        // would pass MAX_WORDS.
        let lights: Vec<GpuLight> = (0..2_000)
            .map(|k| point(Vec3::new(k as f32 * 1e-3, 1.0, 0.0), None))
            .collect();
        let grid = LightGrid::build(&lights, [2_000, 2_000], bounds());
        assert!(grid.words.len() <= MAX_WORDS);
        assert!(grid.box_count() < 24 * 6 * 18);
        assert_eq!(grid.lights_at(Vec3::ONE)[0].len(), 2_000);
    }

    #[test]
    fn grids_are_worth_it_only_for_enough_bounded_lights() {
        let mut ranged: Vec<GpuLight> = (0..8).map(|k| point(Vec3::X * k as f32, Some(1.0))).collect();
        assert!(grid_worth_it(&ranged));
        ranged[3].shadow_path = SHADOW_PATH_EXACT;
        assert!(!grid_worth_it(&ranged), "the exact path's lights are not gridded");
        let unbounded: Vec<GpuLight> = (0..32).map(|k| point(Vec3::X * k as f32, None)).collect();
        assert!(!grid_worth_it(&unbounded));
        let rig: Vec<GpuLight> = (0..12)
            .map(|k| spot(Vec3::X * k as f32, Vec3::NEG_Y, 0.5, None))
            .collect();
        assert!(!grid_worth_it(&rig), "spots without a range reach most of a scene");
    }

    #[test]
    fn empty_or_infinite_bounds_give_a_small_grid_at_the_origin() {
        let lights = vec![point(Vec3::ZERO, Some(1.0)), point(Vec3::X * 9.0, Some(1.0))];
        let infinite = Aabb {
            min: Vec3::splat(f32::NEG_INFINITY),
            max: Vec3::splat(f32::INFINITY),
        };
        let empty = Aabb {
            min: Vec3::ONE,
            max: Vec3::ZERO,
        };
        for bounds in [infinite, empty] {
            let grid = LightGrid::build(&lights, [2, 2], bounds);
            assert!(grid.origin.length() < 0.1 && grid.box_count() >= 1);
            assert_eq!(
                grid.lights_at(grid.origin + Vec3::splat(grid.box_side_m * 0.5))[0],
                &[0u32][..]
            );
            assert_eq!(grid.lights_at(Vec3::ONE)[0], &[0u32, 1][..]);
        }
    }
}
