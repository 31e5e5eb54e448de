//! Where each shadow-map view lies in the map array, and how many texels it gets: the
//! lights' views share one `Depth32Float` array whose layers are twice the setting
//! (`ShadowSettings::shadow_map_size`, a cube face's side) on a side, and each view takes
//! a square of a layer whose side is the layer's over a power of two.
//!
//! Sides: a spot, the sun and a light aimed at the scene see everything they shadow
//! through one view, which takes a whole layer (2 × the setting), so that the views that
//! carry a scene's key shadows are sharper at the same memory; a point light's six cube
//! faces take the setting each. The study measured why (docs/speed-accuracy.md): 2048²
//! maps against 1024² took the studio's shadowed-pixel RMSE from 0.0167 to 0.0127 and the
//! sample's from 0.0221 to 0.0173, at the same frame time. A light with a range shadows
//! nothing past it: its cube faces are halved while a texel at its range stays no wider
//! than a full face's texel at the scene's bounding radius (2r/side ≤ 2R/setting, i.e.
//! side ≥ setting · r/R), down to [`MIN_FACE_SIDE`]. A room of 30 lamps of 1.5 m range
//! (samples' lamp-room, R = 4.5 m) takes 180 faces of 512² (180 MiB) where 16 of its lamps'
//! 96 faces at 1024² took 384 MiB and the rest went without maps.
//!
//! Memory: when the views' squares would take more than [`MAP_MEMORY_BUDGET_BYTES`], the
//! single views come down to the setting first, then the largest cube faces are halved
//! (all of one side at a time) until they fit or reach [`MIN_FACE_SIDE`]. The budget is
//! the most the array took at the default 1024² before views were sized (96 faces), so at
//! the default no scene draws coarser maps than it did; at larger settings a scene of
//! many cube faces does (16 cubes took 1.5 GiB at 2048²).
//!
//! Placing: the squares go largest first, each into the next free cell of its side in
//! the open layer's quadtree (cells in Morton order: since every square taken before is
//! at least as large, the area filled is a whole number of cells of the new side, and
//! that count's Morton decoding is a free cell), a new layer when the open one is full.

/// The most memory the views' squares may take (see the module's documentation).
pub const MAP_MEMORY_BUDGET_BYTES: u64 = 384 << 20;

/// The smallest side a cube face is halved to (or the setting, if smaller).
pub const MIN_FACE_SIDE: u32 = 128;

/// The widest layer the array may have: wgpu's default `max_texture_dimension_2d`, which
/// the renderer asks of the device.
pub const MAX_LAYER_SIZE: u32 = 8192;

/// Bytes of one texel (`Depth32Float`).
const BYTES_PER_TEXEL: u64 = 4;

/// A view asking for a square: a cube face (else a single view), and for a face of a
/// light with a range, that range over the scene's bounding radius.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct WantedView {
    pub cube_face: bool,
    /// The light's range over the scene's bounding radius; None without a range.
    pub range_share: Option<f32>,
}

/// The array's shape and each view's square.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct ShadowAtlas {
    /// Texels per side of a layer.
    pub layer_size: u32,
    /// Layers the views take.
    pub layers: u32,
    /// Per view, in view order: `GpuShadowView::atlas` (corner u, corner v, side as a share
    /// of the layer's, layer).
    pub squares: Vec<[f32; 4]>,
    /// Per view: a cube face (else a single view), and its side in texels.
    sides: Vec<(bool, u32)>,
}

impl ShadowAtlas {
    /// The squares of `wanted` (in view order) for cube faces of `face_size` texels on a
    /// side by the setting (see the module's documentation).
    pub fn new(wanted: &[WantedView], face_size: u32) -> ShadowAtlas {
        let face_size = face_size.clamp(1, MAX_LAYER_SIZE);
        let layer_size = (2 * face_size).min(MAX_LAYER_SIZE);
        let min_face = MIN_FACE_SIDE.min(face_size);
        let mut sides: Vec<(bool, u32)> = wanted
            .iter()
            .map(|view| {
                if !view.cube_face {
                    return (false, layer_size);
                }
                let mut side = face_size;
                if let Some(share) = view.range_share.filter(|share| share.is_finite()) {
                    while side.is_multiple_of(2)
                        && side / 2 >= min_face
                        && (side / 2) as f32 >= face_size as f32 * share
                    {
                        side /= 2;
                    }
                }
                (true, side)
            })
            .collect();
        let bytes = |sides: &[(bool, u32)]| sides.iter().map(|(_, side)| texel_bytes(*side)).sum::<u64>();
        if bytes(&sides) > MAP_MEMORY_BUDGET_BYTES {
            for (cube_face, side) in &mut sides {
                if !*cube_face {
                    *side = face_size;
                }
            }
        }
        while bytes(&sides) > MAP_MEMORY_BUDGET_BYTES {
            let largest = sides
                .iter()
                .filter(|(cube_face, side)| *cube_face && side.is_multiple_of(2) && side / 2 >= min_face)
                .map(|(_, side)| *side)
                .max();
            let Some(largest) = largest else { break };
            for (cube_face, side) in &mut sides {
                if *cube_face && *side == largest {
                    *side /= 2;
                }
            }
        }
        let (squares, layers) = place(&sides, layer_size);
        ShadowAtlas {
            layer_size,
            layers,
            squares,
            sides,
        }
    }

    /// The side in texels of view `k`'s square (0 for a view that is not in the atlas).
    pub fn view_size(&self, k: usize) -> u32 {
        self.sides.get(k).map_or(0, |(_, side)| *side)
    }

    /// The array's memory in bytes.
    pub fn bytes(&self) -> u64 {
        self.layers as u64 * texel_bytes(self.layer_size)
    }

    /// The views' sizes and the array's memory in words, e.g. "6 view(s) at 2048², 18 cube
    /// faces at 1024², 176 MiB".
    pub fn in_words(&self) -> String {
        let mut groups: Vec<(bool, u32, usize)> = Vec::new();
        for &(cube_face, side) in &self.sides {
            match groups.iter_mut().find(|(c, s, _)| *c == cube_face && *s == side) {
                Some(group) => group.2 += 1,
                None => groups.push((cube_face, side, 1)),
            }
        }
        if groups.is_empty() {
            return "no views".to_string();
        }
        // Single views first, then the faces, each largest first.
        groups.sort_by(|a, b| a.0.cmp(&b.0).then(b.1.cmp(&a.1)));
        let parts: Vec<String> = groups
            .iter()
            .map(|&(cube_face, side, count)| match cube_face {
                false => format!("{count} view(s) at {side}²"),
                true => format!("{count} cube faces at {side}²"),
            })
            .collect();
        format!(
            "{}, {:.0} MiB",
            parts.join(", "),
            self.bytes() as f64 / (1u64 << 20) as f64
        )
    }
}

fn texel_bytes(side: u32) -> u64 {
    (side as u64).pow(2) * BYTES_PER_TEXEL
}

/// Each square of `sides` placed in layers of `layer_size` (see the module's
/// documentation), in view order, and the layers taken.
fn place(sides: &[(bool, u32)], layer_size: u32) -> (Vec<[f32; 4]>, u32) {
    let mut order: Vec<usize> = (0..sides.len()).collect();
    order.sort_by(|&a, &b| sides[b].1.cmp(&sides[a].1).then(a.cmp(&b)));
    let layer_area = (layer_size as u64).pow(2);
    let mut squares = vec![[0.0; 4]; sides.len()];
    let (mut layers, mut filled) = (0u32, layer_area);
    for k in order {
        let side = sides[k].1.min(layer_size) as u64;
        if filled + side * side > layer_area {
            layers += 1;
            filled = 0;
        }
        let (x, y) = morton_cell(filled / (side * side));
        filled += side * side;
        let share = side as f32 / layer_size as f32;
        squares[k] = [x as f32 * share, y as f32 * share, share, (layers - 1) as f32];
    }
    (squares, layers)
}

/// The cell at `index` along the Morton (Z-order) curve: x from the even bits, y from
/// the odd ones.
fn morton_cell(index: u64) -> (u64, u64) {
    let (mut x, mut y) = (0, 0);
    for bit in 0..32 {
        x |= ((index >> (2 * bit)) & 1) << bit;
        y |= ((index >> (2 * bit + 1)) & 1) << bit;
    }
    (x, y)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn single() -> WantedView {
        WantedView {
            cube_face: false,
            range_share: None,
        }
    }

    fn face(range_share: Option<f32>) -> WantedView {
        WantedView {
            cube_face: true,
            range_share,
        }
    }

    /// Every texel of every layer is covered by at most one view's square, and each square
    /// lies inside its layer.
    fn assert_no_overlap(atlas: &ShadowAtlas) {
        let size = atlas.layer_size as u64;
        let mut covered = vec![false; (atlas.layers as u64 * size * size) as usize];
        for (k, &[u, v, share, layer]) in atlas.squares.iter().enumerate() {
            let (x0, y0, side) = (
                (u * size as f32) as u64,
                (v * size as f32) as u64,
                (share * size as f32) as u64,
            );
            assert_eq!(side, atlas.view_size(k) as u64, "view {k}'s square is its side");
            assert!(x0 + side <= size && y0 + side <= size && (layer as u32) < atlas.layers);
            for y in y0..y0 + side {
                for x in x0..x0 + side {
                    let texel = &mut covered[(layer as u64 * size * size + y * size + x) as usize];
                    assert!(!*texel, "view {k} overlaps another at layer {layer}, texel {x},{y}");
                    *texel = true;
                }
            }
        }
    }

    #[test]
    fn single_views_take_whole_doubled_layers_and_faces_share_them_four_to_one() {
        // The studio's lights: five spots and the sun, three point lights.
        let wanted: Vec<WantedView> = (0..24).map(|k| if k < 6 { single() } else { face(None) }).collect();
        let atlas = ShadowAtlas::new(&wanted, 1024);
        assert_eq!(atlas.layer_size, 2048);
        assert!((0..6).all(|k| atlas.view_size(k) == 2048 && atlas.squares[k][2] == 1.0));
        assert!((6..24).all(|k| atlas.view_size(k) == 1024 && atlas.squares[k][2] == 0.5));
        assert_eq!(atlas.layers, 6 + 5, "18 faces in 4½ layers");
        assert_eq!(atlas.bytes(), 11 * (16 << 20));
        assert_eq!(atlas.in_words(), "6 view(s) at 2048², 18 cube faces at 1024², 176 MiB");
        assert_no_overlap(&atlas);
    }

    #[test]
    fn many_single_views_come_down_to_the_settings_size() {
        // 40 spots at 2048² would take 640 MiB against 160 MiB at 1024².
        let atlas = ShadowAtlas::new(&vec![single(); 40], 1024);
        assert!((0..40).all(|k| atlas.view_size(k) == 1024));
        assert_eq!(atlas.bytes(), 40 * (4 << 20));
        assert_no_overlap(&atlas);
        // Faces alone cost the same as a layer each at the setting: four to a layer.
        let atlas = ShadowAtlas::new(&vec![face(None); 96], 1024);
        assert_eq!((atlas.view_size(95), atlas.bytes()), (1024, 96 * (4 << 20)));
        // A setting whose doubled layer the device cannot hold.
        assert_eq!(ShadowAtlas::new(&[single()], 8192).layer_size, 8192);
    }

    #[test]
    fn a_lamps_faces_keep_its_range_as_fine_as_a_full_face_keeps_the_scene() {
        // side ≥ setting · r/R: r/R = 1/3 → 512 (341 would be coarser), 1/4 → 256, 1 → 1024.
        let sides = |share: f32| ShadowAtlas::new(&[face(Some(share))], 1024).view_size(0);
        assert_eq!(sides(1.0 / 3.0), 512);
        assert_eq!(sides(0.25), 256);
        assert_eq!(sides(1.5), 1024);
        assert_eq!(sides(0.01), MIN_FACE_SIDE, "no smaller than the least side");
        assert_eq!(sides(f32::NAN), 1024, "a share that is not a number shrinks nothing");
        // The lamp room: 30 lamps of 1.5 m range in a scene of radius 4.5 m.
        let atlas = ShadowAtlas::new(&vec![face(Some(1.5 / 4.5)); 180], 1024);
        assert_eq!(atlas.in_words(), "180 cube faces at 512², 192 MiB");
        assert_no_overlap(&atlas);
    }

    #[test]
    fn past_the_budget_the_largest_faces_are_halved_first() {
        // 16 point lights without a range and 6 with half the scene's radius: 96 + 36 faces.
        let mut wanted = vec![face(None); 96];
        wanted.extend(vec![face(Some(0.5)); 36]);
        let atlas = ShadowAtlas::new(&wanted, 1024);
        let total: u64 = (0..wanted.len()).map(|k| texel_bytes(atlas.view_size(k))).sum();
        assert!(total <= MAP_MEMORY_BUDGET_BYTES, "{total} bytes");
        assert_eq!(atlas.view_size(0), 512, "1024² faces halved once");
        assert_eq!(atlas.view_size(100), 512, "the ranged ones were 512² already");
        assert_no_overlap(&atlas);
        // Mixed sides pack without gaps but the last layer's.
        let mixed: Vec<WantedView> = (0..40)
            .map(|k| match k % 4 {
                0 => single(),
                1 => face(None),
                2 => face(Some(0.4)),
                _ => face(Some(0.1)),
            })
            .collect();
        let atlas = ShadowAtlas::new(&mixed, 256);
        assert_no_overlap(&atlas);
        let used: u64 = (0..40).map(|k| (atlas.view_size(k) as u64).pow(2)).sum();
        assert_eq!(atlas.layers as u64, used.div_ceil(512 * 512));
    }
}
